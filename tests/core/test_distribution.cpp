// shade::piecewise_constant_1d and piecewise_constant_2d: probabilities proportional to the
// weights, samples that agree with pdf and land where pdf says (chi-square), u at the
// edges of [0,1), the all-zero fallback and the validation of the weights.

#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <shade/check/chi2.hpp>
#include <shade/core/distribution.hpp>
#include <shade/core/error.hpp>
#include <shade/core/random.hpp>

namespace {

template <class T>
constexpr T below_one = T(1) - std::numeric_limits<T>::epsilon() / T(2);

// Significance of each chi-square test here, as in the BRDF tests: small enough that a
// correct sampler fails none of a thousand such tests with probability above 0.99.
constexpr double significance = 1e-5;

} // namespace

TEST_CASE_TEMPLATE("piecewise_constant_1d: probabilities in proportion to the weights, density n P_i", T, float, double) {
    const std::vector<T> w{1, 0, 3, 2};
    const shade::piecewise_constant_1d<T> d(w);
    REQUIRE(d.size() == 4);
    CHECK(d.probability(0) == doctest::Approx(1.0 / 6));
    CHECK(d.probability(1) == T(0));
    CHECK(d.probability(2) == doctest::Approx(3.0 / 6));
    CHECK(d.probability(3) == doctest::Approx(2.0 / 6));
    CHECK(d.probability(4) == T(0));
    CHECK(d.pdf(T(0.1)) == doctest::Approx(4.0 / 6));
    CHECK(d.pdf(T(0.3)) == T(0));
    CHECK(d.pdf(T(0.6)) == doctest::Approx(2.0));
    CHECK(d.pdf(below_one<T>) == doctest::Approx(4.0 / 3));
    CHECK(d.cdf().front() == T(0));
    CHECK(d.cdf().back() == T(1));
    double total = 0;
    for (std::size_t i = 0; i < d.size(); ++i) total += double(d.probability(i));
    CHECK(total == doctest::Approx(1.0).epsilon(sizeof(T) == 4 ? 1e-6 : 1e-12)); // differences rounded to T
}

TEST_CASE_TEMPLATE("piecewise_constant_1d: inversion at the edges of u, zero bins skipped, x < 1", T, float, double) {
    const std::vector<T> w{1, 0, 3, 2, 0};
    const shade::piecewise_constant_1d<T> d(w);
    const auto first = d.sample_continuous(T(0));
    CHECK(first.x == T(0));
    CHECK(first.index == 0);
    // u = 1/6 is the first u of bin 2 (bin 1 has no step): never bin 1.
    const auto after_zero = d.sample_continuous(d.cdf()[2]);
    CHECK(after_zero.index == 2);
    CHECK(after_zero.x == doctest::Approx(0.4));
    // u = 1 - ulp: the last bin with weight (bin 3), strictly inside [0, 1), not bin 4.
    const auto last = d.sample_continuous(below_one<T>);
    CHECK(last.index == 3);
    CHECK(last.x < T(0.8));
    CHECK(last.x >= T(0.6));
    CHECK(last.pdf == d.pdf(last.x));
    CHECK(d.sample_discrete(below_one<T>).index == 3);
    CHECK(d.sample_discrete(T(0)).index == 0);
    // Outside the precondition u is clamped rather than read out of range.
#ifdef NDEBUG
    CHECK(d.sample_continuous(T(1)).index == 3);
    CHECK(d.sample_continuous(T(1)).x < T(1));
#endif

    // Many bins, the last holding nearly all the mass: u = 1 - ulp stays inside [0, 1)
    // and in range, and its density is the one pdf reports.
    std::vector<T> many(1000, T(1e-3));
    many.back() = T(1e6);
    const shade::piecewise_constant_1d<T> m(many);
    for (const T u : {T(0), below_one<T>, T(0.5), std::nextafter(T(0), T(1))}) {
        const auto s = m.sample_continuous(u);
        CAPTURE(u);
        CHECK(s.x >= T(0));
        CHECK(s.x < T(1));
        CHECK(s.index < m.size());
        CHECK(std::isfinite(s.pdf));
        CHECK(s.pdf > T(0));
        CHECK(s.pdf == m.pdf(s.x));
        CHECK(s.offset >= T(0));
        CHECK(s.offset < T(1));
    }
}

TEST_CASE_TEMPLATE("piecewise_constant_1d: every sample's pdf is pdf(x), x monotone in u, never in an empty bin", T,
                   float, double) {
    shade::rng random(7);
    std::vector<T> w(37);
    for (std::size_t i = 0; i < w.size(); ++i) w[i] = i % 5 == 2 ? T(0) : random.uniform<T>() * T(100);
    const shade::piecewise_constant_1d<T> d(w);
    int mismatches = 0, empty = 0, outside = 0, reversed = 0;
    T previous = T(-1);
    constexpr int n = 100000;
    for (int k = 0; k < n; ++k) {
        // Increasing u (stratified), so that x must increase too.
        const T u = (T(k) + random.uniform<T>()) / T(n);
        const auto s = d.sample_continuous(std::min(u, below_one<T>));
        if (s.pdf != d.pdf(s.x)) ++mismatches;
        if (w[s.index] == T(0)) ++empty;
        if (!(s.x >= T(0) && s.x < T(1)) || shade::detail::bin_of(s.x, d.size()) != s.index) ++outside;
        if (s.x < previous) ++reversed;
        previous = s.x;
    }
    CHECK(mismatches == 0);
    CHECK(empty == 0);
    CHECK(outside == 0);
    CHECK(reversed == 0);
}

TEST_CASE_TEMPLATE("piecewise_constant_1d: chi-square of continuous and discrete samples against pdf", T, float, double) {
    shade::rng random(11);
    const std::vector<T> w{T(0.5), T(4), T(0), T(1), T(2.5), T(0.01), T(3)};
    const shade::piecewise_constant_1d<T> d(w);
    constexpr std::size_t n = 200000;
    constexpr std::size_t sub = 8; // each bin cut in 8, so the placement inside a bin is tested too
    std::vector<double> observed(w.size() * sub, 0.0), expected(w.size() * sub, 0.0);
    std::vector<double> observed_discrete(w.size(), 0.0), expected_discrete(w.size(), 0.0);
    for (std::size_t i = 0; i < observed.size(); ++i)
        expected[i] = double(n) * double(d.pdf(T((double(i) + 0.5) / double(observed.size())))) /
                      double(observed.size());
    for (std::size_t i = 0; i < w.size(); ++i) expected_discrete[i] = double(n) * double(d.probability(i));
    for (std::size_t k = 0; k < n; ++k) {
        const auto s = d.sample_continuous(random.uniform<T>());
        observed[std::min(std::size_t(double(s.x) * double(observed.size())), observed.size() - 1)] += 1;
        observed_discrete[d.sample_discrete(random.uniform<T>()).index] += 1;
    }
    const auto c = shade::check::pearson_chi2(observed, expected);
    const double p = shade::check::chi2_p_value(c.statistic, double(c.dof));
    MESSAGE("continuous: chi2 = " << c.statistic << ", dof " << c.dof << ", p = " << p);
    CHECK(p > significance);
    const auto cd = shade::check::pearson_chi2(observed_discrete, expected_discrete);
    const double pd = shade::check::chi2_p_value(cd.statistic, double(cd.dof));
    MESSAGE("discrete: chi2 = " << cd.statistic << ", dof " << cd.dof << ", p = " << pd);
    CHECK(pd > significance);
}

TEST_CASE_TEMPLATE("piecewise_constant_1d: all-zero weights fall back to the uniform density", T, float, double) {
    const std::vector<T> w(5, T(0));
    const shade::piecewise_constant_1d<T> d(w);
    for (std::size_t i = 0; i < 5; ++i) CHECK(d.probability(i) == doctest::Approx(0.2));
    CHECK(d.pdf(T(0.77)) == doctest::Approx(1.0));
    const auto s = d.sample_continuous(T(0.3));
    CHECK(s.x == doctest::Approx(0.3));
    CHECK(s.pdf == doctest::Approx(1.0));
}

TEST_CASE_TEMPLATE("piecewise_constant_1d: bad weights throw invalid_parameter naming the parameter", T, float, double) {
    const auto throws_naming = [](std::vector<T> w, const char* name, const char* part) {
        try {
            (void)shade::piecewise_constant_1d<T>(w, name);
            FAIL("no exception");
        } catch (const shade::invalid_parameter& e) {
            CHECK(e.parameter() == name);
            CHECK(std::string(e.what()).find(part) != std::string::npos);
        }
    };
    throws_naming({}, "weights", "between 1 and");
    throws_naming({T(1), T(-1)}, "weights", "at index 1");
    throws_naming({T(1), std::numeric_limits<T>::quiet_NaN()}, "luminance", "nan at index 1");
    throws_naming({std::numeric_limits<T>::infinity()}, "weights", "finite");
    const std::vector<T> ok{T(1)};
    CHECK_NOTHROW((void)shade::piecewise_constant_1d<T>(ok));
}

TEST_CASE_TEMPLATE("piecewise_constant_2d: cell probabilities P(j) P(i | j), samples agree with pdf, chi-square", T,
                   float, double) {
    // 4 columns x 3 rows; the middle row is black (never drawn), one cell dominates.
    const std::vector<T> w{1, 2, 0, 1,  //
                           0, 0, 0, 0,  //
                           T(0.5), 8, 1, T(0.25)};
    const shade::piecewise_constant_2d<T> d(w, 4, 3);
    double sum = 0;
    for (const T x : w) sum += double(x);
    for (std::size_t j = 0; j < 3; ++j)
        for (std::size_t i = 0; i < 4; ++i) {
            CAPTURE(i);
            CAPTURE(j);
            CHECK(d.probability(i, j) == doctest::Approx(double(w[j * 4 + i]) / sum).epsilon(1e-6));
            CHECK(d.pdf(shade::vec2<T>(T((double(i) + 0.5) / 4), T((double(j) + 0.5) / 3))) ==
                  doctest::Approx(12 * double(w[j * 4 + i]) / sum).epsilon(1e-6));
        }
    CHECK(d.probability(4, 0) == T(0));
    CHECK(d.probability(0, 3) == T(0));

    shade::rng random(3);
    constexpr std::size_t n = 200000;
    constexpr std::size_t sub = 4; // sub x sub bins per cell
    const std::size_t bx = 4 * sub, by = 3 * sub;
    std::vector<double> observed(bx * by, 0.0), expected(bx * by, 0.0);
    for (std::size_t j = 0; j < by; ++j)
        for (std::size_t i = 0; i < bx; ++i)
            expected[j * bx + i] = double(n) *
                                   double(d.pdf(shade::vec2<T>(T((double(i) + 0.5) / double(bx)),
                                                               T((double(j) + 0.5) / double(by))))) /
                                   double(bx * by);
    int mismatches = 0, outside = 0;
    for (std::size_t k = 0; k < n; ++k) {
        const auto s = d.sample_continuous(shade::vec2<T>(random.uniform<T>(), random.uniform<T>()));
        if (s.pdf != d.pdf(s.uv)) ++mismatches;
        if (!(s.uv.x >= T(0) && s.uv.x < T(1) && s.uv.y >= T(0) && s.uv.y < T(1)) || s.row == 1) ++outside;
        const std::size_t i = std::min(std::size_t(double(s.uv.x) * double(bx)), bx - 1);
        const std::size_t j = std::min(std::size_t(double(s.uv.y) * double(by)), by - 1);
        observed[j * bx + i] += 1;
    }
    CHECK(mismatches == 0);
    CHECK(outside == 0);
    const auto c = shade::check::pearson_chi2(observed, expected);
    const double p = shade::check::chi2_p_value(c.statistic, double(c.dof));
    MESSAGE("2D: chi2 = " << c.statistic << ", dof " << c.dof << ", p = " << p);
    CHECK(p > significance);

    for (const T a : {T(0), below_one<T>})
        for (const T b : {T(0), below_one<T>}) {
            const auto s = d.sample_continuous(shade::vec2<T>(a, b));
            CHECK(s.uv.x < T(1));
            CHECK(s.uv.y < T(1));
            CHECK(s.column < 4);
            CHECK(s.row < 3);
            CHECK(s.pdf > T(0));
            CHECK(s.pdf == d.pdf(s.uv));
        }
}

TEST_CASE_TEMPLATE("piecewise_constant_2d: bad sizes and weights throw invalid_parameter", T, float, double) {
    const std::vector<T> w(6, T(1));
    CHECK_THROWS_WITH_AS((void)shade::piecewise_constant_2d<T>(w, 4, 2), doctest::Contains("'weights'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::piecewise_constant_2d<T>(w, 0, 6), doctest::Contains("'width'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::piecewise_constant_2d<T>(w, 6, 0), doctest::Contains("'height'"),
                         shade::invalid_parameter);
    std::vector<T> bad = w;
    bad[4] = T(-2);
    CHECK_THROWS_WITH_AS((void)shade::piecewise_constant_2d<T>(bad, 3, 2), doctest::Contains("at index 4"),
                         shade::invalid_parameter);
    const std::vector<T> zeros(6, T(0));
    const shade::piecewise_constant_2d<T> uniform(zeros, 3, 2);
    CHECK(uniform.pdf(shade::vec2<T>(T(0.9), T(0.1))) == doctest::Approx(1.0));
}
