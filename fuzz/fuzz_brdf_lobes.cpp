// libFuzzer target: the lobes OpenPBR Surface is built of that are models of their own:
// shade::eon and fujii_oren_nayar, zeltner_sheen and zeltner_sheen_reciprocal, and
// coupled_plastic (a layer of a GGX dielectric coating over Lambert). Input: byte 0
// float/double, a model byte (0-4 in that order), a colour (rho, the sheen colour or k_d),
// a roughness (EON's, the sheen's), the GGX alpha_x and alpha_y (coupled_plastic), then a
// situation (brdf_target.hpp, which also says what is checked; l and v above the surface
// for a BRDF, and f = 0 below).

#include <concepts>
#include <cstddef>
#include <cstdint>

#include <shade/brdf/coupled_plastic.hpp>
#include <shade/brdf/eon.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/brdf/sheen.hpp>

#include "brdf_target.hpp"
#include "bsdf_target.hpp"

namespace {

using namespace shade;
using fuzz::build;
using fuzz::decode_rgb;

template <class B>
void check(const B& b, const fuzz::brdf_situation<scalar_of<B>>& s) {
    if constexpr (brdf<B>) fuzz::check_brdf(b, s);
    if constexpr (sampled_bsdf<B>) fuzz::check_bsdf(b, s);
}

template <std::floating_point T>
void run(fuzz::input& in) {
    const unsigned model = in.choice(5);
    const rgb<T> colour = decode_rgb<T>(in);
    const T roughness = in.scalar<T>();
    const T alpha_x = in.scalar<T>();
    const T alpha_y = in.scalar<T>();
    const auto s = fuzz::decode_situation<T>(in);
    if (!s) return;
    switch (model) {
    case 0:
        if (const auto b = build<eon<T>>(colour, roughness)) check(*b, *s);
        break;
    case 1:
        if (const auto b = build<fujii_oren_nayar<T>>(colour, roughness)) check(*b, *s);
        break;
    case 2:
        if (const auto b = build<zeltner_sheen<T>>(colour, roughness)) check(*b, *s);
        break;
    case 3:
        if (const auto b = build<zeltner_sheen_reciprocal<T>>(colour, roughness)) check(*b, *s);
        break;
    default:
        if (const auto d = build<ggx<T>>(alpha_x, alpha_y))
            if (const auto b = build<coupled_plastic<T>>(*d, colour)) check(*b, *s);
        break;
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return shade::fuzz::dispatch(data, size, &run<float>, &run<double>);
}
