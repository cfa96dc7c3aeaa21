// Sampling of shade::cook_torrance (sample, pdf): chi^2 of the drawn directions against
// pdf, per-sample consistency with f and pdf, integral of pdf <= 1, the weight variance of
// visible-normal sampling, and deliberately wrong samplers that the chi^2 test must reject.

#include <cmath>
#include <string>

#include <doctest/doctest.h>

#include <shade/brdf/cook_torrance.hpp>

#include "brdf/sampling_support.hpp"
#include "brdf/support.hpp"

using namespace brdf_test;
using shade::vec2;
namespace form = shade::cook_torrance_form;

static_assert(shade::sampled_brdf<shade::cook_torrance<shade::ggx<float>, shade::schlick<float>, shade::smith_ggx<float>>>);
static_assert(shade::sampled_brdf<shade::cook_torrance<shade::beckmann<double>, shade::dielectric_fresnel<double>,
                                                       shade::v_groove<double>, form::paper_1982>>);
static_assert(shade::sampled_brdf<shade::cook_torrance<shade::ggx<double>, shade::schlick<double>,
                                                       shade::smith_height_correlated<double>, form::course>>);

namespace {

// chi^2 tests in this file: about 200; each is rejected at p < 1e-5, so a correct sampler
// fails one of them with probability about 2e-3 (and the seeds are fixed).
constexpr double significance = 1e-5;

// The mirror direction of v about the shading normal, world space: the bins' axis.
template <class T>
vec3<T> mirror(const vec3<T>& v, const shade::surface_point<T>& at) {
    return T(2) * glm::dot(at.n(), v) * at.n() - v;
}

template <class B>
void check_sampler(const B& b, const std::string& name) {
    using T = shade::scalar_of<B>;
    for (const auto& at : {flat<T>(), tilted<T>()}) {
        for (const T theta_v : {T(0), T(0.5), T(1.0471976), T(1.4), T(1.55)}) {
            const vec3<T> v = direction(at, theta_v, T(0.8));
            CAPTURE(name);
            CAPTURE(theta_v);
            const chi2_result chi2 = sampling_chi2(b, v, at, mirror(v, at));
            CAPTURE(chi2.statistic);
            CAPTURE(chi2.dof);
            CAPTURE(chi2.declined);
            CHECK(chi2.p_value > significance);
            // integral of pdf over the sphere <= 1 (the rest is declined samples); the bins'
            // quadrature is good to about 1e-3 here.
            CHECK(chi2.pdf_integral <= 1.003);
            const T rel = sizeof(T) <= 4 ? T(1e-4) : T(1e-10);
            CHECK(check_sample_consistency(b, v, at, 2000, rel) > 0);
        }
    }
}

template <class T, class Masking, class Form = form::walter>
void check_ggx(T ax, T ay, const rgb<T>& k_d, const std::string& name) {
    const shade::cook_torrance<shade::ggx<T>, shade::schlick<T>, Masking, Form> b(
        shade::ggx<T>(ax, ay), shade::schlick<T>(rgb<T>(T(0.9), T(0.6), T(0.3))), rgb<T>(T(0.7)), k_d);
    check_sampler(b, name);
}

template <class T, class Masking, class Form = form::walter>
void check_beckmann(T mx, T my, const rgb<T>& k_d, const std::string& name) {
    const shade::cook_torrance<shade::beckmann<T>, shade::dielectric_fresnel<T>, Masking, Form> b(
        shade::beckmann<T>(mx, my), shade::dielectric_fresnel<T>(T(1.5)), rgb<T>(1), k_d);
    check_sampler(b, name);
}

} // namespace

TEST_CASE_TEMPLATE("cook-torrance sampling: GGX, chi^2 / consistency / integral of pdf", T, float, double) {
    const rgb<T> none(0), some(T(0.5), T(0.3), T(0.1));
    check_ggx<T, shade::smith_ggx<T>>(T(0.01), T(0.01), none, "ggx 0.01, smith");
    check_ggx<T, shade::smith_ggx<T>>(T(1), T(1), none, "ggx 1, smith");
    check_ggx<T, shade::smith_height_correlated<T>>(T(0.05), T(0.5), none, "ggx 0.05 x 0.5, correlated");
    check_ggx<T, shade::v_groove<T>, form::course>(T(0.3), T(0.3), some, "ggx 0.3 + diffuse, v-groove, course");
    check_ggx<T, shade::smith_separable<T>, form::paper_1982>(T(0.5), T(0.05), some, "ggx 0.5 x 0.05 + diffuse, 1982");
}

TEST_CASE_TEMPLATE("cook-torrance sampling: Beckmann, chi^2 / consistency / integral of pdf", T, float, double) {
    const rgb<T> none(0), some(T(0.5), T(0.3), T(0.1));
    check_beckmann<T, shade::smith_beckmann<T>>(T(0.01), T(0.01), none, "beckmann 0.01, rational smith");
    check_beckmann<T, shade::smith_separable<T>>(T(1), T(1), none, "beckmann 1, exact smith");
    check_beckmann<T, shade::smith_height_correlated<T>>(T(0.05), T(0.5), none, "beckmann 0.05 x 0.5, correlated");
    check_beckmann<T, shade::v_groove<T>, form::course>(T(0.3), T(0.3), some, "beckmann 0.3 + diffuse, v-groove, course");
}

TEST_CASE_TEMPLATE("cook-torrance sampling: GGX alpha = 0.01, F = 1: weight nearly constant (relative std dev < 0.05)", T, float, double) {
    // With visible normals and F = 1 the weight is f (n.l)/pdf = G(l, v)/G1(v), which for
    // a smooth surface is close to 1 wherever the lobe is.
    const shade::cook_torrance<shade::ggx<T>, shade::schlick<T>, shade::smith_ggx<T>> b(shade::ggx<T>(T(0.01)),
                                                                                    shade::schlick<T>(rgb<T>(1)));
    for (const auto& at : {flat<T>(), tilted<T>()}) {
        for (const T theta_v : {T(0), T(1.0471976)}) {
            const vec3<T> v = direction(at, theta_v, T(0.3));
            shade::rng random(17);
            double sum = 0, sum2 = 0;
            const int count = 100000;
            for (int i = 0; i < count; ++i) {
                const auto s = b.sample(v, random.uniform<T>(), vec2<T>(random.uniform<T>(), random.uniform<T>()), at);
                const double w = s ? double(s->weight.x) : 0.0;
                sum += w;
                sum2 += w * w;
            }
            const double mean = sum / count;
            const double rsd = std::sqrt(std::max(0.0, sum2 / count - mean * mean)) / mean;
            CAPTURE(theta_v);
            CAPTURE(mean);
            CHECK(rsd < 0.05);
            // The mean weight is the directional albedo: below 1 (energy conserving), above
            // 0.95 for a smooth conductor with F = 1.
            CHECK(mean <= 1.0);
            CHECK(mean > 0.95);
        }
    }
}

namespace {

// A sampler whose pdf is off by a factor (it claims half the density it draws with).
template <class B>
struct pdf_off_by_factor {
    using scalar_type = shade::scalar_of<B>;
    using T = scalar_type;
    B inner;
    rgb<T> f(const vec3<T>& l, const vec3<T>& v, const shade::surface_point<T>& at) const { return inner.f(l, v, at); }
    std::optional<shade::brdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u, const shade::surface_point<T>& at) const {
        return inner.sample(v, uc, u, at);
    }
    T pdf(const vec3<T>& l, const vec3<T>& v, const shade::surface_point<T>& at) const { return T(0.5) * inner.pdf(l, v, at); }
};

// A sampler that draws around the wrong axis: it samples as if v were mirrored across
// the normal's plane through t (a lobe at the wrong azimuth), while pdf is the right one.
template <class B>
struct wrong_axis {
    using scalar_type = shade::scalar_of<B>;
    using T = scalar_type;
    B inner;
    rgb<T> f(const vec3<T>& l, const vec3<T>& v, const shade::surface_point<T>& at) const { return inner.f(l, v, at); }
    std::optional<shade::brdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u, const shade::surface_point<T>& at) const {
        const vec3<T> local = at.shading.to_local(v);
        return inner.sample(at.shading.to_world(vec3<T>(local.x, -local.y, local.z)), uc, u, at);
    }
    T pdf(const vec3<T>& l, const vec3<T>& v, const shade::surface_point<T>& at) const { return inner.pdf(l, v, at); }
};

// Visible normals drawn with the wrong Smith G1 in the density: pdf uses D(h)/(4 v.h) (n.h)
// (the classic D-only sampling density) while the sampler draws visible normals.
template <class B>
struct d_only_pdf {
    using scalar_type = shade::scalar_of<B>;
    using T = scalar_type;
    B inner;
    rgb<T> f(const vec3<T>& l, const vec3<T>& v, const shade::surface_point<T>& at) const { return inner.f(l, v, at); }
    std::optional<shade::brdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u, const shade::surface_point<T>& at) const {
        return inner.sample(v, uc, u, at);
    }
    T pdf(const vec3<T>& l, const vec3<T>& v, const shade::surface_point<T>& at) const {
        const vec3<T> h = glm::normalize(at.shading.to_local(l) + at.shading.to_local(v));
        return inner.distribution().D(h) * h.z / (T(4) * glm::dot(at.shading.to_local(v), h));
    }
};

} // namespace

TEST_CASE_TEMPLATE("cook-torrance sampling: the chi^2 test rejects deliberately wrong samplers", T, float, double) {
    using ggx_model = shade::cook_torrance<shade::ggx<T>, shade::schlick<T>, shade::smith_ggx<T>>;
    using beckmann_model = shade::cook_torrance<shade::beckmann<T>, shade::schlick<T>, shade::smith_beckmann<T>>;
    const shade::schlick<T> f(rgb<T>(T(0.9)));
    for (const auto& at : {flat<T>(), tilted<T>()}) {
        const vec3<T> v = direction(at, T(1.0471976), T(0.8));
        const vec3<T> axis = mirror(v, at);
        for (const T alpha : {T(0.05), T(0.5)}) {
            CAPTURE(alpha);
            const ggx_model g(shade::ggx<T>(alpha, T(2) * alpha), f);
            const beckmann_model b(shade::beckmann<T>(alpha, T(2) * alpha), f);
            // The right samplers pass ...
            CHECK(sampling_chi2(g, v, at, axis).p_value > significance);
            CHECK(sampling_chi2(b, v, at, axis).p_value > significance);
            // ... and each wrong one fails, by far.
            CHECK(sampling_chi2(pdf_off_by_factor<ggx_model>{g}, v, at, axis).p_value < 1e-12);
            CHECK(sampling_chi2(pdf_off_by_factor<beckmann_model>{b}, v, at, axis).p_value < 1e-12);
            CHECK(sampling_chi2(wrong_axis<ggx_model>{g}, v, at, axis).p_value < 1e-12);
            CHECK(sampling_chi2(wrong_axis<beckmann_model>{b}, v, at, axis).p_value < 1e-12);
            CHECK(sampling_chi2(d_only_pdf<ggx_model>{g}, v, at, axis).p_value < 1e-12);
            CHECK(sampling_chi2(d_only_pdf<beckmann_model>{b}, v, at, axis).p_value < 1e-12);
        }
    }
}

TEST_CASE_TEMPLATE("cook-torrance sampling: nullopt below the surface, lobe choice and mixture pdf", T, float, double) {
    const auto at = tilted<T>();
    const rgb<T> k_d(T(0.4), T(0.2), T(0.1));
    const shade::cook_torrance<shade::ggx<T>, shade::schlick<T>, shade::smith_ggx<T>> b(
        shade::ggx<T>(T(0.2)), shade::schlick<T>(rgb<T>(T(0.04))), rgb<T>(1), k_d);
    // v below or on the horizon: nullopt for every uc, u; pdf 0.
    const vec3<T> below = direction(at, T(2), T(0.5));
    CHECK(!b.sample(below, T(0.2), vec2<T>(T(0.3), T(0.6)), at));
    CHECK(!b.sample(below, T(0.9), vec2<T>(T(0.3), T(0.6)), at));
    CHECK(b.pdf(at.n(), below, at) == T(0));
    CHECK(b.pdf(below, at.n(), at) == T(0));
    // P_s from the albedo estimate: w_s = max(k_s F(n.v)) * 4 * 1/4, w_d = max(k_d) = 0.4.
    // At v = n, F = f0 = 0.04: P_s = 0.04/0.44 = 1/11 -> clamped to 0.1.
    CHECK(close(b.specular_probability(T(1)), T(0.1), T(1e-6)));
    // At n.v = 0.2: F = 0.04 + 0.96 * 0.8^5 = 0.354568: P_s = 0.354568/0.754568.
    CHECK(close(b.specular_probability(T(0.2)), T(0.354568) / T(0.754568), T(1e-5)));
    // The pdf is the mixture: P_s G1(v) D(h)/(4 n.v) + (1 - P_s) n.l/pi; at l = v = n,
    // h = n: G1 = 1, D = 1/(pi 0.04): 0.1 * 25/(4 pi) + 0.9/pi = (0.625 + 0.9)/pi.
    CHECK(close(b.pdf(at.n(), at.n(), at), T(1.525) / shade::pi<T>, T(1e-5)));
    // Without k_d the specular lobe is always chosen, without k_s the diffuse one.
    const shade::cook_torrance<shade::ggx<T>, shade::schlick<T>, shade::smith_ggx<T>> spec(
        shade::ggx<T>(T(0.2)), shade::schlick<T>(rgb<T>(T(0.04))));
    const shade::cook_torrance<shade::ggx<T>, shade::schlick<T>, shade::smith_ggx<T>> diffuse(
        shade::ggx<T>(T(0.2)), shade::schlick<T>(rgb<T>(T(0.04))), rgb<T>(0), k_d);
    CHECK(spec.specular_probability(T(0.5)) == T(1));
    CHECK(diffuse.specular_probability(T(0.5)) == T(0));
    CHECK(close(diffuse.pdf(at.n(), at.n(), at), shade::inv_pi<T>, T(1e-6)));
}
