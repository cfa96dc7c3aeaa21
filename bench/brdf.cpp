// BRDF evaluation and sampling of every reflection model in shade/brdf, in float and double.
//
//   brdf/<type>/<model>                      f(l, v) on 512 precomputed direction pairs (both
//                                            above the surface, so no model takes its early
//                                            "below the horizon" exit); baseline lambert.
//   brdf_sampling/<type>/<model>/<variant>   the same model's f, sample(v, uc, u) and pdf(l, v)
//                                            on the same pairs and 512 random (uc, u) (sample
//                                            and pdf for the models that sample), and
//                                            legacy_f: f of the model as it was before the
//                                            sampling redesign (bench/legacy/, the same
//                                            parameters; none for the zeltner_sheen
//                                            models and eon, which came after it);
//                                            baseline f.
//                                            Floors of what a sampler cannot avoid:
//                                            lambert/cosine_direction (the cosine-hemisphere
//                                            map of u and the frame, no BRDF at all),
//                                            {phong,blinn_phong}/power_cosine_direction (the
//                                            power-cosine map, exponent 32, and the frame) and
//                                            cook_torrance_{ggx,beckmann}_smith/visible_normal
//                                            (the distribution's visible-normal draw alone).
//
// The binary runs its benchmarks in random interleaved order (Google Benchmark's
// --benchmark_enable_random_interleaving, switched on in main below unless given), so
// that the ratios inside a group are not biased by the order in which they ran.
// See bench/support.hpp for names, counters and the callgrind mode.

#include <cstddef>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include <shade/brdf/ashikhmin_shirley.hpp>
#include <shade/brdf/blinn_phong.hpp>
#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/eon.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/brdf/microfacet.hpp>
#include <shade/brdf/oren_nayar.hpp>
#include <shade/brdf/phong.hpp>
#include <shade/brdf/sheen.hpp>
#include <shade/core/random.hpp>
#include <shade/core/surface_point.hpp>

#include "legacy/ashikhmin_shirley.hpp"
#include "legacy/blinn_phong.hpp"
#include "legacy/cook_torrance.hpp"
#include "legacy/lambert.hpp"
#include "legacy/oren_nayar.hpp"
#include "legacy/phong.hpp"
#include "support.hpp"

namespace {

constexpr std::size_t pair_count = 512;

template <class T>
using v3 = shade::vec3<T>;

template <class T>
struct inputs {
    std::vector<v3<T>> l, v;
    std::vector<T> uc;
    std::vector<shade::vec2<T>> u;
    shade::surface_point<T> at;
};

// Unit directions uniformly distributed over the upper hemisphere around n = (0, 0, 1),
// with cos(theta) >= 0.05 so that every pair takes a model's full evaluation path.
template <class T>
v3<T> random_upper(shade::rng& g) {
    for (;;) {
        const v3<T> p(T(2) * g.uniform<T>() - T(1), T(2) * g.uniform<T>() - T(1), g.uniform<T>());
        const T len = glm::length(p);
        if (len > T(0.1) && len <= T(1) && p.z / len >= T(0.05)) return p / len;
    }
}

template <class T>
const inputs<T>& data() {
    static const inputs<T> d = [] {
        shade::rng g(41);
        inputs<T> out;
        for (std::size_t i = 0; i < pair_count; ++i) {
            out.l.push_back(random_upper<T>(g));
            out.v.push_back(random_upper<T>(g));
        }
        for (std::size_t i = 0; i < pair_count; ++i) {
            out.uc.push_back(g.uniform<T>());
            out.u.emplace_back(g.uniform<T>(), g.uniform<T>());
        }
        out.at = shade::surface_point<T>::at(v3<T>(0, 0, 0), v3<T>(0, 0, 1));
        return out;
    }();
    return d;
}

template <class B>
void add_f(const std::string& name, const B& model) {
    using T = typename B::scalar_type;
    const inputs<T>& d = data<T>();
    shade_bench::add(name, double(pair_count), [&d, model] {
        for (std::size_t i = 0; i < pair_count; ++i) {
            shade::rgb<T> f = model.f(d.l[i], d.v[i], d.at);
            benchmark::DoNotOptimize(f);
        }
    });
}

template <class B>
void add_sampling(const std::string& group, const B& model);

// f of the new model under brdf/<type>/<name>, and f, sample, pdf (when it samples) of the
// new model and f of the legacy one under brdf_sampling/<type>/<name>/.
template <class B, class Legacy>
void add_model(const std::string& type, const std::string& name, const B& model, const Legacy& legacy) {
    add_f("brdf/" + type + "/" + name, model);
    const std::string group = "brdf_sampling/" + type + "/" + name + "/";
    add_f(group + "f", model);
    add_f(group + "legacy_f", legacy);
    if constexpr (shade::sampled_brdf<B>) add_sampling(group, model);
}

// As above for a model that has no legacy version (written after the sampling redesign).
template <class B>
void add_model(const std::string& type, const std::string& name, const B& model) {
    add_f("brdf/" + type + "/" + name, model);
    const std::string group = "brdf_sampling/" + type + "/" + name + "/";
    add_f(group + "f", model);
    if constexpr (shade::sampled_brdf<B>) add_sampling(group, model);
}

// sample(v, uc, u) and pdf(l, v) of `model` under group + "sample" and group + "pdf".
template <class B>
void add_sampling(const std::string& group, const B& model) {
    using T = typename B::scalar_type;
    const inputs<T>& d = data<T>();
    shade_bench::add(group + "sample", double(pair_count), [&d, model] {
        for (std::size_t i = 0; i < pair_count; ++i) {
            auto s = model.sample(d.v[i], d.uc[i], d.u[i], d.at);
            benchmark::DoNotOptimize(s);
        }
    });
    shade_bench::add(group + "pdf", double(pair_count), [&d, model] {
        for (std::size_t i = 0; i < pair_count; ++i) {
            T p = model.pdf(d.l[i], d.v[i], d.at);
            benchmark::DoNotOptimize(p);
        }
    });
}

// The direction a cosine sampler draws (square_to_cosine_hemisphere, then the frame), and
// the visible normal a microfacet sampler draws, with no BRDF evaluated: the part of sample()
// that no implementation of it can skip.
template <class T>
void add_sampling_floors(const std::string& type) {
    const inputs<T>& d = data<T>();
    shade_bench::add("brdf_sampling/" + type + "/lambert/cosine_direction", double(pair_count), [&d] {
        for (std::size_t i = 0; i < pair_count; ++i) {
            v3<T> l = d.at.shading.to_world(shade::square_to_cosine_hemisphere(d.u[i]));
            benchmark::DoNotOptimize(l);
        }
    });
    // The power-cosine map the Phong and Blinn-Phong lobes draw from (exponent 32, as their
    // models below), into the shading frame: less than either lobe's draw (Phong also builds
    // a frame about the mirror direction, Blinn-Phong reflects v about the drawn h).
    const auto add_power_cosine = [&d](const std::string& name) {
        shade_bench::add(name, double(pair_count), [&d] {
            for (std::size_t i = 0; i < pair_count; ++i) {
                v3<T> l = d.at.shading.to_world(shade::square_to_power_cosine_hemisphere(d.u[i], T(32)));
                benchmark::DoNotOptimize(l);
            }
        });
    };
    add_power_cosine("brdf_sampling/" + type + "/phong/power_cosine_direction");
    add_power_cosine("brdf_sampling/" + type + "/blinn_phong/power_cosine_direction");
    const auto add_visible_normal = [&d](const std::string& name, const auto& distribution) {
        shade_bench::add(name, double(pair_count), [&d, distribution] {
            for (std::size_t i = 0; i < pair_count; ++i) {
                v3<T> m = distribution.sample_visible_normal(d.at.shading.to_local(d.v[i]), d.u[i]);
                benchmark::DoNotOptimize(m);
            }
        });
    };
    add_visible_normal("brdf_sampling/" + type + "/cook_torrance_ggx_smith/visible_normal", shade::ggx<T>(T(0.3)));
    add_visible_normal("brdf_sampling/" + type + "/cook_torrance_beckmann_smith/visible_normal",
                       shade::beckmann<T>(T(0.3)));
}

template <class T>
void register_all(const std::string& type) {
    namespace old = shade_legacy;
    const shade::rgb<T> k_d(T(0.5), T(0.4), T(0.3));
    const shade::rgb<T> k_s(T(0.04));
    const shade::rgb<T> f0(T(0.95), T(0.64), T(0.54));
    add_model(type, "lambert", shade::lambert<T>(k_d), old::lambert<T>(k_d));
    add_model(type, "phong", shade::phong<T>(k_d, k_s, T(32)), old::phong<T>(k_d, k_s, T(32)));
    add_model(type, "blinn_phong", shade::blinn_phong<T>(k_d, k_s, T(32)), old::blinn_phong<T>(k_d, k_s, T(32)));
    add_model(type, "oren_nayar_trig", shade::oren_nayar_trig<T>(k_d, T(0.3)), old::oren_nayar_trig<T>(k_d, T(0.3)));
    add_model(type, "oren_nayar_trig_free", shade::oren_nayar<T>(k_d, T(0.3)), old::oren_nayar<T>(k_d, T(0.3)));
    add_model(type, "eon", shade::eon<T>(k_d, T(0.5)));
    add_model(type, "eon_approximate", shade::eon<T, shade::eon_albedo::approximate>(k_d, T(0.5)));
    add_model(type, "ashikhmin_shirley", shade::ashikhmin_shirley<T>(k_d, k_s, T(10), T(100)),
              old::ashikhmin_shirley<T>(k_d, k_s, T(10), T(100)));
    using shade::beckmann, shade::ggx, shade::schlick;
    add_model(type, "cook_torrance_beckmann_v_groove",
              shade::cook_torrance<beckmann<T>, schlick<T>, shade::v_groove<T>>(beckmann<T>(T(0.3)), schlick<T>(f0),
                                                                               shade::rgb<T>(1), k_d),
              old::cook_torrance<old::beckmann<T>, old::schlick<T>, old::v_groove<T>>(
                  old::beckmann<T>(T(0.3)), old::schlick<T>(f0), shade::rgb<T>(1), k_d));
    add_model(type, "cook_torrance_beckmann_smith",
              shade::cook_torrance<beckmann<T>, schlick<T>, shade::smith_beckmann<T>>(
                  beckmann<T>(T(0.3)), schlick<T>(f0), shade::rgb<T>(1), k_d),
              old::cook_torrance<old::beckmann<T>, old::schlick<T>, old::smith_beckmann<T>>(
                  old::beckmann<T>(T(0.3)), old::schlick<T>(f0), shade::rgb<T>(1), k_d));
    add_model(type, "cook_torrance_ggx_v_groove",
              shade::cook_torrance<ggx<T>, schlick<T>, shade::v_groove<T>>(ggx<T>(T(0.3)), schlick<T>(f0),
                                                                          shade::rgb<T>(1), k_d),
              old::cook_torrance<old::ggx<T>, old::schlick<T>, old::v_groove<T>>(
                  old::ggx<T>(T(0.3)), old::schlick<T>(f0), shade::rgb<T>(1), k_d));
    add_model(type, "cook_torrance_ggx_smith",
              shade::cook_torrance<ggx<T>, schlick<T>, shade::smith_ggx<T>>(ggx<T>(T(0.3)), schlick<T>(f0),
                                                                           shade::rgb<T>(1), k_d),
              old::cook_torrance<old::ggx<T>, old::schlick<T>, old::smith_ggx<T>>(
                  old::ggx<T>(T(0.3)), old::schlick<T>(f0), shade::rgb<T>(1), k_d));
    add_model(type, "zeltner_sheen", shade::zeltner_sheen<T>(k_d, T(0.5)));
    add_model(type, "zeltner_sheen_reciprocal", shade::zeltner_sheen_reciprocal<T>(k_d, T(0.5)));
    add_sampling_floors<T>(type);
}

const bool registered = [] {
    register_all<float>("float");
    register_all<double>("double");
    return true;
}();

} // namespace

// Google Benchmark's main with random interleaving switched on unless the command line
// sets it (bench/support.hpp).
int main(int argc, char** argv) { return shade_bench::main(argc, argv); }
