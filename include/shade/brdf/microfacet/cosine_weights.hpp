#pragma once
// The GGX reflection lobe's measure of the cosine c = v·h between the view and the half
// vector, tabulated as weights of fixed nodes in c: the directional albedo of the lobe with
// any Fresnel factor that depends on c alone (a thin film, Schlick, F82, the exact
// dielectric) is then a weighted sum of that Fresnel at the nodes. The weights are written
// by examples/albedo_tables --cosine-weights into detail/cosine_weight_data.hpp.
//
// Not part of shade/shade.hpp: include this header where it is used.

#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>

#include <glm/common.hpp>

#include <shade/brdf/microfacet/detail/cosine_weight_data.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/core/types.hpp>

namespace shade::detail {

/// Node k of the grid shared by c and mu: c_k = (k / (n - 1))^(3/2), n =
/// cosine_weight_nodes, denser toward grazing cosines where Fresnel factors bend most.
[[nodiscard]] inline double cosine_weight_node(std::size_t k) noexcept {
    const double x = double(k) / double(cosine_weight_nodes - 1);
    return x * std::sqrt(x);
}

/// The alpha of row j of the table: alpha_j = (j / (m - 1))^2, m = cosine_weight_alpha_nodes
/// (uniform in sqrt(alpha) over [0, 1]).
[[nodiscard]] inline double cosine_weight_alpha(std::size_t j) noexcept {
    const double s = double(j) / double(cosine_weight_alpha_nodes - 1);
    return s * s;
}

/// The quadrature of ggx_cosine_weights: calls visit(c, weight) for each of the strata^2
/// midpoints of the visible-normal sampler's square whose reflected direction lies above the
/// surface, weight = G2(v, l) / G1(v) / strata^2, so that sum weight F(c) is the lobe's
/// albedo with the Fresnel F; alpha <= 0 visits (mu, 1) once. mu is clamped to [1e-4, 1].
template <class Visit>
void visit_ggx_cosine_measure(double mu, double alpha, std::size_t strata, Visit&& visit) {
    mu = glm::clamp(mu, 1e-4, 1.0);
    if (!(alpha > 0)) {
        visit(mu, 1.0);
        return;
    }
    const ggx<double> d(unchecked, alpha, alpha);
    const vec3<double> v(std::sqrt((1 - mu) * (1 + mu)), 0, mu);
    const double lambda_v = d.Lambda(v);
    const double cell = 1 / (double(strata) * double(strata));
    for (std::size_t i = 0; i < strata; ++i) {
        for (std::size_t j = 0; j < strata; ++j) {
            const vec2<double> u((double(i) + 0.5) / double(strata), (double(j) + 0.5) / double(strata));
            const vec3<double> h = d.sample_visible_normal(v, u);
            const double c = glm::dot(v, h);
            const vec3<double> l = 2 * c * h - v;
            if (!(l.z > 0) || !(c > 0)) continue;
            // G2 / G1(v) = (1 + Lambda(v)) / (1 + Lambda(v) + Lambda(l)), the height-correlated
            // G2 (Heitz 2014, JCGT 3(2), eq. 99) over G1(v) = 1 / (1 + Lambda(v)).
            visit(c, cell * (1 + lambda_v) / (1 + lambda_v + d.Lambda(l)));
        }
    }
}

/// The weights w_k(mu, alpha) of the table's definition, computed: for the single-scattering
/// GGX reflection lobe with F = 1 and height-correlated Smith masking at the view of cosine
/// mu, its albedo E_F(v) = integral of f cos(theta_l) dl for a Fresnel F(v·h) is
///
///     E_F(v) = integral F(v·h) D_v(h) G2(v, l) / G1(v) dh,   l = reflect(v, h),
///
/// (D_v the distribution of visible normals, Heitz 2018, "Sampling the GGX Distribution of
/// Visible Normals", JCGT 7(4), eq. 1; dl = 4 (v·h) dh, Walter et al. 2007, eq. 14; G2 = 0
/// for l below the surface), i.e. the integral of F against the measure m_v of c = v·h.
/// w_k is the integral of the hat function of node k (1 at c_k, 0 at its neighbours,
/// linear between, in the grid's coordinate x = c^(2/3)) against m_v, so that sum_k w_k
/// F(c_k) integrates exactly an F linear between the nodes in x. m_v is integrated by the
/// midpoint rule on strata^2 cells of the visible-normal sampler's square
/// (ggx::sample_visible_normal). alpha = 0 gives the hat weights of c = mu. mu is clamped to
/// [1e-4, 1] (the sampler needs v above the horizon). Writes cosine_weight_nodes values to
/// out.
inline void ggx_cosine_weights(double mu, double alpha, std::size_t strata, double* out) noexcept {
    constexpr std::size_t n = cosine_weight_nodes;
    for (std::size_t k = 0; k < n; ++k) out[k] = 0;
    visit_ggx_cosine_measure(mu, alpha, strata, [&](double c, double weight) {
        const double x = glm::clamp(std::cbrt(c * c), 0.0, 1.0) * double(n - 1);
        const std::size_t k = glm::min(std::size_t(x), n - 2);
        const double t = x - double(k);
        out[k] += weight * (1 - t);
        out[k + 1] += weight * t;
    });
}

/// The directional albedo of the GGX reflection lobe of roughness alpha with a Fresnel
/// factor F(c), c = v·h, as a row over the view cosine: at construction, F (a callable
/// T -> rgb<T>) is read at the cosine_weight_nodes nodes c_k and each view node's
/// E_F(mu_j) = sum_k w_k(mu_j, alpha) F(c_k) is summed, the weights read from
/// cosine_weight_data.hpp, linear in sqrt(alpha) between its rows; at(mu) interpolates the
/// row linearly in x = mu^(2/3) (the grid's coordinate; for alpha -> 0 this is the linear
/// interpolation of F itself, the smooth lobe's albedo). alpha is clamped to [0, 1].
/// The accuracy of the table (its quadrature and interpolation) is stated in the data
/// header; F's own variation between the nodes adds its linear-interpolation error.
template <std::floating_point T>
class fresnel_albedo_row {
public:
    fresnel_albedo_row() = default;

    template <class Fresnel>
    fresnel_albedo_row(T alpha, const Fresnel& F) {
        constexpr std::size_t n = cosine_weight_nodes, m = cosine_weight_alpha_nodes;
        std::array<rgb<T>, n> f_nodes;
        for (std::size_t k = 0; k < n; ++k) f_nodes[k] = F(T(cosine_weight_node(k)));
        const double s = std::sqrt(glm::clamp(double(alpha), 0.0, 1.0)) * double(m - 1);
        const std::size_t j = glm::min(std::size_t(s), m - 2);
        const double t = s - double(j);
        const float* lower = cosine_weight_table + j * n * n;
        const float* upper = lower + n * n;
        for (std::size_t i = 0; i < n; ++i) {
            rgb<T> sum(0);
            for (std::size_t k = 0; k < n; ++k) {
                const double w = (1 - t) * double(lower[i * n + k]) + t * double(upper[i * n + k]);
                sum += T(w) * f_nodes[k];
            }
            row_[i] = sum;
        }
    }

    /// Raises each view node's sum by margin(j, i) (a double for alpha row j and view node
    /// i of the table), interpolated in sqrt(alpha) as the weights are: with an upper bound
    /// of the sum's shortfall for a known family of F (the thin films of
    /// detail/thin_film_margin_data.hpp) the row then reads high, never low. alpha as at
    /// construction.
    template <class Margin>
    void raise(T alpha, const Margin& margin) {
        constexpr std::size_t n = cosine_weight_nodes, m = cosine_weight_alpha_nodes;
        const double s = std::sqrt(glm::clamp(double(alpha), 0.0, 1.0)) * double(m - 1);
        const std::size_t j = glm::min(std::size_t(s), m - 2);
        const double t = s - double(j);
        for (std::size_t i = 0; i < n; ++i) row_[i] += rgb<T>(T((1 - t) * margin(j, i) + t * margin(j + 1, i)));
    }

    /// E_F at view cosine mu (clamped to [0, 1]), per channel.
    [[nodiscard]] rgb<T> at(T mu) const noexcept {
        constexpr std::size_t n = cosine_weight_nodes;
        const T c = glm::clamp(mu, T(0), T(1));
        const T x = std::cbrt(c * c) * T(n - 1);
        const std::size_t k = glm::min(std::size_t(x), n - 2);
        const T t = x - T(k);
        return (T(1) - t) * row_[k] + t * row_[k + 1];
    }

private:
    std::array<rgb<T>, cosine_weight_nodes> row_{};
};

/// One view's sum of fresnel_albedo_row without keeping a row: e = sum_k w_k F(c_k) per
/// channel (the lobe's albedo with F) and mass = sum_k w_k (its albedo with F = 1), the
/// weights at (alpha, mu) interpolated bilinearly in sqrt(alpha) and x = mu^(2/3) as
/// fresnel_albedo_row builds and reads them.
template <std::floating_point T>
struct fresnel_albedo_sum {
    rgb<T> e{0};
    T mass = 0;
};

/// fresnel_albedo_sum for F given at the nodes (f_nodes[k] = F(c_k)), at roughness alpha
/// (clamped to [0, 1]) and view cosine mu (clamped to [0, 1]); a NaN alpha or mu is read
/// as 0.
template <std::floating_point T>
[[nodiscard]] fresnel_albedo_sum<T> fresnel_albedo_at(T alpha, T mu,
                                                      const std::array<rgb<T>, cosine_weight_nodes>& f_nodes) noexcept {
    constexpr std::size_t n = cosine_weight_nodes, m = cosine_weight_alpha_nodes;
    const double s = std::sqrt(alpha > T(0) ? glm::min(double(alpha), 1.0) : 0.0) * double(m - 1);
    const std::size_t j = glm::min(std::size_t(s), m - 2);
    const double t = s - double(j);
    const double c = mu > T(0) ? glm::min(double(mu), 1.0) : 0.0;
    const double x = std::cbrt(c * c) * double(n - 1);
    const std::size_t i = glm::min(std::size_t(x), n - 2);
    const double u = x - double(i);
    const float* w00 = cosine_weight_table + (j * n + i) * n;
    const float* w01 = w00 + n;
    const float* w10 = w00 + n * n;
    const float* w11 = w10 + n;
    const double a00 = (1 - t) * (1 - u), a01 = (1 - t) * u, a10 = t * (1 - u), a11 = t * u;
    fresnel_albedo_sum<T> out;
    for (std::size_t k = 0; k < n; ++k) {
        const double w = a00 * double(w00[k]) + a01 * double(w01[k]) + a10 * double(w10[k]) + a11 * double(w11[k]);
        out.e += T(w) * f_nodes[k];
        out.mass += T(w);
    }
    return out;
}

} // namespace shade::detail
