// libFuzzer target: shade::environment_light in the physical mode: sample_incident,
// pdf_incident (1 / (4 pi) everywhere), incident_radiance, the classic sample, and
// any_light's forwarding (the checks of light_target.hpp).
//
// Input: byte 0 bit 0 double/float; the emission (intensity, ambient, diffuse,
// specular); then the situation of light_target.hpp (p, u, w). The sample/pdf agreement
// is checked for every sample (the density is constant).

#include <cstddef>
#include <cstdint>

#include <shade/light/environment.hpp>

#include "light_target.hpp"

namespace {

using namespace shade;

template <std::floating_point T>
void run(fuzz::input& in) {
    auto r = fuzz::light_reader<T>(in);
    const emission<T> e = fuzz::decode_emission(r);
    const auto s = fuzz::decode_light_situation(r);
    const auto light = fuzz::build<environment_light<T>>(e);
    if (!light) return;
    fuzz::check_light(*light, s, [](const incident_sample<T>&) { return true; });
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return shade::fuzz::dispatch(data, size, &run<float>, &run<double>);
}
