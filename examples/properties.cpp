// properties: runs every shade reflection model through the property checks of
// shade/check and reports the outcome as a Markdown table (stdout), plus a white-furnace
// plot (directional albedo against viewing angle) as a PNG.
//
//   properties [--out white_furnace.png] [--strata N]
//
// The table in docs/properties.md is this program's output.

#include <charconv>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <shade/shade.hpp>

#include "support/canvas.hpp"

namespace {

using T = double;
using shade::rgb;
using shade::vec3;

struct row {
    std::string name;
    bool positive = false;
    bool reciprocal = false;
    double max_albedo = 0;
    bool conserving = false;
    std::vector<double> curve; // albedo (max channel) against theta_v, azimuth 0
    rgb<float> colour;
};

struct settings {
    std::string out = "white_furnace.png";
    std::size_t strata = 128;
};

constexpr std::size_t curve_points = 30;

template <class B>
row evaluate(const std::string& name, const B& model, const settings& s, rgb<float> colour) {
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    shade::check::pair_options pairs{.pairs = 20000};
    pairs.model = name;
    shade::check::albedo_options albedo{.strata = s.strata, .view_angles = 16, .azimuths = 4};
    albedo.model = name;
    row r;
    r.name = name;
    r.colour = colour;
    r.positive = shade::check::positivity(model, at, pairs).passed;
    r.reciprocal = shade::check::reciprocity(model, at, pairs).passed;
    const auto energy = shade::check::energy_conservation(model, at, albedo);
    r.conserving = energy.passed;
    r.max_albedo = energy.worst;
    auto curve_options = albedo;
    curve_options.view_angles = curve_points;
    curve_options.azimuths = 1;
    for (const auto& p : shade::check::white_furnace(model, at, curve_options))
        r.curve.push_back(std::max({p.albedo.x, p.albedo.y, p.albedo.z}));
    return r;
}

std::vector<row> evaluate_all(const settings& s) {
    using namespace shade;
    const rgb<T> one(1), half(0.5), zero(0);
    std::vector<row> rows;
    // Colours of the plot's curves (linear RGB).
    const auto c = [](float r, float g, float b) { return rgb<float>(r, g, b); };
    rows.push_back(evaluate("Lambert (k_d = 1)", lambert<T>(one), s, c(0.1f, 0.1f, 0.1f)));
    rows.push_back(evaluate("Phong classic, / n.l (k_s = 1, n = 10)", classic_phong<T>(zero, one, 10), s, c(0.8f, 0.1f, 0.1f)));
    rows.push_back(evaluate("Phong modified, unnormalized (k_s = 1, n = 2)", modified_phong<T>(zero, one, 2), s, c(0.9f, 0.5f, 0.0f)));
    rows.push_back(evaluate("Phong normalized (k_d = k_s = 0.5, n = 20)", normalized_phong<T>(half, half, 20), s, c(0.1f, 0.5f, 0.1f)));
    rows.push_back(evaluate("Blinn-Phong classic, / n.l (k_s = 1, n = 20)",
                            blinn_phong<T, blinn_phong_form::classic>(zero, one, 20), s, c(0.6f, 0.1f, 0.6f)));
    rows.push_back(evaluate("Blinn-Phong normalized (k_d = k_s = 0.5, n = 50)", blinn_phong<T>(half, half, 50), s, c(0.1f, 0.3f, 0.8f)));
    rows.push_back(evaluate("Cook-Torrance Walter, Beckmann/Smith, m = 0.3, F = 1",
                            cook_torrance<beckmann<T>, schlick<T>, smith_beckmann<T>>(beckmann<T>(0.3), schlick<T>(one)),
                            s, c(0.0f, 0.6f, 0.6f)));
    rows.push_back(evaluate("Cook-Torrance Walter, GGX/Smith, alpha = 0.3, F = 1",
                            cook_torrance<ggx<T>, schlick<T>, smith_ggx<T>>(ggx<T>(0.3), schlick<T>(one)), s,
                            c(0.3f, 0.3f, 0.9f)));
    rows.push_back(evaluate("Cook-Torrance Walter, Beckmann/V-groove, m = 0.3, F = 1",
                            cook_torrance<beckmann<T>, schlick<T>, v_groove<T>>(beckmann<T>(0.3), schlick<T>(one)), s,
                            c(0.5f, 0.5f, 0.2f)));
    rows.push_back(evaluate("Cook-Torrance course slides (4/pi), Beckmann/V-groove, m = 0.3, F = 1",
                            cook_torrance<beckmann<T>, schlick<T>, v_groove<T>, cook_torrance_form::course>(
                                beckmann<T>(0.3), schlick<T>(one)),
                            s, c(0.9f, 0.2f, 0.5f)));
    rows.push_back(evaluate("Cook-Torrance 1982 paper (x4), Beckmann/V-groove, m = 0.3, F = 1",
                            cook_torrance<beckmann<T>, schlick<T>, v_groove<T>, cook_torrance_form::paper_1982>(
                                beckmann<T>(0.3), schlick<T>(one)),
                            s, c(0.5f, 0.2f, 0.0f)));
    rows.push_back(evaluate("Oren-Nayar (rho = 0.8, sigma = 0.3)", oren_nayar<T>(rgb<T>(0.8), 0.3), s, c(0.6f, 0.4f, 0.2f)));
    rows.push_back(evaluate("Oren-Nayar (rho = 1, sigma = 0.5)", oren_nayar<T>(one, 0.5), s, c(0.8f, 0.6f, 0.3f)));
    rows.push_back(evaluate("Ashikhmin-Shirley (R_d = 0.8, R_s = 0.2, p = 10, 200)",
                            ashikhmin_shirley<T>(rgb<T>(0.8), rgb<T>(0.2), 10, 200), s, c(0.2f, 0.7f, 0.3f)));
    return rows;
}

void print_table(const std::vector<row>& rows, const settings& s) {
    std::printf("| model | positive | reciprocal | max albedo | energy conserving |\n");
    std::printf("|---|---|---|---|---|\n");
    for (const auto& r : rows)
        std::printf("| %s | %s | %s | %.3f | %s |\n", r.name.c_str(), r.positive ? "yes" : "**no**",
                    r.reciprocal ? "yes" : "**no**", r.max_albedo, r.conserving ? "yes" : "**no**");
    std::printf("\nPositivity and reciprocity: 20000 direction pairs each (hard cases first). Max albedo: "
                "over 16 viewing angles (0 to 89 degrees) x 4 azimuths, %zu^2 stratified samples (cosine-weighted mixed with lobes around the mirror direction) "
                "samples per view; energy conserving means max albedo <= 1.01.\n",
                s.strata);
}

void plot(const std::vector<row>& rows, const std::string& path) {
    const int width = 900, height = 560;
    const float left = 70, right = 560, top = 40, bottom = 500;
    shade::examples::canvas c(width, height, rgb<float>(1));
    // Albedo axis from 0 to 2.5 (the unnormalized offenders go above 1).
    const float max_albedo = 2.5f;
    const auto x_of = [&](double theta_deg) { return left + float(theta_deg / 90.0) * (right - left); };
    const auto y_of = [&](double a) { return bottom - float(std::min(a, double(max_albedo)) / max_albedo) * (bottom - top); };
    const rgb<float> grey(0.6f);
    for (int k = 0; k <= 5; ++k) {
        const float a = 0.5f * float(k);
        c.line(left, y_of(a), right, y_of(a), rgb<float>(0.85f), 1.0f);
        char label[16];
        std::snprintf(label, sizeof label, "%.1f", double(a));
        c.text(left - 40, y_of(a) - 6, label, grey);
    }
    for (int d = 0; d <= 90; d += 15) {
        c.line(x_of(d), top, x_of(d), bottom, rgb<float>(0.9f), 1.0f);
        c.text(x_of(d) - 8, bottom + 8, std::to_string(d), grey);
    }
    c.line(left, y_of(1.0), right, y_of(1.0), rgb<float>(0.2f), 2.0f); // albedo = 1
    c.line(left, bottom, right, bottom, rgb<float>(0.2f), 1.5f);
    c.line(left, top, left, bottom, rgb<float>(0.2f), 1.5f);
    c.text(left, 12, "white furnace: directional albedo vs viewing angle (deg)", rgb<float>(0.1f));
    float legend_y = top;
    for (const auto& r : rows) {
        std::vector<shade::vec2<float>> pts;
        for (std::size_t i = 0; i < r.curve.size(); ++i)
            pts.emplace_back(x_of(89.0 * double(i) / double(r.curve.size() - 1)), y_of(r.curve[i]));
        c.polyline(pts, r.colour, 2.0f);
        c.line(right + 15, legend_y + 5, right + 35, legend_y + 5, r.colour, 3.0f);
        std::string label = r.name;
        if (label.size() > 44) label = label.substr(0, 43) + "~";
        c.text(right + 40, legend_y, label, rgb<float>(0.1f), 1.0f);
        legend_y += 16;
    }
    shade::examples::save_png(path, c.to_image());
}

[[noreturn]] void fail(const std::string& message) {
    std::fprintf(stderr, "properties: %s (try --help)\n", message.c_str());
    std::exit(2);
}

} // namespace

int main(int argc, char** argv) {
    settings s;
    for (int i = 1; i < argc; ++i) {
        const std::string_view opt = argv[i];
        if (opt == "--help" || opt == "-h") {
            std::puts("usage: properties [--out FILE.png] [--strata N]\n\n"
                      "Runs every shade model through the positivity, reciprocity and energy checks,\n"
                      "prints a Markdown table and writes the white-furnace plot (default white_furnace.png).\n"
                      "--strata N: N^2 samples per albedo estimate (default 128, at least 2).");
            return 0;
        }
        if (i + 1 >= argc) fail("option " + std::string(opt) + " needs a value");
        const std::string_view value = argv[++i];
        if (opt == "--out") {
            s.out = value;
        } else if (opt == "--strata") {
            const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), s.strata);
            if (ec != std::errc() || end != value.data() + value.size() || s.strata < 2)
                fail("--strata needs a whole number >= 2, got '" + std::string(value) + "'");
        } else {
            fail("unknown option '" + std::string(opt) + "'");
        }
    }
    if (!std::ofstream(s.out, std::ios::binary | std::ios::app)) fail("cannot write '" + s.out + "'");
    try {
        const auto rows = evaluate_all(s);
        print_table(rows, s);
        plot(rows, s.out);
        std::fprintf(stderr, "properties: wrote %s\n", s.out.c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "properties: %s\n", e.what());
        return 1;
    }
    return 0;
}
