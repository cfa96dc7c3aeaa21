#include <cmath>

#include <doctest/doctest.h>

#include <shade/brdf/cook_torrance.hpp>

#include "brdf/support.hpp"

using namespace brdf_test;
namespace form = shade::cook_torrance_form;

template <class T>
using beckmann_v_groove = shade::cook_torrance<shade::beckmann<T>, shade::schlick<T>, shade::v_groove<T>>;
template <class T>
using ggx_smith = shade::cook_torrance<shade::ggx<T>, shade::schlick<T>, shade::smith_ggx<T>>;

static_assert(shade::split_brdf<beckmann_v_groove<float>>);
static_assert(shade::split_brdf<ggx_smith<double>>);
static_assert(shade::split_brdf<shade::cook_torrance<shade::beckmann<float>, shade::dielectric_fresnel<float>,
                                                     shade::smith_beckmann<float>, form::paper_1982>>);
// m_x, m_y and the three reciprocals D uses, f0, k_s, k_d: the stateless G takes no space.
static_assert(sizeof(beckmann_v_groove<float>) == sizeof(float) * 14);

namespace {

template <class T>
constexpr T tol = sizeof(T) <= 4 ? T(1e-5) : T(1e-12);

} // namespace

TEST_CASE_TEMPLATE("cook-torrance: hand values at l = v = n", T, float, double) {
    // h = n: D = 1/(pi m^2), G = 1 (V-groove and Smith), F = F(1) = f0, n.l = n.v = 1.
    // Walter:  f_s = f0 D / 4       = f0 / (4 pi m^2)
    // course:  f_s = f0 D / pi      = f0 / (pi^2 m^2)
    // paper:   f_s = f0 D           = f0 / (pi m^2)
    // m = 0.5, f0 = 0.04, k_s = 1: Walter 0.04/pi, course 0.16/pi^2, paper 0.16/pi.
    for (const auto& at : {flat<T>(), tilted<T>()}) {
        const shade::beckmann<T> d(T(0.5));
        const shade::schlick<T> f(rgb<T>(T(0.04)));
        const beckmann_v_groove<T> walter(d, f);
        const shade::cook_torrance<shade::beckmann<T>, shade::schlick<T>, shade::v_groove<T>, form::course> course(d, f);
        const shade::cook_torrance<shade::beckmann<T>, shade::schlick<T>, shade::v_groove<T>, form::paper_1982> paper(d, f);
        const auto n = at.n();
        CHECK(close(walter.f(n, n, at), rgb<T>(T(0.04) / shade::pi<T>), tol<T>));
        CHECK(close(course.f(n, n, at), rgb<T>(T(0.16) / (shade::pi<T> * shade::pi<T>)), tol<T>));
        CHECK(close(paper.f(n, n, at), rgb<T>(T(0.16) / shade::pi<T>), tol<T>));
        // GGX + Smith: G1(1) = 1; alpha = 0.25: D = 16/pi, f_s = f0 * 16/(4 pi) = 0.16/pi.
        const ggx_smith<T> g(shade::ggx<T>(T(0.25)), f);
        CHECK(close(g.f(n, n, at), rgb<T>(T(0.16) / shade::pi<T>), tol<T>));
    }
}

TEST_CASE_TEMPLATE("cook-torrance: hand values for a mirror pair at 60 degrees", T, float, double) {
    // l at 60 deg, v its mirror image: h = n, D = 1/(pi m^2), v.h = n.l = n.v = 1/2,
    // F = f0 + (1 - f0)/32. V-groove G = min(1, 2*1*(1/2)/(1/2)) = 1.
    // Walter: f_s = F D / (4 * 1/4) = F/(pi m^2). m = 0.5: 4F/pi.
    for (const auto& at : {flat<T>(), tilted<T>()}) {
        const rgb<T> f0(T(0.04), T(0.5), T(0.9));
        const rgb<T> F = f0 + (rgb<T>(1) - f0) / T(32);
        const auto l = direction(at, shade::pi<T> / 3, T(0.25));
        const auto v = direction(at, shade::pi<T> / 3, T(0.25) + shade::pi<T>);
        const beckmann_v_groove<T> model(shade::beckmann<T>(T(0.5)), shade::schlick<T>(f0));
        CHECK(close(model.f(l, v, at), T(4) / shade::pi<T> * F, T(10) * tol<T>));
        // GGX alpha = 0.5 with Smith: D = 4/pi; G1(1/2) = 1/(1/2 + sqrt(1/4 + 0.25*0.75)) =
        // 1/(0.5 + sqrt(0.4375)); G = G1^2; f_s = F (4/pi) G1^2.
        const T g1 = T(1) / (T(0.5) + std::sqrt(T(0.4375)));
        const ggx_smith<T> g(shade::ggx<T>(T(0.5)), shade::schlick<T>(f0));
        CHECK(close(g.f(l, v, at), T(4) / shade::pi<T> * g1 * g1 * F, T(10) * tol<T>));
    }
}

TEST_CASE_TEMPLATE("cook-torrance: the forms differ from the default by 4/pi and 4", T, float, double) {
    const auto at = tilted<T>();
    const shade::ggx<T> d(T(0.3));
    const shade::dielectric_fresnel<T> f(T(1.5));
    const shade::cook_torrance<shade::ggx<T>, shade::dielectric_fresnel<T>, shade::smith_ggx<T>> walter(d, f);
    const shade::cook_torrance<shade::ggx<T>, shade::dielectric_fresnel<T>, shade::smith_ggx<T>, form::course> course(d, f);
    const shade::cook_torrance<shade::ggx<T>, shade::dielectric_fresnel<T>, shade::smith_ggx<T>, form::paper_1982> paper(d, f);
    CHECK(form::course::factor_vs_walter == doctest::Approx(4.0 / shade::pi<double>));
    CHECK(form::paper_1982::factor_vs_walter == 4.0);
    for (const auto& p : random_pairs(at, 300)) {
        const rgb<T> w = walter.f(p.l, p.v, at);
        CHECK(close(course.f(p.l, p.v, at), w * T(4) / shade::pi<T>, tol<T>));
        CHECK(close(paper.f(p.l, p.v, at), w * T(4), tol<T>));
    }
}

TEST_CASE_TEMPLATE("cook-torrance: Lambert base plus k_s-weighted specular, split for lit", T, float, double) {
    // f = k_d/pi + k_s f_s; f_diffuse and f_specular are the two parts.
    const auto at = tilted<T>();
    const rgb<T> k_d(T(0.3), T(0.2), T(0.1)), k_s(T(0.5));
    const beckmann_v_groove<T> spec_only(shade::beckmann<T>(T(0.4)), shade::schlick<T>(rgb<T>(T(0.05))));
    const beckmann_v_groove<T> mixed(shade::beckmann<T>(T(0.4)), shade::schlick<T>(rgb<T>(T(0.05))), k_s, k_d);
    for (const auto& p : random_pairs(at, 100)) {
        CHECK(close(mixed.f_diffuse(p.l, p.v, at), k_d / shade::pi<T>, tol<T>));
        CHECK(close(mixed.f_specular(p.l, p.v, at), k_s * spec_only.f(p.l, p.v, at), tol<T>));
        CHECK(close(mixed.f(p.l, p.v, at), mixed.f_diffuse(p.l, p.v, at) + mixed.f_specular(p.l, p.v, at), tol<T>));
    }
}

TEST_CASE_TEMPLATE("cook-torrance: reciprocal to the last bit", T, float, double) {
    // Every factor is computed symmetrically (h from l + v, v.h from |l + v|, products of
    // n.l and n.v), so f(l, v) and f(v, l) are the same floating-point number.
    const auto at = tilted<T>();
    const beckmann_v_groove<T> a(shade::beckmann<T>(T(0.2)), shade::schlick<T>(rgb<T>(T(0.3))));
    const ggx_smith<T> b(shade::ggx<T>(T(0.2)), shade::schlick<T>(rgb<T>(T(0.3))));
    for (const auto& p : random_pairs(at, 1000)) {
        CHECK(a.f(p.l, p.v, at) == a.f(p.v, p.l, at));
        CHECK(b.f(p.l, p.v, at) == b.f(p.v, p.l, at));
    }
}

TEST_CASE_TEMPLATE("cook-torrance: zero below, finite and non-negative for degenerate pairs and extreme roughness", T, float, double) {
    const rgb<T> k_s(T(0.8)), k_d(T(0.2));
    for (const auto& at : {flat<T>(), tilted<T>()}) {
        for (const T r : {T(1e-4), T(0.5), T(1)}) {
            CAPTURE(r);
            const shade::schlick<T> f(rgb<T>(T(0.9)));
            const shade::dielectric_fresnel<T> fd(T(1.5));
            const beckmann_v_groove<T> a(shade::beckmann<T>(r), f, k_s, k_d);
            const shade::cook_torrance<shade::beckmann<T>, shade::dielectric_fresnel<T>, shade::smith_beckmann<T>, form::paper_1982> b(shade::beckmann<T>(r), fd, k_s, k_d);
            const ggx_smith<T> c(shade::ggx<T>(r), f, k_s, k_d);
            const shade::cook_torrance<shade::ggx<T>, shade::schlick<T>, shade::v_groove<T>, form::course> d(shade::ggx<T>(r), f, k_s, k_d);
            check_zero_below(a, at);
            check_zero_below(c, at);
            check_finite_non_negative(a, at);
            check_finite_non_negative(b, at);
            check_finite_non_negative(c, at);
            check_finite_non_negative(d, at);
        }
    }
}

TEST_CASE_TEMPLATE("cook-torrance: invalid parameters throw naming the parameter", T, float, double) {
    const shade::beckmann<T> d(T(0.3));
    const shade::schlick<T> f(rgb<T>(T(0.04)));
    check_throws_naming([&] { (void)beckmann_v_groove<T>(d, f, rgb<T>(-1)); }, "k_s");
    check_throws_naming([&] { (void)beckmann_v_groove<T>(d, f, rgb<T>(1), rgb<T>(0, std::numeric_limits<T>::quiet_NaN(), 0)); }, "k_d");
    check_throws_naming([&] { (void)beckmann_v_groove<T>(d, f, rgb<T>(std::numeric_limits<T>::max())); }, "k_s");
    CHECK_NOTHROW((void)beckmann_v_groove<T>(shade::unchecked, d, f, rgb<T>(-1)));
}

TEST_CASE_TEMPLATE("cook-torrance: an overflowing peak names the distribution's parameter", T, float, double) {
    const shade::schlick<T> f(rgb<T>(T(0.04)));
    // ggx(unchecked, 0): D(n) = 1/(pi 0) = inf: the fault is alpha's, not k_s's.
    check_throws_naming([&] { (void)ggx_smith<T>(shade::ggx<T>(shade::unchecked, T(0)), f); }, "alpha");
    check_throws_naming([&] { (void)ggx_smith<T>(shade::ggx<T>(shade::unchecked, T(0.5), T(0)), f); }, "alpha_y");
    check_throws_naming([&] { (void)beckmann_v_groove<T>(shade::beckmann<T>(shade::unchecked, T(0)), f); }, "m");
    check_throws_naming([&] { (void)beckmann_v_groove<T>(shade::beckmann<T>(shade::unchecked, std::numeric_limits<T>::quiet_NaN()), f); }, "m");
    // A valid distribution with a huge k_s still names k_s.
    check_throws_naming([&] { (void)ggx_smith<T>(shade::ggx<T>(T(0.3)), f, rgb<T>(std::numeric_limits<T>::max())); }, "k_s");
}

TEST_CASE_TEMPLATE("cook-torrance: anisotropic hand values follow the frame's tangent", T, float, double) {
    // GGX (0.2, 0.5), Smith, F0 = 0.04, l = v = n: D = 1/(pi 0.1), G = 1:
    // f = 0.04 D / 4 = 0.1/pi.
    using model = shade::cook_torrance<shade::ggx<T>, shade::schlick<T>, shade::smith_separable<T>>;
    const model aniso(shade::ggx<T>(T(0.2), T(0.5)), shade::schlick<T>(rgb<T>(T(0.04))));
    for (const auto& at : {flat<T>(), tilted<T>()}) {
        CHECK(close(aniso.f(at.n(), at.n(), at), rgb<T>(T(0.1) / shade::pi<T>), tol<T>));
        // v = n, l at 2 theta_h in the t-n plane: h at theta_h along t, where
        // D = (alpha_x/alpha_y) D_ggx(cos theta_h, alpha_x) (see test_ggx); in the b-n plane
        // (alpha_y/alpha_x) D_ggx(cos theta_h, alpha_y). f = F(v.h) D G1(l) G1(v) / (4 n.l).
        const T theta_h = T(0.3);
        for (const T phi : {T(0), shade::pi<T> / 2}) {
            const vec3<T> l = direction(at, T(2) * theta_h, phi);
            const T alpha_along = phi == T(0) ? T(0.2) : T(0.5);
            const T ratio = phi == T(0) ? T(0.4) : T(2.5);
            const T D = ratio * shade::D_ggx(std::cos(theta_h), alpha_along);
            const T g1_l = shade::G1_smith_ggx(std::cos(T(2) * theta_h), alpha_along);
            const rgb<T> F = shade::F_schlick(rgb<T>(T(0.04)), std::cos(theta_h));
            CAPTURE(phi);
            CHECK(close(aniso.f(l, at.n(), at), F * (D * g1_l / (T(4) * std::cos(T(2) * theta_h))), T(20) * tol<T>));
        }
    }
}

namespace {

// A distribution written against the cosine-only contract (user code from before the
// local-frame terms): it must keep working in cook_torrance.
template <class T>
struct cosine_only_ggx {
    using scalar_type = T;
    [[nodiscard]] T D(T n_dot_h) const noexcept { return shade::D_ggx(n_dot_h, T(0.25)); }
    [[nodiscard]] T peak() const noexcept { return T(16) / shade::pi<T>; }
};

} // namespace

TEST_CASE_TEMPLATE("cook-torrance: a cosine-only user distribution still works (no sampling)", T, float, double) {
    using model = shade::cook_torrance<cosine_only_ggx<T>, shade::schlick<T>, shade::v_groove<T>>;
    static_assert(shade::split_brdf<model>);
    static_assert(!shade::sampled_brdf<model>);
    const model b(cosine_only_ggx<T>{}, shade::schlick<T>(rgb<T>(T(0.04))));
    // l = v = n: D = 16/pi, G = 1: f = 0.04 * 16/(4 pi) = 0.16/pi (as ggx_smith above).
    const auto at = tilted<T>();
    CHECK(close(b.f(at.n(), at.n(), at), rgb<T>(T(0.16) / shade::pi<T>), tol<T>));
    check_throws_naming([&] { (void)shade::cook_torrance<cosine_only_ggx<T>, shade::schlick<T>, shade::v_groove<T>>(
                            cosine_only_ggx<T>{}, shade::schlick<T>(rgb<T>(T(0.04))), rgb<T>(-1)); }, "k_s");
}

TEST_CASE_TEMPLATE("cook-torrance: height-correlated and separable Smith forms are reciprocal and finite", T, float, double) {
    const auto at = tilted<T>();
    const shade::cook_torrance<shade::beckmann<T>, shade::schlick<T>, shade::smith_height_correlated<T>> a(
        shade::beckmann<T>(T(0.05), T(0.5)), shade::schlick<T>(rgb<T>(T(0.3))));
    const shade::cook_torrance<shade::ggx<T>, shade::schlick<T>, shade::smith_separable<T>> b(
        shade::ggx<T>(T(0.5), T(0.05)), shade::schlick<T>(rgb<T>(T(0.3))));
    for (const auto& p : random_pairs(at, 1000)) {
        CHECK(a.f(p.l, p.v, at) == a.f(p.v, p.l, at));
        CHECK(b.f(p.l, p.v, at) == b.f(p.v, p.l, at));
    }
    check_finite_non_negative(a, at);
    check_finite_non_negative(b, at);
    check_zero_below(a, at);
}
