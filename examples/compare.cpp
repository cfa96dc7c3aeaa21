// compare: colour differences (CIEDE2000) between two images, or between a region of an
// image and a measured CIE L*a*b* value. Prints mean, 95th percentile and maximum Delta E00
// and the mean L*a*b* of each side; optionally writes a Delta E00 heat map.
//
// Pixels are 8-bit sRGB (IEC 61966-2-1), decoded to linear sRGB, converted to XYZ and to
// L*a*b* relative to D65 (default) or D50 (Bradford-adapted, for measurements reported
// against the ICC D50 white). Run with --help for usage.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <shade/color/convert.hpp>
#include <shade/color/delta_e.hpp>

#include "support/cli.hpp"
#include "support/image.hpp"

namespace {

using real = double;

constexpr int exit_ok = 0;
constexpr int exit_threshold_exceeded = 1;
constexpr int exit_error = 2;

constexpr const char* usage_text = R"(Usage:
  compare IMAGE_A IMAGE_B [options]
      Delta E00 per pixel between two images of the same size.
  compare IMAGE --lab L,a,b [options]
      Delta E00 per pixel between IMAGE and one measured CIE L*a*b* colour.

Images are read as 8-bit sRGB (PNG, or JPEG/BMP/TGA via stb_image; alpha is ignored).

Options:
  --region X,Y,W,H     compare only the W x H pixels whose top-left corner is column X,
                       row Y (in both images); default: the whole image
  --lab L,a,b          the measured L*a*b* colour to compare against
  --white d65|d50      white point of L*a*b* (default d65, the white of sRGB; use d50 for
                       values measured against the ICC D50 white)
  --heatmap OUT.png    write a W x H PNG of the per-pixel Delta E00: black at 0, through
                       red and yellow, to white at --scale and above; its path is
                       checked before any work, and the file appears only when complete
  --scale S            Delta E00 shown as white in the heat map, in (0, 1e6]
                       (default 10)
  --fail-above STAT=T  exit with status 1 if STAT (mean, p95 or max) of Delta E00 > T
  --help               show this help

Output: the mean L*a*b* of each side (the arithmetic mean of the per-pixel L*a*b*), and
the mean, 95th percentile (nearest rank) and maximum of the per-pixel Delta E00
(CIEDE2000, Sharma, Wu & Dalal 2005).

Exit status: 0 on success, 1 if --fail-above is exceeded, 2 on a usage error or an
unreadable, mismatched or invalid input (with a message on stderr).
)";

namespace ex = shade::examples;

/// A usage or input error: printed as "compare: error: <message>", exit status 2.
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
    std::optional<threshold> fail_above;
};

real parse_real(std::string_view text, std::string_view what) {
    real value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
        throw usage_error(std::string(what) + ": '" + std::string(text) + "' is not a finite number");
    return value;
}

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

options parse(int argc, char** argv, bool& help) {
    options o;
    help = false;
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        auto value = [&](std::string_view name) -> std::string_view {
            if (i + 1 >= argc) throw usage_error(std::string(name) + " needs a value");
            return argv[++i];
        };
        if (arg == "--help" || arg == "-h") {
            help = true;
            return o;
        } else if (arg == "--region") {
            const std::string_view v = value(arg);
            const auto parts = split(v, ',');
            if (parts.size() != 4)
                throw usage_error("--region expects X,Y,W,H (four integers), got '" + std::string(v) + "'");
            constexpr int max = std::numeric_limits<int>::max();
            o.area = region{ex::parse_integer(std::string(arg) + " X", parts[0], 0, max),
                            ex::parse_integer(std::string(arg) + " Y", parts[1], 0, max),
                            ex::parse_integer(std::string(arg) + " W", parts[2], 1, max),
                            ex::parse_integer(std::string(arg) + " H", parts[3], 1, max)};
        } else if (arg == "--lab") {
            const std::string_view v = value(arg);
            const auto parts = split(v, ',');
            if (parts.size() != 3)
                throw usage_error("--lab expects L,a,b (three numbers), got '" + std::string(v) + "'");
            o.measured = shade::lab<real>{parse_real(parts[0], "--lab L"), parse_real(parts[1], "--lab a"),
                                          parse_real(parts[2], "--lab b")};
        } else if (arg == "--white") {
            const std::string_view v = value(arg);
            if (v != "d65" && v != "d50")
                throw usage_error("--white must be d65 or d50, got '" + std::string(v) + "'");
            o.white = std::string(v);
        } else if (arg == "--heatmap") {
            o.heatmap = std::string(value(arg));
            if (o.heatmap->empty()) throw usage_error("--heatmap needs a non-empty file name");
        } else if (arg == "--scale") {
            o.scale = ex::parse_real(arg, value(arg), 0, 1e6, ex::lower_limit::exclusive);
        } else if (arg == "--fail-above") {
            const std::string_view v = value(arg);
            const auto parts = split(v, '=');
            if (parts.size() != 2)
                throw usage_error("--fail-above expects STAT=T with STAT mean, p95 or max, got '" +
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
                throw usage_error("--fail-above: unknown statistic '" + t.name + "' (use mean, p95 or max)");
            t.limit = parse_real(parts[1], "--fail-above threshold");
            o.fail_above = t;
        } else if (arg.size() > 1 && arg[0] == '-') {
            throw usage_error("unknown option '" + std::string(arg) + "' (see --help)");
        } else {
            o.images.emplace_back(arg);
        }
    }
    if (o.measured) {
        if (o.images.size() != 1)
            throw usage_error("--lab compares one image with a measured colour: give exactly one image (got " +
                              std::to_string(o.images.size()) + ")");
    } else if (o.images.size() != 2) {
        throw usage_error("give two images, or one image and --lab L,a,b (got " + std::to_string(o.images.size()) +
                          " image arguments; see --help)");
    }
    return o;
}

std::string size_text(const shade::examples::image& img) {
    return std::to_string(img.width) + "x" + std::to_string(img.height);
}

region checked_region(const std::optional<region>& requested, const shade::examples::image& img,
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

    const ex::image a = ex::load_image(o.images[0]);
    std::optional<ex::image> b;
    if (!o.measured) {
        b = ex::load_image(o.images[1]);
        if (a.width != b->width || a.height != b->height)
            throw usage_error("image sizes differ: '" + o.images[0] + "' is " + size_text(a) + ", '" + o.images[1] +
                              "' is " + size_text(*b));
    }
    const region r = checked_region(o.area, a, o.images[0]);

    const std::size_t count = std::size_t(r.w) * std::size_t(r.h);
    std::vector<real> delta_e;
    delta_e.reserve(count);
    shade::lab<real> sum_a{0, 0, 0}, sum_b{0, 0, 0};
    for (int y = r.y; y < r.y + r.h; ++y)
        for (int x = r.x; x < r.x + r.w; ++x) {
            const shade::lab<real> lab_a = convert.to_lab(a.at(x, y));
            const shade::lab<real> lab_b = b ? convert.to_lab(b->at(x, y)) : *o.measured;
            delta_e.push_back(shade::delta_e_2000(lab_a, lab_b));
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

    std::printf("region: %d,%d,%d,%d (%zu pixels), L*a*b* white %s\n", r.x, r.y, r.w, r.h, count,
                o.white == "d50" ? "D50" : "D65");
    print_lab(("mean L*a*b* " + o.images[0] + ":").c_str(), {sum_a.L / n, sum_a.a / n, sum_a.b / n});
    if (b)
        print_lab(("mean L*a*b* " + o.images[1] + ":").c_str(), {sum_b.L / n, sum_b.a / n, sum_b.b / n});
    else
        print_lab("measured L*a*b*:", *o.measured);
    std::printf("Delta E00 mean: %.4f\n", mean);
    std::printf("Delta E00 p95:  %.4f\n", p95);
    std::printf("Delta E00 max:  %.4f\n", max);

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
    try {
        bool help = false;
        const options o = parse(argc, argv, help);
        if (help) {
            std::fputs(usage_text, stdout);
            return exit_ok;
        }
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "compare: error: %s\n", e.what());
        return exit_error;
    }
}
