#pragma once
// OpenEXR output (and input, for tests and tools) of radiance images, through Debian's
// OpenEXR library (only the examples depend on it, never the shade library).

#include <filesystem>

#include "render.hpp"

namespace tracer {

/// Writes `image` to `path` as an OpenEXR scan-line file: channels R, G and B of 32-bit
/// float (Imf::FLOAT, not half: the values read back are exactly the render's, rounded
/// to float), linear radiance without tone mapping, rows from the top of the image,
/// lossless ZIP compression. Throws std::runtime_error "cannot write EXR '<path>': <reason>"
/// when OpenEXR fails (e.g. a missing directory).
void save_exr(const std::filesystem::path& path, const radiance_image& image);

/// Reads the R, G and B channels of the OpenEXR file at `path` (converted to float by
/// OpenEXR whatever their stored type; a missing channel reads as 0) into a radiance
/// image of the file's data window size. Throws std::runtime_error "cannot read EXR
/// '<path>': <reason>" when the file is missing or not an OpenEXR file.
[[nodiscard]] radiance_image load_exr(const std::filesystem::path& path);

} // namespace tracer
