// lobes: polar plots of shade's reflection models in the plane of incidence, in the manner
// of the polar plot of Disney's BRDF Explorer (Burley 2012).
//
//   lobes --out DIR
//
// For each model and each incident angle theta_l in {0, 30, 60, 75} degrees the plot
// shows, for view directions v in the plane of incidence (theta_v from -90 to 90 degrees,
// the light arriving from the left, the mirror direction on the right), the radius
//
//     rho(v) = Y(f(l, v)) cos(theta_l)      (1/sr)
//
// i.e. the BRDF value times the cosine of the INCIDENT angle: the radiance reflected
// toward v per unit of light arriving from l, which is what shade::lit computes (up to
// the light's colour and pi). Y is the Rec. 709 luminance of the RGB value (the parameters
// below are grey, so Y is the value of every channel). Each plot's radius is normalised to
// the largest rho over all its curves (both planes for an anisotropic model); that maximum
// is printed in the panel's title. cos(theta_v) is not applied: a Lambertian surface draws
// semicircles.
//
// Anisotropic models (Ashikhmin-Shirley with p_u != p_v) get two panels: the plane
// spanned by n and the tangent t, and the plane spanned by n and the bitangent b.
//
// Writes DIR/lobes_<model>.png for every model and DIR/lobes_all.png with every panel.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <stdexcept>
#include <system_error>
#include <utility>
#include <vector>

#include <shade/brdf/ashikhmin_shirley.hpp>
#include <shade/brdf/blinn_phong.hpp>
#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/brdf/oren_nayar.hpp>
#include <shade/brdf/phong.hpp>

#include "support/canvas.hpp"
#include "support/cli.hpp"
#include "support/image.hpp"

namespace {

using real = double;
using rgb = shade::rgb<real>;
using vec3 = shade::vec3<real>;
using colour = shade::rgb<float>;

constexpr real pi = shade::pi<real>;

constexpr std::string_view usage = R"(usage: lobes [options]

Polar plots of shade's BRDF lobes in the plane of incidence: for incident angles
theta_l = 0, 30, 60 and 75 degrees, the radius is f(l, v) cos(theta_l) (luminance, 1/sr)
for view directions v in the plane of incidence, normalised to each plot's maximum.
Anisotropic models show the plane along the tangent t and the plane along the bitangent b.

Writes DIR/lobes_<model>.png for each model and DIR/lobes_all.png with all of them.

options:
  --out DIR   output directory, created if missing (default out/); each PNG is written
              to a temporary file there and renamed when complete
  --help      this text
)";

/// A BRDF as a function of (l, v) in the local frame n = +z, t = +x, b = +y.
using brdf_function = std::function<rgb(const vec3&, const vec3&)>;

/// Wraps a shade BRDF evaluated at a surface point whose shading frame is the identity
/// (surface_point's default frame: t = x, b = y, n = z).
template <class B>
brdf_function wrap(B b) {
    return [b](const vec3& l, const vec3& v) { return b.f(l, v, shade::surface_point<real>{}); };
}

/// One model to plot.
struct model {
    std::string file;       ///< DIR/lobes_<file>.png
    std::string title;      ///< panel title
    std::string parameters; ///< parameter line under the title
    brdf_function f;
    bool anisotropic = false; ///< two panels: the n-t and the n-b plane
};

std::vector<model> models() {
    using namespace shade;
    const rgb kd(0.2);
    const rgb ks(0.6);
    return {
        {"lambert", "Lambert", "k_d = 0.8", wrap(lambert<real>(rgb(0.8))), false},
        {"phong_classic", "classic Phong (divides by n.l)", "k_d = 0.2, k_s = 0.6, n = 20",
         wrap(classic_phong<real>(kd, ks, 20)), false},
        {"phong_normalized", "normalized Phong", "k_d = 0.2, k_s = 0.6, n = 20",
         wrap(normalized_phong<real>(kd, ks, 20)), false},
        {"blinn_phong", "Blinn-Phong (normalized)", "k_d = 0.2, k_s = 0.6, n = 80",
         wrap(blinn_phong<real>(kd, ks, 80)), false},
        {"cook_torrance_beckmann", "Cook-Torrance, Beckmann", "m = 0.3, Schlick F0 = 0.9 (a metal), V-groove G, no diffuse",
         wrap(cook_torrance<beckmann<real>, schlick<real>, v_groove<real>>(beckmann<real>(0.3), schlick<real>(rgb(0.9)))),
         false},
        {"cook_torrance_ggx", "Cook-Torrance, GGX", "alpha = 0.3, Schlick F0 = 0.9 (a metal), Smith G, no diffuse",
         wrap(cook_torrance<ggx<real>, schlick<real>, smith_ggx<real>>(ggx<real>(0.3), schlick<real>(rgb(0.9)))),
         false},
        {"oren_nayar", "Oren-Nayar", "rho = 0.8, sigma = 0.5 rad", wrap(oren_nayar<real>(rgb(0.8), 0.5)), false},
        {"ashikhmin_shirley", "Ashikhmin-Shirley", "R_d = 0.2, R_s = 0.3, p_u = 10, p_v = 400",
         wrap(ashikhmin_shirley<real>(rgb(0.2), rgb(0.3), 10, 400)), true},
    };
}

/// The incident angles (degrees) and their curve colours (linear RGB).
struct incidence {
    real degrees;
    colour c;
};
const incidence incidences[] = {
    {0, {0.02f, 0.12f, 0.75f}},
    {30, {0.02f, 0.42f, 0.08f}},
    {60, {0.85f, 0.33f, 0.01f}},
    {75, {0.75f, 0.02f, 0.05f}},
};

/// Rec. 709 luminance (the Y row of the linear sRGB -> XYZ matrix, IEC 61966-2-1).
real luminance(const rgb& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

/// Samples of theta_v over the open interval (-90, 90) degrees (f is 0 at the horizon).
constexpr int samples = 1441;

real theta_v_of(int k) { return (-90 + 180 * (real(k) + 0.5) / real(samples)) * pi / 180; }

/// A direction at polar angle theta (signed: negative toward -axis) in the plane spanned by
/// n = z and the unit tangent-plane axis `axis`.
vec3 in_plane(real theta, const vec3& axis) { return std::sin(theta) * axis + std::cos(theta) * vec3(0, 0, 1); }

/// rho(theta_v) = Y(f(l, v)) cos(theta_l) for every sample, l at -theta_l (from the left).
std::vector<real> curve(const model& m, real theta_l_degrees, const vec3& axis) {
    const real theta_l = theta_l_degrees * pi / 180;
    const vec3 l = in_plane(-theta_l, axis);
    std::vector<real> rho(samples);
    for (int k = 0; k < samples; ++k) {
        const vec3 v = in_plane(theta_v_of(k), axis);
        rho[std::size_t(k)] = luminance(m.f(l, v)) * std::cos(theta_l);
        if (!std::isfinite(rho[std::size_t(k)]) || rho[std::size_t(k)] < 0)
            throw std::runtime_error(m.title + ": f is not finite and >= 0 at theta_v = " +
                                     std::to_string(theta_v_of(k) * 180 / pi) + " deg");
    }
    return rho;
}

/// One panel: a model in one plane.
struct panel {
    const model* m;
    vec3 axis;              ///< t = (1, 0, 0) or b = (0, 1, 0)
    std::string plane_name; ///< for the title
};

constexpr int panel_width = 640;
constexpr int panel_height = 420;
constexpr int legend_height = 64;

const colour ink{0.02f, 0.02f, 0.02f};
const colour grid{0.55f, 0.55f, 0.55f};
const colour faint{0.8f, 0.8f, 0.8f};
const colour paper{0.96f, 0.96f, 0.96f};

void draw_panel(shade::examples::canvas& c, float x0, float y0, const panel& p, real rho_max) {
    char max_text[64];
    std::snprintf(max_text, sizeof max_text, "max = %.4g /sr", rho_max);
    c.text(x0 + 14, y0 + 10, p.m->title + p.plane_name, ink, 2.2f);
    c.text(x0 + 14, y0 + 36, p.m->parameters, ink, 1.5f);
    c.text(x0 + 14, y0 + 54, std::string("f cos(theta_l), radius / max, ") + max_text, ink, 1.5f);
    // The peak of each curve in its colour, so that curves drawn small can still be read.
    float x = x0 + 14;
    c.text(x, y0 + 72, "peaks:", ink, 1.5f);
    x += 66;
    for (const auto& inc : incidences) {
        real peak = 0;
        for (const real r : curve(*p.m, inc.degrees, p.axis)) peak = std::max(peak, r);
        char peak_text[32];
        std::snprintf(peak_text, sizeof peak_text, "%.3g", peak);
        c.text(x, y0 + 72, peak_text, inc.c, 1.5f);
        x += 90;
    }

    const float ox = x0 + float(panel_width) / 2;
    const float oy = y0 + float(panel_height) - 34;
    const float radius = 265;
    const auto at = [&](real theta, real r) {
        return shade::vec2<float>(ox + float(r * std::sin(theta)) * radius, oy - float(r * std::cos(theta)) * radius);
    };
    // Grid: circles at 1/4 .. 1 of the maximum, rays every 30 degrees, the surface line.
    for (int ring = 1; ring <= 4; ++ring) {
        std::vector<shade::vec2<float>> arc;
        for (int k = 0; k <= 180; ++k) arc.push_back(at((real(k) - 90) * pi / 180, real(ring) / 4));
        c.polyline(arc, ring == 4 ? grid : faint, 1.0f);
    }
    for (int deg = -90; deg <= 90; deg += 30) {
        const auto end = at(deg * pi / 180, 1.0);
        c.line(ox, oy, end.x, end.y, faint, 1.0f);
        const auto label = at(deg * pi / 180, 1.07);
        const std::string text = std::to_string(deg);
        c.text(label.x - 4.5f * float(text.size()), label.y - 6, text, grid, 1.5f);
    }
    c.line(ox - radius * 1.08f, oy, ox + radius * 1.08f, oy, grid, 1.5f);
    // Incident directions (thin) and lobes (thick), one colour per theta_l.
    for (const auto& inc : incidences) {
        const real theta_l = inc.degrees * pi / 180;
        const auto tip = at(-theta_l, 1.0);
        c.line(ox, oy, tip.x, tip.y, inc.c, 1.0f);
        const std::vector<real> rho = curve(*p.m, inc.degrees, p.axis);
        std::vector<shade::vec2<float>> points;
        points.reserve(rho.size());
        for (int k = 0; k < samples; ++k) points.push_back(at(theta_v_of(k), rho[std::size_t(k)] / rho_max));
        c.polyline(points, inc.c, 2.2f);
    }
}

void draw_legend(shade::examples::canvas& c, float y0) {
    float x = 14;
    for (const auto& inc : incidences) {
        c.fill_rect(x, y0 + 10, x + 26, y0 + 16, inc.c);
        c.text(x + 34, y0 + 6, "theta_l = " + std::to_string(int(inc.degrees)), ink, 1.5f);
        x += 150;
    }
    c.text(14, y0 + 26, "light from the left (thin lines: l), v in the plane of incidence;", ink, 1.5f);
    c.text(14, y0 + 42, "radius: f(l,v) cos(theta_l) / max, angles theta_v in degrees", ink, 1.5f);
}

/// The largest rho over every curve of the panels (the normalisation of one model).
real max_over(const std::vector<panel>& panels) {
    real m = 0;
    for (const auto& p : panels)
        for (const auto& inc : incidences)
            for (const real r : curve(*p.m, inc.degrees, p.axis)) m = std::max(m, r);
    if (!(m > 0)) throw std::runtime_error(panels.front().m->title + ": the lobe is zero everywhere");
    return m;
}

std::vector<panel> panels_of(const model& m) {
    if (!m.anisotropic) return {{&m, vec3(1, 0, 0), ""}};
    return {{&m, vec3(1, 0, 0), ", plane n-t"}, {&m, vec3(0, 1, 0), ", plane n-b"}};
}

} // namespace

int main(int argc, char** argv) {
    namespace ex = shade::examples;
    return ex::run_cli("lobes", [&] {
        std::filesystem::path out = "out";
        ex::command_line args(argc, argv);
        while (args.next()) {
            if (args.flag("--help") || args.flag("-h")) {
                std::fputs(usage.data(), stdout);
                return 0;
            }
            if (args.option("--out")) out = args.path();
            else args.unknown();
        }
        // Fail before drawing, not after, if the directory cannot be made or written to:
        // the overview's temporary file is created now.
        std::error_code ec;
        std::filesystem::create_directories(out, ec);
        if (ec) throw ex::usage_error("cannot create output directory '" + out.string() + "': " + ec.message());
        if (!std::filesystem::is_directory(out, ec))
            throw ex::usage_error("output path '" + out.string() + "' is not a directory");
        ex::output_file overview(out / "lobes_all.png");

        const std::vector<model> all = models();
        // The overview: three panels per row.
        std::vector<std::pair<panel, real>> every;
        for (const auto& m : all) {
            const auto panels = panels_of(m);
            const real rho_max = max_over(panels);
            ex::canvas c(panel_width * int(panels.size()), panel_height + legend_height, paper);
            for (std::size_t k = 0; k < panels.size(); ++k) {
                draw_panel(c, float(k) * panel_width, 0, panels[k], rho_max);
                every.emplace_back(panels[k], rho_max);
            }
            draw_legend(c, panel_height);
            ex::output_file file(out / ("lobes_" + m.file + ".png"));
            ex::save_png(file.temporary(), c.to_image());
            file.commit();
            std::printf("wrote %s\n", file.target().string().c_str());
        }
        constexpr int columns = 3;
        const int rows = (int(every.size()) + columns - 1) / columns;
        ex::canvas c(panel_width * columns, panel_height * rows + legend_height, paper);
        for (std::size_t k = 0; k < every.size(); ++k)
            draw_panel(c, float(int(k) % columns * panel_width), float(int(k) / columns * panel_height),
                       every[k].first, every[k].second);
        draw_legend(c, float(panel_height * rows));
        ex::save_png(overview.temporary(), c.to_image());
        overview.commit();
        std::printf("wrote %s\n", overview.target().string().c_str());
        return 0;
    });
}
