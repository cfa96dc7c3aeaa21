// shade::openpbr_surface against the lobes it is made of, and against Lambert (issue 32).
//
//   openpbr/float/<operation>/<variant>
//
// operation, each on 512 precomputed random inputs visited in a random order:
//   f       f(l, v)
//   pdf     pdf(l, v)
//   sample  sample(v, uc, u) (shade::sample_bsdf for the lobes; radiance mode)
// v is uniform over the upper hemisphere; l over the upper hemisphere for the opaque
// materials and over the whole sphere for rough glass (which also transmits). Every
// direction has |cos(theta)| >= 0.05, so that no model takes its "on the horizon" exit.
//
// variant:
//   lambert                    the baseline, shade::lambert (albedo 0.8)
//   <material>                 shade::openpbr_surface of a preset of
//                              shade/material/openpbr_presets.hpp: default_material,
//                              metal (copper: F82 metal, roughness 0.25), rough_glass
//                              (frosted_glass: roughness 0.4, index 1.52, transmission 1)
//                              and coated_plastic (a coat of roughness 0.1 over a red
//                              dielectric of roughness 0.4)
//   <material>.<lobe>          each lobe that material evaluates, alone, with the
//                              parameters openpbr_surface gives it (the lobe types are
//                              openpbr_surface's own: coat_lobe, metal_lobe, specular_lobe,
//                              transmission_lobe, diffuse_lobe), on the material's inputs
// bench/report.py divides each material's time by the sum of its lobes' times (what the
// layering costs on top of the lobes) and by lambert's.
//
// Float only, as a renderer would call it. The binary runs its benchmarks in random
// interleaved order (bench/support.hpp).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include <glm/geometric.hpp>

#include <shade/brdf/lambert.hpp>
#include <shade/bsdf/bsdf.hpp>
#include <shade/core/random.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/material/openpbr_parameters.hpp>
#include <shade/material/openpbr_presets.hpp>
#include <shade/material/openpbr_surface.hpp>

#include "support.hpp"

namespace {

using T = float;
using v3 = shade::vec3<T>;
using surface = shade::openpbr_surface<T>;

constexpr std::size_t input_count = 512;

struct inputs {
    std::vector<v3> v, l_above, l_sphere;
    std::vector<T> uc;
    std::vector<shade::vec2<T>> u;
    std::vector<std::uint32_t> order; ///< a random permutation of the indices
    shade::surface_point<T> at;
};

// A unit direction uniform over the hemisphere around +z (sign 1) or -z (sign -1), with
// |cos(theta)| >= 0.05 (rejection from the unit ball).
v3 random_direction(shade::rng& g, T sign) {
    for (;;) {
        const v3 p(T(2) * g.uniform<T>() - T(1), T(2) * g.uniform<T>() - T(1), sign * g.uniform<T>());
        const T len = glm::length(p);
        if (len > T(0.1) && len <= T(1) && sign * p.z / len >= T(0.05)) return p / len;
    }
}

const inputs& data() {
    static const inputs d = [] {
        shade::rng g(45);
        inputs out;
        for (std::size_t i = 0; i < input_count; ++i) {
            out.v.push_back(random_direction(g, T(1)));
            out.l_above.push_back(random_direction(g, T(1)));
            out.l_sphere.push_back(random_direction(g, g.uniform<T>() < T(0.5) ? T(1) : T(-1)));
            out.uc.push_back(g.uniform<T>());
            out.u.emplace_back(g.uniform<T>(), g.uniform<T>());
        }
        out.order = shade_bench::random_order(input_count, 46);
        out.at = shade::surface_point<T>::at(v3(0, 0, 0), v3(0, 0, 1));
        return out;
    }();
    return d;
}

// f, pdf and sample of `model` as openpbr/float/<operation>/<name>, l from `l`.
template <class B>
void add_model(const std::string& name, const B& model, const std::vector<v3>& l) {
    const inputs& d = data();
    shade_bench::add("openpbr/float/f/" + name, double(input_count), [&d, &l, model] {
        for (const std::uint32_t i : d.order) {
            shade::rgb<T> f = model.f(l[i], d.v[i], d.at);
            benchmark::DoNotOptimize(f);
        }
    });
    shade_bench::add("openpbr/float/pdf/" + name, double(input_count), [&d, &l, model] {
        for (const std::uint32_t i : d.order) {
            T p = model.pdf(l[i], d.v[i], d.at);
            benchmark::DoNotOptimize(p);
        }
    });
    shade_bench::add("openpbr/float/sample/" + name, double(input_count), [&d, model] {
        for (const std::uint32_t i : d.order) {
            auto s = shade::sample_bsdf(model, d.v[i], d.uc[i], d.u[i], d.at, shade::transport_mode::radiance);
            benchmark::DoNotOptimize(s);
        }
    });
}

// The GGX of roughness r and anisotropy a (openpbr::roughness_to_alpha), as
// openpbr_surface builds its rough lobes.
shade::ggx<T> distribution(T r, T a) {
    const auto alpha = shade::openpbr::roughness_to_alpha(r, a);
    return shade::ggx<T>(alpha.t, alpha.b);
}

// The thin film openpbr_surface's Fresnel terms carry (weight 0 in these materials: set,
// not evaluated).
shade::thin_film_fresnel<T> film_of(const shade::openpbr_parameters<T>& p) {
    return shade::thin_film_fresnel<T>::over_dielectric(p.specular_ior, p.thin_film_ior, p.thin_film_thickness * T(1000));
}

// The specular reflection lobe of an uncoated or coated dielectric base.
surface::specular_lobe specular_of(const shade::openpbr_parameters<T>& p) {
    const T r = shade::openpbr::coat_roughened(p.specular_roughness, p.coat_roughness, p.coat_weight);
    const T eta = shade::openpbr::modulated_ior_ratio(
        shade::openpbr::specular_ior_ratio(p.specular_ior, T(1), p.coat_ior, p.coat_weight), p.specular_weight);
    return surface::specular_lobe(distribution(r, p.specular_roughness_anisotropy),
                                  shade::openpbr::surface_fresnel<T>::dielectric(eta, p.specular_color, T(0), film_of(p)));
}

surface::diffuse_lobe diffuse_of(const shade::openpbr_parameters<T>& p) {
    return surface::diffuse_lobe(p.base_weight * p.base_color, p.base_diffuse_roughness);
}

void register_all() {
    namespace o = shade::openpbr;
    const inputs& d = data();
    add_model("lambert", shade::lambert<T>(shade::rgb<T>(T(0.8))), d.l_above);

    const auto defaults = o::default_material<T>();
    add_model("default_material", surface(defaults), d.l_above);
    add_model("default_material.specular", specular_of(defaults), d.l_above);
    add_model("default_material.diffuse", diffuse_of(defaults), d.l_above);

    const auto metal = o::copper<T>();
    add_model("metal", surface(metal), d.l_above);
    add_model("metal.metal",
              surface::metal_lobe(distribution(metal.specular_roughness, metal.specular_roughness_anisotropy),
                                  o::surface_fresnel<T>::metal(
                                      shade::f82_tint<T>(metal.base_weight * metal.base_color, metal.specular_color,
                                                         metal.specular_weight),
                                      T(0), film_of(metal))),
              d.l_above);

    const auto glass = o::frosted_glass<T>();
    add_model("rough_glass", surface(glass), d.l_sphere);
    add_model("rough_glass.specular", specular_of(glass), d.l_sphere);
    add_model("rough_glass.transmission",
              surface::transmission_lobe(distribution(glass.specular_roughness, glass.specular_roughness_anisotropy),
                                         glass.specular_ior),
              d.l_sphere);

    const auto plastic = o::coated_plastic<T>();
    add_model("coated_plastic", surface(plastic), d.l_above);
    add_model("coated_plastic.coat",
              surface::coat_lobe(distribution(plastic.coat_roughness, plastic.coat_roughness_anisotropy),
                                 shade::dielectric_fresnel<T>(plastic.coat_ior)),
              d.l_above);
    add_model("coated_plastic.specular", specular_of(plastic), d.l_above);
    add_model("coated_plastic.diffuse", diffuse_of(plastic), d.l_above);
}

const bool registered = [] {
    register_all();
    return true;
}();

} // namespace

int main(int argc, char** argv) { return shade_bench::main(argc, argv); }
