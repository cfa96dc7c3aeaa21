// libFuzzer target: shade::sum_over_lights over a list of any_light (directional, point,
// spot, area) with one of the shaders: lit Lambert, lit Blinn-Phong with ambient, toon,
// Gooch, a checker of Lambert and toon, a gradient of Gooch and Blinn-Phong.
//
// Input: byte 0 bit 0 double/float; a shader byte and its parameters; a light count
// (1..3) and per light a kind byte and its parameters (emission: intensity, ambient,
// diffuse, specular; then position, axis and angles, corner and edges as the kind needs);
// the shaded point p, its normal n and the view direction v; a visibility byte (always,
// a bool, a scalar or an rgb transmittance, decoded and clamped to [0, 1]); a
// samples_per_side byte (signed: values < 1 must throw).
//
// Checked, with every shader and light built by its validating constructor (a rejected
// parameter must throw exactly shade::invalid_parameter), n and v unit and p finite:
//   * always: no crash, no sanitizer report, no exception but invalid_parameter;
//   * when the scene is bounded (every decoded number within 1e6 in magnitude): the sum
//     is never NaN and never negative in any channel. Beyond that, parameters near the
//     largest finite value make products of two valid values overflow (e.g. lit Lambert
//     with k_d = FLT_MAX: pi (n.l) k_d/pi rounds to inf, times a light channel of 0 is
//     NaN); docs/robustness.md states this limit;
//   * the sum is finite when the scene is moderate: every decoded number within 1e3 in
//     magnitude, shininess <= 1e3, and p at least 1e-2 away from every point and spot
//     light and from the plane of every area light (otherwise a legitimately huge
//     1/r^2 times a large BRDF may overflow to +inf, which is still not NaN).

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <vector>

#include <glm/geometric.hpp>

#include <shade/brdf/blinn_phong.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/light/any_light.hpp>
#include <shade/shading/checker.hpp>
#include <shade/shading/gooch.hpp>
#include <shade/shading/gradient.hpp>
#include <shade/shading/shader.hpp>
#include <shade/shading/sum_over_lights.hpp>
#include <shade/shading/toon.hpp>

#include "brdf_target.hpp"
#include "expect.hpp"
#include "input.hpp"
#include "light_target.hpp"

namespace {

using namespace shade;
using fuzz::build;
using fuzz::expect;

/// The reader of this target: moderate within 1e3, bounded within 1e6 (see above).
template <std::floating_point T>
using reader = fuzz::tracking_reader<T>;

/// Decodes one light, or nothing if its constructor rejects the parameters. Tracks, in
/// near, whether p (known only later) must be checked against a position or a plane:
/// the light's position (point, spot) or corner and normal (area) are recorded.
template <std::floating_point T>
struct decoded_light {
    std::optional<any_light<T>> light;
    vec3<T> anchor{0, 0, 0};
    std::optional<vec3<T>> plane_normal; // set for area lights
};

template <std::floating_point T>
[[nodiscard]] decoded_light<T> decode_light(reader<T>& r) {
    decoded_light<T> out;
    const unsigned kind = r.in.choice(4);
    const emission<T> e = fuzz::decode_emission(r);
    const auto law = static_cast<falloff>(r.in.choice(4)); // 3 is invalid on purpose
    if (kind == 0) {
        if (auto l = build<directional_light<T>>(r.vector(), e)) out.light.emplace(*l);
    } else if (kind == 1) {
        out.anchor = r.vector();
        if (auto l = build<point_light<T>>(out.anchor, e, law)) out.light.emplace(*l);
    } else if (kind == 2) {
        out.anchor = r.vector();
        const vec3<T> axis = r.vector();
        const T inner = r.scalar();
        const T outer = r.scalar();
        if (auto l = build<spot_light<T>>(out.anchor, axis, inner, outer, e, law))
            out.light.emplace(*l);
    } else {
        out.anchor = r.vector();
        const vec3<T> edge_u = r.vector();
        const vec3<T> edge_v = r.vector();
        const auto sides = static_cast<sidedness>(r.in.choice(3)); // 2 is invalid
        if (auto l = build<area_light<T>>(out.anchor, edge_u, edge_v, e, sides)) {
            out.plane_normal = l->normal();
            out.light.emplace(*l);
        }
    }
    return out;
}

/// Runs the sum with shader s and checks it.
template <class S, std::floating_point T>
void check_sum(const char* name, const S& s, const surface_point<T>& at, const vec3<T>& v,
               const std::vector<any_light<T>>& lights, fuzz::input& in, bool bounded,
               bool moderate) {
    const unsigned visibility = in.choice(4);
    const T tau_scalar = std::clamp(in.scalar<T>(), T(0), T(1)); // NaN stays NaN: skipped
    const bool tau_bool = in.flag();
    const int samples_per_side = static_cast<std::int8_t>(in.byte()) % 4;
    if (std::isnan(tau_scalar)) return;
    std::optional<rgb<T>> sum;
    try {
        switch (visibility) {
        case 0:
            sum = sum_over_lights(s, at, v, lights, always_visible{}, samples_per_side);
            break;
        case 1:
            sum = sum_over_lights(s, at, v, lights, [&](const light_sample<T>&) { return tau_bool; },
                                  samples_per_side);
            break;
        case 2:
            sum = sum_over_lights(s, at, v, lights, [&](const light_sample<T>&) { return tau_scalar; },
                                  samples_per_side);
            break;
        default:
            sum = sum_over_lights(
                s, at, v, lights,
                [&](const light_sample<T>&) { return rgb<T>(tau_scalar, T(1) - tau_scalar, T(1)); },
                samples_per_side);
            break;
        }
    } catch (const invalid_parameter&) {
        expect(samples_per_side < 1, "sum_over_lights threw for a valid samples_per_side");
        return;
    }
    expect(samples_per_side >= 1, "sum_over_lights accepted samples_per_side < 1");
    const rgb<T>& c = *sum;
    const bool no_nan = !std::isnan(c.x) && !std::isnan(c.y) && !std::isnan(c.z);
    const bool non_negative = c.x >= T(0) && c.y >= T(0) && c.z >= T(0);
    if (!bounded) return;
    if (!no_nan || !non_negative || (moderate && !fuzz::finite_non_negative(c))) {
        fuzz::show("p", at.p);
        fuzz::show("n", at.n());
        fuzz::show("v", v);
        fuzz::show("sum", c);
        std::fprintf(stderr, "  shader = %s, visibility = %u, samples_per_side = %d, lights:",
                     name, visibility, samples_per_side);
        for (const auto& l : lights) std::fprintf(stderr, " %zu", l.get().index());
        std::fprintf(stderr, " (0 directional, 1 point, 2 spot, 3 area)\n");
    }
    expect(no_nan, "sum_over_lights returned NaN");
    expect(non_negative, "sum_over_lights returned a negative channel");
    if (moderate) expect(fuzz::finite_non_negative(c), "sum_over_lights overflowed in a moderate scene");
}

template <std::floating_point T>
void run(fuzz::input& in) {
    reader<T> r{in, T(1e3), T(1e6)};
    const unsigned which = in.choice(6);
    const rgb<T> colour_a = r.vector();
    const rgb<T> colour_b = r.vector();
    const rgb<T> colour_c = r.vector();
    const T shininess = r.scalar();
    const T size_or_period = r.scalar();
    const vec3<T> direction = r.vector();
    const int levels = 1 + static_cast<int>(in.choice(5)); // 1 is invalid on purpose

    std::vector<any_light<T>> lights;
    std::vector<decoded_light<T>> decoded;
    const unsigned count = 1 + in.choice(3);
    for (unsigned i = 0; i < count; ++i) {
        decoded.push_back(decode_light(r));
        if (decoded.back().light) lights.push_back(*decoded.back().light);
    }
    surface_point<T> at;
    at.p = r.vector();
    const auto n = fuzz::unit_or_nothing(in.vector<T>());
    const auto v = fuzz::unit_or_nothing(in.vector<T>());
    if (!n || !v || !is_finite(at.p)) return;
    at.shading = frame<T>::from_normal(*n);

    const bool bounded = r.bounded;
    bool moderate = r.moderate && shininess <= T(1e3);
    for (const auto& d : decoded) {
        if (!d.light) continue;
        const vec3<T> offset = at.p - d.anchor;
        if (d.plane_normal)
            moderate = moderate && std::abs(glm::dot(offset, *d.plane_normal)) >= T(1e-2);
        else if (!std::holds_alternative<directional_light<T>>(d.light->get()))
            moderate = moderate && glm::length(offset) >= T(1e-2);
    }

    toon_params<T> tp;
    tp.diffuse = colour_a;
    tp.specular = colour_b;
    tp.ambient = colour_c;
    tp.shininess = shininess;
    tp.diffuse_levels = levels;
    tp.specular_levels = levels + 1;
    gooch_params<T> gp;
    gp.diffuse = colour_a;
    gp.highlight = colour_b;
    gp.blue = colour_c;
    gp.shininess = shininess;

    switch (which) {
    case 0:
        if (const auto b = build<lambert<T>>(colour_a)) check_sum("lit lambert", *b, at, *v, lights, in, bounded, moderate);
        break;
    case 1:
        if (const auto b = build<blinn_phong<T>>(colour_a, colour_b, shininess)) {
            if (!is_finite(colour_c) || colour_c.x < T(0) || colour_c.y < T(0) || colour_c.z < T(0))
                break; // lit's ambient reflectance must be >= 0 (documented precondition)
            check_sum("lit blinn_phong", lit<blinn_phong<T>>{*b, colour_c}, at, *v, lights, in, bounded, moderate);
        }
        break;
    case 2:
        if (const auto t = build<toon<T>>(tp)) check_sum("toon", *t, at, *v, lights, in, bounded, moderate);
        break;
    case 3:
        if (const auto g = build<gooch<T>>(gp)) check_sum("gooch", *g, at, *v, lights, in, bounded, moderate);
        break;
    case 4: {
        const auto b = build<lambert<T>>(colour_a);
        const auto t = build<toon<T>>(tp);
        if (!b || !t) break;
        if (const auto c = build<checker<lambert<T>, toon<T>>>(*b, *t, size_or_period, T(0.5)))
            check_sum("checker(lambert, toon)", *c, at, *v, lights, in, bounded, moderate);
        break;
    }
    default: {
        const auto g = build<gooch<T>>(gp);
        const auto b = build<blinn_phong<T>>(colour_a, colour_b, shininess);
        if (!g || !b) break;
        if (const auto c = build<gradient<gooch<T>, blinn_phong<T>>>(*g, *b, direction,
                                                                     size_or_period))
            check_sum("gradient(gooch, blinn_phong)", *c, at, *v, lights, in, bounded, moderate);
        break;
    }
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return shade::fuzz::dispatch(data, size, &run<float>, &run<double>);
}
