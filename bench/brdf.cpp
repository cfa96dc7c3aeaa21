// BRDF evaluation: f(l, v, at) of every reflection model in shade/brdf, in float and
// double, on the same 512 precomputed direction pairs (both above the surface, so no
// model takes its early "below the horizon" exit). Includes the trig-based and the
// trig-free Oren-Nayar evaluation, and Cook-Torrance with each distribution / masking
// pair. See bench/support.hpp for names, counters and the callgrind mode.

#include <cstddef>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include <shade/brdf/ashikhmin_shirley.hpp>
#include <shade/brdf/blinn_phong.hpp>
#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/brdf/microfacet.hpp>
#include <shade/brdf/oren_nayar.hpp>
#include <shade/brdf/phong.hpp>
#include <shade/core/random.hpp>
#include <shade/core/surface_point.hpp>

#include "support.hpp"

namespace {

constexpr std::size_t pair_count = 512;

template <class T>
using v3 = shade::vec3<T>;

template <class T>
struct directions {
    std::vector<v3<T>> l, v;
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
const directions<T>& data() {
    static const directions<T> d = [] {
        shade::rng g(41);
        directions<T> out;
        for (std::size_t i = 0; i < pair_count; ++i) {
            out.l.push_back(random_upper<T>(g));
            out.v.push_back(random_upper<T>(g));
        }
        out.at = shade::surface_point<T>::at(v3<T>(0, 0, 0), v3<T>(0, 0, 1));
        return out;
    }();
    return d;
}

template <class B>
void add_model(const std::string& group, const std::string& name, const B& model) {
    using T = typename B::scalar_type;
    const directions<T>& d = data<T>();
    shade_bench::add(group + name, double(pair_count), [&d, model] {
        for (std::size_t i = 0; i < pair_count; ++i) {
            shade::rgb<T> f = model.f(d.l[i], d.v[i], d.at);
            benchmark::DoNotOptimize(f);
        }
    });
}

template <class T>
void register_all(const char* type) {
    const std::string group = std::string("brdf/") + type + "/";
    const shade::rgb<T> k_d(T(0.5), T(0.4), T(0.3));
    const shade::rgb<T> k_s(T(0.04));
    const shade::rgb<T> f0(T(0.95), T(0.64), T(0.54));
    add_model(group, "lambert", shade::lambert<T>(k_d));
    add_model(group, "phong", shade::phong<T>(k_d, k_s, T(32)));
    add_model(group, "blinn_phong", shade::blinn_phong<T>(k_d, k_s, T(32)));
    add_model(group, "oren_nayar_trig", shade::oren_nayar_trig<T>(k_d, T(0.3)));
    add_model(group, "oren_nayar_trig_free", shade::oren_nayar<T>(k_d, T(0.3)));
    add_model(group, "ashikhmin_shirley", shade::ashikhmin_shirley<T>(k_d, k_s, T(10), T(100)));
    using shade::beckmann, shade::ggx, shade::schlick;
    add_model(group, "cook_torrance_beckmann_v_groove",
              shade::cook_torrance<beckmann<T>, schlick<T>, shade::v_groove<T>>(
                  beckmann<T>(T(0.3)), schlick<T>(f0), shade::rgb<T>(1), k_d));
    add_model(group, "cook_torrance_beckmann_smith",
              shade::cook_torrance<beckmann<T>, schlick<T>, shade::smith_beckmann<T>>(
                  beckmann<T>(T(0.3)), schlick<T>(f0), shade::rgb<T>(1), k_d));
    add_model(group, "cook_torrance_ggx_v_groove",
              shade::cook_torrance<ggx<T>, schlick<T>, shade::v_groove<T>>(
                  ggx<T>(T(0.3)), schlick<T>(f0), shade::rgb<T>(1), k_d));
    add_model(group, "cook_torrance_ggx_smith",
              shade::cook_torrance<ggx<T>, schlick<T>, shade::smith_ggx<T>>(
                  ggx<T>(T(0.3)), schlick<T>(f0), shade::rgb<T>(1), k_d));
}

const bool registered = [] {
    register_all<float>("float");
    register_all<double>("double");
    return true;
}();

} // namespace
