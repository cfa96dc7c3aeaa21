#pragma once
// Measured complex indices of refraction eta + i kappa of a few metals, as
// shade::conductor_fresnel terms (in air: the index relative to the incident medium is the
// metal's own). One value per RGB channel, each the measurement at one wavelength of the
// source table, without interpolation:
//
//   R: 659.5 nm (1.88 eV),  G: 548.6 nm (2.26 eV),  B: 450.9 nm (2.75 eV)
//
// (the photon energies of Johnson and Christy's table nearest to 650, 550 and 450 nm).
// Sources:
//   gold, silver, copper: Johnson, Christy 1972, "Optical Constants of the Noble Metals",
//     Physical Review B 6(12): 4370-4379, table I (as tabulated by refractiveindex.info,
//     database/data/main/{Au,Ag,Cu}/nk/Johnson.yml);
//   aluminium: Rakic, Djurisic, Elazar, Majewski 1998, "Optical properties of metallic
//     films for vertical-cavity optoelectronic devices", Applied Optics 37(22): 5271-5283,
//     the Lorentz-Drude model with their parameters for Al (omega_p = 14.98 eV,
//     f_0 = 0.523, Gamma_0 = 0.047 eV; oscillators (f, Gamma, omega) = (0.227, 0.333,
//     0.162), (0.050, 0.312, 1.544), (0.166, 1.351, 1.808), (0.030, 3.382, 3.473) eV),
//     evaluated at the same three photon energies and rounded to four digits.
// A single wavelength per channel is an approximation of the spectral reflectance
// integrated against the RGB matching functions; it keeps each metal's hue (gold and
// copper reflect red best, silver and aluminium are nearly neutral).

#include <concepts>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/core/types.hpp>

namespace shade::metals {

/// Gold (Johnson, Christy 1972): eta = (0.14, 0.43, 1.38), kappa = (3.697, 2.455, 1.914).
template <std::floating_point T>
[[nodiscard]] conductor_fresnel<T> gold() noexcept {
    return conductor_fresnel<T>(unchecked, rgb<T>(T(0.14), T(0.43), T(1.38)), rgb<T>(T(3.697), T(2.455), T(1.914)));
}

/// Silver (Johnson, Christy 1972): eta = (0.05, 0.06, 0.04), kappa = (4.483, 3.586, 2.657).
template <std::floating_point T>
[[nodiscard]] conductor_fresnel<T> silver() noexcept {
    return conductor_fresnel<T>(unchecked, rgb<T>(T(0.05), T(0.06), T(0.04)), rgb<T>(T(4.483), T(3.586), T(2.657)));
}

/// Copper (Johnson, Christy 1972): eta = (0.22, 1.02, 1.24), kappa = (3.747, 2.577, 2.397).
template <std::floating_point T>
[[nodiscard]] conductor_fresnel<T> copper() noexcept {
    return conductor_fresnel<T>(unchecked, rgb<T>(T(0.22), T(1.02), T(1.24)), rgb<T>(T(3.747), T(2.577), T(2.397)));
}

/// Aluminium (Rakic et al. 1998, Lorentz-Drude model): eta = (1.4665, 0.9596, 0.5925),
/// kappa = (7.5603, 6.4430, 5.3215).
template <std::floating_point T>
[[nodiscard]] conductor_fresnel<T> aluminium() noexcept {
    return conductor_fresnel<T>(unchecked, rgb<T>(T(1.4665), T(0.9596), T(0.5925)), rgb<T>(T(7.5603), T(6.4430), T(5.3215)));
}

} // namespace shade::metals
