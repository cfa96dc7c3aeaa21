// trace: shade's reference ray tracer. Renders one of the built-in scenes to a PNG.
//
//   trace --scene gallery --width 640 --height 360 --spp 4 --out gallery.png
//
// Direct lighting from every light with shadow rays (area lights sampled n x n), several
// jittered samples per pixel, exposure + Reinhard tone map + sRGB encoding. The same
// arguments give the same bytes whatever --threads is.

#include <charconv>
#include <chrono>
#include <cstdio>
#include <exception>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#endif

#include "support/image.hpp"
#include "tracer/render.hpp"
#include "tracer/scenes.hpp"

namespace {

constexpr std::string_view usage = R"(usage: trace [options]

Renders one of shade's reference scenes to a PNG image.

options:
  --scene NAME     gallery (default): one sphere per shading model on a checker plane;
                   mesh: a tessellated torus with flat, Gouraud and Phong shading;
                   lights: hard shadows from point/directional lights, soft from an area light
  --width N        image width in pixels (default 640)
  --height N       image height in pixels (default 360)
  --spp N          samples per pixel (default 4)
  --threads N      worker threads (default: all cores; the image does not depend on it)
  --area-samples N area lights are sampled N x N times per hit (default 4)
  --exposure X     exposure multiplier before tone mapping (default 1)
  --seed N         seed of the per-pixel random numbers (default 1)
  --out FILE       output PNG (default <scene>.png)
  --quiet          no progress bar (it is drawn only when stderr is a terminal)
  --help           this text
)";

// True when stderr is a terminal, where a redrawn progress bar belongs (in a log file or a
// pipe it would only add lines of carriage returns).
bool stderr_is_terminal() {
#if defined(__unix__) || defined(__APPLE__)
    return isatty(STDERR_FILENO) == 1;
#else
    return false;
#endif
}

struct arguments {
    std::string scene = "gallery";
    tracer::render_options render;
    double exposure = 1;
    std::string out;
    bool quiet = false;
};

[[noreturn]] void fail(const std::string& message) {
    std::fprintf(stderr, "trace: %s\n(try --help)\n", message.c_str());
    std::exit(2);
}

template <class N>
N parse_number(std::string_view option, std::string_view text) {
    N value{};
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size())
        fail("option " + std::string(option) + " needs a number, got '" + std::string(text) + "'");
    return value;
}

int parse_positive(std::string_view option, std::string_view text) {
    const int value = parse_number<int>(option, text);
    if (value <= 0) fail("option " + std::string(option) + " must be positive, got " + std::string(text));
    return value;
}

arguments parse(int argc, char** argv) {
    arguments a;
    a.render.width = 640;
    a.render.height = 360;
    for (int i = 1; i < argc; ++i) {
        const std::string_view opt = argv[i];
        if (opt == "--help" || opt == "-h") {
            std::fputs(usage.data(), stdout);
            std::exit(0);
        }
        if (opt == "--quiet") {
            a.quiet = true;
            continue;
        }
        if (i + 1 >= argc) fail("option " + std::string(opt) + " needs a value");
        const std::string_view value = argv[++i];
        if (opt == "--scene") a.scene = value;
        else if (opt == "--width") a.render.width = parse_positive(opt, value);
        else if (opt == "--height") a.render.height = parse_positive(opt, value);
        else if (opt == "--spp") a.render.spp = parse_positive(opt, value);
        else if (opt == "--threads") a.render.threads = parse_positive(opt, value);
        else if (opt == "--area-samples") a.render.lighting.area_samples_per_side = parse_positive(opt, value);
        else if (opt == "--seed") a.render.seed = parse_number<std::uint64_t>(opt, value);
        else if (opt == "--exposure") {
            a.exposure = parse_number<double>(opt, value);
            if (!(a.exposure > 0) || !std::isfinite(a.exposure)) fail("option --exposure must be a positive number");
        } else if (opt == "--out") a.out = value;
        else fail("unknown option '" + std::string(opt) + "'");
    }
    if (!tracer::is_scene_name(a.scene))
        fail("unknown scene '" + a.scene + "' (known: " + tracer::scene_names() + ")");
    if (a.out.empty()) a.out = a.scene + ".png";
    return a;
}

} // namespace

int main(int argc, char** argv) {
    const arguments args = parse(argc, argv);
    // Fail before rendering, not after, if the output cannot be written.
    {
        std::ofstream probe(args.out, std::ios::binary | std::ios::app);
        if (!probe) fail("cannot write output file '" + args.out + "'");
    }
    try {
        const auto start = std::chrono::steady_clock::now();
        const double aspect = double(args.render.width) / double(args.render.height);
        const tracer::scene scene = tracer::make_scene(args.scene, aspect);
        tracer::render_options options = args.render;
        options.progress = !args.quiet && stderr_is_terminal();
        const auto radiance = tracer::render(scene, options);
        shade::examples::save_png(args.out, tracer::to_srgb8(radiance, args.exposure));
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("%s: %dx%d, %d spp -> %s (%.2f s)\n", args.scene.c_str(), args.render.width,
                    args.render.height, args.render.spp, args.out.c_str(), seconds);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "trace: %s\n", e.what());
        return 1;
    }
    return 0;
}
