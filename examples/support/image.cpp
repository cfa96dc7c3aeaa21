#include "support/image.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

namespace shade::examples {

namespace {

[[noreturn]] void fail(const char* verb, const std::filesystem::path& path, const std::string& reason) {
    throw std::runtime_error(std::string("cannot ") + verb + " image '" + path.string() + "': " + reason);
}

struct file_closer {
    void operator()(std::FILE* f) const noexcept { std::fclose(f); }
};

struct stbi_freer {
    void operator()(stbi_uc* p) const noexcept { stbi_image_free(p); }
};

} // namespace

image image::filled(int width, int height, srgb8 fill) {
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("image size must be positive (got " + std::to_string(width) + "x" +
                                    std::to_string(height) + ")");
    image img;
    img.width = width;
    img.height = height;
    img.pixels.resize(3 * std::size_t(width) * std::size_t(height));
    for (std::size_t i = 0; i < img.pixels.size(); i += 3) {
        img.pixels[i] = fill.r;
        img.pixels[i + 1] = fill.g;
        img.pixels[i + 2] = fill.b;
    }
    return img;
}

image load_image(const std::filesystem::path& path) {
    // Open the file ourselves so that a missing or unreadable file reports the system's
    // reason (errno) rather than stb's generic "can't fopen".
    errno = 0;
    const std::unique_ptr<std::FILE, file_closer> file(std::fopen(path.c_str(), "rb"));
    if (!file) fail("read", path, errno != 0 ? std::strerror(errno) : "cannot open file");
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) fail("read", path, "is a directory");

    int width = 0, height = 0, channels_in_file = 0;
    const std::unique_ptr<stbi_uc, stbi_freer> data(
        stbi_load_from_file(file.get(), &width, &height, &channels_in_file, 3));
    if (!data) {
        const char* reason = stbi_failure_reason();
        fail("read", path, std::string("not a readable image (") + (reason ? reason : "unknown error") + ")");
    }
    image img;
    img.width = width;
    img.height = height;
    const std::size_t size = 3 * std::size_t(width) * std::size_t(height);
    img.pixels.assign(data.get(), data.get() + size);
    return img;
}

void save_png(const std::filesystem::path& path, const image& img) {
    if (img.width <= 0 || img.height <= 0)
        fail("write", path, "image size must be positive (got " + std::to_string(img.width) + "x" +
                                std::to_string(img.height) + ")");
    const std::size_t expected = 3 * std::size_t(img.width) * std::size_t(img.height);
    if (img.pixels.size() != expected)
        fail("write", path, "pixel buffer holds " + std::to_string(img.pixels.size()) + " bytes, expected " +
                                std::to_string(expected) + " for " + std::to_string(img.width) + "x" +
                                std::to_string(img.height) + " RGB");
    if (img.width > std::numeric_limits<int>::max() / 3) fail("write", path, "image too wide for PNG row stride");
    errno = 0;
    const int ok = stbi_write_png(path.c_str(), img.width, img.height, 3, img.pixels.data(), img.width * 3);
    if (ok == 0) fail("write", path, errno != 0 ? std::strerror(errno) : "PNG encoder failed");
}

} // namespace shade::examples
