// tracer::save_exr and tracer::load_exr (examples/tracer/exr.hpp) through OpenEXR.

#include "tracer/exr.hpp"

#include <cstddef>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

namespace tracer {

namespace {

// Interleaved RGB floats, and the three slices that describe them to OpenEXR. The slice
// base pointers are those of pixel (0, 0) of the data window, whose origin is (0, 0) for
// the files written here; for a window elsewhere OpenEXR addresses
// base + x * x_stride + y * y_stride with absolute coordinates, so the base is shifted
// back by the window's origin.
Imf::FrameBuffer rgb_slices(std::vector<float>& data, int width, int min_x, int min_y) {
    const std::size_t x_stride = 3 * sizeof(float);
    const std::size_t y_stride = x_stride * std::size_t(width);
    const std::ptrdiff_t origin =
        -std::ptrdiff_t(min_x) * std::ptrdiff_t(x_stride) - std::ptrdiff_t(min_y) * std::ptrdiff_t(y_stride);
    Imf::FrameBuffer frame;
    const char* names[3] = {"R", "G", "B"};
    for (std::size_t k = 0; k < 3; ++k) {
        char* base = reinterpret_cast<char*>(data.data() + k) + origin;
        frame.insert(names[k], Imf::Slice(Imf::FLOAT, base, x_stride, y_stride, 1, 1, 0.0));
    }
    return frame;
}

} // namespace

void save_exr(const std::filesystem::path& path, const radiance_image& image) {
    std::vector<float> data(std::size_t(image.width) * std::size_t(image.height) * 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (std::size_t k = 0; k < 3; ++k) data[3 * i + k] = static_cast<float>(image.pixels[i][int(k)]);
    try {
        Imf::Header header(image.width, image.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        for (const char* name : {"R", "G", "B"}) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
        Imf::OutputFile file(path.c_str(), header);
        file.setFrameBuffer(rgb_slices(data, image.width, 0, 0));
        file.writePixels(image.height);
    } catch (const std::exception& e) {
        throw std::runtime_error("cannot write EXR '" + path.string() + "': " + e.what());
    }
}

radiance_image load_exr(const std::filesystem::path& path) {
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i window = file.header().dataWindow();
        radiance_image image;
        image.width = window.max.x - window.min.x + 1;
        image.height = window.max.y - window.min.y + 1;
        std::vector<float> data(std::size_t(image.width) * std::size_t(image.height) * 3, 0.0f);
        file.setFrameBuffer(rgb_slices(data, image.width, window.min.x, window.min.y));
        file.readPixels(window.min.y, window.max.y);
        image.pixels.resize(std::size_t(image.width) * std::size_t(image.height));
        for (std::size_t i = 0; i < image.pixels.size(); ++i)
            image.pixels[i] = rgb(data[3 * i], data[3 * i + 1], data[3 * i + 2]);
        return image;
    } catch (const std::exception& e) {
        throw std::runtime_error("cannot read EXR '" + path.string() + "': " + e.what());
    }
}

} // namespace tracer
