#pragma once
// shade::checker and shade::checker_2d: a 3D or planar checkerboard of two shaders or
// BRDFs.

#include <cmath>
#include <concepts>
#include <optional>
#include <string>
#include <utility>

#include <shade/brdf/brdf.hpp>
#include <shade/core/error.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>
#include <shade/light/light_sample.hpp>
#include <shade/shading/shader.hpp>

namespace shade {

namespace detail {

/// 1 if floor(x) is odd, else 0 (also 0 for NaN). Exact for every finite x: floor(x) is an
/// integer-valued float, halving it is exact, and an odd integer halved has fraction 1/2.
/// Unlike a cast to int it handles negative x (floor, not truncation) and never
/// overflows.
template <std::floating_point T>
[[nodiscard]] inline int floor_parity(T x) noexcept {
    const T half = std::floor(x) * T(0.5);
    return (half - std::floor(half)) == T(0.5) ? 1 : 0;
}

/// The checker cell parity of coordinates c_i with cell size s and bias b:
/// (floor(c_0/s + b) + floor(c_1/s + b) + ...) mod 2, for negative coordinates too.
template <std::floating_point T, std::same_as<T>... C>
[[nodiscard]] inline int checker_parity(T size, T bias, C... c) noexcept {
    return (floor_parity(c / size + bias) + ...) & 1;
}

/// Checks a checker's cell size (> 0) and bias (in [0, 1)).
template <std::floating_point T>
void require_checker_size_bias(T size, T bias) {
    (void)require_positive("size", size);
    if (!std::isfinite(bias) || !(bias >= T(0) && bias < T(1)))
        throw invalid_parameter("bias", "must lie in [0, 1)", detail::to_text(bias));
}

/// The members shared by the checkers: given Derived::parity(at) (0 or 1), use the first
/// or the second child. If both children are BRDFs the result is a BRDF (f, and
/// f_diffuse/f_specular if both split, sample and pdf if both are sampled BRDFs: those of
/// the child selected at `at`, so the checker samples exactly what it evaluates);
/// otherwise it is a shader (a BRDF child is lifted with shade_of, i.e. lit without
/// ambient).
template <class Derived, shader_or_brdf S0, shader_or_brdf S1>
class select2 {
public:
    using scalar_type = scalar_of<S0>;
    using T = scalar_type;
    static_assert(std::same_as<scalar_of<S0>, scalar_of<S1>>,
                  "both children must have the same scalar type");

    /// The child used where parity is 0.
    [[nodiscard]] const S0& first() const noexcept { return s0_; }
    /// The child used where parity is 1.
    [[nodiscard]] const S1& second() const noexcept { return s1_; }

    /// BRDF value (1/sr, no cosine) of the child selected at `at`.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const
        requires(brdf<S0> && brdf<S1>)
    {
        return self().parity(at) == 0 ? s0_.f(l, v, at) : s1_.f(l, v, at);
    }

    /// Diffuse part of the BRDF value of the child selected at `at`.
    [[nodiscard]] rgb<T> f_diffuse(const vec3<T>& l, const vec3<T>& v,
                                   const surface_point<T>& at) const
        requires(split_brdf<S0> && split_brdf<S1>)
    {
        return self().parity(at) == 0 ? s0_.f_diffuse(l, v, at) : s1_.f_diffuse(l, v, at);
    }

    /// Specular part of the BRDF value of the child selected at `at`.
    [[nodiscard]] rgb<T> f_specular(const vec3<T>& l, const vec3<T>& v,
                                    const surface_point<T>& at) const
        requires(split_brdf<S0> && split_brdf<S1>)
    {
        return self().parity(at) == 0 ? s0_.f_specular(l, v, at) : s1_.f_specular(l, v, at);
    }

    /// The selected child's sample(v, uc, u, at) (shade::sampled_brdf).
    [[nodiscard]] std::optional<brdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                       const surface_point<T>& at) const
        requires(sampled_brdf<S0> && sampled_brdf<S1>)
    {
        return self().parity(at) == 0 ? s0_.sample(v, uc, u, at) : s1_.sample(v, uc, u, at);
    }

    /// The selected child's pdf(l, v, at): the density (1/sr) sample() draws l with.
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const
        requires(sampled_brdf<S0> && sampled_brdf<S1>)
    {
        return self().parity(at) == 0 ? s0_.pdf(l, v, at) : s1_.pdf(l, v, at);
    }

    /// Radiance (light_sample units) reflected toward v by the child selected at `at`.
    [[nodiscard]] rgb<T> shade(const surface_point<T>& at, const vec3<T>& v,
                               const light_sample<T>& s) const
        requires(!(brdf<S0> && brdf<S1>))
    {
        return self().parity(at) == 0 ? shade_of(s0_, at, v, s) : shade_of(s1_, at, v, s);
    }

protected:
    select2(S0 s0, S1 s1) : s0_(std::move(s0)), s1_(std::move(s1)) {}

private:
    [[nodiscard]] const Derived& self() const noexcept { return static_cast<const Derived&>(*this); }

    S0 s0_;
    S1 s1_;
};

} // namespace detail

/// A 3D checkerboard (solid texture) of cubes of side `size`: the first child where
///   parity(p) = (floor(p.x/s + b) + floor(p.y/s + b) + floor(p.z/s + b)) mod 2
/// is 0, the second where it is 1 (floor and a mod that are correct for negative
/// coordinates).
///
/// Bias b (default 1/2): with b = 0 the cell boundaries lie on the planes p_i = k s, which
/// is exactly where scenes put floors and walls (y = 0); a ray hit on such a plane has
/// y = +-(rounding error), and floor(y/s) flips between -1 and 0 from pixel to pixel
/// (noise). With b = 1/2 the cells are centred on the lattice points k s, so those planes
/// lie mid-cell, half a cell away from any boundary; boundaries move to (k + 1/2) s, and
/// a surface there would flicker instead (pass another bias if your scene has one).
///
/// Both children BRDFs: a BRDF. Otherwise: a shader. See detail::select2.
template <shader_or_brdf S0, shader_or_brdf S1>
class checker : public detail::select2<checker<S0, S1>, S0, S1> {
    using base = detail::select2<checker<S0, S1>, S0, S1>;

public:
    using typename base::scalar_type;
    using T = scalar_type;

    /// A checker of s0 and s1 with cell size `size` (> 0) and bias in [0, 1). Throws
    /// shade::invalid_parameter naming "size" or "bias".
    checker(S0 s0, S1 s1, T size, T bias = T(0.5))
        : base(std::move(s0), std::move(s1)), size_(size), bias_(bias) {
        detail::require_checker_size_bias(size, bias);
    }

    /// The cube side.
    [[nodiscard]] T size() const noexcept { return size_; }
    /// The bias added to p_i / size before flooring.
    [[nodiscard]] T bias() const noexcept { return bias_; }

    /// 0 where the first child is used, 1 where the second is (see the class comment).
    [[nodiscard]] int parity(const vec3<T>& p) const noexcept {
        return detail::checker_parity(size_, bias_, p.x, p.y, p.z);
    }
    /// parity(at.p).
    [[nodiscard]] int parity(const surface_point<T>& at) const noexcept { return parity(at.p); }

private:
    T size_;
    T bias_;
};

template <shader_or_brdf S0, shader_or_brdf S1>
checker(S0, S1, scalar_of<S0>) -> checker<S0, S1>;
template <shader_or_brdf S0, shader_or_brdf S1>
checker(S0, S1, scalar_of<S0>, scalar_of<S0>) -> checker<S0, S1>;

/// The two coordinates a planar checker uses: the surface parameters at.uv, or two
/// world-space axes of at.p.
enum class checker_plane { uv, xy, xz, yz };

/// A 2D checkerboard of squares of side `size` in the coordinates (a, b) chosen by `plane`
/// (at.uv, or two components of at.p): the first child where
///   (floor(a/s + bias) + floor(b/s + bias)) mod 2
/// is 0, the second where it is 1. The same bias rule as shade::checker (default 1/2, cells
/// centred on the lattice); for uv patterns that should start at a cell corner at uv = 0,
/// pass bias 0. Both children BRDFs: a BRDF. Otherwise: a shader.
template <shader_or_brdf S0, shader_or_brdf S1>
class checker_2d : public detail::select2<checker_2d<S0, S1>, S0, S1> {
    using base = detail::select2<checker_2d<S0, S1>, S0, S1>;

public:
    using typename base::scalar_type;
    using T = scalar_type;

    /// A planar checker of s0 and s1 with square side `size` (> 0) on `plane`, bias in
    /// [0, 1). Throws shade::invalid_parameter naming "size", "bias" or "plane".
    checker_2d(S0 s0, S1 s1, T size, checker_plane plane = checker_plane::uv, T bias = T(0.5))
        : base(std::move(s0), std::move(s1)), size_(size), bias_(bias), plane_(plane) {
        detail::require_checker_size_bias(size, bias);
        if (plane != checker_plane::uv && plane != checker_plane::xy &&
            plane != checker_plane::xz && plane != checker_plane::yz)
            throw invalid_parameter("plane", "must be uv, xy, xz or yz",
                                    std::to_string(static_cast<int>(plane)));
    }

    /// The square side.
    [[nodiscard]] T size() const noexcept { return size_; }
    /// The bias added to each coordinate / size before flooring.
    [[nodiscard]] T bias() const noexcept { return bias_; }
    /// Which coordinates are used.
    [[nodiscard]] checker_plane plane() const noexcept { return plane_; }

    /// The 2D coordinates of `at` on the chosen plane.
    [[nodiscard]] vec2<T> coordinates(const surface_point<T>& at) const noexcept {
        switch (plane_) {
        case checker_plane::uv: return at.uv;
        case checker_plane::xy: return vec2<T>(at.p.x, at.p.y);
        case checker_plane::xz: return vec2<T>(at.p.x, at.p.z);
        case checker_plane::yz: return vec2<T>(at.p.y, at.p.z);
        }
        return at.uv;
    }

    /// 0 where the first child is used at the 2D coordinates c, 1 where the second is.
    [[nodiscard]] int parity(const vec2<T>& c) const noexcept {
        return detail::checker_parity(size_, bias_, c.x, c.y);
    }
    /// parity(coordinates(at)).
    [[nodiscard]] int parity(const surface_point<T>& at) const noexcept {
        return parity(coordinates(at));
    }

private:
    T size_;
    T bias_;
    checker_plane plane_;
};

template <shader_or_brdf S0, shader_or_brdf S1>
checker_2d(S0, S1, scalar_of<S0>) -> checker_2d<S0, S1>;
template <shader_or_brdf S0, shader_or_brdf S1>
checker_2d(S0, S1, scalar_of<S0>, checker_plane) -> checker_2d<S0, S1>;
template <shader_or_brdf S0, shader_or_brdf S1>
checker_2d(S0, S1, scalar_of<S0>, checker_plane, scalar_of<S0>) -> checker_2d<S0, S1>;

} // namespace shade
