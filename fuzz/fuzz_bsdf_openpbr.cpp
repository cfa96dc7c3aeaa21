// libFuzzer target: shade::openpbr_surface. Input: byte 0 float/double, a byte whose bit 0
// sets geometry_thin_walled, a situation (brdf_target.hpp; l and v on either side), then
// any number of edits of the default parameters, each a parameter byte (an index into
// kParameters below, modulo its size), for a colour a channel byte (0-2 one channel, 3 all
// three), and the value (a scalar). The material built from them by its validating
// constructor is checked as every BSDF (bsdf_target.hpp); in situations 0-6 its emission
// toward v has no NaN and no negative channel (+inf allowed: valid luminance times colour
// may overflow), its interior medium has no NaN, and its dispersed index at 380, 587.6 and
// 780 nm is finite and > 0.

#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>

#include <shade/material/openpbr_surface.hpp>

#include "brdf_target.hpp"
#include "bsdf_target.hpp"

namespace {

using namespace shade;

/// A parameter of openpbr_parameters<T>: a scalar or a colour member.
template <std::floating_point T>
struct parameter {
    T openpbr_parameters<T>::*scalar = nullptr;
    rgb<T> openpbr_parameters<T>::*colour = nullptr;
};

template <std::floating_point T>
constexpr std::array<parameter<T>, 43> kParameters{{
    {&openpbr_parameters<T>::base_weight, nullptr},
    {nullptr, &openpbr_parameters<T>::base_color},
    {&openpbr_parameters<T>::base_diffuse_roughness, nullptr},
    {&openpbr_parameters<T>::base_metalness, nullptr},
    {&openpbr_parameters<T>::specular_weight, nullptr},
    {nullptr, &openpbr_parameters<T>::specular_color},
    {&openpbr_parameters<T>::specular_roughness, nullptr},
    {&openpbr_parameters<T>::specular_roughness_anisotropy, nullptr},
    {&openpbr_parameters<T>::specular_ior, nullptr},
    {&openpbr_parameters<T>::transmission_weight, nullptr},
    {nullptr, &openpbr_parameters<T>::transmission_color},
    {&openpbr_parameters<T>::transmission_depth, nullptr},
    {nullptr, &openpbr_parameters<T>::transmission_scatter},
    {&openpbr_parameters<T>::transmission_scatter_anisotropy, nullptr},
    {&openpbr_parameters<T>::transmission_dispersion_scale, nullptr},
    {&openpbr_parameters<T>::transmission_dispersion_abbe_number, nullptr},
    {&openpbr_parameters<T>::subsurface_weight, nullptr},
    {nullptr, &openpbr_parameters<T>::subsurface_color},
    {&openpbr_parameters<T>::subsurface_radius, nullptr},
    {nullptr, &openpbr_parameters<T>::subsurface_radius_scale},
    {&openpbr_parameters<T>::subsurface_scatter_anisotropy, nullptr},
    {&openpbr_parameters<T>::coat_weight, nullptr},
    {nullptr, &openpbr_parameters<T>::coat_color},
    {&openpbr_parameters<T>::coat_roughness, nullptr},
    {&openpbr_parameters<T>::coat_roughness_anisotropy, nullptr},
    {&openpbr_parameters<T>::coat_ior, nullptr},
    {&openpbr_parameters<T>::coat_darkening, nullptr},
    {&openpbr_parameters<T>::fuzz_weight, nullptr},
    {nullptr, &openpbr_parameters<T>::fuzz_color},
    {&openpbr_parameters<T>::fuzz_roughness, nullptr},
    {&openpbr_parameters<T>::thin_film_weight, nullptr},
    {&openpbr_parameters<T>::thin_film_thickness, nullptr},
    {&openpbr_parameters<T>::thin_film_ior, nullptr},
    {&openpbr_parameters<T>::emission_luminance, nullptr},
    {nullptr, &openpbr_parameters<T>::emission_color},
    {&openpbr_parameters<T>::geometry_opacity, nullptr},
    // The lobes' weights again, so that mutations reach the layered configurations often.
    {&openpbr_parameters<T>::base_metalness, nullptr},
    {&openpbr_parameters<T>::transmission_weight, nullptr},
    {&openpbr_parameters<T>::subsurface_weight, nullptr},
    {&openpbr_parameters<T>::coat_weight, nullptr},
    {&openpbr_parameters<T>::fuzz_weight, nullptr},
    {&openpbr_parameters<T>::thin_film_weight, nullptr},
    {&openpbr_parameters<T>::specular_roughness, nullptr},
}};

template <std::floating_point T>
bool no_nan(const rgb<T>& c) {
    return !std::isnan(c.x) && !std::isnan(c.y) && !std::isnan(c.z);
}

template <std::floating_point T>
void run(fuzz::input& in) {
    openpbr_parameters<T> p;
    p.geometry_thin_walled = in.flag();
    const auto s = fuzz::decode_situation<T>(in);
    if (!s) return;
    for (int edits = 0; edits < 64 && !in.exhausted(); ++edits) {
        const auto& which = kParameters<T>[in.choice(unsigned(kParameters<T>.size()))];
        if (which.scalar != nullptr) {
            p.*which.scalar = in.scalar<T>();
        } else {
            const unsigned channel = in.choice(4);
            const T x = in.scalar<T>();
            if (channel == 3)
                p.*which.colour = rgb<T>(x);
            else
                (p.*which.colour)[int(channel)] = x;
        }
    }
    const auto m = fuzz::build<openpbr_surface<T>>(p);
    if (!m) return;
    fuzz::check_bsdf(*m, *s);
    const rgb<T> e = m->emission(s->v, s->at);
    const openpbr::homogeneous_medium<T> medium = m->interior();
    if (!s->unit) return;
    const bool emission_ok = no_nan(e) && e.x >= T(0) && e.y >= T(0) && e.z >= T(0);
    const bool medium_ok = no_nan(medium.sigma_t) && no_nan(medium.albedo) && !std::isnan(medium.g);
    bool ior_ok = true;
    for (const T lambda : {T(380), T(587.6), T(780)}) {
        const T n = m->specular_ior_at(lambda);
        ior_ok = ior_ok && std::isfinite(n) && n > T(0);
    }
    if (!emission_ok || !medium_ok) {
        fuzz::show(*s);
        fuzz::show("emission", e);
        fuzz::show("sigma_t", medium.sigma_t);
        fuzz::show("albedo", medium.albedo);
    }
    fuzz::expect(emission_ok, "openpbr_surface: emission NaN or negative");
    fuzz::expect(medium_ok, "openpbr_surface: interior medium has a NaN");
    fuzz::expect(ior_ok, "openpbr_surface: specular_ior_at is not finite and > 0 in the visible range");
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return shade::fuzz::dispatch(data, size, &run<float>, &run<double>);
}
