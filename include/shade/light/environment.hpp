#pragma once
// shade::environment_light: uniform radiance from every direction, infinitely far away.

#include <concepts>
#include <optional>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/types.hpp>
#include <shade/light/emission.hpp>
#include <shade/light/incident_sample.hpp>
#include <shade/light/light_sample.hpp>

namespace shade {

/// A constant environment light: radiance L = emitted().physical() in W/(m^2 sr) arrives
/// from every direction, from infinitely far away (a ray that leaves the scene sees L).
/// The irradiance it gives an unoccluded surface is pi L. sample_incident(p, u) chooses a
/// direction uniformly on the sphere (density 1 / (4 pi) per steradian; half the samples
/// fall below any given surface and are worth zero there). The classic sample(p, u) is
/// that direction weighted by 1 / pdf = 4 pi.
template <std::floating_point T>
class environment_light {
public:
    using scalar_type = T;

    /// Throws shade::invalid_parameter naming the bad emission member.
    explicit environment_light(const emission<T>& e = {}) : emission_(validated(e)) {}

    /// The emitted intensity and colours.
    [[nodiscard]] const emission<T>& emitted() const noexcept { return emission_; }
    /// The radiance L in W/(m^2 sr).
    [[nodiscard]] rgb<T> radiance() const noexcept { return emission_.physical(); }

    /// Always false: the environment is sampled many times.
    [[nodiscard]] static constexpr bool is_delta() noexcept { return false; }

    /// The physical sample at p: a uniform direction on the sphere, at infinity, radiance
    /// L, pdf 1 / (4 pi). Nothing when L is zero.
    [[nodiscard]] std::optional<incident_sample<T>> sample_incident(const vec3<T>& p,
                                                                    const vec2<T>& u) const noexcept {
        (void)p;
        if (radiance() == rgb<T>(0)) return std::nullopt;
        incident_sample<T> s;
        s.l = square_to_uniform_sphere(u);
        s.radiance = radiance();
        s.pdf = T(1) / (T(4) * pi<T>);
        return s;
    }

    /// 1 / (4 pi) for every direction (1/sr).
    [[nodiscard]] static constexpr T pdf_incident(const vec3<T>& p, const vec3<T>& l) noexcept {
        (void)p;
        (void)l;
        return T(1) / (T(4) * pi<T>);
    }

    /// L for every direction: the radiance a ray that leaves the scene along l sees.
    [[nodiscard]] rgb<T> incident_radiance(const vec3<T>& p, const vec3<T>& l) const noexcept {
        (void)p;
        (void)l;
        return radiance();
    }

    /// The classic light sample along a uniform direction, weighted by 4 pi.
    [[nodiscard]] light_sample<T> sample(const vec3<T>& p, const vec2<T>& u) const noexcept {
        (void)p;
        return detail::make_sample(emission_, square_to_uniform_sphere(u), infinity<T>, T(4) * pi<T>);
    }

private:
    emission<T> emission_;
};

} // namespace shade
