// shade::bvh_light_sampler: its probabilities sum to 1 less the chance of a walk that ends
// where nothing can light the point, and sample() reports exactly what probability()
// computes; draws follow the probabilities (chi-square); dark lights and lights facing away
// are never chosen; lights at infinity share the choice with the tree; bad bounds are refused
// by name; the direct-irradiance estimate through it agrees with the one through
// power_light_sampler; and over 12000 emissive triangles of widely varying power its
// variance is >= 3x lower than power sampling's (issue 33, item 2). Also
// shade::light_bounds_of: boxes and cones hold what the lights light.

#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <shade/check/chi2.hpp>
#include <shade/core/error.hpp>
#include <shade/core/random.hpp>
#include <shade/light/any_light.hpp>
#include <shade/light/bvh_light_sampler.hpp>
#include <shade/light/light_bounds_of.hpp>
#include <shade/light/light_sampler.hpp>

namespace {

// Draws in a fixed order: the order in which a constructor's arguments are evaluated differs
// between compilers, and the scenes below should be the same under each.
template <class T>
shade::vec2<T> uniform2(shade::rng& g) {
    const T x = g.uniform<T>();
    const T y = g.uniform<T>();
    return {x, y};
}

template <class T>
shade::vec3<T> uniform3(shade::rng& g) {
    const T x = g.uniform<T>();
    const T y = g.uniform<T>();
    const T z = g.uniform<T>();
    return {x, y, z};
}

template <class T>
shade::vec3<T> random_unit(shade::rng& g) {
    for (;;) {
        const shade::vec3<T> v = T(2) * uniform3<T>(g) - T(1);
        const T len2 = glm::dot(v, v);
        if (len2 > T(1e-4) && len2 <= T(1)) return v / std::sqrt(len2);
    }
}

/// A one-sided triangle light of about `size` around `center`, facing `facing` (unit), of
/// power `power` W (grey).
template <class T>
shade::triangle_light<T> make_triangle(shade::rng& g, const shade::vec3<T>& center, const shade::vec3<T>& facing, T size,
                                       T power, shade::sidedness sides = shade::sidedness::one_sided) {
    const shade::vec3<T> t = shade::detail::any_perpendicular(facing);
    const shade::vec3<T> b = glm::cross(facing, t);
    const T a = size * (T(0.5) + g.uniform<T>());
    const shade::vec3<T> v0 = center + a * t;
    const shade::vec3<T> v1 = center + a * (T(-0.5) * t + T(0.866) * b);
    const shade::vec3<T> v2 = center + a * (T(-0.5) * t - T(0.866) * b);
    // Area of this triangle: (3 sqrt(3) / 4) a^2 (up to the rounded 0.866); the radiance that
    // gives the power is Phi / (pi A) per emitting side.
    const T area = T(0.5) * glm::length(glm::cross(v1 - v0, v2 - v0));
    const T sides_count = sides == shade::sidedness::two_sided ? T(2) : T(1);
    const T radiance = power / (shade::pi<T> * area * sides_count);
    return shade::triangle_light<T>(v0, v1, v2, shade::emission<T>::from_physical(shade::rgb<T>(radiance)), sides);
}

/// `count` triangles in the box [-extent, extent]^3 facing random ways, powers log-uniform
/// over [1e-2, 1e2].
template <class T>
std::vector<shade::any_light<T>> random_lights(shade::rng& g, std::size_t count, T extent) {
    std::vector<shade::any_light<T>> lights;
    for (std::size_t i = 0; i < count; ++i) {
        const shade::vec3<T> c = extent * (T(2) * uniform3<T>(g) - T(1));
        const T power = std::pow(T(10), T(4) * g.uniform<T>() - T(2));
        const auto sides = i % 7 == 0 ? shade::sidedness::two_sided : shade::sidedness::one_sided;
        lights.push_back(make_triangle<T>(g, c, random_unit<T>(g), T(0.3), power, sides));
    }
    // A point light and a spot among them.
    lights.push_back(shade::point_light<T>(shade::vec3<T>(T(0.5), T(0.2), T(-0.3)),
                                           shade::emission<T>::from_physical(shade::rgb<T>(T(2)))));
    lights.push_back(shade::spot_light<T>(shade::vec3<T>(T(-1), T(0.5), T(1)), shade::vec3<T>(0, 0, -1), T(0.3), T(0.6),
                                          shade::emission<T>::from_physical(shade::rgb<T>(T(5)))));
    return lights;
}

template <class T>
std::vector<shade::light_bounds<T>> bounds_of(const std::vector<shade::any_light<T>>& lights) {
    std::vector<shade::light_bounds<T>> b;
    for (const auto& l : lights) b.push_back(shade::light_bounds_of(l, T(100)));
    return b;
}

template <class T>
shade::light_sample_context<T> random_context(shade::rng& g, T extent, bool with_surface) {
    shade::light_sample_context<T> ctx;
    ctx.p = extent * (T(2) * uniform3<T>(g) - T(1));
    if (with_surface) ctx.n = ctx.ns = random_unit<T>(g);
    return ctx;
}

/// The direct irradiance (grey, the red channel) one light sample gives at ctx: radiance
/// times max(0, n.l) over the light's solid-angle pdf, or 0 when the light gives no sample.
template <class T>
double irradiance_sample(const shade::any_light<T>& light, const shade::light_sample_context<T>& ctx,
                         const shade::vec2<T>& u) {
    const auto s = light.sample_incident(ctx, u);
    if (!s || !(s->pdf > T(0))) return 0;
    const double cos_i = double(glm::dot(ctx.n, s->l));
    if (!(cos_i > 0)) return 0;
    return double(s->radiance.x) * cos_i / double(s->pdf);
}

} // namespace

TEST_CASE_TEMPLATE("bvh_light_sampler: probabilities sum to 1; sample() reports probability() bit for bit", T, float, double) {
    shade::rng g(7);
    const auto lights = random_lights<T>(g, 300, T(4));
    const auto bounds = bounds_of(lights);
    const shade::bvh_light_sampler<T> s(bounds);
    REQUIRE(s.size() == lights.size());
    // Rounding: each probability is a product of ~20 quotients, each off by an ulp or two.
    const double tolerance = 1000 * double(std::numeric_limits<T>::epsilon());
    // Points among the lights (inside some of the tree's boxes, where walks may dead-end:
    // see the class comment) and points outside all of them, facing the lights or not.
    for (const bool among : {true, false}) {
        int dead_end_contexts = 0;
        double dead_end_mass = 0;
        const int contexts = 60;
        for (int c = 0; c < contexts; ++c) {
            auto ctx = random_context<T>(g, T(5), c % 4 != 0);
            if (!among) {
                ctx.p = T(8) * random_unit<T>(g);
                if (c % 4 != 0) ctx.n = ctx.ns = glm::normalize(T(-1) * ctx.p + T(4) * random_unit<T>(g));
            }
            double sum = 0;
            for (std::size_t i = 0; i < lights.size(); ++i) sum += double(s.probability(ctx, i));
            CHECK(sum <= 1 + tolerance);
            dead_end_contexts += sum < 1 - tolerance ? 1 : 0;
            int nothing = 0;
            const int draws = 400;
            for (int k = 0; k < draws; ++k) {
                const auto choice = s.sample(ctx, (T(k) + g.uniform<T>()) / T(draws));
                if (!choice) {
                    ++nothing;
                    continue;
                }
                REQUIRE(choice->index < lights.size());
                CHECK(choice->probability > T(0));
                CHECK(choice->probability == s.probability(ctx, choice->index)); // bit for bit
            }
            // Nothing is returned only with the probability q = 1 - sum (a binomial count).
            const double q = 1 - sum > 0 ? 1 - sum : 0;
            CHECK(std::fabs(double(nothing) - draws * q) <= 4 * std::sqrt(draws * q * (1 - q)) + 1);
            dead_end_mass += q;
        }
        MESSAGE(std::string(among ? "among the lights" : "outside the lights") << ": probabilities sum below 1 in "
                << dead_end_contexts << " of " << contexts << " contexts; mean chance of a dead end "
                << dead_end_mass / contexts);
        // Lights facing every way make parents' cones wider than their children's: from outside
        // the lights a few percent of walks end where both children are dark.
        CHECK(dead_end_mass / contexts < (among ? 0.4 : 0.1));
    }
}

TEST_CASE_TEMPLATE("bvh_light_sampler: draws follow probability() (chi-square)", T, float, double) {
    shade::rng g(19);
    const auto lights = random_lights<T>(g, 300, T(3));
    const shade::bvh_light_sampler<T> s(bounds_of(lights));
    const int contexts = 4;
    const double alpha = shade::check::sidak_significance(0.001, contexts);
    for (int c = 0; c < contexts; ++c) {
        const auto ctx = random_context<T>(g, T(3), c != 0);
        const std::size_t draws = 200000;
        std::vector<double> observed(lights.size(), 0), expected(lights.size(), 0);
        for (std::size_t i = 0; i < lights.size(); ++i) expected[i] = double(draws) * double(s.probability(ctx, i));
        for (std::size_t k = 0; k < draws; ++k)
            if (const auto choice = s.sample(ctx, g.uniform<T>())) observed[choice->index] += 1;
        const auto chi2 = shade::check::pearson_chi2(observed, expected);
        const double p_value = shade::check::chi2_p_value(chi2.statistic, double(chi2.dof));
        CHECK_MESSAGE(p_value > alpha, "context " << c << ": chi2 " << chi2.statistic << " dof " << chi2.dof);
    }
}

TEST_CASE_TEMPLATE("bvh_light_sampler: dark lights and lights facing away are never chosen", T, float, double) {
    shade::rng g(3);
    // Lights on the plane z = 0: the first faces up (+z), the second down (-z), the third is
    // dark, the fourth faces up; p is above the plane on a surface facing down (a ceiling).
    std::vector<shade::any_light<T>> lights;
    lights.push_back(make_triangle<T>(g, {0, 0, 0}, {0, 0, 1}, T(0.5), T(10)));
    lights.push_back(make_triangle<T>(g, {1, 0, 0}, {0, 0, -1}, T(0.5), T(10)));
    lights.push_back(make_triangle<T>(g, {0, 1, 0}, {0, 0, 1}, T(0.5), T(10)));
    lights.push_back(make_triangle<T>(g, {1, 1, 0}, {0, 0, 1}, T(0.5), T(1)));
    auto bounds = bounds_of(lights);
    bounds[2].power = T(0);
    const shade::bvh_light_sampler<T> s(bounds);
    const shade::light_sample_context<T> ctx{{T(0.4), T(0.3), T(2)}, {0, 0, -1}, {0, 0, -1}};
    CHECK(s.probability(ctx, 1) == T(0));
    CHECK(s.probability(ctx, 2) == T(0));
    CHECK(s.probability(ctx, 0) > T(0));
    CHECK(s.probability(ctx, 3) > T(0));
    CHECK(s.probability(ctx, 0) + s.probability(ctx, 3) == doctest::Approx(1.0));
    CHECK(s.probability(ctx, 4) == T(0)); // no such light
    for (int k = 0; k < 2000; ++k) {
        const auto c = s.sample(ctx, g.uniform<T>());
        REQUIRE(c);
        CHECK((c->index == 0 || c->index == 3));
    }
    // Below the plane on a floor facing up, only the light facing down can reach the point
    // (the rest is the chance of a dead end: the box of lights 0 and 3 is seen within 90
    // degrees of their normal, theirs are not).
    const shade::light_sample_context<T> below{{T(0.9), T(0.1), T(-1)}, {0, 0, 1}, {0, 0, 1}};
    CHECK(s.probability(below, 1) > T(0.5));
    for (const std::size_t i : {std::size_t(0), std::size_t(2), std::size_t(3)}) CHECK(s.probability(below, i) == T(0));
    for (int k = 0; k < 200; ++k)
        if (const auto c = s.sample(below, g.uniform<T>())) CHECK(c->index == 1);
    // Below the plane on a surface facing down: no light can reach it; nothing is drawn.
    const shade::light_sample_context<T> dark{{T(0.9), T(0.1), T(-1)}, {0, 0, -1}, {0, 0, -1}};
    for (std::size_t i = 0; i < lights.size(); ++i) CHECK(s.probability(dark, i) == T(0));
    CHECK(!s.sample(dark, T(0.3)));
    // No lights at all, or only dark ones.
    CHECK(!shade::bvh_light_sampler<T>(std::span<const shade::light_bounds<T>>{}).sample(ctx, T(0.5)));
    CHECK(!shade::bvh_light_sampler<T>(std::vector<shade::light_bounds<T>>{bounds[2]}).sample(ctx, T(0.5)));
}

TEST_CASE_TEMPLATE("bvh_light_sampler: lights at infinity share the choice with the tree", T, float, double) {
    shade::rng g(5);
    std::vector<shade::any_light<T>> lights;
    lights.push_back(shade::directional_light<T>(shade::vec3<T>(0, 0, 1), shade::emission<T>::from_physical(shade::rgb<T>(1))));
    lights.push_back(make_triangle<T>(g, {0, 0, 0}, {0, 0, 1}, T(0.5), T(10)));
    lights.push_back(shade::environment_light<T>(shade::emission<T>::from_physical(shade::rgb<T>(T(0.2)))));
    lights.push_back(make_triangle<T>(g, {2, 0, 0}, {0, 0, 1}, T(0.5), T(3)));
    lights.push_back(shade::environment_light<T>(shade::emission<T>::from_physical(shade::rgb<T>(0))));
    const auto bounds = bounds_of(lights);
    CHECK(bounds[0].at_infinity);
    CHECK(bounds[2].at_infinity);
    const shade::bvh_light_sampler<T> s(bounds);
    // Above the triangles (which face up), on a surface facing down: the tree and the two
    // bright lights at infinity, 1/3 each.
    const shade::light_sample_context<T> above{{T(1), 0, T(1)}, {0, 0, -1}, {0, 0, -1}};
    CHECK(s.probability(above, 0) == doctest::Approx(1.0 / 3));
    CHECK(s.probability(above, 2) == doctest::Approx(1.0 / 3));
    CHECK(s.probability(above, 4) == T(0)); // dark
    CHECK(double(s.probability(above, 1)) + double(s.probability(above, 3)) == doctest::Approx(1.0 / 3));
    // Below them (they face up): the lights at infinity take all of it.
    const shade::light_sample_context<T> below{{T(1), 0, T(-1)}, {0, 0, -1}, {0, 0, -1}};
    CHECK(s.probability(below, 0) == doctest::Approx(0.5));
    CHECK(s.probability(below, 2) == doctest::Approx(0.5));
    CHECK(s.probability(below, 1) == T(0));
    std::vector<double> observed(lights.size(), 0);
    for (int k = 0; k < 3000; ++k) {
        const auto c = s.sample(above, g.uniform<T>());
        REQUIRE(c);
        CHECK(c->probability == s.probability(above, c->index));
        observed[c->index] += 1;
        const auto d = s.sample(below, g.uniform<T>());
        REQUIRE(d);
        CHECK((d->index == 0 || d->index == 2));
    }
    CHECK(observed[4] == 0);
    CHECK(observed[0] == doctest::Approx(1000).epsilon(0.15));
}

TEST_CASE_TEMPLATE("bvh_light_sampler: bad bounds are refused, naming lights", T, float, double) {
    const auto parameter_of = [](shade::light_bounds<T> b) {
        try {
            const shade::bvh_light_sampler<T> s(std::vector<shade::light_bounds<T>>{b});
        } catch (const shade::invalid_parameter& e) {
            return e.parameter();
        }
        return std::string("(accepted)");
    };
    shade::light_bounds<T> good;
    good.box.grow(shade::vec3<T>(0));
    good.power = T(1);
    CHECK(parameter_of(good) == "(accepted)");
    auto b = good;
    b.power = T(-1);
    CHECK(parameter_of(b) == "lights");
    b.power = std::numeric_limits<T>::quiet_NaN();
    CHECK(parameter_of(b) == "lights");
    b = good;
    b.power = std::numeric_limits<T>::infinity();
    CHECK(parameter_of(b) == "lights");
    b = good;
    b.box = {};
    CHECK(parameter_of(b) == "lights");
    b = good;
    b.box.grow(shade::vec3<T>(std::numeric_limits<T>::infinity()));
    CHECK(parameter_of(b) == "lights");
    b = good;
    b.axis = shade::vec3<T>(0, 0, 2);
    CHECK(parameter_of(b) == "lights");
    b = good;
    b.theta_e = T(2);
    CHECK(parameter_of(b) == "lights");
    b = good;
    b.theta_o = T(-0.1);
    CHECK(parameter_of(b) == "lights");
    CHECK(parameter_of(shade::light_bounds<T>::infinite(T(-1))) == "lights");
    CHECK(parameter_of(shade::light_bounds<T>::infinite(T(2))) == "(accepted)");
}

TEST_CASE_TEMPLATE("bvh_light_sampler: direct irradiance agrees with power sampling's (unbiased)", T, float, double) {
    shade::rng g(23);
    const auto lights = random_lights<T>(g, 200, T(3));
    const shade::bvh_light_sampler<T> bvh(bounds_of(lights));
    const auto power = shade::power_light_sampler<T>::from_lights(std::span<const shade::any_light<T>>(lights), T(100));
    for (int c = 0; c < 3; ++c) {
        const auto ctx = random_context<T>(g, T(2), true);
        const int n_samples = 200000;
        double sum[2] = {0, 0}, sum2[2] = {0, 0};
        for (int k = 0; k < n_samples; ++k) {
            const T u = g.uniform<T>();
            const shade::vec2<T> u2 = uniform2<T>(g);
            double x[2] = {0, 0};
            if (const auto choice = bvh.sample(ctx, u))
                x[0] = irradiance_sample(lights[choice->index], ctx, u2) / double(choice->probability);
            if (const auto choice = power.sample(u))
                x[1] = irradiance_sample(lights[choice->index], ctx, u2) / double(choice->probability);
            for (int m = 0; m < 2; ++m) {
                sum[m] += x[m];
                sum2[m] += x[m] * x[m];
            }
        }
        double mean[2], se[2];
        for (int m = 0; m < 2; ++m) {
            mean[m] = sum[m] / n_samples;
            se[m] = std::sqrt((sum2[m] / n_samples - mean[m] * mean[m]) / (n_samples - 1));
        }
        MESSAGE("irradiance: bvh " << mean[0] << " +- " << se[0] << ", power " << mean[1] << " +- " << se[1]);
        CHECK(std::fabs(mean[0] - mean[1]) <= 4 * std::sqrt(se[0] * se[0] + se[1] * se[1]));
    }
}

namespace {

/// The acceptance scene of issue 33, item 2: 12000 one-sided emissive triangles scattered over
/// a 100 x 100 area at heights 1 to 10 above the floor z = 0, most facing down within 60
/// degrees, one in five facing anywhere; one in ten bright (log-uniform 1 to 10^4 W), the
/// rest dim (log-uniform 10^-3 to 10^-1 W): powers over seven orders of magnitude.
template <class T>
std::vector<shade::any_light<T>> many_lights_scene(shade::rng& g) {
    std::vector<shade::any_light<T>> lights;
    for (int i = 0; i < 12000; ++i) {
        const shade::vec3<T> c = shade::vec3<T>(-50, -50, 1) + shade::vec3<T>(100, 100, 9) * uniform3<T>(g);
        shade::vec3<T> facing = random_unit<T>(g);
        if (i % 5 != 0) {
            // Down within 60 degrees: cos in [0.5, 1] uniformly (uniform in solid angle).
            const T cos_t = T(0.5) + T(0.5) * g.uniform<T>();
            const T phi = T(2) * shade::pi<T> * g.uniform<T>();
            const T sin_t = std::sqrt(T(1) - cos_t * cos_t);
            facing = shade::vec3<T>(sin_t * std::cos(phi), sin_t * std::sin(phi), -cos_t);
        }
        const bool bright = i % 10 == 0;
        const T power = bright ? std::pow(T(10), T(4) * g.uniform<T>()) : std::pow(T(10), T(2) * g.uniform<T>() - T(3));
        lights.push_back(make_triangle<T>(g, c, facing, T(0.3), power));
    }
    return lights;
}

/// The variance of the one-sample direct-irradiance estimator X = g_i(y) / P_i, light i chosen
/// with probability P_i and y uniform by area on it (g_i = L cos_i cos_light A / r^2):
///   Var X = sum_i E[g_i^2] / P_i - (sum_i E[g_i])^2,
/// with E[g_i] and E[g_i^2] from a 4 x 4 stratified grid of samples per light (the same for
/// every sampler, so two samplers' variances differ only through P). Also returns the
/// irradiance (sum_i E[g_i]) and the part of it carried by lights of probability 0 (which an
/// unbiased sampler must not have).
struct exact_variance {
    double irradiance = 0;
    double variance = 0;
    double missed = 0; ///< irradiance from lights the sampler never chooses
};

template <class T, class Probability>
exact_variance variance_of(const std::vector<shade::any_light<T>>& lights, const std::vector<double>& first,
                           const std::vector<double>& second, Probability probability) {
    exact_variance v;
    double second_moment = 0;
    for (std::size_t i = 0; i < lights.size(); ++i) {
        v.irradiance += first[i];
        const double p = double(probability(i));
        if (p > 0) second_moment += second[i] / p;
        else v.missed += first[i];
    }
    v.variance = second_moment - v.irradiance * v.irradiance;
    return v;
}

/// Sample mean and variance of n draws of x(), with the standard error of the variance
/// (sqrt((m4 - s^4) / n), m4 the fourth central moment).
struct sample_stats {
    double mean = 0, variance = 0, variance_se = 0;
};

template <class Draw>
sample_stats stats_of(int n, Draw draw) {
    std::vector<double> x(static_cast<std::size_t>(n));
    double sum = 0;
    for (auto& xi : x) sum += xi = draw();
    sample_stats s;
    s.mean = sum / n;
    double m2 = 0, m4 = 0;
    for (const double xi : x) {
        const double d = (xi - s.mean) * (xi - s.mean);
        m2 += d;
        m4 += d * d;
    }
    s.variance = m2 / (n - 1);
    m4 /= n;
    s.variance_se = std::sqrt(std::fmax(0.0, m4 - s.variance * s.variance) / n);
    return s;
}

} // namespace

TEST_CASE_TEMPLATE("bvh_light_sampler: >= 3x lower variance than power sampling over 12000 emissive triangles", T, float, double) {
    shade::rng g(2018);
    const auto lights = many_lights_scene<T>(g);
    const auto bounds = bounds_of(lights);
    const shade::bvh_light_sampler<T> bvh(bounds);
    const auto power = shade::power_light_sampler<T>::from_lights(std::span<const shade::any_light<T>>(lights), T(100));
    struct point {
        shade::vec3<T> p, n;
    };
    const point points[] = {
        {{0, 0, 0}, {0, 0, 1}},        // floor, centre
        {{20, -10, 0}, {0, 0, 1}},     // floor
        {{-48, 48, 0}, {0, 0, 1}},     // floor, in a corner
        {{35, 30, 0}, {0, 0, 1}},      // floor
        {{50, 0, 5}, {-1, 0, 0}},      // a wall at the edge, facing in
        {{-10, 5, 5}, {0, 0, 1}},      // a surface among the lights, facing up
    };
    double worst_exact = std::numeric_limits<double>::infinity();
    double relative_bvh = 0, relative_power = 0;
    for (const point& pt : points) {
        const shade::light_sample_context<T> ctx{pt.p, pt.n, pt.n};
        // E[g_i] and E[g_i^2] per light, from a 4 x 4 stratified grid.
        std::vector<double> first(lights.size()), second(lights.size());
        for (std::size_t i = 0; i < lights.size(); ++i) {
            double s1 = 0, s2 = 0;
            for (int a = 0; a < 4; ++a)
                for (int b = 0; b < 4; ++b) {
                    const shade::vec2<T> u = (shade::vec2<T>(T(a), T(b)) + uniform2<T>(g)) / T(4);
                    const double x = irradiance_sample(lights[i], ctx, u);
                    s1 += x;
                    s2 += x * x;
                }
            first[i] = s1 / 16;
            second[i] = s2 / 16;
        }
        const auto with_bvh = variance_of(lights, first, second, [&](std::size_t i) { return bvh.probability(ctx, i); });
        const auto with_power = variance_of(lights, first, second, [&](std::size_t i) { return power.probability(i); });
        CHECK(with_bvh.missed == 0); // the importance is a bound: no light that lights p is left out
        CHECK(with_power.missed == 0);
        const double exact_ratio = with_power.variance / with_bvh.variance;
        // Sampling each light in proportion to its share of the irradiance (what a perfect
        // importance would give): the headroom left.
        const auto ideal = variance_of(lights, first, second, [&](std::size_t i) { return first[i] / with_bvh.irradiance; });
        // The same, measured: one light sample per estimate, 40000 estimates each.
        const int n = 40000;
        const auto mc = [&](bool use_bvh) {
            return stats_of(n, [&] {
                const T u = g.uniform<T>();
                const shade::vec2<T> u2 = uniform2<T>(g);
                const auto choice = use_bvh ? bvh.sample(ctx, u) : power.sample(u);
                if (!choice) return 0.0;
                return irradiance_sample(lights[choice->index], ctx, u2) / double(choice->probability);
            });
        };
        const sample_stats b = mc(true), w = mc(false);
        const double ratio = w.variance / b.variance;
        const double ratio_rel_se = std::sqrt(std::pow(b.variance_se / b.variance, 2) + std::pow(w.variance_se / w.variance, 2));
        MESSAGE("p = (" << pt.p.x << ", " << pt.p.y << ", " << pt.p.z << "): irradiance " << with_bvh.irradiance
                << "; variance power / bvh = " << exact_ratio << " (from per-light moments), " << ratio << " +- "
                << ratio * ratio_rel_se << " (measured, " << n << " samples each; means " << b.mean << ", " << w.mean
                << "); bvh / ideal = " << with_bvh.variance / ideal.variance);
        // Both estimators are unbiased: their means agree with the irradiance.
        CHECK(std::fabs(b.mean - with_bvh.irradiance) <= 4 * std::sqrt(b.variance / n) + 1e-3 * with_bvh.irradiance);
        CHECK(std::fabs(w.mean - with_bvh.irradiance) <= 4 * std::sqrt(w.variance / n) + 1e-3 * with_bvh.irradiance);
        // The moments' ratio is what the variance is; the measured one, whose power-sampling
        // variance is heavy-tailed (rare close bright lights), must not contradict it.
        CHECK(exact_ratio >= 2);
        CHECK(ratio * (1 + 3 * ratio_rel_se) >= 2);
        worst_exact = std::fmin(worst_exact, exact_ratio);
        relative_bvh += with_bvh.variance / (with_bvh.irradiance * with_bvh.irradiance);
        relative_power += with_power.variance / (with_bvh.irradiance * with_bvh.irradiance);
    }
    // Over the scene: the relative variance (variance / irradiance^2, what an image's noise
    // looks like) summed over the points.
    MESSAGE("variance power / bvh: lowest over the points " << worst_exact << ", of the summed relative variance "
            << relative_power / relative_bvh);
    CHECK(relative_power / relative_bvh >= 3);
}

TEST_CASE_TEMPLATE("light_bounds_of: boxes hold the lights, cones hold the directions they light", T, float, double) {
    // Every point a light's sample reaches lies in its box, and every direction from that
    // point to p lies within theta_o + theta_e of the axis; lights at infinity have none.
    using v3 = shade::vec3<T>;
    const auto e = shade::emission<T>::from_physical(shade::rgb<T>(T(3)));
    std::vector<shade::any_light<T>> lights;
    lights.push_back(shade::area_light<T>(v3(1, 2, 3), v3(T(0.5), 0, T(0.2)), v3(0, T(0.7), 0), e));
    lights.push_back(shade::disk_light<T>(v3(-1, 0, 2), glm::normalize(v3(1, 2, -1)), T(0.4), e, shade::sidedness::two_sided));
    lights.push_back(shade::sphere_light<T>(v3(0, -2, 1), T(0.3), e));
    lights.push_back(shade::spot_light<T>(v3(0, 0, 4), v3(0, 0, -1), T(0.2), T(0.5), e));
    lights.push_back(shade::point_light<T>(v3(2, 2, 2), e));
    shade::rng g(41);
    lights.push_back(make_triangle<T>(g, v3(0, 1, -1), glm::normalize(v3(1, 1, 1)), T(0.5), T(4)));
    lights.push_back(shade::directional_light<T>(v3(0, 0, 1), e));
    for (const auto& light : lights) {
        const shade::light_bounds<T> b = shade::light_bounds_of(light, T(10));
        const bool directional = &light == &lights.back();
        CHECK(b.at_infinity == directional);
        if (directional) {
            CHECK(b.power > T(0));
            continue;
        }
        CHECK(b.power == doctest::Approx(double(shade::detail::power_luminance(light.power(T(10))))));
        // Slack for the rounding of sampled points and of the box's own corners.
        const T slack = T(1e-4);
        int reached = 0;
        for (int k = 0; k < 2000; ++k) {
            const v3 p = T(5) * random_unit<T>(g);
            const auto s = light.sample_incident(p, uniform2<T>(g));
            if (!s) continue;
            ++reached;
            const v3 x = p + s->distance * s->l;
            CHECK(x.x >= b.box.lo.x - slack);
            CHECK(x.y >= b.box.lo.y - slack);
            CHECK(x.z >= b.box.lo.z - slack);
            CHECK(x.x <= b.box.hi.x + slack);
            CHECK(x.y <= b.box.hi.y + slack);
            CHECK(x.z <= b.box.hi.z + slack);
            // The direction from x to p is within theta_o + theta_e of the axis.
            const T angle = shade::detail::safe_acos(glm::dot(b.axis, -s->l));
            CHECK(angle <= b.theta_o + b.theta_e + T(1e-3));
        }
        CHECK(reached > 100);
    }
}
