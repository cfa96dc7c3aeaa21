// trace: shade's reference ray tracer. Renders one of the built-in scenes to a PNG, or to
// a PFM or an OpenEXR file (linear radiance, no tone map): the output name's extension
// chooses, and any other extension is refused before rendering.
//
//   trace --scene gallery --width 640 --height 360 --spp 4 --out gallery.png
//   trace --scene furnace --integrator path --out out/furnace.pfm
//   trace --scene cornell --integrator path --out out/cornell.exr
//   trace --scene openpbr --integrator path --spp 256 --out docs/openpbr.png
//
// Direct lighting in the classic mode (area lights sampled n x n), or path tracing in
// physical units (next-event estimation and BRDF sampling combined by MIS, Russian
// roulette); several jittered samples per pixel; for PNG, exposure + Reinhard tone map +
// sRGB encoding. The same arguments give the same bytes whatever --threads is.

#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "support/cli.hpp"
#include "support/image.hpp"
#include "tracer/exr.hpp"
#include "tracer/pfm.hpp"
#include "tracer/render.hpp"
#include "tracer/scenes.hpp"

namespace {

constexpr std::string_view usage = R"(usage: trace [options]

Renders one of shade's reference scenes to a PNG image, or to linear radiance (PFM, EXR).

options:
  --scene NAME     gallery (default): one sphere per shading model on a checker plane;
                   mesh: a tessellated torus with flat, Gouraud and Phong shading;
                   lights: hard shadows from point/directional lights, soft from an area light;
                   furnace: a white Lambert sphere in a white environment (path: all 1);
                   furnace-conductor: the same with a rough conductor of F = 1;
                   glass-furnace: a smooth glass sphere behind a thin pane and a
                   compensated rough glass sphere in it, invisible (path: all 1);
                   energy: rough gold spheres in a white environment, single
                   scattering (top) and compensated for multiple scattering (bottom);
                   enclosure: inside a glowing sphere of albedo 0.8 (path: all 5);
                   veach: glossy plates and four sphere lights (compare --strategy);
                   cornell: a red/green room with an OBJ pyramid and a sphere light (path);
                   glass: that room with a rough glass pyramid, a glass sphere and a thin
                   glass pane (path)
                   openpbr: twelve OpenPBR Surface presets (metals, coated, fuzz, glass,
                   thin film, subsurface) in a studio: gradient sky and a key light (path);
                   openpbr-furnace: their white versions in a white environment (path:
                   1 wherever a material conserves energy)
  --integrator M   direct (default): classic direct lighting; path: path tracing in
                   physical units with next-event estimation, MIS and Russian roulette
  --strategy S     path integrator only: mis (default), light or brdf sampling alone
  --sampler S      path integrator: independent (default) uniform numbers, or sobol:
                   Owen-scrambled Sobol points, less noise at the same spp (use powers
                   of two)
  --lights S       path integrator: which light next-event estimation samples: bvh
                   (default; the light BVH, by power, distance and orientation), power
                   (by emitted power) or uniform
  --envmap FILE    path integrator only: light the scene with a latitude-longitude
                   environment map, linear radiance from a PFM or OpenEXR file (row 0
                   at the zenith, +y up, the image's centre toward -z), importance-sampled
                   by luminance; it adds to the scene's own lights
  --envmap-scale X multiplier of the map's values, in [0, 1e6] (default 1)
  --bounces N      path integrator only: scattering events at most, 1 to 100000
                   (default 1024; 1 is direct lighting)
  --width N        image width in pixels, 1 to 16384 (default 640)
  --height N       image height in pixels, 1 to 16384 (default 360)
  --spp N          samples per pixel, 1 to 65536 (default 4)
  --threads N      worker threads, 1 to 1024 (default: all cores; the image does not
                   depend on it)
  --area-samples N area lights are sampled N x N times per hit, 1 to 256 (default 4)
  --exposure X     exposure multiplier before tone mapping, in (0, 1e6] (default 1)
  --seed N         seed of the per-pixel random numbers (default 1)
  --out FILE       output image (default <scene>.png); its extension sets the format:
                   .png (exposure, tone map, 8-bit sRGB), .pfm or .exr (linear
                   radiance, 32-bit float RGB); any other is refused before rendering.
                   Written to a temporary file next to it and renamed when complete,
                   so a failed or interrupted run never leaves a partial FILE
  --quiet          no progress bar (it is drawn only when stderr is a terminal and
                   the render takes more than a second)
  --help           this text

limits: at most 2^26 pixels (width x height) and 2^32 samples (pixels x spp).
)";

// Limits checked before anything is allocated or rendered: an image side of at most
// 16384 pixels, at most 2^26 pixels (the radiance buffer then stays under 1 GiB in double,
// 3 x 8 bytes a pixel, and the 8-bit image under 200 MiB) and at most 2^32 samples in all
// (pixels x spp, hours of rendering on a desktop CPU).
constexpr int max_side = 16384;
constexpr std::uint64_t max_pixels = std::uint64_t(1) << 26;
constexpr int max_spp = 1 << 16;
constexpr std::uint64_t max_samples = std::uint64_t(1) << 32;
constexpr int max_threads = 1024;
constexpr int max_area_samples = 256;

struct arguments {
    std::string scene = "gallery";
    tracer::render_options render;
    double exposure = 1;
    std::filesystem::path out;
    std::string format; ///< ".png", ".pfm" or ".exr", from out's extension
    std::filesystem::path envmap;  ///< empty: none
    double envmap_scale = 1;
    bool quiet = false;
    bool help = false;
};

arguments parse(int argc, char** argv) {
    namespace ex = shade::examples;
    arguments a;
    a.render.width = 640;
    a.render.height = 360;
    bool out_given = false;
    ex::command_line args(argc, argv);
    while (args.next()) {
        if (args.flag("--help") || args.flag("-h")) {
            a.help = true;
            return a;
        }
        if (args.flag("--quiet")) a.quiet = true;
        else if (args.option("--scene")) a.scene = args.text();
        else if (args.option("--width")) a.render.width = args.integer(1, max_side);
        else if (args.option("--height")) a.render.height = args.integer(1, max_side);
        else if (args.option("--spp")) a.render.spp = args.integer(1, max_spp);
        else if (args.option("--threads")) a.render.threads = args.integer(1, max_threads);
        else if (args.option("--integrator")) {
            const std::string m(args.text());
            if (m == "direct") a.render.method = tracer::integrator::direct;
            else if (m == "path") a.render.method = tracer::integrator::path;
            else throw ex::usage_error("option --integrator must be direct or path, got '" + m + "'");
        } else if (args.option("--strategy")) {
            const std::string m(args.text());
            if (m == "mis") a.render.path.sampling = tracer::strategy::mis;
            else if (m == "light") a.render.path.sampling = tracer::strategy::light;
            else if (m == "brdf") a.render.path.sampling = tracer::strategy::brdf;
            else throw ex::usage_error("option --strategy must be mis, light or brdf, got '" + m + "'");
        } else if (args.option("--sampler")) {
            const std::string m(args.text());
            if (m == "independent") a.render.sampler = tracer::sampler_kind::independent;
            else if (m == "sobol") a.render.sampler = tracer::sampler_kind::sobol;
            else throw ex::usage_error("option --sampler must be independent or sobol, got '" + m + "'");
        } else if (args.option("--lights")) {
            const std::string m(args.text());
            if (m == "bvh") a.render.path.lights = tracer::light_selection::bvh;
            else if (m == "power") a.render.path.lights = tracer::light_selection::power;
            else if (m == "uniform") a.render.path.lights = tracer::light_selection::uniform;
            else throw ex::usage_error("option --lights must be bvh, power or uniform, got '" + m + "'");
        } else if (args.option("--envmap")) {
            a.envmap = args.path();
        } else if (args.option("--envmap-scale")) {
            a.envmap_scale = args.real(0, 1e6);
        } else if (args.option("--bounces")) a.render.path.max_bounces = args.integer(1, 100000);
        else if (args.option("--area-samples")) a.render.lighting.area_samples_per_side = args.integer(1, max_area_samples);
        else if (args.option("--seed")) a.render.seed = args.integer<std::uint64_t>(0, UINT64_MAX);
        else if (args.option("--exposure")) a.exposure = args.real(0, 1e6, ex::lower_limit::exclusive);
        else if (args.option("--out")) {
            a.out = args.path();
            out_given = true;
        } else args.unknown();
    }
    if (!tracer::is_scene_name(a.scene))
        throw ex::usage_error("unknown scene '" + a.scene + "' (known: " + tracer::scene_names() + ")");
    const std::uint64_t pixels = std::uint64_t(a.render.width) * std::uint64_t(a.render.height);
    ex::check_limit("the image size (--width x --height) in pixels", pixels, max_pixels);
    ex::check_limit("the number of samples (--width x --height x --spp)", pixels * std::uint64_t(a.render.spp),
                    max_samples);
    if (!out_given) a.out = a.scene + ".png";
    a.format = ex::output_format("--out", a.out, {".png", ".pfm", ".exr"});
    if (!a.envmap.empty() && a.render.method != tracer::integrator::path)
        throw ex::usage_error("option --envmap needs --integrator path");
    return a;
}

// The environment map of --envmap: a PFM or EXR file (told apart by the extension; any
// other is refused) as an environment_map_light, +y up and the image's centre toward -z
// (the scenes' cameras look along -z). A file that cannot be read or used is a usage error.
std::shared_ptr<const shade::environment_map_light<tracer::real>> load_environment(const std::filesystem::path& path,
                                                                                 double scale) {
    namespace ex = shade::examples;
    std::string format = path.extension().string();
    for (char& c : format) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (format != ".pfm" && format != ".exr")
        throw ex::usage_error("option --envmap: cannot read '" + path.string() + "': unsupported format '" + format +
                              "' (supported: .pfm, .exr)");
    try {
        const tracer::radiance_image image = format == ".pfm" ? tracer::load_pfm(path) : tracer::load_exr(path);
        const auto orientation = shade::frame<tracer::real>::from_normal_tangent({0, 1, 0}, {0, 0, -1});
        return std::make_shared<const shade::environment_map_light<tracer::real>>(
            image.width, image.height, std::span<const tracer::rgb>(image.pixels), scale, orientation);
    } catch (const std::exception& e) {
        throw ex::usage_error(std::string("option --envmap: ") + e.what());
    }
}

} // namespace

int main(int argc, char** argv) {
    return shade::examples::run_cli("trace", [&] {
        const arguments args = parse(argc, argv);
        if (args.help) {
            std::fputs(usage.data(), stdout);
            return 0;
        }
        // The output path is checked (and its temporary file created) before rendering.
        shade::examples::output_file out(args.out);
        const auto start = std::chrono::steady_clock::now();
        const double aspect = double(args.render.width) / double(args.render.height);
        tracer::scene scene = tracer::make_scene(args.scene, aspect);
        if (!args.envmap.empty()) scene.environment_map = load_environment(args.envmap, args.envmap_scale);
        tracer::render_options options = args.render;
        options.progress = !args.quiet;
        const auto radiance = tracer::render(scene, options);
        if (args.format == ".pfm")
            tracer::save_pfm(out.temporary(), radiance);
        else if (args.format == ".exr")
            tracer::save_exr(out.temporary(), radiance);
        else
            shade::examples::save_png(out.temporary(), tracer::to_srgb8(radiance, args.exposure));
        out.commit();
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("%s: %dx%d, %d spp -> %s (%.2f s)\n", args.scene.c_str(), args.render.width,
                    args.render.height, args.render.spp, args.out.c_str(), seconds);
        return 0;
    });
}
