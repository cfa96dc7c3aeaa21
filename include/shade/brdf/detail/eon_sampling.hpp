#pragma once
// The importance sampler of shade::eon and shade::fujii_oren_nayar: a mixture of a clipped
// linearly transformed cosine (CLTC) lobe and the uniform hemisphere, after
//
//   Portsmouth, Kutz, Hill 2025, "EON: A Practical Energy-Preserving Rough Diffuse BRDF",
//   JCGT 14(1), sec. "Importance sampling" and its GLSL listing (ltc_coeffs, cltc_sample,
//   cltc_pdf, sample_EON, pdf_EON).
//
// Everything here works in the "lobe frame" of a view: the shading frame turned about n so
// that v lies in the half-plane x >= 0, y = 0 (detail::view_azimuth).

#include <cmath>
#include <concepts>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/core/math.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/types.hpp>

namespace shade::detail {

/// The turn about n that brings the local view direction into the half-plane x >= 0, y = 0:
/// (cos, sin) of its azimuth, and (1, 0) when v lies on n (its azimuth is undefined there;
/// the lobe then has an arbitrary but fixed orientation, the same in sample() and pdf()).
template <std::floating_point T>
struct view_azimuth {
    T cos_phi = T(1);
    T sin_phi = T(0);

    /// From the view direction in the shading frame (n = +z).
    [[nodiscard]] static view_azimuth of(const vec3<T>& v_local) noexcept {
        const T len2 = v_local.x * v_local.x + v_local.y * v_local.y;
        if (len2 >= std::numeric_limits<T>::min()) {
            const T inv = T(1) / std::sqrt(len2);
            return {v_local.x * inv, v_local.y * inv};
        }
        // A tangent part so small that its square is subnormal (or 0) would come out of the
        // division above off unit length: scale it to a largest component of 1 first.
        const T largest = glm::max(std::abs(v_local.x), std::abs(v_local.y));
        if (!(largest > T(0))) return {};
        const T x = v_local.x / largest;
        const T y = v_local.y / largest;
        const T inv = T(1) / std::sqrt(x * x + y * y);
        return {x * inv, y * inv};
    }
    /// w (shading frame) in the lobe frame.
    [[nodiscard]] vec3<T> to_lobe(const vec3<T>& w) const noexcept {
        return {cos_phi * w.x + sin_phi * w.y, cos_phi * w.y - sin_phi * w.x, w.z};
    }
    /// w (lobe frame) in the shading frame.
    [[nodiscard]] vec3<T> from_lobe(const vec3<T>& w) const noexcept {
        return {cos_phi * w.x - sin_phi * w.y, sin_phi * w.x + cos_phi * w.y, w.z};
    }
};

/// The linear transform M = [[a, 0, b], [0, c, 0], [d, 0, 1]] (rows) of the EON sampler's
/// LTC lobe, in the lobe frame. Portsmouth, Kutz, Hill 2025, listing function ltc_coeffs:
/// rational fits in mu = n·v and the roughness r, with M = identity (the cosine lobe) at
/// r = 0. Over mu in [0, 1] and r in [0, 1], c >= 0.95 and a - b d >= 0.95, so det(M) > 0
/// (tests/brdf/test_eon.cpp checks it on a grid).
template <std::floating_point T>
struct eon_ltc {
    T a = T(1);
    T b = T(0);
    T c = T(1);
    T d = T(0);

    /// The fitted M for mu = n·v (clamped to [0, 1]) and roughness r in [0, 1].
    [[nodiscard]] static eon_ltc fit(T mu, T r) noexcept {
        mu = glm::clamp(mu, T(0), T(1));
        eon_ltc m;
        m.a = T(1) + r * (T(0.303392) + (T(-0.518982) + T(0.111709) * mu) * mu +
                          (T(-0.276266) + T(0.335918) * mu) * r);
        // mu^3 - 1.43545 < -0.43 on [0, 1]: never a division by zero.
        m.b = r * (T(-1.16407) + T(1.15859) * mu + (T(0.150815) - T(0.150105) * mu) * r) /
              (mu * mu * mu - T(1.43545));
        m.c = T(1) + r * (T(0.20013) + (T(-0.506373) + T(0.261777) * mu) * mu);
        // -1.0743 + mu (0.0725628 + mu) < -1.7e-3 on [0, 1] (its root is at mu = 1.0008).
        m.d = r * (T(0.540852) + (T(-1.01625) + T(0.475392) * mu) * mu) /
              (T(-1.0743) + mu * (T(0.0725628) + mu));
        return m;
    }
    /// det(M) = c (a - b d).
    [[nodiscard]] T det() const noexcept { return c * (a - b * d); }
    /// The fraction s = (1 + 1/sqrt(1 + d^2)) / 2 of the projected unit disk that the
    /// clipped cosine lobe covers (see cltc_sample).
    [[nodiscard]] T clipped_fraction() const noexcept { return T(0.5) * (T(1) + T(1) / std::sqrt(T(1) + d * d)); }
};

/// The density (1/sr) of cltc_sample at the unit direction w (lobe frame, w.z > 0).
///
/// With w_o = M^-1 w / |M^-1 w| the original direction, D(w) = D_o(w_o) |M^-1| / |M^-1 w|^3
/// (the change of variables of Heitz, Dupuy, Hill, Neubelt 2016, "Real-Time Polygonal-Light
/// Shading with Linearly Transformed Cosines", ACM TOG 35(4), sec. 3), and D_o(w_o) = w_o.z / (pi s) on the clipped
/// region (cltc_sample). Written with the adjugate m = adj(M) w = det(M) M^-1 w, which needs
/// no division: D = det(M)^2 m.z / (|m|^4 pi s). 0 where m.z <= 0 (w_o below the horizon:
/// directions the clipped lobe never reaches).
template <std::floating_point T>
[[nodiscard]] inline T cltc_pdf(const eon_ltc<T>& m, const vec3<T>& w) noexcept {
    const vec3<T> adj(m.c * (w.x - m.b * w.z), (m.a - m.b * m.d) * w.y, m.c * (m.a * w.z - m.d * w.x));
    if (!(adj.z > T(0))) return T(0);
    const T len2 = glm::dot(adj, adj);
    return sqr(m.det() / len2) * adj.z * inv_pi<T> / m.clipped_fraction();
}

/// A direction (lobe frame, not normalised; its z can round to <= 0 at the horizon) drawn
/// from the clipped LTC lobe with u in [0, 1)^2.
///
/// The original directions w_o whose image M w_o lies above the horizon are those with
/// d w_o.x + w_o.z >= 0. Projected onto the unit disk, for d <= 0 that region is
/// x <= v_z sqrt(1 - y^2) with v_z = 1/sqrt(1 + d^2), of area pi s (s = (1 + v_z)/2).
/// A uniform disk point (polar map) is squeezed row by row onto it,
/// x -> -((1 - s) sqrt(1 - y^2) + s x), which keeps it uniform, and is lifted to the
/// hemisphere (Malley): a cosine density over the clipped region, w_o.z / (pi s)
/// (Portsmouth, Kutz, Hill 2025, listing function cltc_sample). For d > 0 (the fit gives
/// d <= 0.0035 r there, for mu above 0.99991) the region is the mirror image,
/// x >= -v_z sqrt(1 - y^2), and the point is squeezed without the sign change, so that the
/// drawn region is the clipped one for every fitted M.
template <std::floating_point T>
[[nodiscard]] inline vec3<T> cltc_sample(const eon_ltc<T>& m, const vec2<T>& u) noexcept {
    const T radius = std::sqrt(u.x);
    const sin_cos<T> phi = sin_cos_two_pi(u.y);
    const T x = radius * phi.cos;
    const T y = radius * phi.sin;
    const T s = m.clipped_fraction();
    const T row = safe_sqrt((T(1) - y) * (T(1) + y));
    const T squeezed = (T(1) - s) * row + s * x;
    const T wx = m.d > T(0) ? squeezed : -squeezed;
    const vec3<T> w_o(wx, y, safe_sqrt(T(1) - wx * wx - y * y));
    return {m.a * w_o.x + m.b * w_o.z, m.c * w_o.y, m.d * w_o.x + w_o.z};
}

/// The probability that the EON sampler draws from the uniform hemisphere rather than the
/// CLTC lobe: r^0.1 (0.162925 - 0.372058 mu + 0.538233 mu^2 - 0.290822 mu^3), with
/// r_pow = r^0.1 (Portsmouth, Kutz, Hill 2025, listing function sample_EON). The cubic
/// decreases on [0, 1] from 0.163 to 0.038, so the probability is > 0 for every r > 0 (the
/// uniform lobe then covers every direction where f > 0), and 0 at r = 0 (M is the
/// identity: the cosine lobe alone, proportional to Lambert's f cos).
template <std::floating_point T>
[[nodiscard]] inline T eon_uniform_probability(T mu, T r_pow) noexcept {
    mu = glm::clamp(mu, T(0), T(1));
    return r_pow * (T(0.162925) + mu * (T(-0.372058) + (T(0.538233) - T(0.290822) * mu) * mu));
}

} // namespace shade::detail
