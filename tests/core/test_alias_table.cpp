// shade::alias_table (Walker 1977, Vose 1991): every index is drawn with probability
// w_i / sum(w) (exactly, for u swept over a fine grid; and by a chi-square test of random
// draws), zero weights are never drawn, and bad weights are refused by name.

#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <shade/check/chi2.hpp>
#include <shade/core/alias_table.hpp>
#include <shade/core/error.hpp>
#include <shade/core/random.hpp>

namespace {

// The fraction of a uniform grid of m values of u in [0, 1) mapped to each index. A grid
// of m = n 2^k points with 2^k a multiple of the thresholds' denominators measures each
// bin's split exactly; for general thresholds the error per bin is at most 1/m.
template <class T>
std::vector<double> grid_frequencies(const shade::alias_table<T>& table, std::size_t m) {
    std::vector<double> hits(table.size(), 0);
    for (std::size_t j = 0; j < m; ++j) hits[table.sample(T((double(j) + 0.5) / double(m))).index] += 1;
    for (auto& h : hits) h /= double(m);
    return hits;
}

} // namespace

TEST_CASE_TEMPLATE("alias_table: probabilities are the normalised weights, and draws follow them", T, float, double) {
    const std::vector<T> weights{T(1), T(0), T(3), T(0.5), T(10), T(0), T(2.5)};
    const shade::alias_table<T> table(weights);
    REQUIRE(table.size() == weights.size());
    const double sum = 17;
    for (std::size_t i = 0; i < weights.size(); ++i) CHECK(table.probability(i) == doctest::Approx(double(weights[i]) / sum));
    // Every u of a fine grid (m = 2^16 points, exact in float too): an index gets its own
    // bin's part below the threshold and the parts above it of the bins it is the alias
    // of; each part's share is measured to within one grid step, 1/m, so an index's share
    // is within (n + 1)/m of its probability.
    const std::size_t m = 1 << 16;
    const auto freq = grid_frequencies(table, m);
    const double tolerance = double(weights.size() + 1) / double(m);
    for (std::size_t i = 0; i < weights.size(); ++i) CHECK(std::abs(freq[i] - double(weights[i]) / sum) <= tolerance);
    for (std::size_t i = 0; i < weights.size(); ++i)
        if (weights[i] == T(0)) CHECK(freq[i] == 0);
    // Random draws against the probabilities: Pearson's chi-square at alpha = 1e-3.
    shade::rng random(7);
    const std::size_t draws = 200000;
    std::vector<double> observed(weights.size(), 0), expected(weights.size());
    for (std::size_t k = 0; k < draws; ++k) {
        const auto c = table.sample(random.uniform<T>());
        REQUIRE(c.index < weights.size());
        CHECK_MESSAGE(c.probability == table.probability(c.index), "the draw reports its index's probability");
        observed[c.index] += 1;
    }
    for (std::size_t i = 0; i < weights.size(); ++i) expected[i] = double(draws) * double(weights[i]) / sum;
    const auto chi2 = shade::check::pearson_chi2(observed, expected);
    CHECK(shade::check::chi2_p_value(chi2.statistic, double(chi2.dof)) > 1e-3);
}

TEST_CASE_TEMPLATE("alias_table: edge values of u, one entry, many entries", T, float, double) {
    const std::vector<T> one{T(2)};
    const shade::alias_table<T> single(one);
    CHECK(single.sample(T(0)).index == 0);
    CHECK(single.sample(T(0)).probability == T(1));
    // u just below 1 and u = 1 (outside the precondition) stay inside the table.
    const std::vector<T> w{T(1), T(1), T(0)};
    const shade::alias_table<T> table(w);
    CHECK(table.sample(std::nextafter(T(1), T(0))).index < 2);
    CHECK(table.sample(T(1)).index < 2);
    // 10^5 weights 1..n: probability of i is (i + 1) / (n (n + 1) / 2).
    const std::size_t n = 100000;
    std::vector<T> ramp(n);
    for (std::size_t i = 0; i < n; ++i) ramp[i] = T(i + 1);
    const shade::alias_table<T> big(ramp);
    const double total = double(n) * double(n + 1) / 2;
    CHECK(big.probability(n - 1) == doctest::Approx(double(n) / total));
    CHECK(big.probability(0) == doctest::Approx(1 / total));
}

TEST_CASE_TEMPLATE("alias_table: bad weights are refused naming 'weights'", T, float, double) {
    const auto parameter_of = [](std::vector<T> w) {
        try {
            shade::alias_table<T> t(w);
        } catch (const shade::invalid_parameter& e) {
            return e.parameter();
        }
        return std::string("(accepted)");
    };
    CHECK(parameter_of({}) == "weights");
    CHECK(parameter_of({T(1), T(-1)}) == "weights");
    CHECK(parameter_of({T(1), std::numeric_limits<T>::quiet_NaN()}) == "weights");
    CHECK(parameter_of({T(1), std::numeric_limits<T>::infinity()}) == "weights");
    CHECK(parameter_of({T(0), T(0)}) == "weights");
}
