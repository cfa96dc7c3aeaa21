#pragma once
// What the BRDF fuzz targets share: decoding a shading situation (normal, tangent, l, v)
// from the input, and the checks every BRDF must pass on it.
//
// Situation layout (after the target's own parameters; input.hpp decodes the scalars):
//   normal n and tangent t (vectors; n normalised with require_direction, a zero or
//   non-finite n makes the input uninteresting and it is skipped; a tangent parallel to n
//   falls back to frame::from_normal), then a byte choosing how l and v are made:
//     0  both decoded and normalised          4  l = n, v decoded
//     1  v = l                                5  v = n, l decoded
//     2  v = -l (h undefined)                 6  l grazing: decoded, made orthogonal to n
//     3  v = the mirror of l about n (h = n)  7  raw: l and v as decoded, not normalised,
//                                                possibly non-finite
// then the random numbers of sample(): uc and u = (u_x, u_y), three scalars each mapped into
// [0, 1) (to_unit_interval).
// Checks, for a BRDF built by its validating constructor (parameters it rejects must throw
// exactly shade::invalid_parameter, caught by the target):
//   * situations 0-6 (unit l, v, n): f, and f_diffuse and f_specular for a split BRDF,
//     are finite and >= 0 in every channel, and f is exactly 0 when n·l <= 0 or n·v <= 0;
//   * for a BRDF that samples (shade::sampled_brdf), in situations 0-6: pdf(l, v, at) is
//     finite and >= 0, sample(v, uc, u, at) returns nothing for v not above the surface,
//     and a sample that is returned has a finite unit l
//     above the surface (n·l > 0), a finite pdf > 0, f and weight finite and >= 0, and
//     weight = f |n·l| / pdf (relative 1e-4 per channel, brdf.hpp's contract, plus f / pdf
//     times 32 epsilon for the rounding of a grazing n·l taken in world space; +inf allowed
//     where that exact value exceeds the largest T, from valid parameters near it);
//   * situation 7: f (and pdf and sample) are evaluated (ASan/UBSan watch them); nothing is
//     promised for them.

#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>

#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/core/error.hpp>
#include <shade/core/frame.hpp>
#include <shade/core/math.hpp>
#include <shade/core/surface_point.hpp>

#include "expect.hpp"
#include "input.hpp"

namespace shade::fuzz {

/// One shading situation: the point with its frame, l and v, and whether l and v are unit
/// vectors (situations 0-6) so that the BRDF's contract applies.
template <std::floating_point T>
struct brdf_situation {
    surface_point<T> at;
    vec3<T> l;
    vec3<T> v;
    bool unit = true;
    T uc = T(0);    ///< sample()'s lobe-selection number, in [0, 1)
    vec2<T> u{0, 0}; ///< sample()'s direction numbers, in [0, 1)^2
};

/// x mapped into [0, 1): its fractional part x - floor(x) (so -0.25 -> 0.75), 0 for a
/// non-finite x, and the largest number below 1 where that part rounds to 1 (x = -1e-30).
template <std::floating_point T>
[[nodiscard]] T to_unit_interval(T x) noexcept {
    if (!std::isfinite(x)) return T(0);
    const T y = x - std::floor(x);
    return y < T(1) ? y : T(1) - std::numeric_limits<T>::epsilon() / 2;
}

/// Normalises w, or returns nothing when w is zero or not finite.
template <std::floating_point T>
[[nodiscard]] std::optional<vec3<T>> unit_or_nothing(const vec3<T>& w) {
    try {
        return require_direction("w", w);
    } catch (const invalid_parameter&) {
        return std::nullopt;
    }
}

/// Decodes a situation (see the top of this file), or nothing for an unusable normal or
/// direction.
template <std::floating_point T>
[[nodiscard]] std::optional<brdf_situation<T>> decode_situation(input& in) {
    const auto n = unit_or_nothing(in.vector<T>());
    const vec3<T> tangent = in.vector<T>();
    if (!n) return std::nullopt;
    brdf_situation<T> s;
    try {
        s.at.shading = frame<T>::from_normal_tangent(*n, tangent);
    } catch (const invalid_parameter&) {
        s.at.shading = frame<T>::from_normal(*n);
    }
    const unsigned how = in.choice(8);
    const vec3<T> a = in.vector<T>();
    const vec3<T> b = in.vector<T>();
    s.uc = to_unit_interval(in.scalar<T>());
    s.u.x = to_unit_interval(in.scalar<T>());
    s.u.y = to_unit_interval(in.scalar<T>());
    if (how == 7) {
        s.l = a;
        s.v = b;
        s.unit = false;
        return s;
    }
    const auto l = unit_or_nothing(a);
    const auto v = unit_or_nothing(b);
    switch (how) {
    case 0:
        if (!l || !v) return std::nullopt;
        s.l = *l;
        s.v = *v;
        break;
    case 1:
    case 2:
        if (!l) return std::nullopt;
        s.l = *l;
        s.v = how == 1 ? *l : -*l;
        break;
    case 3: {
        if (!l) return std::nullopt;
        s.l = *l;
        const auto mirror = unit_or_nothing(T(2) * glm::dot(*n, *l) * *n - *l);
        if (!mirror) return std::nullopt;
        s.v = *mirror;
        break;
    }
    case 4:
    case 5:
        if (!v) return std::nullopt;
        s.l = how == 4 ? *n : *v;
        s.v = how == 4 ? *v : *n;
        break;
    default: {
        if (!l || !v) return std::nullopt;
        const auto grazing = unit_or_nothing(*l - *n * glm::dot(*n, *l));
        if (!grazing) return std::nullopt;
        s.l = *grazing;
        s.v = *v;
        break;
    }
    }
    return s;
}

/// Prints a situation (context for a failing expect).
template <std::floating_point T>
void show(const brdf_situation<T>& s) {
    show("n", s.at.n());
    show("t", s.at.shading.t);
    show("l", s.l);
    show("v", s.v);
}

/// True when a sample's weight (one channel) is f |n.l| / pdf, the sampling contract of
/// brdf.hpp and bsdf.hpp: within 1e-4 relative, plus f / pdf times 32 epsilon (the model
/// takes n.l in its local frame; the one here in world space differs by a few ulps of 1,
/// which matters for a grazing l), or, where that exact value exceeds the largest T (valid
/// parameters near it), any weight >= 0 (+inf; not NaN), setting overflows.
template <std::floating_point T>
[[nodiscard]] bool weight_agrees(T f, T pdf, T abs_n_dot_l, T weight, bool& overflows) noexcept {
    const long double exact = static_cast<long double>(f) * abs_n_dot_l / pdf;
    if (exact > static_cast<long double>(std::numeric_limits<T>::max())) {
        overflows = true;
        return weight >= T(0);
    }
    return std::isfinite(weight) &&
           std::abs(static_cast<long double>(weight) - exact) <=
               1e-4L * exact + static_cast<long double>(f) / pdf * 32 * static_cast<long double>(std::numeric_limits<T>::epsilon()) +
                   static_cast<long double>(std::numeric_limits<T>::min());
}

/// Samples b in situation s and checks the sampling contract (see the top of this file).
template <sampled_brdf B>
void check_sampling(const B& b, const brdf_situation<scalar_of<B>>& s) {
    using T = scalar_of<B>;
    const T pdf = b.pdf(s.l, s.v, s.at);
    const std::optional<brdf_sample<T>> x = b.sample(s.v, s.uc, s.u, s.at);
    if (!s.unit) return;
    if (!(std::isfinite(pdf) && pdf >= T(0))) {
        show(s);
        show("pdf", pdf);
    }
    expect(std::isfinite(pdf) && pdf >= T(0), "BRDF pdf is NaN, infinite or negative for unit directions");
    if (!x) return;
    if (!(glm::dot(s.at.n(), s.v) > T(0))) show(s);
    expect(glm::dot(s.at.n(), s.v) > T(0), "sample returned a direction for v not above the surface");
    const T n_dot_l = glm::dot(s.at.n(), x->l);
    const bool l_ok = is_finite(x->l) && is_unit_length(x->l) && n_dot_l > T(0);
    const bool pdf_ok = std::isfinite(x->pdf) && x->pdf > T(0);
    // f and weight finite and >= 0, except that a weight whose exact value f |n.l| / pdf
    // exceeds the largest T (valid parameters near it, e.g. k_s = FLT_MAX: the overflow the
    // guarantees do not cover) may be +inf.
    const bool f_ok = finite_non_negative(x->f);
    bool weight_ok = f_ok && pdf_ok;
    bool weight_overflows = false;
    if (weight_ok) {
        for (int i = 0; i < 3; ++i)
            weight_ok = weight_ok && weight_agrees(x->f[i], x->pdf, std::abs(n_dot_l), x->weight[i], weight_overflows);
    }
    const bool values_ok = f_ok && (weight_overflows || finite_non_negative(x->weight));
    if (!l_ok || !pdf_ok || !values_ok || !weight_ok) {
        show(s);
        show("uc", s.uc);
        show("u.x", s.u.x);
        show("u.y", s.u.y);
        show("sampled l", x->l);
        show("sampled f", x->f);
        show("sampled pdf", x->pdf);
        show("sampled weight", x->weight);
    }
    expect(l_ok, "sampled l is not a finite unit vector above the surface");
    expect(pdf_ok, "sampled pdf is not finite and > 0");
    expect(values_ok, "sampled f or weight is NaN, infinite or negative");
    expect(weight_ok, "sampled weight is not f |n.l| / pdf");
}

/// Evaluates b in situation s and checks the BRDF contract (see the top of this file).
template <brdf B>
void check_brdf(const B& b, const brdf_situation<scalar_of<B>>& s) {
    using T = scalar_of<B>;
    if constexpr (sampled_brdf<B>) check_sampling(b, s);
    const rgb<T> f = b.f(s.l, s.v, s.at);
    if (!s.unit) return;
    const bool below = !(glm::dot(s.at.n(), s.l) > T(0)) || !(glm::dot(s.at.n(), s.v) > T(0));
    const bool f_ok = finite_non_negative(f);
    const bool zero_ok = !below || f == rgb<T>(0);
    if (!f_ok || !zero_ok) {
        show(s);
        show("f", f);
    }
    expect(f_ok, "BRDF value is NaN, infinite or negative for valid parameters");
    expect(zero_ok, "BRDF value is not 0 with l or v below the horizon");
    if constexpr (split_brdf<B>) {
        const rgb<T> f_d = b.f_diffuse(s.l, s.v, s.at);
        const rgb<T> f_s = b.f_specular(s.l, s.v, s.at);
        if (!finite_non_negative(f_d) || !finite_non_negative(f_s)) {
            show(s);
            show("f_diffuse", f_d);
            show("f_specular", f_s);
        }
        expect(finite_non_negative(f_d), "BRDF diffuse part is NaN, infinite or negative");
        expect(finite_non_negative(f_s), "BRDF specular part is NaN, infinite or negative");
    }
}

/// B built by its validating constructor from args, or nothing when that throws
/// shade::invalid_parameter (the only exception it may throw; any other escapes and
/// libFuzzer reports it).
template <class B, class... Args>
[[nodiscard]] std::optional<B> build(Args&&... args) {
    try {
        return B(std::forward<Args>(args)...);
    } catch (const invalid_parameter&) {
        return std::nullopt;
    }
}

/// Decodes three scalars as a colour (any values; validating constructors judge them).
template <std::floating_point T>
[[nodiscard]] rgb<T> decode_rgb(input& in) noexcept {
    return in.vector<T>();
}

/// The body of the targets of models with forms (Phong, Blinn-Phong): a form byte picks
/// one of Models (the same model in each of its forms), then k_d, k_s, shininess and a
/// situation are decoded, and the model built from them, if valid, is checked.
template <std::floating_point T, class... Models>
void run_forms(input& in) {
    const unsigned form = in.choice(static_cast<unsigned>(sizeof...(Models)));
    const rgb<T> k_d = decode_rgb<T>(in);
    const rgb<T> k_s = decode_rgb<T>(in);
    const T shininess = in.scalar<T>();
    const auto s = decode_situation<T>(in);
    unsigned index = 0;
    const auto check_if_chosen = [&]<class B>() {
        if (form != index++) return;
        const auto b = build<B>(k_d, k_s, shininess);
        if (b && s) check_brdf(*b, *s);
    };
    (check_if_chosen.template operator()<Models>(), ...);
}

/// The common entry of the BRDF targets: byte 0 picks double (bit 0 set) or float and the
/// rest of the input goes to run_float or run_double. Returns 0.
inline int dispatch(const std::uint8_t* data, std::size_t size, void (*run_float)(input&),
                    void (*run_double)(input&)) {
    input in(data, size);
    if ((in.byte() & 1u) != 0)
        run_double(in);
    else
        run_float(in);
    return 0;
}

} // namespace shade::fuzz
