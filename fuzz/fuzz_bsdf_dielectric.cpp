// libFuzzer target: shade's interfaces that transmit or have delta lobes: rough_dielectric over
// GGX and Beckmann, compensated_rough_dielectric over both, smooth_dielectric, thin_dielectric
// and smooth_conductor. Input: byte 0 float/double, a model byte (0-6 in that order), the
// distribution's alpha_x and alpha_y, eta, the conductor's complex index (eta, kappa as two
// colours; read for every model), then a situation (brdf_target.hpp; l and v on either side).
// bsdf_target.hpp says what is checked.

#include <concepts>
#include <cstddef>
#include <cstdint>

#include <shade/brdf/microfacet/beckmann.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/bsdf/compensated_rough_dielectric.hpp>
#include <shade/bsdf/rough_dielectric.hpp>
#include <shade/bsdf/smooth_conductor.hpp>
#include <shade/bsdf/smooth_dielectric.hpp>
#include <shade/bsdf/thin_dielectric.hpp>

#include "brdf_target.hpp"
#include "bsdf_target.hpp"

namespace {

using namespace shade;
using fuzz::build;
using fuzz::decode_rgb;

template <std::floating_point T>
void run(fuzz::input& in) {
    const unsigned model = in.choice(7);
    const T alpha_x = in.scalar<T>();
    const T alpha_y = in.scalar<T>();
    const T eta = in.scalar<T>();
    const rgb<T> conductor_eta = decode_rgb<T>(in);
    const rgb<T> conductor_kappa = decode_rgb<T>(in);
    const auto s = fuzz::decode_situation<T>(in);
    if (!s) return;
    const auto ggx_lobe = build<ggx<T>>(alpha_x, alpha_y);
    const auto beckmann_lobe = build<beckmann<T>>(alpha_x, alpha_y);
    switch (model) {
    case 0:
        if (ggx_lobe)
            if (const auto b = build<rough_dielectric<ggx<T>>>(*ggx_lobe, eta)) fuzz::check_bsdf(*b, *s);
        break;
    case 1:
        if (beckmann_lobe)
            if (const auto b = build<rough_dielectric<beckmann<T>>>(*beckmann_lobe, eta)) fuzz::check_bsdf(*b, *s);
        break;
    case 2:
        if (ggx_lobe)
            if (const auto b = build<compensated_rough_dielectric<T>>(*ggx_lobe, eta)) fuzz::check_bsdf(*b, *s);
        break;
    case 3:
        if (beckmann_lobe)
            if (const auto b = build<compensated_rough_dielectric<T, beckmann<T>>>(*beckmann_lobe, eta))
                fuzz::check_bsdf(*b, *s);
        break;
    case 4:
        if (const auto b = build<smooth_dielectric<T>>(eta)) fuzz::check_bsdf(*b, *s);
        break;
    case 5:
        if (const auto b = build<thin_dielectric<T>>(eta)) fuzz::check_bsdf(*b, *s);
        break;
    default:
        if (const auto b = build<smooth_conductor<T>>(conductor_eta, conductor_kappa)) fuzz::check_bsdf(*b, *s);
        break;
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return shade::fuzz::dispatch(data, size, &run<float>, &run<double>);
}
