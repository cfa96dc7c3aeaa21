#pragma once
// The white furnace of shade::compensated_rough_dielectric over anisotropic GGX, for
// tests/bsdf/test_compensated_rough_dielectric_anisotropic.cpp and the denser sweep of
// tests/sweep/test_dielectric_anisotropic_sweep.cpp: R + T split into the two parts of the
// model, each estimated independently of the tables: the single-scattering R + T with
// rough_dielectric's own sampler (the lobe choice integrated out, bsdf/dielectric_albedo.hpp),
// and the integral of f_ms = f - f_single (importance mode) times |n·l| over the sphere through
// f only, by the midpoint rule in (sqrt(|n·l|), azimuth) on 32 x 64 cells per hemisphere.

#include <cmath>
#include <cstddef>

#include <glm/geometric.hpp>

#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/bsdf/bsdf.hpp>
#include <shade/bsdf/compensated_rough_dielectric.hpp>
#include <shade/core/math.hpp>

#include "bsdf/dielectric_albedo.hpp"

namespace bsdf_test::anisotropic {

using shade::transport_mode;
template <class T>
using compensated = shade::compensated_rough_dielectric<T>;

// The frame of the tests: n = +z, t = +x (alpha_x along x).
template <class T>
shade::surface_point<T> flat_frame() {
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    return at;
}

// The unit view at cosine mu (> 0 outside, < 0 inside) and azimuth phi (degrees from t).
template <class T>
shade::vec3<T> view(double mu, double phi_degrees) {
    const double phi = phi_degrees * shade::pi<double> / 180, m = std::abs(mu), s = std::sqrt((1 - m) * (1 + m));
    return shade::vec3<T>(T(s * std::cos(phi)), T(s * std::sin(phi)), T(mu));
}

// integral of f_ms(l, v) |n·l| dl over the sphere, f_ms = f - f_single in importance mode:
// the midpoint rule in (x, phi) with mu_l = x^2, dl = 2 x dx dphi, on each hemisphere.
template <class T>
double multiple_scattering_albedo(const compensated<T>& model, const shade::vec3<T>& v) {
    const auto at = flat_frame<T>();
    constexpr int nx = 32, nphi = 64;
    double sum = 0;
    for (const double sign : {1.0, -1.0})
        for (int i = 0; i < nx; ++i) {
            const double x = (i + 0.5) / nx, mu = x * x, s = std::sqrt((1 - mu) * (1 + mu));
            for (int k = 0; k < nphi; ++k) {
                const double phi = (k + 0.5) / nphi * 2 * shade::pi<double>;
                const shade::vec3<T> l(T(s * std::cos(phi)), T(s * std::sin(phi)), T(sign * mu));
                const double f_ms = double(shade::bsdf_f(model, l, v, at, transport_mode::importance).x) -
                                    double(shade::bsdf_f(model.single_scattering(), l, v, at, transport_mode::importance).x);
                sum += f_ms * mu * 2 * x;
            }
        }
    return sum * 2 * shade::pi<double> / (double(nx) * nphi);
}

struct furnace {
    double single = 0;   ///< single-scattering R + T
    double multiple = 0; ///< integral of f_ms |n·l|
    double error = 0;    ///< standard error of `single`
    [[nodiscard]] double total() const { return single + multiple; }
};

// R + T of the compensated interface for the local view v (either side).
template <class T>
furnace white_furnace(const compensated<T>& model, const shade::vec3<T>& v, std::size_t strata = 160) {
    const bool inside = v.z < T(0);
    const auto& d = model.distribution();
    // Seen from inside, the interface is the outside view of the inverted one, mirrored.
    const shade::rough_dielectric<shade::ggx<double>> mirrored{
        shade::ggx<double>(double(d.alpha_x()), double(d.alpha_y())), inside ? 1 / double(model.eta()) : double(model.eta())};
    const shade::vec3<double> v_up(double(v.x), double(v.y), std::abs(double(v.z)));
    const auto e = single_scattering_albedo(mirrored, glm::normalize(v_up), strata, 5);
    return {e.albedo.x, multiple_scattering_albedo(model, v), e.standard_error.x};
}

// R + T of the compensated interface for the local view v (either side) without the
// integral of f_ms: 1 + E_true(v) - E_read(v), E_true the single-scattering R + T estimated
// as white_furnace does and E_read the model's own single_scattering_albedo. Exact when f_ms
// returns 1 - E_read(v) (test_compensated_rough_dielectric_anisotropic.cpp checks that it does,
// to 4e-4); `error` is the standard error of E_true.
template <class T>
furnace table_furnace(const compensated<T>& model, const shade::vec3<T>& v, std::size_t strata = 128) {
    const bool inside = v.z < T(0);
    const auto& d = model.distribution();
    const shade::rough_dielectric<shade::ggx<double>> mirrored{
        shade::ggx<double>(double(d.alpha_x()), double(d.alpha_y())), inside ? 1 / double(model.eta()) : double(model.eta())};
    const shade::vec3<double> v_up(double(v.x), double(v.y), std::abs(double(v.z)));
    const auto e = single_scattering_albedo(mirrored, glm::normalize(v_up), strata, 5);
    const double read = double(model.single_scattering_albedo(v, flat_frame<T>()));
    return {e.albedo.x, 1 - read, e.standard_error.x};
}

} // namespace bsdf_test::anisotropic
