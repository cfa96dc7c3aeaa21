// shade::uniform_light_sampler and shade::power_light_sampler: choice probabilities equal
// the stated ones (1/n, Phi_i / sum Phi), draws follow them, dark lights are never chosen,
// an all-dark scene falls back to uniform, and bad powers are refused by name.

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <shade/check/chi2.hpp>
#include <shade/core/error.hpp>
#include <shade/core/random.hpp>
#include <shade/light/light_sampler.hpp>

TEST_CASE_TEMPLATE("uniform_light_sampler: 1/n each, every light reachable", T, float, double) {
    const shade::uniform_light_sampler<T> none(0);
    CHECK(!none.sample(T(0.5)));
    CHECK(none.probability(0) == T(0));
    const shade::uniform_light_sampler<T> s(3);
    CHECK(s.sample(T(0)).value().index == 0);
    CHECK(s.sample(T(0.5)).value().index == 1);
    CHECK(s.sample(std::nextafter(T(1), T(0))).value().index == 2);
    CHECK(s.sample(T(0.9)).value().probability == doctest::Approx(1.0 / 3));
    CHECK(s.probability(2) == doctest::Approx(1.0 / 3));
    CHECK(s.probability(3) == T(0));
}

TEST_CASE_TEMPLATE("power_light_sampler: probabilities proportional to power; draws follow them", T, float, double) {
    const std::vector<T> powers{T(100), T(0), T(1), T(10), T(0.1)};
    const shade::power_light_sampler<T> s(powers);
    const double total = 111.1;
    for (std::size_t i = 0; i < powers.size(); ++i) CHECK(s.probability(i) == doctest::Approx(double(powers[i]) / total));
    CHECK(s.probability(powers.size()) == T(0));
    shade::rng random(11);
    const std::size_t draws = 300000;
    std::vector<double> observed(powers.size(), 0), expected(powers.size());
    for (std::size_t k = 0; k < draws; ++k) {
        const auto c = s.sample(random.uniform<T>());
        REQUIRE(c);
        CHECK(c->index != 1); // the dark light
        CHECK(c->probability == s.probability(c->index));
        observed[c->index] += 1;
    }
    for (std::size_t i = 0; i < powers.size(); ++i) expected[i] = double(draws) * double(powers[i]) / total;
    const auto chi2 = shade::check::pearson_chi2(observed, expected);
    CHECK(shade::check::chi2_p_value(chi2.statistic, double(chi2.dof)) > 1e-3);
}

TEST_CASE_TEMPLATE("power_light_sampler: RGB powers by luminance; all dark is uniform; bad powers refused", T, float, double) {
    // Luminance of (1, 0, 0) is 0.2126 and of (0, 1, 0) 0.7152: probabilities 0.2126/0.9278 and
    // 0.7152/0.9278.
    const std::vector<shade::rgb<T>> rgb_powers{{1, 0, 0}, {0, 1, 0}};
    const auto s = shade::power_light_sampler<T>::from_rgb(rgb_powers);
    CHECK(s.probability(0) == doctest::Approx(0.2126 / 0.9278));
    CHECK(s.probability(1) == doctest::Approx(0.7152 / 0.9278));
    const std::vector<T> dark{T(0), T(0), T(0), T(0)};
    const shade::power_light_sampler<T> all_dark(dark);
    CHECK(all_dark.probability(3) == T(0.25));
    CHECK(all_dark.sample(T(0.8)).value().index == 3);
    const shade::power_light_sampler<T> empty(std::span<const T>{});
    CHECK(!empty.sample(T(0.1)));
    const auto parameter_of = [](std::vector<T> p) {
        try {
            shade::power_light_sampler<T> t(p);
        } catch (const shade::invalid_parameter& e) {
            return e.parameter();
        }
        return std::string("(accepted)");
    };
    CHECK(parameter_of({T(1), T(-2)}) == "powers");
    CHECK(parameter_of({std::numeric_limits<T>::quiet_NaN()}) == "powers");
    CHECK(parameter_of({T(1), std::numeric_limits<T>::infinity()}) == "powers");
}
