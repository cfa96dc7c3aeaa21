#pragma once
// Internal pieces of the models whose lobes are all delta lobes (shade/bsdf): their f and
// pdf, which are 0, and the construction of a delta lobe's bsdf_sample.

#include <cmath>
#include <concepts>

#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/detail/directions.hpp>
#include <shade/bsdf/bsdf.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade::detail {

/// The f and pdf of a model made only of delta lobes (shade/bsdf/bsdf.hpp), for it to
/// inherit: both are 0 for every pair of directions.
template <std::floating_point T>
struct delta_lobes {
    using scalar_type = T;

    /// 0: delta lobes add nothing to f at any given pair of directions.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        assert_unit_directions(l, v, at);
        return rgb<T>(0);
    }

    /// 0: the model draws only delta directions, which have no density.
    [[nodiscard]] T pdf(const vec3<T>& /*l*/, const vec3<T>& /*v*/, const surface_point<T>& /*at*/) const noexcept {
        return T(0);
    }
};

/// The bsdf_sample of a delta lobe (shade/bsdf/bsdf.hpp) at `at`: direction l, the lobe's
/// throughput and the probability of having chosen the lobe (> 0). Returns
/// f = throughput / max(|n·l|, cos_floor), pdf = probability,
/// weight = throughput / probability, with the given flags (specular included) and eta.
template <std::floating_point T>
[[nodiscard]] inline bsdf_sample<T> make_specular_sample(const vec3<T>& l, const rgb<T>& throughput, T probability,
                                                         const surface_point<T>& at, bsdf_flags flags,
                                                         T eta) noexcept {
    const T abs_n_dot_l = std::abs(glm::dot(at.n(), l));
    return bsdf_sample<T>{l, throughput / floored_cos(abs_n_dot_l), probability, throughput / probability,
                          flags | bsdf_flags::specular, eta};
}

} // namespace shade::detail
