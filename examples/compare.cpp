// compare: colour differences (CIEDE2000) between two images, or between a region of an
// image and a measured CIE L*a*b* value. Prints mean, 95th percentile and maximum Delta E00,
// the mean L*a*b* of each side and the differences in linear RGB; optionally writes a
// Delta E00 heat map.
//
// Images are PNG (or JPEG, BMP, TGA: 8-bit sRGB, IEC 61966-2-1, decoded to linear sRGB) or
// PFM and OpenEXR (linear sRGB radiance, what `trace` writes), told apart by their first
// bytes. Every pixel is linear sRGB, multiplied by --exposure, converted to XYZ and to
// L*a*b* relative to D65 (default) or D50 (Bradford-adapted, for measurements reported
// against the ICC D50 white). Run with --help for usage.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <shade/color/convert.hpp>
#include <shade/color/delta_e.hpp>
#include <shade/color/srgb.hpp>

#include "support/cli.hpp"
#include "support/image.hpp"
#include "tracer/exr.hpp"
#include "tracer/pfm.hpp"

namespace {

using real = double;

constexpr int exit_ok = 0;
constexpr int exit_threshold_exceeded = 1;
constexpr int exit_error = 2;

constexpr const char* usage_text = R"(usage:
  compare IMAGE_A IMAGE_B [options]
      Delta E00 per pixel between two images of the same size.
  compare IMAGE --lab L,a,b [options]
      Delta E00 per pixel between IMAGE and one measured CIE L*a*b* colour.

Images: PNG (or JPEG, BMP, TGA through stb_image; 8-bit sRGB, alpha ignored), PFM or
OpenEXR (linear radiance, e.g. from `trace --out x.pfm` or `x.exr`), recognised by their
contents; the two images may be of different kinds.

How Delta E is computed: 8-bit pixels are decoded to linear sRGB (display white = 1);
PFM and EXR pixels are linear sRGB already. Both are multiplied by --exposure and taken
relative to the L*a*b* white: linear (1, 1, 1) is L* = 100, brighter HDR values give
L* > 100 by the same CIE formula (no tone map, no clipping). Non-finite pixels are refused.

Options:
  --region X,Y,W,H     compare only the W x H pixels whose top-left corner is column X,
                       row Y (in both images); default: the whole image
  --lab L,a,b          the measured L*a*b* colour to compare against
  --white d65|d50      white point of L*a*b* (default d65, the white of sRGB; use d50 for
                       values measured against the ICC D50 white)
  --exposure X         multiplier of the linear values before L*a*b*, in (0, 1e6]
                       (default 1): choose it so that the HDR range you care about
                       sits near linear 1
  --heatmap OUT.png    write a W x H PNG of the per-pixel Delta E00: black at 0, through
                       red and yellow, to white at --scale and above; its path is
                       checked before any work, and the file appears only when complete
  --scale S            Delta E00 shown as white in the heat map, in (0, 1e6]
                       (default 10)
  --fail-above STAT=T  exit with status 1 if STAT (mean, p95 or max) of Delta E00 > T
  --help               show this help

Output: the mean L*a*b* of each side (the arithmetic mean of the per-pixel L*a*b*), the
mean, 95th percentile (nearest rank) and maximum of the per-pixel Delta E00 (CIEDE2000,
Sharma, Wu & Dalal 2005), and the mean and largest absolute difference and the root mean
square difference of the linear RGB channels (after --exposure; over pixels and channels).

Exit status: 0 on success, 1 if --fail-above is exceeded, 2 on a usage error, an
unreadable, mismatched or invalid input, or a heat map that cannot be written (with a
message on stderr).
)";

namespace ex = shade::examples;

using ex::usage_error;

struct region {
    int x = 0, y = 0, w = 0, h = 0;
};

enum class statistic { mean, p95, max };

struct threshold {
    statistic stat = statistic::mean;
    real limit = 0;
    std::string name;
};

struct options {
    std::vector<std::string> images;
    std::optional<region> area;
    std::optional<shade::lab<real>> measured;
    std::string white = "d65";
    std::optional<std::string> heatmap;
    real scale = 10;
    real exposure = 1;
    std::optional<threshold> fail_above;
};

std::vector<std::string_view> split(std::string_view text, char separator) {
    std::vector<std::string_view> parts;
    std::size_t start = 0;
    while (true) {
        const std::size_t pos = text.find(separator, start);
        parts.push_back(text.substr(start, pos == std::string_view::npos ? std::string_view::npos : pos - start));
        if (pos == std::string_view::npos) break;
        start = pos + 1;
    }
    return parts;
}

// A measured L*a*b* component: any finite number within 1e6 (L* above 100 is allowed, as
// an HDR pixel can have it).
constexpr real lab_limit = 1e6;

options parse(int argc, char** argv, bool& help) {
    options o;
    help = false;
    ex::command_line args(argc, argv);
    while (args.next()) {
        if (args.flag("--help") || args.flag("-h")) {
            help = true;
            return o;
        }
        if (args.option("--region")) {
            const auto parts = split(args.text(), ',');
            if (parts.size() != 4)
                throw usage_error("option --region needs X,Y,W,H (four whole numbers), got '" + std::string(args.text()) +
                                  "'");
            constexpr int max = std::numeric_limits<int>::max();
            o.area = region{ex::parse_integer("--region X", parts[0], 0, max),
                            ex::parse_integer("--region Y", parts[1], 0, max),
                            ex::parse_integer("--region W", parts[2], 1, max),
                            ex::parse_integer("--region H", parts[3], 1, max)};
        } else if (args.option("--lab")) {
            const auto parts = split(args.text(), ',');
            if (parts.size() != 3)
                throw usage_error("option --lab needs L,a,b (three numbers), got '" + std::string(args.text()) + "'");
            o.measured = shade::lab<real>{ex::parse_real("--lab L", parts[0], -lab_limit, lab_limit),
                                          ex::parse_real("--lab a", parts[1], -lab_limit, lab_limit),
                                          ex::parse_real("--lab b", parts[2], -lab_limit, lab_limit)};
        } else if (args.option("--white")) {
            const std::string_view v = args.text();
            if (v != "d65" && v != "d50")
                throw usage_error("option --white must be d65 or d50, got '" + std::string(v) + "'");
            o.white = std::string(v);
        } else if (args.option("--heatmap")) {
            o.heatmap = args.path().string();
            (void)ex::output_format("--heatmap", *o.heatmap, {".png"});
        } else if (args.option("--scale")) {
            o.scale = args.real(0, 1e6, ex::lower_limit::exclusive);
        } else if (args.option("--exposure")) {
            o.exposure = args.real(0, 1e6, ex::lower_limit::exclusive);
        } else if (args.option("--fail-above")) {
            const std::string_view v = args.text();
            const auto parts = split(v, '=');
            if (parts.size() != 2)
                throw usage_error("option --fail-above needs STAT=T with STAT mean, p95 or max, got '" +
                                  std::string(v) + "'");
            threshold t;
            t.name = std::string(parts[0]);
            if (parts[0] == "mean")
                t.stat = statistic::mean;
            else if (parts[0] == "p95")
                t.stat = statistic::p95;
            else if (parts[0] == "max")
                t.stat = statistic::max;
            else
                throw usage_error("option --fail-above: unknown statistic '" + t.name + "' (use mean, p95 or max)");
            t.limit = ex::parse_real("--fail-above T", parts[1], 0, std::numeric_limits<real>::max());
            o.fail_above = t;
        } else if (args.is_option()) {
            args.unknown();
        } else {
            o.images.emplace_back(args.current());
        }
    }
    if (o.measured) {
        if (o.images.size() != 1)
            throw usage_error("--lab compares one image with a measured colour: give exactly one image (got " +
                              std::to_string(o.images.size()) + ")");
    } else if (o.images.size() != 2) {
        throw usage_error("give two images, or one image and --lab L,a,b (got " + std::to_string(o.images.size()) +
                          " image arguments)");
    }
    return o;
}

/// An input image as linear sRGB, whatever its file format.
struct linear_image {
    int width = 0;
    int height = 0;
    std::vector<shade::rgb<real>> pixels; ///< row-major, top row first
    [[nodiscard]] const shade::rgb<real>& at(int x, int y) const {
        return pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    }
};

enum class file_kind { pfm, exr, other };

// The kind of an image file from its first bytes: "PF"/"Pf" and a whitespace for PFM, the
// magic number 76 2f 31 01 for OpenEXR; anything else goes to stb_image.
file_kind sniff(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::array<char, 4> head{};
    in.read(head.data(), head.size());
    if (in.gcount() < 3) return file_kind::other;
    const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
    if (head[0] == 'P' && (head[1] == 'F' || head[1] == 'f') && space(head[2])) return file_kind::pfm;
    if (in.gcount() == 4 && static_cast<unsigned char>(head[0]) == 0x76 && static_cast<unsigned char>(head[1]) == 0x2f &&
        static_cast<unsigned char>(head[2]) == 0x31 && static_cast<unsigned char>(head[3]) == 0x01)
        return file_kind::exr;
    return file_kind::other;
}

// Reads any supported image as linear sRGB times `exposure`. Throws usage_error (an input
// error: exit status 2) naming the file when it cannot be read or has a non-finite pixel.
linear_image load_linear(const std::string& path, real exposure) {
    linear_image out;
    try {
        const file_kind kind = sniff(path);
        if (kind == file_kind::other) {
            const ex::image img = ex::load_image(path);
            out.width = img.width;
            out.height = img.height;
            out.pixels.reserve(std::size_t(img.width) * std::size_t(img.height));
            for (int y = 0; y < img.height; ++y)
                for (int x = 0; x < img.width; ++x) out.pixels.push_back(shade::decode_srgb8<real>(img.at(x, y)));
        } else {
            const tracer::radiance_image img = kind == file_kind::pfm ? tracer::load_pfm(path) : tracer::load_exr(path);
            out.width = img.width;
            out.height = img.height;
            out.pixels.assign(img.pixels.begin(), img.pixels.end());
        }
    } catch (const usage_error&) {
        throw;
    } catch (const std::exception& e) {
        throw usage_error(e.what());
    }
    for (std::size_t i = 0; i < out.pixels.size(); ++i) {
        const auto& c = out.pixels[i];
        if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z))
            throw usage_error("image '" + path + "': pixel (" + std::to_string(i % std::size_t(out.width)) + ", " +
                              std::to_string(i / std::size_t(out.width)) + ") is not finite");
        out.pixels[i] = c * exposure;
    }
    return out;
}

std::string size_text(const linear_image& img) {
    return std::to_string(img.width) + "x" + std::to_string(img.height);
}

region checked_region(const std::optional<region>& requested, const linear_image& img,
                      const std::string& path) {
    if (!requested) return {0, 0, img.width, img.height};
    const region r = *requested;
    // Compared in 64-bit so that X + W cannot overflow int.
    if (static_cast<long long>(r.x) + r.w > img.width || static_cast<long long>(r.y) + r.h > img.height)
        throw usage_error("region " + std::to_string(r.x) + "," + std::to_string(r.y) + "," + std::to_string(r.w) +
                          "," + std::to_string(r.h) + " lies outside '" + path + "' (" + size_text(img) + ")");
    return r;
}

/// Heat-map colour of a Delta E00 value: t = dE/scale clamped to [0, 1], piecewise linear
/// in code values from black (t = 0) to red (1/3), yellow (2/3) and white (1).
shade::srgb8 heat_colour(real delta_e, real scale) {
    const real t = std::clamp(delta_e / scale, real(0), real(1));
    const auto ramp = [](real u) { return static_cast<std::uint8_t>(std::lround(255 * std::clamp(u, 0.0, 1.0))); };
    return {ramp(3 * t), ramp(3 * t - 1), ramp(3 * t - 2)};
}

void print_lab(const char* label, const shade::lab<real>& c) {
    std::printf("%-26s L* %9.4f  a* %9.4f  b* %9.4f\n", label, c.L, c.a, c.b);
}

int run(const options& o) {
    // The heat map's path is checked (and its temporary file created) before any work, so
    // a bad path fails before results are printed; the file appears only when complete.
    std::optional<ex::output_file> heatmap_file;
    if (o.heatmap) heatmap_file.emplace(*o.heatmap);
    const auto white = o.white == "d50" ? shade::white_point<real>::d50() : shade::white_point<real>::d65();
    const shade::srgb_lab_converter<real> convert(white);

    const linear_image a = load_linear(o.images[0], o.exposure);
    std::optional<linear_image> b;
    if (!o.measured) {
        b = load_linear(o.images[1], o.exposure);
        if (a.width != b->width || a.height != b->height)
            throw usage_error("image sizes differ: '" + o.images[0] + "' is " + size_text(a) + ", '" + o.images[1] +
                              "' is " + size_text(*b));
    }
    const region r = checked_region(o.area, a, o.images[0]);

    const std::size_t count = std::size_t(r.w) * std::size_t(r.h);
    std::vector<real> delta_e;
    delta_e.reserve(count);
    shade::lab<real> sum_a{0, 0, 0}, sum_b{0, 0, 0};
    real linear_sum = 0, linear_max = 0, linear_sum2 = 0; // |a - b| over the channels (two images only)
    for (int y = r.y; y < r.y + r.h; ++y)
        for (int x = r.x; x < r.x + r.w; ++x) {
            const shade::lab<real> lab_a = convert.to_lab(a.at(x, y));
            const shade::lab<real> lab_b = b ? convert.to_lab(b->at(x, y)) : *o.measured;
            delta_e.push_back(shade::delta_e_2000(lab_a, lab_b));
            if (b) {
                const shade::rgb<real> d = glm::abs(a.at(x, y) - b->at(x, y));
                linear_sum += d.x + d.y + d.z;
                linear_sum2 += d.x * d.x + d.y * d.y + d.z * d.z;
                linear_max = std::max({linear_max, d.x, d.y, d.z});
            }
            sum_a = {sum_a.L + lab_a.L, sum_a.a + lab_a.a, sum_a.b + lab_a.b};
            sum_b = {sum_b.L + lab_b.L, sum_b.a + lab_b.a, sum_b.b + lab_b.b};
        }

    const real n = real(count);
    real total = 0;
    for (const real d : delta_e) total += d;
    const real mean = total / n;
    std::vector<real> sorted = delta_e;
    std::sort(sorted.begin(), sorted.end());
    // Nearest-rank percentile: the smallest value with at least 95% of values <= it.
    const std::size_t rank = std::size_t(std::ceil(0.95 * n));
    const real p95 = sorted[std::max<std::size_t>(rank, 1) - 1];
    const real max = sorted.back();

    std::printf("region: %d,%d,%d,%d (%zu pixels), L*a*b* white %s, exposure %.6g\n", r.x, r.y, r.w, r.h, count,
                o.white == "d50" ? "D50" : "D65", o.exposure);
    print_lab(("mean L*a*b* " + o.images[0] + ":").c_str(), {sum_a.L / n, sum_a.a / n, sum_a.b / n});
    if (b)
        print_lab(("mean L*a*b* " + o.images[1] + ":").c_str(), {sum_b.L / n, sum_b.a / n, sum_b.b / n});
    else
        print_lab("measured L*a*b*:", *o.measured);
    std::printf("Delta E00 mean: %.4f\n", mean);
    std::printf("Delta E00 p95:  %.4f\n", p95);
    std::printf("Delta E00 max:  %.4f\n", max);
    if (b) {
        std::printf("linear RGB |a - b| mean: %.6g\n", linear_sum / (3 * n));
        std::printf("linear RGB |a - b| max:  %.6g\n", linear_max);
        std::printf("linear RGB RMSE:         %.6g\n", std::sqrt(linear_sum2 / (3 * n)));
    }

    if (o.heatmap) {
        auto heat = ex::image::filled(r.w, r.h);
        for (int y = 0; y < r.h; ++y)
            for (int x = 0; x < r.w; ++x)
                heat.set(x, y, heat_colour(delta_e[std::size_t(y) * std::size_t(r.w) + std::size_t(x)], o.scale));
        ex::save_png(heatmap_file->temporary(), heat);
        heatmap_file->commit();
        std::printf("heat map: %s (white = Delta E00 %.4g)\n", o.heatmap->c_str(), o.scale);
    }

    if (o.fail_above) {
        const threshold& t = *o.fail_above;
        const real value = t.stat == statistic::mean ? mean : (t.stat == statistic::p95 ? p95 : max);
        if (value > t.limit) {
            std::printf("FAIL: Delta E00 %s %.4f exceeds %.4g\n", t.name.c_str(), value, t.limit);
            return exit_threshold_exceeded;
        }
        std::printf("PASS: Delta E00 %s %.4f <= %.4g\n", t.name.c_str(), value, t.limit);
    }
    return exit_ok;
}

} // namespace

int main(int argc, char** argv) {
    // Input errors are usage errors (status 2, "(try --help)"); any other failure, such as
    // a heat map that cannot be written, is status 2 as well, so that status 1 means only
    // "--fail-above exceeded".
    return ex::run_cli(
        "compare",
        [&] {
            bool help = false;
            const options o = parse(argc, argv, help);
            if (help) {
                std::fputs(usage_text, stdout);
                return exit_ok;
            }
            return run(o);
        },
        exit_error);
}
