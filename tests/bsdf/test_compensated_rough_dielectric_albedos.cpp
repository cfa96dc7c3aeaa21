// shade::compensated_rough_dielectric::reflectance and ::transmittance against Monte-Carlo
// estimates from the model's own sample() (importance mode, weights split by the sample's
// flags), both sides, float and double.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <utility>
#include <vector>

#include <doctest/doctest.h>

#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/bsdf/compensated_rough_dielectric.hpp>
#include <shade/core/random.hpp>

namespace {

// The generated headers state, at the cell centres with mu >= 0.05, the largest difference
// between the table and a fresh estimate: the reflection table's per side
// (dielectric_reflection_albedo_data.hpp: 1.9e-3 entering, 1.8e-2 exiting) and the GGX
// total-albedo table's (dielectric_albedo_data.hpp, 5.1e-3). Bounds at or above them.
constexpr double reflection_accuracy[2] = {2e-3, 1.8e-2}; // v outside (entering), inside (exiting)
constexpr double total_accuracy = 5.1e-3;

struct split {
    double reflected = 0, transmitted = 0;       // mean importance-mode weight by flag
    double reflected_se = 0, transmitted_se = 0; // standard errors
};

// R and T of `model` for the local view v by its own sampler, the weight of each sample
// added to the reflected or the transmitted sum by its flags (a lost sample adds to
// neither): `replicas` independent estimates of strata^2 samples each, u stratified on a
// strata x strata grid and uc over strata^2 strata, assigned to the u cells by a permutation
// drawn afresh for each replica (Latin-hypercube style: a fixed assignment would tie uc to u
// and bias the estimate; a uniformly random one leaves every sample uniform over
// [0, 1)^3); the mean of the replicas, and its standard error from their spread.
template <class T>
split sampled(const shade::compensated_rough_dielectric<T>& model, const shade::vec3<T>& v, std::size_t strata,
              std::size_t replicas, std::uint64_t seed) {
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    shade::rng random(seed);
    const std::size_t n = strata * strata;
    const T below_one = T(1) - std::numeric_limits<T>::epsilon();
    double sum[2] = {0, 0}, sum_sq[2] = {0, 0};
    std::vector<std::size_t> uc_stratum(n);
    for (std::size_t r = 0; r < replicas; ++r) {
        // Fisher-Yates: a uniformly random permutation of the uc strata.
        std::iota(uc_stratum.begin(), uc_stratum.end(), std::size_t(0));
        for (std::size_t k = n - 1; k > 0; --k)
            std::swap(uc_stratum[k], uc_stratum[std::min(std::size_t(random.uniform<double>() * double(k + 1)), k)]);
        double replica[2] = {0, 0};
        for (std::size_t i = 0; i < strata; ++i)
            for (std::size_t j = 0; j < strata; ++j) {
                const shade::vec2<T> u(glm::min(T((double(i) + random.uniform<double>()) / double(strata)), below_one),
                                       glm::min(T((double(j) + random.uniform<double>()) / double(strata)), below_one));
                const T uc = glm::min(T((double(uc_stratum[i * strata + j]) + random.uniform<double>()) / double(n)), below_one);
                const auto s = model.sample(v, uc, u, at, shade::transport_mode::importance);
                if (s) replica[shade::is_transmission(s->flags) ? 1 : 0] += double(s->weight.x);
            }
        for (int k = 0; k < 2; ++k) {
            replica[k] /= double(n);
            sum[k] += replica[k];
            sum_sq[k] += replica[k] * replica[k];
        }
    }
    split out;
    const double m = double(replicas);
    out.reflected = sum[0] / m;
    out.transmitted = sum[1] / m;
    out.reflected_se = std::sqrt(std::max(sum_sq[0] / m - out.reflected * out.reflected, 0.0) / (m - 1));
    out.transmitted_se = std::sqrt(std::max(sum_sq[1] / m - out.transmitted * out.transmitted, 0.0) / (m - 1));
    return out;
}

} // namespace

TEST_CASE_TEMPLATE("compensated_rough_dielectric: reflectance and transmittance agree with its own sampler, both sides", T,
                   float, double) {
    // The sampler's R is R_ss(true) + what f_ms reflects, which integrates to
    // (1 - tau_s)(1 - E_s(v)) with the same tabulated E_s as reflectance() (up to the E_avg
    // quadrature, < 1e-4): reflectance() differs from it by the reflection table's error
    // alone. transmittance() = E_s - R_ss + tau_s (1 - E_s) carries both tables' errors.
    // Plus 4 standard errors of the estimate.
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    int views = 0;
    double worst_r[2] = {0, 0}, worst_t[2] = {0, 0}, worst_se = 0;
    const double mus[] = {0.1, 0.3, 0.6, 0.95};
    const double alphas[] = {0.05, 0.3, 0.8};
    const double etas[] = {1.33, 1.5, 2.2};
    for (std::size_t a = 0; a < 3; ++a)
        for (std::size_t e = 0; e < 3; ++e) {
            const shade::compensated_rough_dielectric<T> model{shade::ggx<T>(T(alphas[a])), T(etas[e])};
            for (std::size_t side = 0; side < 2; ++side) {
                // Two views per (alpha, eta, side), cycling through the cosines.
                for (std::size_t k = 0; k < 2; ++k) {
                    if ((a + e + side + k) % 2 == 1 && views >= 20) continue;
                    const double mu = mus[(a + 2 * e + side + 2 * k) % 4];
                    const double s = std::sqrt((1 - mu) * (1 + mu));
                    const shade::vec3<T> v(T(s), T(0), T(side == 0 ? mu : -mu));
                    const split mc = sampled(model, v, 96, 8, 1000 + std::uint64_t(views));
                    const double r = double(model.reflectance(v, at));
                    const double t = double(model.transmittance(v, at));
                    CAPTURE(alphas[a]);
                    CAPTURE(etas[e]);
                    CAPTURE(side);
                    CAPTURE(mu);
                    CAPTURE(mc.reflected);
                    CAPTURE(mc.transmitted);
                    CHECK(r >= 0.0);
                    CHECK(t >= 0.0);
                    CHECK(std::abs(r + t - 1) < 1e-5); // the compensation is on for all of these
                    CHECK(std::abs(r - mc.reflected) <= reflection_accuracy[side] + 1e-4 + 4 * mc.reflected_se);
                    CHECK(std::abs(t - mc.transmitted) <=
                          reflection_accuracy[side] + total_accuracy + 1e-4 + 4 * mc.transmitted_se);
                    worst_r[side] = std::max(worst_r[side], std::abs(r - mc.reflected));
                    worst_t[side] = std::max(worst_t[side], std::abs(t - mc.transmitted));
                    worst_se = std::max({worst_se, mc.reflected_se, mc.transmitted_se});
                    ++views;
                }
            }
        }
    CHECK(views >= 20);
    MESSAGE(views << " views: |R - sampled| <= " << worst_r[0] << " outside, " << worst_r[1] << " inside; |T - sampled| <= "
                  << worst_t[0] << " outside, " << worst_t[1] << " inside; standard errors <= " << worst_se);
}

TEST_CASE_TEMPLATE("compensated_rough_dielectric: reflectance and transmittance at the limits", T, float, double) {
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    const shade::compensated_rough_dielectric<T> glass(shade::ggx<T>(T(0.3)), T(1.5));
    // A view on the surface: nothing arrives, both 0.
    CHECK(glass.reflectance(shade::vec3<T>(1, 0, 0), at) == T(0));
    CHECK(glass.transmittance(shade::vec3<T>(1, 0, 0), at) == T(0));
    // A nearly smooth interface (alpha = 1e-4): f_ms is off (it loses < 1e-6), R = F(mu,
    // eta_s) of the smooth interface (shade::dielectric_reflection_albedo's limit) and T =
    // E_s - R with E_s = 1 but for masking; from inside beyond the critical angle, R = 1.
    const shade::compensated_rough_dielectric<T> smooth(shade::ggx<T>(T(1e-4)), T(1.5));
    const T mu = T(0.6), s = std::sqrt((T(1) - mu) * (T(1) + mu));
    CHECK(double(smooth.reflectance(shade::vec3<T>(s, 0, mu), at)) ==
          doctest::Approx(shade::F_dielectric(0.6, 1.5)).epsilon(1e-3));
    CHECK(double(smooth.transmittance(shade::vec3<T>(s, 0, mu), at)) ==
          doctest::Approx(1 - shade::F_dielectric(0.6, 1.5)).epsilon(2e-3));
    // mu = 0.6 < mu_c = sqrt(5) / 3 = 0.745 from inside: total internal reflection.
    CHECK(double(smooth.reflectance(shade::vec3<T>(s, 0, -mu), at)) == doctest::Approx(1.0).epsilon(1e-3));
    CHECK(double(smooth.transmittance(shade::vec3<T>(s, 0, -mu), at)) < 1e-3);
}
