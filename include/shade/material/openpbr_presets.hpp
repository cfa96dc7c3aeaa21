#pragma once
// Named OpenPBR Surface parameter sets for the specification's characteristic materials
// (metals with an F82 edge tint, a coated metal, coated plastic, fuzz, rough diffuse,
// glass, a thin-film bubble, subsurface), and the white-furnace variant of any of them.
//
//   const auto gold = shade::openpbr::gold<float>();        // an openpbr_parameters<float>
//   for (const auto& m : shade::openpbr::presets<double>()) use(m.name, m.parameters);
//
// Where a value comes from the OpenPBR repository's example materials
// (github.com/AcademySoftwareFoundation/OpenPBR, examples/open_pbr_*.mtlx, release 1.1.1),
// the preset says which file; those files give colours in ACEScg, converted here to linear
// Rec. 709 (from_acescg). Values not from there are marked as this library's choice.
//
// Not part of shade/shade.hpp: include this header where it is used.

#include <array>
#include <concepts>
#include <string_view>

#include <glm/common.hpp>

#include <shade/core/types.hpp>
#include <shade/material/openpbr_parameters.hpp>

namespace shade::openpbr {

/// An ACEScg colour (ACES AP1 primaries, the ACES white point; Academy S-2014-004) as
/// linear Rec. 709 / sRGB (D65 white), each channel clamped to [0, 1] (the range of
/// OpenPBR's colour parameters; saturated colours such as gold's fall slightly outside
/// Rec. 709). The matrix is M_709^-1 B^-1 diag(B w_65 / B w_60) B M_AP1, M_X the primaries'
/// RGB-to-XYZ matrix, B the Bradford cone response (Lam 1985), w the white points' XYZ;
/// each row sums to 1, so grey stays grey.
template <std::floating_point T>
[[nodiscard]] inline rgb<T> from_acescg(const rgb<T>& c) noexcept {
    const rgb<T> linear(T(1.705051) * c.x - T(0.621792) * c.y - T(0.083259) * c.z,
                        T(-0.130256) * c.x + T(1.140805) * c.y - T(0.010548) * c.z,
                        T(-0.024003) * c.x - T(0.128969) * c.y + T(1.152972) * c.z);
    return glm::clamp(linear, rgb<T>(0), rgb<T>(1));
}

/// The specification's defaults (open_pbr_default.mtlx): a grey dielectric (base_color
/// 0.8, specular_roughness 0.3, specular_ior 1.5) over a Lambertian-like diffuse base.
template <std::floating_point T>
[[nodiscard]] inline openpbr_parameters<T> default_material() noexcept {
    return {};
}

/// Gold, open_pbr_gold.mtlx: a metal (base_metalness 1) whose base_color is its
/// normal-incidence reflectance and specular_color its F82 edge tint, nearly mirror
/// (specular_roughness 0.02).
template <std::floating_point T>
[[nodiscard]] inline openpbr_parameters<T> gold() noexcept {
    openpbr_parameters<T> p;
    p.base_metalness = T(1);
    p.base_color = from_acescg(rgb<T>(T(0.929), T(0.788), T(0.374)));
    p.specular_color = from_acescg(rgb<T>(T(0.987), T(1.013), T(0.997)));
    p.specular_roughness = T(0.02);
    return p;
}

/// Brushed aluminium, open_pbr_aluminum_brushed.mtlx: a metal of specular_roughness 0.2
/// stretched along the tangent (specular_roughness_anisotropy 0.9; the brushing runs along
/// the surface point's tangent).
template <std::floating_point T>
[[nodiscard]] inline openpbr_parameters<T> brushed_aluminium() noexcept {
    openpbr_parameters<T> p;
    p.base_metalness = T(1);
    p.base_color = from_acescg(rgb<T>(T(0.918), T(0.922), T(0.923)));
    p.specular_color = from_acescg(rgb<T>(T(0.921), T(0.934), T(0.955)));
    p.specular_roughness = T(0.2);
    p.specular_roughness_anisotropy = T(0.9);
    return p;
}

/// Copper, open_pbr_copper.mtlx: a metal with an F82 tint, specular_roughness 0.02 there;
/// 0.25 here (this library's choice, so that the gallery shows a rough metal next to the
/// mirror-like gold).
template <std::floating_point T>
[[nodiscard]] inline openpbr_parameters<T> copper() noexcept {
    openpbr_parameters<T> p;
    p.base_metalness = T(1);
    p.base_color = from_acescg(rgb<T>(T(0.811), T(0.643), T(0.542)));
    p.specular_color = from_acescg(rgb<T>(T(0.970), T(0.950), T(0.946)));
    p.specular_roughness = T(0.25);
    return p;
}

/// Car paint, open_pbr_carpaint.mtlx's colour, roughnesses and indices (base_color
/// ACEScg (0.1, 0.6, 0.9), specular_roughness 0.3, specular_ior 1.6, a full coat of
/// roughness 0.02 and coat_ior 1.6), with base_metalness 1 (this library's choice: a
/// metallic paint, a coat over a coloured metal; the example's base is a dielectric).
template <std::floating_point T>
[[nodiscard]] inline openpbr_parameters<T> car_paint() noexcept {
    openpbr_parameters<T> p;
    p.base_metalness = T(1);
    p.base_color = from_acescg(rgb<T>(T(0.1), T(0.6), T(0.9)));
    p.specular_roughness = T(0.3);
    p.specular_ior = T(1.6);
    p.coat_weight = T(1);
    p.coat_roughness = T(0.02);
    p.coat_ior = T(1.6);
    return p;
}

/// Coated plastic (this library's choice; no example file): a red rough dielectric
/// (base_color (0.7, 0.08, 0.05), specular_roughness 0.4) under a full, slightly rough coat
/// (coat_roughness 0.1) of coat_ior 1.5.
template <std::floating_point T>
[[nodiscard]] inline openpbr_parameters<T> coated_plastic() noexcept {
    openpbr_parameters<T> p;
    p.base_color = rgb<T>(T(0.7), T(0.08), T(0.05));
    p.specular_roughness = T(0.4);
    p.coat_weight = T(1);
    p.coat_roughness = T(0.1);
    p.coat_ior = T(1.5);
    return p;
}

/// Velvet, open_pbr_velvet.mtlx: a dark violet rough diffuse base (base_diffuse_roughness
/// 1, specular_roughness 1) under half-covering fuzz (fuzz_weight 0.5, fuzz_roughness 0.5).
template <std::floating_point T>
[[nodiscard]] inline openpbr_parameters<T> velvet() noexcept {
    openpbr_parameters<T> p;
    p.base_color = from_acescg(rgb<T>(T(0.062), T(0.01), T(0.269)));
    p.base_diffuse_roughness = T(1);
    p.specular_roughness = T(1);
    p.fuzz_weight = T(0.5);
    p.fuzz_color = from_acescg(rgb<T>(T(0.315), T(0.237), T(0.465)));
    p.fuzz_roughness = T(0.5);
    return p;
}

/// Rubber: open_pbr_tire.mtlx's specular_roughness 0.7 with the roughest diffuse base
/// (base_diffuse_roughness 1, the EON lobe's flattest) and an orange base_color (0.6, 0.25,
/// 0.05) (both this library's choice; the tyre's near-black base_color 0.023 would hide the
/// diffuse lobe).
template <std::floating_point T>
[[nodiscard]] inline openpbr_parameters<T> rubber() noexcept {
    openpbr_parameters<T> p;
    p.base_color = rgb<T>(T(0.6), T(0.25), T(0.05));
    p.base_diffuse_roughness = T(1);
    p.specular_roughness = T(0.7);
    return p;
}

/// Glass, open_pbr_glass.mtlx: a smooth (specular_roughness 0) fully transmissive
/// dielectric of specular_ior 1.52 with the dispersion of a crown glass (Abbe number 64).
template <std::floating_point T>
[[nodiscard]] inline openpbr_parameters<T> glass() noexcept {
    openpbr_parameters<T> p;
    p.specular_roughness = T(0);
    p.specular_ior = T(1.52);
    p.transmission_weight = T(1);
    p.transmission_dispersion_scale = T(1);
    p.transmission_dispersion_abbe_number = T(64);
    return p;
}

/// Frosted glass: glass() with specular_roughness 0.4 (this library's choice).
template <std::floating_point T>
[[nodiscard]] inline openpbr_parameters<T> frosted_glass() noexcept {
    openpbr_parameters<T> p = glass<T>();
    p.specular_roughness = T(0.4);
    return p;
}

/// Soap bubble, open_pbr_soapbubble.mtlx: a thin-walled, fully transmissive, smooth shell
/// of index 1 (no interface of its own) carrying a 0.5 um film of index 1.4, whose
/// interference alone colours the reflection.
template <std::floating_point T>
[[nodiscard]] inline openpbr_parameters<T> soap_bubble() noexcept {
    openpbr_parameters<T> p;
    p.specular_roughness = T(0);
    p.specular_ior = T(1);
    p.transmission_weight = T(1);
    p.thin_film_weight = T(1);
    p.thin_film_thickness = T(0.5);
    p.thin_film_ior = T(1.4);
    p.geometry_thin_walled = true;
    return p;
}

/// Marble (a wax-like translucent solid), open_pbr_marble.mtlx: full subsurface
/// (subsurface_weight 1) of a warm white subsurface_color with a mean free path longest in
/// red (subsurface_radius 1 scene unit times subsurface_radius_scale), smooth
/// (specular_roughness 0).
template <std::floating_point T>
[[nodiscard]] inline openpbr_parameters<T> marble() noexcept {
    openpbr_parameters<T> p;
    p.specular_roughness = T(0);
    p.subsurface_weight = T(1);
    p.subsurface_color = from_acescg(rgb<T>(T(0.813), T(0.793), T(0.759)));
    p.subsurface_radius_scale = from_acescg(rgb<T>(T(0.851), T(0.557), T(0.395)));
    return p;
}

/// A preset and its name (snake_case, as the function that makes it).
template <std::floating_point T>
struct named_parameters {
    std::string_view name;
    openpbr_parameters<T> parameters;
};

/// Every preset of this header, in the order listed in it.
template <std::floating_point T>
[[nodiscard]] inline std::array<named_parameters<T>, 12> presets() noexcept {
    return {{{"default_material", default_material<T>()},
             {"gold", gold<T>()},
             {"brushed_aluminium", brushed_aluminium<T>()},
             {"copper", copper<T>()},
             {"car_paint", car_paint<T>()},
             {"coated_plastic", coated_plastic<T>()},
             {"velvet", velvet<T>()},
             {"rubber", rubber<T>()},
             {"glass", glass<T>()},
             {"frosted_glass", frosted_glass<T>()},
             {"soap_bubble", soap_bubble<T>()},
             {"marble", marble<T>()}}};
}

/// The white-furnace version of p: every colour white (base, specular, transmission,
/// subsurface, coat, fuzz), base_weight 1, no interior medium (transmission_depth 0,
/// transmission_scatter 0) and no emission; roughnesses, indices, weights of the layers,
/// thin film, opacity and thin-walledness kept. A material that conserves energy then
/// neither absorbs nor emits: in a uniform environment of radiance 1 it is invisible.
template <std::floating_point T>
[[nodiscard]] inline openpbr_parameters<T> white_furnace_variant(openpbr_parameters<T> p) noexcept {
    const rgb<T> white(1);
    p.base_weight = T(1);
    p.base_color = white;
    p.specular_color = white;
    p.transmission_color = white;
    p.transmission_depth = T(0);
    p.transmission_scatter = rgb<T>(0);
    p.subsurface_color = white;
    p.coat_color = white;
    p.fuzz_color = white;
    p.emission_luminance = T(0);
    return p;
}

} // namespace shade::openpbr
