#include <algorithm>
#include <cmath>
#include <numbers>

#include <doctest/doctest.h>

#include <shade/brdf/ashikhmin_shirley.hpp>

#include "brdf/support.hpp"
#include "brdf/sampling.hpp"

using namespace brdf_test;

static_assert(shade::split_brdf<shade::ashikhmin_shirley<float>>);
static_assert(shade::split_brdf<shade::ashikhmin_shirley<double>>);

namespace {

template <class T>
constexpr T tol = sizeof(T) <= 4 ? T(2e-5) : T(1e-12);

} // namespace

TEST_CASE_TEMPLATE("ashikhmin-shirley: hand values at l = v = n", T, float, double) {
    // h = n: (n.h)^e = 1, v.h = 1, max(n.l, n.v) = 1, F = R_s.
    // f_s = sqrt((p_u+1)(p_v+1))/(8 pi) R_s; p_u = 3, p_v = 15: sqrt(64) = 8: f_s = R_s/pi.
    // f_d = 28 R_d/(23 pi) (1 - R_s) (1 - (1/2)^5)^2 = 28/(23 pi) (31/32)^2 R_d (1 - R_s).
    const rgb<T> r_d(T(0.5), T(0.3), T(0.1)), r_s(T(0.05), T(0.1), T(0.2));
    const shade::ashikhmin_shirley<T> model(r_d, r_s, T(3), T(15));
    for (const auto& at : {flat<T>(), tilted<T>()}) {
        const auto n = at.n();
        CHECK(close(model.f_specular(n, n, at), r_s / shade::pi<T>, tol<T>));
        const T k = T(28) / (T(23) * shade::pi<T>) * shade::sqr(T(31) / T(32));
        CHECK(close(model.f_diffuse(n, n, at), k * r_d * (rgb<T>(1) - r_s), tol<T>));
    }
}

TEST_CASE_TEMPLATE("ashikhmin-shirley: mirror pair and the anisotropic exponent along t and b", T, float, double) {
    const rgb<T> r_s(T(0.1));
    const T p_u = T(10), p_v = T(100);
    const T c = std::sqrt((p_u + 1) * (p_v + 1)) / (T(8) * shade::pi<T>);
    const shade::ashikhmin_shirley<T> model(rgb<T>(0), r_s, p_u, p_v);
    for (const auto& at : {flat<T>(), tilted<T>()}) {
        // Mirror pair at 60 deg: h = n, v.h = max(n.l, n.v) = 1/2, F = R_s + (1 - R_s)/32:
        // f_s = c F / (1/4) = 4 c F.
        const rgb<T> F = r_s + (rgb<T>(1) - r_s) / T(32);
        const auto l = direction(at, shade::pi<T> / 3, T(1));
        const auto v = direction(at, shade::pi<T> / 3, T(1) + shade::pi<T>);
        CHECK(close(model.f(l, v, at), T(4) * c * F, tol<T>));
        // v = n, l at 60 deg toward t (azimuth 0): h at 30 deg toward t, so h.b = 0 and the
        // exponent is p_u: f_s = c cos(30)^p_u / (cos(30) * 1) * F(cos 30).
        // Toward b (azimuth 90 deg) the exponent is p_v.
        const T c30 = std::sqrt(T(3)) / T(2);
        const rgb<T> F30 = shade::F_schlick(r_s, c30);
        const auto l_t = direction(at, shade::pi<T> / 3, T(0));
        const auto l_b = direction(at, shade::pi<T> / 3, shade::pi<T> / 2);
        CHECK(close(model.f(l_t, at.n(), at), c * std::pow(c30, p_u) / c30 * F30, T(10) * tol<T>));
        CHECK(close(model.f(l_b, at.n(), at), c * std::pow(c30, p_v) / c30 * F30, T(100) * tol<T>));
    }
}

TEST_CASE_TEMPLATE("ashikhmin-shirley: isotropic when p_u = p_v, reciprocal always", T, float, double) {
    const auto at = tilted<T>();
    const shade::ashikhmin_shirley<T> iso(rgb<T>(T(0.4)), rgb<T>(T(0.05)), T(50), T(50));
    const shade::ashikhmin_shirley<T> aniso(rgb<T>(T(0.4)), rgb<T>(T(0.05)), T(5), T(500));
    // Rotating both directions about n leaves the isotropic model unchanged.
    const T spin = T(0.9);
    for (const T theta_l : {T(0.2), T(0.7), T(1.3)}) {
        const auto l = direction(at, theta_l, T(0.1)), v = direction(at, T(0.5), T(2));
        const auto l2 = direction(at, theta_l, T(0.1) + spin), v2 = direction(at, T(0.5), T(2) + spin);
        CHECK(close(iso.f(l, v, at), iso.f(l2, v2, at), T(100) * tol<T>));
    }
    for (const auto& p : random_pairs(at, 1000)) {
        CHECK(iso.f(p.l, p.v, at) == iso.f(p.v, p.l, at));
        CHECK(aniso.f(p.l, p.v, at) == aniso.f(p.v, p.l, at));
    }
}

TEST_CASE_TEMPLATE("ashikhmin-shirley: zero below, finite and non-negative for degenerate pairs and extreme exponents", T, float, double) {
    for (const auto& at : {flat<T>(), tilted<T>()}) {
        for (const T p : {T(0), T(1), T(1e4)}) {
            CAPTURE(p);
            const shade::ashikhmin_shirley<T> a(rgb<T>(T(0.5)), rgb<T>(T(0.05)), p, p);
            const shade::ashikhmin_shirley<T> b(rgb<T>(T(0.5)), rgb<T>(1), p, T(1e4) - p);
            check_zero_below(a, at);
            check_finite_non_negative(a, at);
            check_finite_non_negative(b, at);
        }
    }
}

TEST_CASE_TEMPLATE("ashikhmin-shirley: invalid parameters throw naming the parameter", T, float, double) {
    using A = shade::ashikhmin_shirley<T>;
    const rgb<T> ok(T(0.5));
    check_throws_naming([&] { (void)A(rgb<T>(-1), ok, T(1), T(1)); }, "r_d");
    check_throws_naming([&] { (void)A(ok, rgb<T>(T(1.5)), T(1), T(1)); }, "r_s");
    check_throws_naming([&] { (void)A(ok, rgb<T>(T(-0.1)), T(1), T(1)); }, "r_s");
    check_throws_naming([&] { (void)A(ok, ok, T(-1), T(1)); }, "p_u");
    check_throws_naming([&] { (void)A(ok, ok, T(1), std::numeric_limits<T>::quiet_NaN()); }, "p_v");
    check_throws_naming([&] { (void)A(ok, ok, shade::infinity<T>, T(1)); }, "p_u");
    // The largest finite exponent is valid: f_s <= sqrt(p_u + 1) sqrt(2)/(8 pi) / eps^2 fits T.
    CHECK_NOTHROW((void)A(ok, ok, std::numeric_limits<T>::max(), T(1)));
    CHECK_NOTHROW((void)A(shade::unchecked, ok, ok, T(-1), T(-1)));
}

static_assert(shade::sampled_brdf<shade::ashikhmin_shirley<float>>);
static_assert(shade::sampled_brdf<shade::ashikhmin_shirley<double>>);

TEST_CASE_TEMPLATE("ashikhmin-shirley: sample and pdf agree, integrate to <= 1 and pass chi-square", T, float, double) {
    // Isotropic, anisotropic both ways, and the sharp 10^4 lobe; diffuse + specular and
    // specular only.
    struct params {
        T p_u, p_v;
    };
    for (const params p : {params{T(1), T(1)}, params{T(100), T(100)}, params{T(10), T(1000)},
                           params{T(1000), T(10)}, params{T(1e4), T(1e4)}}) {
        CAPTURE(p.p_u);
        CAPTURE(p.p_v);
        const double rounding = pdf_rounding(std::max(p.p_u, p.p_v));
        check_sampled_model(shade::ashikhmin_shirley<T>(rgb<T>(T(0.5)), rgb<T>(T(0.3)), p.p_u, p.p_v), flat<T>(),
                            rounding);
        check_sampled_model(shade::ashikhmin_shirley<T>(rgb<T>(T(0.5)), rgb<T>(T(0.3)), p.p_u, p.p_v),
                            tilted<T>(), rounding);
        check_sampled_model(shade::ashikhmin_shirley<T>(rgb<T>(0), rgb<T>(T(0.9)), p.p_u, p.p_v), flat<T>(),
                            rounding);
    }
}

TEST_CASE_TEMPLATE("ashikhmin-shirley: the lobe probability and the pdf by hand", T, float, double) {
    // P_s = mean(R_s) / (mean(R_d (1 - R_s)) + mean(R_s)) = 0.2 / (0.5 * 0.8 + 0.2) = 1/3.
    const auto at = flat<T>();
    const shade::ashikhmin_shirley<T> model(rgb<T>(T(0.5)), rgb<T>(T(0.2)), T(10), T(30));
    CHECK(close(model.lobe_probability(), T(1) / T(3), T(1e-6)));
    // v at 60 deg, l its mirror (h = n, v.h = 1/2, n.l = 1/2): p_h = sqrt(11 * 31)/(2 pi),
    // pdf = (2/3)(1/2)/pi + (1/3) p_h / (4 * 1/2).
    const auto v = direction(at, shade::pi<T> / 3, T(0.4));
    const auto l = direction(at, shade::pi<T> / 3, T(0.4) + shade::pi<T>);
    const T p_h = std::sqrt(T(11) * T(31)) / (T(2) * shade::pi<T>);
    CHECK(close(model.pdf(l, v, at), T(1) / (T(3) * shade::pi<T>) + p_h / T(6), T(1e-5)));
}

TEST_CASE_TEMPLATE("ashikhmin-shirley: f_diffuse within 1e-4 (float) / 1e-9 (double) of a long double reference, grazing included", T, float, double) {
    // f_d = 28 R_d/(23 pi) (1 - R_s)(1 - (1 - n.l/2)^5)(1 - (1 - n.v/2)^5), the reference
    // in long double from the exact values of n.l = l.z and n.v = v.z (n = +z). At n.l = 1e-4
    // the textbook form 1 - (1 - x/2)^5 cancels ~4 of float's 7 digits; the factored form
    // does not. The formula is well conditioned everywhere (relative condition number <= 1
    // in each cosine).
    const auto at = flat<T>();
    const T tol = sizeof(T) <= 4 ? T(1e-4) : T(1e-9);
    const shade::ashikhmin_shirley<T> model(rgb<T>(T(0.8)), rgb<T>(T(0.25)), T(10), T(10));
    const auto g = [](long double x) { return 1 - std::pow(1 - x / 2, 5); };
    for (const T c_l : {T(1e-4), T(1e-3), T(0.2), T(1)}) {
        for (const T c_v : {T(1e-4), T(0.5), T(1)}) {
            const vec3<T> l = glm::normalize(vec3<T>(std::sqrt((1 - c_l) * (1 + c_l)), 0, c_l));
            const vec3<T> v = glm::normalize(vec3<T>(0, std::sqrt((1 - c_v) * (1 + c_v)), c_v));
            CAPTURE(c_l);
            CAPTURE(c_v);
            const long double ref = 28.0L * 0.8L * (1 - 0.25L) / (23 * std::numbers::pi_v<long double>) *
                                    g(std::min<long double>(l.z, 1)) * g(std::min<long double>(v.z, 1));
            const long double mine = model.f_diffuse(l, v, at).x;
            CHECK(std::abs(mine - ref) <= tol * ref);
        }
    }
}

TEST_CASE("ashikhmin-shirley (float): f_specular within 1e-4 of the double value at grazing, well-conditioned inputs") {
    // The same float inputs (l, v, the frame) evaluated by the float model and, cast to
    // double, by the double model, which serves as the exact value: it rounds 2^29 times
    // less finely. The claim is about evaluation, not about the rounding of the inputs, so
    // it is tested only where the problem is well conditioned: moving l or v by 2^-24 rad
    // (what rounding a unit vector to float does) changes f_s by at most 1e-5, a tenth of
    // the goal. There a float evaluation should lose little more: rounding h to float is
    // itself such a turn (<= 1e-5), and (n.h)^e = exp(x), x = e log(n.h), carries a few
    // relative roundings of x times |x|. The condition roughly bounds e tan(theta_h) by
    // 1e-5 * 2^24 = 168, so |x| ~ e theta_h^2 / 2 <= 168^2 / (2 e) <= 141 for the exponents
    // here (>= 100), and 4 roundings of 2^-24 give 141 * 4 * 6e-8 = 3.4e-5. Both together stay
    // under the goal of 1e-4, which pow(n.h, e) misses: n.h rounds near 1 by up to
    // 2^-24, times e = 1000 already 6e-5, and h's own rounding adds as much.
    // Grazing: l at 80 to 89 degrees, v near its mirror direction (or both swapped), so h
    // is well defined and l, v are far from antiparallel; exponents up to 10^4, anisotropic
    // both ways, so the lobe is narrow and n.h rounds close to 1.
    struct exponents {
        float p_u, p_v;
    };
    shade::surface_point<float> tilted_at = tilted<float>();
    int tested = 0;
    double worst = 0;
    for (const auto& at : {flat<float>(), tilted_at}) {
        shade::surface_point<double> at_double;
        at_double.shading.t = glm::dvec3(at.shading.t);
        at_double.shading.b = glm::dvec3(at.shading.b);
        at_double.shading.n = glm::dvec3(at.shading.n);
        for (const exponents p : {exponents{100, 1000}, exponents{1000, 100}, exponents{1000, 1000},
                                  exponents{1e4f, 1e4f}}) {
            const rgb<float> r_s(0.05f, 0.2f, 0.9f);
            const shade::ashikhmin_shirley<float> model(rgb<float>(0), r_s, p.p_u, p.p_v);
            const shade::ashikhmin_shirley<double> exact(rgb<double>(0), glm::dvec3(r_s), p.p_u, p.p_v);
            const auto f_exact = [&](const glm::dvec3& l, const glm::dvec3& v) {
                return exact.f_specular(l, v, at_double);
            };
            for (const float theta_l_deg : {80.0f, 85.0f, 87.0f, 89.0f}) {
                for (const float below_deg : {0.0f, 2.0f, 5.0f, 10.0f, 15.0f}) {
                    for (const float phi_l : {0.3f, 1.0f, 2.2f}) {
                        for (const float off_mirror_deg : {0.0f, 2.0f, 5.0f, 10.0f}) {
                            const float deg = shade::pi<float> / 180;
                            const vec3<float> a = direction(at, theta_l_deg * deg, phi_l);
                            const vec3<float> b = direction(at, (theta_l_deg - below_deg) * deg,
                                                            phi_l + shade::pi<float> + off_mirror_deg * deg);
                            for (const bool swap : {false, true}) {
                                const vec3<float> l = swap ? b : a;
                                const vec3<float> v = swap ? a : b;
                                const glm::dvec3 ld(l), vd(v);
                                const rgb<double> f0 = f_exact(ld, vd);
                                if (!(f0.x > 0)) continue;
                                // The condition: the largest relative change of f_s when l or v
                                // turns by 2^-24 rad about any of three axes.
                                double kappa_u = 0;
                                for (int k = 0; k < 6; ++k) {
                                    const glm::dvec3 axis(k % 3 == 0, k % 3 == 1, k % 3 == 2);
                                    const glm::dvec3 lk = k < 3 ? glm::normalize(ld + 0x1p-24 * glm::cross(axis, ld)) : ld;
                                    const glm::dvec3 vk = k < 3 ? vd : glm::normalize(vd + 0x1p-24 * glm::cross(axis, vd));
                                    const rgb<double> fk = f_exact(lk, vk);
                                    for (int c = 0; c < 3; ++c)
                                        kappa_u = std::max(kappa_u, std::abs(fk[c] - f0[c]) / f0[c]);
                                }
                                if (kappa_u > 1e-5) continue;
                                ++tested;
                                const rgb<float> f = model.f_specular(l, v, at);
                                double error = 0;
                                for (int c = 0; c < 3; ++c) error = std::max(error, std::abs(f[c] - f0[c]) / f0[c]);
                                worst = std::max(worst, error);
                                CAPTURE(p.p_u);
                                CAPTURE(p.p_v);
                                CAPTURE(theta_l_deg);
                                CAPTURE(below_deg);
                                CAPTURE(phi_l);
                                CAPTURE(off_mirror_deg);
                                CAPTURE(swap);
                                CAPTURE(kappa_u);
                                CHECK(error <= 1e-4);
                            }
                        }
                    }
                }
            }
        }
    }
    MESSAGE("worst relative error of float f_s: " << worst << " over " << tested << " inputs");
    // The grid must keep enough well-conditioned grazing inputs to mean something.
    CHECK(tested >= 200);
}
