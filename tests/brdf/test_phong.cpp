#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <doctest/doctest.h>

#include <shade/brdf/phong.hpp>
#include <shade/check/doctest.hpp>
#include <shade/check/reciprocity.hpp>
#include <shade/core/frame.hpp>
#include <shade/core/sampling.hpp>
#include <shade/shading/shader.hpp>

#include "brdf/support.hpp"
#include "brdf/sampling.hpp"

using namespace brdf_test;

static_assert(shade::split_brdf<shade::phong<float, shade::phong_form::classic>>);
static_assert(shade::split_brdf<shade::phong<double, shade::phong_form::modified>>);
static_assert(shade::split_brdf<shade::normalized_phong<float>>);
static_assert(shade::split_brdf<shade::normalized_phong<double>>);
static_assert(!shade::phong_form::classic::reciprocal && shade::phong_form::normalized::reciprocal);

namespace {

// Hand values are built from sin/cos of rounded angles and raised to powers up to 10, so
// they agree to a few dozen ulps, not to the last bit.
template <class T>
constexpr T tol = sizeof(T) <= 4 ? T(1e-5) : T(1e-12);

} // namespace

TEST_CASE_TEMPLATE("phong normalized: at r = v the lobe is k_s (n+2)/(2 pi)", T, float, double) {
    // l at 50 deg, v its mirror image: r = v, so (r.v)^n = 1 and f_s = k_s (n + 2)/(2 pi).
    // n = 10, k_s = 0.5: 0.5 * 12 / (2 pi) = 3/pi. f_d = k_d/pi = 0.2/pi. f = 3.2/pi.
    for (const auto& at : {flat<T>(), tilted<T>()}) {
        const shade::normalized_phong<T> model(rgb<T>(T(0.2)), rgb<T>(T(0.5)), T(10));
        const auto l = direction(at, T(0.8726646), T(0.4));
        const auto v = direction(at, T(0.8726646), T(0.4) + shade::pi<T>);
        CHECK(close(model.f_specular(l, v, at), rgb<T>(3 / shade::pi<T>), tol<T>));
        CHECK(close(model.f(l, v, at), rgb<T>(T(3.2) / shade::pi<T>), tol<T>));
    }
}

TEST_CASE_TEMPLATE("phong modified: f_s = k_s cos^n of the angle between r and v", T, float, double) {
    // l = n so r = n; v at 60 deg: r.v = 1/2. n = 2, k_s = 1: f_s = 1/4 (no normalization).
    const auto at = flat<T>();
    const shade::modified_phong<T> model(rgb<T>(0), rgb<T>(1), T(2));
    CHECK(close(model.f(at.n(), direction(at, shade::pi<T> / 3, T(0)), at), rgb<T>(T(0.25)), tol<T>));
    // Shininess 0: the lobe is the constant k_s (0^0 = 1), even where r.v < 0.
    const shade::modified_phong<T> flat_lobe(rgb<T>(0), rgb<T>(T(0.3)), T(0));
    const auto l = direction(at, T(1.2), T(0));
    const auto v = direction(at, T(1.2), T(0)); // l = v at 69 deg: r.v = cos(2*69 deg) < 0
    CHECK(close(flat_lobe.f(l, v, at), rgb<T>(T(0.3)), tol<T>));
}

TEST_CASE_TEMPLATE("phong classic: divides by n.l and so reproduces the classic model through lit", T, float, double) {
    // At l = v = n: r.v = 1, n.l = 1: f_s = k_s/pi. At l at 60 deg and v its mirror:
    // r.v = 1, n.l = 1/2: f_s = k_s/(pi/2) = 2 k_s/pi.
    const auto at = flat<T>();
    const shade::classic_phong<T> model(rgb<T>(0), rgb<T>(T(0.5)), T(20));
    CHECK(close(model.f(at.n(), at.n(), at), rgb<T>(T(0.5) / shade::pi<T>), tol<T>));
    const auto l = direction(at, shade::pi<T> / 3, T(0));
    const auto v = direction(at, shade::pi<T> / 3, shade::pi<T>);
    CHECK(close(model.f(l, v, at), rgb<T>(T(1) / shade::pi<T>), tol<T>));

    // Through lit: k_d I_d (n.l) + k_s I_s (r.v)^n exactly. l at 40 deg, v at 30 deg on the
    // other side, azimuth offset 0.5 rad: evaluate the classic formula by hand.
    const rgb<T> k_d(T(0.3), T(0.2), T(0.1));
    const rgb<T> k_s(T(0.6));
    const T n = T(8);
    const shade::lit shader{shade::classic_phong<T>(k_d, k_s, n)};
    shade::light_sample<T> s;
    s.l = direction(at, T(0.6981317), T(0));
    s.diffuse = rgb<T>(T(1.5));
    s.specular = rgb<T>(T(2));
    const auto view = direction(at, T(0.5235988), shade::pi<T> + T(0.5));
    const T n_dot_l = glm::dot(at.n(), s.l);
    const shade::vec3<T> r = T(2) * n_dot_l * at.n() - s.l;
    const rgb<T> classic = k_d * s.diffuse * n_dot_l + k_s * s.specular * std::pow(glm::dot(r, view), n);
    CHECK(close(shader.shade(at, view, s), classic, tol<T>));
}

TEST_CASE_TEMPLATE("phong: reciprocity holds for modified and normalized, not for classic", T, float, double) {
    const auto at = tilted<T>();
    const shade::modified_phong<T> modified(rgb<T>(T(0.1)), rgb<T>(T(0.5)), T(5));
    const shade::normalized_phong<T> normalized(rgb<T>(T(0.1)), rgb<T>(T(0.5)), T(5));
    const shade::classic_phong<T> classic(rgb<T>(0), rgb<T>(T(0.5)), T(5));
    int classic_differs = 0;
    for (const auto& p : random_pairs(at, 300)) {
        CHECK(close(modified.f(p.l, p.v, at), modified.f(p.v, p.l, at), tol<T>));
        CHECK(close(normalized.f(p.l, p.v, at), normalized.f(p.v, p.l, at), tol<T>));
        // classic: f(l, v) n.l = f(v, l) n.v, so the two differ whenever n.l != n.v.
        const T n_dot_l = glm::dot(at.n(), p.l);
        const T n_dot_v = glm::dot(at.n(), p.v);
        const rgb<T> a = classic.f(p.l, p.v, at) * n_dot_l;
        const rgb<T> b = classic.f(p.v, p.l, at) * n_dot_v;
        if (n_dot_l > T(1e-3) && n_dot_v > T(1e-3)) CHECK(close(a, b, T(100) * tol<T>));
        if (!close(classic.f(p.l, p.v, at), classic.f(p.v, p.l, at), T(1e-3))) ++classic_differs;
    }
    CHECK(classic_differs > 100);
}

TEST_CASE_TEMPLATE("phong: zero below, finite and non-negative for degenerate pairs and extreme shininess", T, float, double) {
    for (const auto& at : {flat<T>(), tilted<T>()}) {
        for (const T n : {T(0), T(1), T(1e4)}) {
            CAPTURE(n);
            const rgb<T> k_d(T(0.2)), k_s(T(0.7));
            const shade::classic_phong<T> a(k_d, k_s, n);
            const shade::modified_phong<T> b(k_d, k_s, n);
            const shade::normalized_phong<T> c(k_d, k_s, n);
            check_zero_below(a, at);
            check_zero_below(b, at);
            check_zero_below(c, at);
            check_finite_non_negative(a, at);
            check_finite_non_negative(b, at);
            check_finite_non_negative(c, at);
        }
    }
}

TEST_CASE_TEMPLATE("phong: invalid parameters throw naming the parameter", T, float, double) {
    using P = shade::normalized_phong<T>;
    const rgb<T> ok(T(0.5));
    const T nan = std::numeric_limits<T>::quiet_NaN();
    check_throws_naming([&] { (void)P(rgb<T>(-1), ok, T(1)); }, "k_d");
    check_throws_naming([&] { (void)P(ok, rgb<T>(0, -1, 0), T(1)); }, "k_s");
    check_throws_naming([&] { (void)P(ok, rgb<T>(nan), T(1)); }, "k_s");
    check_throws_naming([&] { (void)P(ok, ok, T(-1)); }, "shininess");
    check_throws_naming([&] { (void)P(ok, ok, nan); }, "shininess");
    check_throws_naming([&] { (void)P(ok, ok, shade::infinity<T>); }, "shininess");
    // Finite but overflowing together: k_s * (n + 2)/(2 pi) = Inf.
    check_throws_naming([&] { (void)P(ok, rgb<T>(std::numeric_limits<T>::max()), T(100)); }, "k_s");
    CHECK_NOTHROW((void)P(shade::unchecked, rgb<T>(-1), ok, T(-1)));
}

static_assert(shade::sampled_brdf<shade::classic_phong<float>>);
static_assert(shade::sampled_brdf<shade::modified_phong<double>>);
static_assert(shade::sampled_brdf<shade::normalized_phong<float>>);
static_assert(shade::sampled_brdf<shade::normalized_phong<double>>);

TEST_CASE_TEMPLATE("phong: sample and pdf agree, integrate to <= 1 and pass chi-square (exponents 1 and 10^4)", T, float, double) {
    for (const T s : {T(1), T(1e4)}) {
        CAPTURE(s);
        const rgb<T> k_d(T(0.3), T(0.2), T(0.1)), k_s(T(0.5));
        check_sampled_model(shade::normalized_phong<T>(k_d, k_s, s), flat<T>(), pdf_rounding(s));
        check_sampled_model(shade::normalized_phong<T>(k_d, k_s, s), tilted<T>(), pdf_rounding(s));
        check_sampled_model(shade::modified_phong<T>(rgb<T>(0), rgb<T>(T(0.1)), s), flat<T>(), pdf_rounding(s));
        check_sampled_model(shade::classic_phong<T>(k_d, k_s, s), flat<T>(), pdf_rounding(s));
        // Specular only: every direction comes from the lobe about r.
        check_sampled_model(shade::normalized_phong<T>(rgb<T>(0), k_s, s), flat<T>(), pdf_rounding(s));
    }
}

TEST_CASE_TEMPLATE("phong: the lobe probability and the pdf by hand", T, float, double) {
    // Normalized Phong, s = 10: the lobe's albedo estimate is mean(k_s) c 2 pi/(s + 2) =
    // mean(k_s) = 0.5 (c = 12/(2 pi)); the diffuse one mean(k_d) = 0.25: P_s = 0.5/0.75 = 2/3.
    const auto at = flat<T>();
    const shade::normalized_phong<T> model(rgb<T>(T(0.25)), rgb<T>(T(0.5)), T(10));
    CHECK(close(model.lobe_probability(), T(2) / T(3), T(1e-6)));
    // v at 30 deg, l its mirror image (r = l): pdf = (1/3) cos(30 deg)/pi + (2/3) 11/(2 pi) * 1.
    const auto v = direction(at, shade::pi<T> / 6, T(0));
    const auto l = direction(at, shade::pi<T> / 6, shade::pi<T>);
    const T expected = std::sqrt(T(3)) / T(2) / (T(3) * shade::pi<T>) + T(11) / (T(3) * shade::pi<T>);
    CHECK(close(model.pdf(l, v, at), expected, T(1e-5)));
    // Classic form, s = 3: lobe estimate mean(k_s) (1/pi) 2 pi/(s + 1) = 0.5 * 2/4 = 0.25,
    // equal to the diffuse estimate 0.25: P_s = 1/2.
    const shade::classic_phong<T> classic(rgb<T>(T(0.25)), rgb<T>(T(0.5)), T(3));
    CHECK(close(classic.lobe_probability(), T(0.5), T(1e-6)));
    // Black model: P_s = 1/2, sample still returns directions (with f = 0).
    const shade::modified_phong<T> black(rgb<T>(0), rgb<T>(0), T(5));
    CHECK(black.lobe_probability() == T(0.5));
}

namespace {

// Deliberately wrong samplers around a correct model, to show the checks catch them. Each
// forwards f (and pdf, unless it changes it) to the model.
template <class T>
struct forwarding {
    using scalar_type = T;
    shade::normalized_phong<T> m;
    rgb<T> f(const vec3<T>& l, const vec3<T>& v, const shade::surface_point<T>& at) const { return m.f(l, v, at); }
    T pdf(const vec3<T>& l, const vec3<T>& v, const shade::surface_point<T>& at) const { return m.pdf(l, v, at); }
};

// (a) The pdf reported by sample() and pdf() is twice the true density.
template <class T>
struct pdf_doubled : forwarding<T> {
    using forwarding<T>::m;
    T pdf(const vec3<T>& l, const vec3<T>& v, const shade::surface_point<T>& at) const { return 2 * m.pdf(l, v, at); }
    std::optional<shade::brdf_sample<T>> sample(const vec3<T>& v, T uc, const shade::vec2<T>& u,
                                                const shade::surface_point<T>& at) const {
        auto s = m.sample(v, uc, u, at);
        if (s) {
            s->pdf *= 2;
            s->weight /= 2;
        }
        return s;
    }
};

// (b) The lobe drawn about n instead of the mirror direction r; pdf() is the true one of
// the model (about r), and sample() reports f and pdf at the l it returns.
template <class T>
struct wrong_axis : forwarding<T> {
    using forwarding<T>::m;
    std::optional<shade::brdf_sample<T>> sample(const vec3<T>& v, T uc, const shade::vec2<T>& u,
                                                const shade::surface_point<T>& at) const {
        const vec3<T> l = uc < m.lobe_probability()
                              ? at.shading.to_world(shade::square_to_power_cosine_hemisphere(u, m.shininess()))
                              : at.shading.to_world(shade::square_to_cosine_hemisphere(u));
        const T n_dot_l = glm::dot(at.n(), l);
        if (!(n_dot_l > 0) || !(glm::dot(at.n(), v) > 0)) return std::nullopt;
        return shade::detail::make_brdf_sample(l, m.f(l, v, at), m.pdf(l, v, at), n_dot_l);
    }
};

// (c) sample() reports a pdf 10 % off the pdf() at its direction.
template <class T>
struct inconsistent : forwarding<T> {
    using forwarding<T>::m;
    std::optional<shade::brdf_sample<T>> sample(const vec3<T>& v, T uc, const shade::vec2<T>& u,
                                                const shade::surface_point<T>& at) const {
        auto s = m.sample(v, uc, u, at);
        if (s) s->pdf *= T(1.1);
        return s;
    }
};

} // namespace

TEST_CASE_TEMPLATE("phong: deliberately wrong samplers fail the sampling checks", T, float, double) {
    const auto at = flat<T>();
    const shade::normalized_phong<T> model(rgb<T>(T(0.2)), rgb<T>(T(0.6)), T(20));
    const auto v = direction(at, T(0.7), T(0.3));
    static_assert(shade::sampled_brdf<pdf_doubled<T>> && shade::sampled_brdf<wrong_axis<T>>);
    // The correct model passes (the checks are not failing everything).
    const sampling_report good = check_sampling(model, v, at);
    CHECK(good.p_value > chi2_significance);
    CHECK(good.integral <= 1 + good.integral_error + 1e-6);
    // (a) pdf x 2: the integral is ~2 and chi-square rejects.
    const sampling_report doubled = check_sampling(pdf_doubled<T>{{model}}, v, at);
    CHECK(doubled.integral > T(1.5));
    CHECK(doubled.p_value < chi2_significance);
    // (b) lobe about n: chi-square rejects; f and pdf still agree at the drawn points.
    const sampling_report axis = check_sampling(wrong_axis<T>{{model}}, v, at);
    CHECK(axis.disagreements == 0);
    CHECK(axis.p_value < chi2_significance);
    // (c) sample's pdf 10 % off pdf(): every sample disagrees.
    const sampling_report off = check_sampling(inconsistent<T>{{model}}, v, at, 1000);
    CHECK(off.disagreements == 1000 - int(std::lround((1 - off.drawn_fraction) * 1000)));
    CHECK(off.disagreements > 0);
}


TEST_CASE_TEMPLATE("phong, shininess 10^4: a normal one ulp off unit length changes neither the pdf's integral nor reciprocity", T, float, double) {
    // A float normal is unit only to within an ulp or so. Phong's cosine r.v with
    // r = 2 (n.l) n - l is 2 (n.l)(n.v) - l.v, and 2 (n.l)(n.v) scales with |n|^2: at
    // |n| = 1 + d the cosine near the peak is too large by about 4 d, and cos^s by 4 s d
    // (5e-3 at s = 10^4, d = 2^-23), which no rounding of l or v explains.
    //
    // (a) The pdf's integral at v along the normal (view 0 deg), compared with the same
    // model in double at the unit normal n / |n|. With k_d = 0 the pdf is the lobe alone,
    // (s + 1)/(2 pi) cos^s(theta) about the mirror direction r of v, here r = n / |n|, and
    // its exact integral is 1 (the whole lobe is above the horizon). pdf_over_cap integrates
    // it in polar coordinates about r (computed in double), theta in [0, 0.1]:
    //   * outside the cap cos^s(theta) <= cos^s(0.1) = exp(-50): no mass is missed;
    //   * the midpoint rule in theta errs by (h^2/24) (g'(0.1) - g'(0)) for
    //     g(theta) = (s + 1) cos^s(theta) sin(theta), i.e. h^2 (s + 1)/24 = 1.0e-6 with
    //     h = 0.1/2000;
    //   * in phi the integrand is smooth and periodic, where the midpoint rule converges
    //     faster than any power of the step; 32 points integrate the slight asymmetry of a
    //     lobe whose axis is off by ~1e-7 rad exactly enough.
    // The float pdf also carries rounding: the cosine is rounded near 1 (by up to 2^-25
    // relative), which the power s turns into up to 3e-4 at a point, of either sign; the
    // 64000-point mean averages it. A systematic error is what this test is for: one that
    // depends only on n and v (|n|, or the rounding of n.v and n.n near 1) shifts every point
    // the same way. The requirement is 1e-3.
    //
    // (b) Reciprocity through the property kit, with its own float tolerance
    // (default_reciprocity_tolerance: 1e-3): Phong's r.v is symmetric in l and v only if
    // it is computed so; a rounded, non-unit normal must not break that.
    //
    // The classic form has the same pdf as the others (k_d = 0 makes P_s = 1 in every
    // form), so (a) covers it; it is not reciprocal, so (b) leaves it out.
    const T s = T(1e4);
    const rgb<T> k_s(T(0.5));
    const shade::normalized_phong<T> normalized(rgb<T>(0), k_s, s);
    const shade::classic_phong<T> classic(rgb<T>(0), k_s, s);
    const shade::modified_phong<T> modified(rgb<T>(0), k_s, s);
    const shade::normalized_phong<double> reference(rgb<double>(0), rgb<double>(0.5), 1e4);
    for (const auto& [n, v] : normals_off_unit_length<T>()) {
        const double length = glm::length(glm::dvec3(n));
        CAPTURE(length - 1);
        const auto at = shade::surface_point<T>::at(vec3<T>(0), n);
        const glm::dvec3 unit_n = glm::normalize(glm::dvec3(n));
        const auto at_double = shade::surface_point<double>::at(glm::dvec3(0), unit_n);
        const glm::dvec3 unit_v = glm::normalize(glm::dvec3(v));
        const glm::dvec3 r = 2 * glm::dot(unit_n, unit_v) * unit_n - unit_v;
        const double exact = pdf_over_cap(reference, unit_v, at_double, r, 0.1);
        const double mine = pdf_over_cap(normalized, v, at, r, 0.1);
        const double mine_classic = pdf_over_cap(classic, v, at, r, 0.1);
        CAPTURE(exact);
        CAPTURE(mine);
        CHECK(std::abs(exact - 1) <= 1e-5);
        CHECK(std::abs(mine - exact) <= 1e-3);
        CHECK(std::abs(mine_classic - exact) <= 1e-3);

        shade::check::pair_options pairs{.pairs = 4000};
        pairs.model = "normalized phong, s = 10^4";
        shade::check::doctest_expect(shade::check::reciprocity(normalized, at, pairs));
        pairs.model = "modified phong, s = 10^4";
        shade::check::doctest_expect(shade::check::reciprocity(modified, at, pairs));
    }
}
