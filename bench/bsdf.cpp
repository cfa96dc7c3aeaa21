// BSDF evaluation, sampling and density of the dielectrics next to the conductors, in float
// and double (issue 31, item 6).
//
//   bsdf/<type>/<operation>/<model>
//
// operation, each on 512 precomputed random inputs visited in a random order (so a
// model's branches, e.g. reflection or refraction, total internal reflection, are not
// learnt by the branch predictor as a fixed sequence):
//   f_reflection      f(l, v), l and v above the surface
//   f_transmission    f(l, v), v above, l below (a BRDF returns 0 early)
//   pdf_reflection    pdf(l, v) on the pairs of f_reflection
//   pdf_transmission  pdf(l, v) on the pairs of f_transmission
//   sample_outside    shade::sample_bsdf(v, uc, u, radiance mode), v above
//   sample_inside     the same with v below (from inside glass; a BRDF returns nullopt)
// Directions are uniform over their hemisphere with |cos(theta)| >= 0.05, so that no model
// takes its "on the horizon" exit.
//
// model: the baseline ggx_conductor (shade::make_ggx_conductor: GGX, Schlick's Fresnel,
// height-correlated Smith), ggx_conductor_exact_fresnel (the same with the exact conductor
// Fresnel of gold, shade::metals::gold), smooth_conductor (gold), smooth_dielectric, thin_dielectric,
// rough_dielectric_ggx and rough_dielectric_beckmann (eta 1.5, alpha 0.3 for the rough
// ones), and shade::compensated_rough_dielectric over anisotropic GGX 0.05 x 0.5 (eta 1.5)
// reading its tables (compensated_dielectric_anisotropic_tables) or a
// shade::rough_dielectric_albedo_grid of its interface (compensated_dielectric_anisotropic_grid).
// The delta models' f and pdf are the contract's constant 0 (shade/bsdf/bsdf.hpp); their rows
// show what that costs.
//
// The binary runs its benchmarks in random interleaved order (see shade_bench::main in
// bench/support.hpp), so that the ratios of a group are not biased by the order in which
// they ran. See bench/support.hpp for names, counters and the callgrind mode.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include <shade/brdf/aliases.hpp>
#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/metals.hpp>
#include <shade/brdf/microfacet.hpp>
#include <shade/bsdf/bsdf.hpp>
#include <shade/bsdf/compensated_rough_dielectric.hpp>
#include <shade/bsdf/rough_dielectric_albedo_grid.hpp>
#include <shade/bsdf/rough_dielectric.hpp>
#include <shade/bsdf/smooth_conductor.hpp>
#include <shade/bsdf/smooth_dielectric.hpp>
#include <shade/bsdf/thin_dielectric.hpp>
#include <shade/core/random.hpp>
#include <shade/core/surface_point.hpp>

#include "support.hpp"

namespace {

constexpr std::size_t input_count = 512;

template <class T>
using v3 = shade::vec3<T>;

template <class T>
struct inputs {
    std::vector<v3<T>> v_above, v_below, l_above, l_below;
    std::vector<T> uc;
    std::vector<shade::vec2<T>> u;
    std::vector<std::uint32_t> order; ///< a random permutation of the indices
    shade::surface_point<T> at;
};

// A unit direction uniform over the hemisphere around +z (sign 1) or -z (sign -1), with
// |cos(theta)| >= 0.05 (rejection from the unit ball).
template <class T>
v3<T> random_direction(shade::rng& g, T sign) {
    for (;;) {
        const v3<T> p(T(2) * g.uniform<T>() - T(1), T(2) * g.uniform<T>() - T(1), sign * g.uniform<T>());
        const T len = glm::length(p);
        if (len > T(0.1) && len <= T(1) && sign * p.z / len >= T(0.05)) return p / len;
    }
}

template <class T>
const inputs<T>& data() {
    static const inputs<T> d = [] {
        shade::rng g(43);
        inputs<T> out;
        for (std::size_t i = 0; i < input_count; ++i) {
            out.v_above.push_back(random_direction<T>(g, T(1)));
            out.v_below.push_back(random_direction<T>(g, T(-1)));
            out.l_above.push_back(random_direction<T>(g, T(1)));
            out.l_below.push_back(random_direction<T>(g, T(-1)));
            out.uc.push_back(g.uniform<T>());
            out.u.emplace_back(g.uniform<T>(), g.uniform<T>());
        }
        out.order = shade_bench::random_order(input_count, 44);
        out.at = shade::surface_point<T>::at(v3<T>(0, 0, 0), v3<T>(0, 0, 1));
        return out;
    }();
    return d;
}

// The six operations of `model` under bsdf/<type>/<operation>/<name>.
template <class B>
void add_model(const std::string& type, const std::string& name, const B& model) {
    using T = typename B::scalar_type;
    const inputs<T>& d = data<T>();
    const std::string prefix = "bsdf/" + type + "/";
    const auto add_f = [&](const std::string& operation, const std::vector<v3<T>>& l) {
        shade_bench::add(prefix + operation + "/" + name, double(input_count), [&d, &l, model] {
            for (const std::uint32_t i : d.order) {
                shade::rgb<T> f = model.f(l[i], d.v_above[i], d.at);
                benchmark::DoNotOptimize(f);
            }
        });
    };
    const auto add_pdf = [&](const std::string& operation, const std::vector<v3<T>>& l) {
        shade_bench::add(prefix + operation + "/" + name, double(input_count), [&d, &l, model] {
            for (const std::uint32_t i : d.order) {
                T p = model.pdf(l[i], d.v_above[i], d.at);
                benchmark::DoNotOptimize(p);
            }
        });
    };
    const auto add_sample = [&](const std::string& operation, const std::vector<v3<T>>& v) {
        shade_bench::add(prefix + operation + "/" + name, double(input_count), [&d, &v, model] {
            for (const std::uint32_t i : d.order) {
                auto s = shade::sample_bsdf(model, v[i], d.uc[i], d.u[i], d.at, shade::transport_mode::radiance);
                benchmark::DoNotOptimize(s);
            }
        });
    };
    add_f("f_reflection", d.l_above);
    add_f("f_transmission", d.l_below);
    add_pdf("pdf_reflection", d.l_above);
    add_pdf("pdf_transmission", d.l_below);
    add_sample("sample_outside", d.v_above);
    add_sample("sample_inside", d.v_below);
}

template <class T>
void register_all(const std::string& type) {
    using shade::beckmann, shade::ggx;
    // Gold: the exact Fresnel of shade::metals::gold (Johnson, Christy 1972), and its reflectance
    // at normal incidence as Schlick's f0.
    const shade::conductor_fresnel<T> gold = shade::metals::gold<T>();
    const shade::rgb<T> gold_f0 = gold.f0();
    const T alpha = T(0.3), eta = T(1.5);
    add_model(type, "ggx_conductor", shade::make_ggx_conductor(alpha, gold_f0));
    add_model(type, "ggx_conductor_exact_fresnel",
              shade::cook_torrance<ggx<T>, shade::conductor_fresnel<T>, shade::smith_height_correlated<T>>(
                  ggx<T>(alpha), gold));
    add_model(type, "smooth_conductor", shade::smooth_conductor<T>(gold));
    add_model(type, "smooth_dielectric", shade::smooth_dielectric<T>(eta));
    add_model(type, "thin_dielectric", shade::thin_dielectric<T>(eta));
    add_model(type, "rough_dielectric_ggx", shade::rough_dielectric<ggx<T>>(ggx<T>(alpha), eta));
    add_model(type, "rough_dielectric_beckmann", shade::rough_dielectric<beckmann<T>>(beckmann<T>(alpha), eta));
    // The grid outlives the models that point to it (a static of this instantiation).
    const ggx<T> anisotropic(T(0.05), T(0.5));
    static const shade::rough_dielectric_albedo_grid<T> grid(anisotropic, eta);
    add_model(type, "compensated_dielectric_anisotropic_tables", shade::compensated_rough_dielectric<T>(anisotropic, eta));
    add_model(type, "compensated_dielectric_anisotropic_grid", shade::compensated_rough_dielectric<T>(anisotropic, eta, grid));
}

const bool registered = [] {
    register_all<float>("float");
    register_all<double>("double");
    return true;
}();

} // namespace

int main(int argc, char** argv) { return shade_bench::main(argc, argv); }
