#pragma once
// shade::spherical_triangle: the triangle a planar triangle covers on the unit sphere of
// directions around a point, its solid angle, and Arvo's area-preserving map from the unit
// square onto it (uniform sampling by solid angle).
//
// Arvo 1995, "Stratified Sampling of Spherical Triangles", SIGGRAPH 95, section 3 (the
// sub-triangle of area A_hat = u_0 A and the vertex C_hat it ends at) and section 4 (the
// point on the arc from B to C_hat). The internal angles come from the normals of the three
// great circles, as the angles between their planes.
//
// The arithmetic is done in double for either T: the spherical excess
// alpha + beta + gamma - pi loses about |log10(area)| digits to cancellation, which float
// cannot spare for the small triangles a renderer still samples this way.

#include <cmath>
#include <concepts>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <shade/core/math.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// The spherical triangle with unit vertices a, b, c (directions from a point to the
/// vertices of a planar triangle), with its internal angles and its area, the solid angle
/// in sr. Built by make_spherical_triangle; `area` is 0 for degenerate triangles (two
/// vertices in the same or opposite directions, or all three on one great circle), which
/// sample_spherical_triangle must not be given.
struct spherical_triangle {
    glm::dvec3 a{0, 0, 1}, b{0, 0, 1}, c{0, 0, 1}; ///< unit vertex directions
    double alpha = 0, beta = 0, gamma = 0;         ///< internal angles at a, b and c (radians)
    double area = 0;                               ///< alpha + beta + gamma - pi, in sr (>= 0)
};

namespace detail {

/// The angle between unit vectors x and y in [0, pi], from the chord |x - y| (or
/// |x + y| past pi / 2) rather than acos(x·y), which is inaccurate near 0 and pi.
[[nodiscard]] inline double angle_between_unit(const glm::dvec3& x, const glm::dvec3& y) noexcept {
    if (glm::dot(x, y) < 0) return pi<double> - 2 * std::asin(std::fmin(1.0, glm::length(x + y) / 2));
    return 2 * std::asin(std::fmin(1.0, glm::length(y - x) / 2));
}

/// x - (x·unit) unit normalized: the unit vector along x orthogonal to `unit` (Gram-Schmidt).
[[nodiscard]] inline glm::dvec3 orthogonal_unit(const glm::dvec3& x, const glm::dvec3& unit) noexcept {
    return glm::normalize(x - glm::dot(x, unit) * unit);
}

} // namespace detail

/// The spherical triangle that the triangle v0, v1, v2 covers seen from p: its vertices are
/// the unit directions from p to v0, v1, v2, and its area the solid angle the triangle
/// subtends at p (in sr, in [0, 2 pi)). The angle at each vertex is the angle between the
/// planes of the two great circles through it (the planes' normals a x b, b x c, c x a).
/// Degenerate triangles (p on the triangle's plane or line, a vertex at p) get area 0.
template <std::floating_point T>
[[nodiscard]] spherical_triangle make_spherical_triangle(const vec3<T>& p, const vec3<T>& v0, const vec3<T>& v1,
                                                         const vec3<T>& v2) noexcept {
    const glm::dvec3 o(p);
    spherical_triangle s;
    const glm::dvec3 d0 = glm::dvec3(v0) - o, d1 = glm::dvec3(v1) - o, d2 = glm::dvec3(v2) - o;
    const double l0 = glm::length(d0), l1 = glm::length(d1), l2 = glm::length(d2);
    if (!(l0 > 0) || !(l1 > 0) || !(l2 > 0) || !std::isfinite(l0 + l1 + l2)) return s;
    s.a = d0 / l0;
    s.b = d1 / l1;
    s.c = d2 / l2;
    glm::dvec3 n_ab = glm::cross(s.a, s.b), n_bc = glm::cross(s.b, s.c), n_ca = glm::cross(s.c, s.a);
    const double m_ab = glm::length(n_ab), m_bc = glm::length(n_bc), m_ca = glm::length(n_ca);
    if (!(m_ab > 0) || !(m_bc > 0) || !(m_ca > 0)) return s;
    n_ab /= m_ab;
    n_bc /= m_bc;
    n_ca /= m_ca;
    s.alpha = detail::angle_between_unit(n_ab, -n_ca);
    s.beta = detail::angle_between_unit(n_bc, -n_ab);
    s.gamma = detail::angle_between_unit(n_ca, -n_bc);
    const double area = s.alpha + s.beta + s.gamma - pi<double>;
    s.area = area > 0 && std::isfinite(area) ? area : 0;
    return s;
}

namespace detail {

/// shade::sample_spherical_triangle in double, for callers that go on computing in double.
[[nodiscard]] inline glm::dvec3 sample_spherical_triangle(const spherical_triangle& s, double u0, double u1) noexcept {
    // Section 3: the vertex c_hat that makes the sub-triangle's area a_hat = u.x area.
    const double a_hat = u0 * s.area;
    const double sin_phi = std::sin(a_hat - s.alpha), cos_phi = std::cos(a_hat - s.alpha);
    const double cos_alpha = std::cos(s.alpha), sin_alpha = std::sin(s.alpha);
    const double uu = cos_phi - cos_alpha;
    const double vv = sin_phi + sin_alpha * glm::dot(s.a, s.b); // cos of the arc from a to b
    const double num = (vv * cos_phi - uu * sin_phi) * cos_alpha - vv;
    const double den = (vv * sin_phi + uu * cos_phi) * sin_alpha;
    // 0/0 only where the sub-triangle is empty (u.x = 0 with a degenerate angle): c_hat = a.
    double q = den != 0 ? num / den : 1.0;
    q = std::isfinite(q) ? std::fmax(-1.0, std::fmin(1.0, q)) : 1.0;
    const glm::dvec3 c_hat = q * s.a + std::sqrt(std::fmax(0.0, 1 - q * q)) * detail::orthogonal_unit(s.c, s.a);
    // Section 4: the point on the arc from b to c_hat.
    const double z = 1 - u1 * (1 - glm::dot(c_hat, s.b));
    const double zc = std::fmax(-1.0, std::fmin(1.0, z));
    const glm::dvec3 w = zc * s.b + std::sqrt(std::fmax(0.0, 1 - zc * zc)) * detail::orthogonal_unit(c_hat, s.b);
    return glm::normalize(w);
}

} // namespace detail

/// The unit direction inside the spherical triangle s at sample pair u in [0,1)^2, uniform
/// by solid angle: density 1 / s.area (1/sr). Arvo 1995 (see the file comment): u.x chooses
/// the sub-triangle a, b, c_hat of area u.x s.area (c_hat on the arc from a to c), u.y
/// the point on the arc from b to c_hat whose cosine to b is 1 - u.y (1 - b·c_hat). The map
/// keeps strata: neighbouring u give neighbouring directions.
/// Precondition: s.area > 0 (not degenerate).
template <std::floating_point T>
[[nodiscard]] vec3<T> sample_spherical_triangle(const spherical_triangle& s, const vec2<T>& u) noexcept {
    return vec3<T>(detail::sample_spherical_triangle(s, double(u.x), double(u.y)));
}

} // namespace shade
