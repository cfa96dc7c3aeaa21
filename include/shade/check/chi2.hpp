#pragma once
// The statistics behind the sampling checks: the chi-square goodness-of-fit statistic over
// binned counts (with pooling of low-expectation bins), its p-value from the regularized
// incomplete gamma function, and the Šidák-corrected significance level for a family of
// tests. Plain functions on numbers, usable without any BRDF.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <span>
#include <vector>

#include <shade/core/error.hpp>

namespace shade::check {

/// The regularized upper incomplete gamma function Q(a, x) = Γ(a, x) / Γ(a), for a > 0,
/// x >= 0 (Q = 1 - P; Abramowitz & Stegun 1964, "Handbook of Mathematical Functions",
/// 6.5.1-6.5.3). Evaluated as in Press, Teukolsky, Vetterling & Flannery 2007, "Numerical
/// Recipes", 3rd ed., sec. 6.2: for x < a + 1 by the series of P (A&S 6.5.29),
///   P(a, x) = e^-x x^a / Γ(a + 1) * Σ_{n>=0} x^n / ((a + 1)(a + 2)...(a + n)),
/// otherwise by the continued fraction of Q (A&S 6.5.31),
///   Q(a, x) = e^-x x^a / Γ(a) * 1/(x + 1 - a - 1(1 - a)/(x + 3 - a - 2(2 - a)/(x + 5 - a - ...))),
/// evaluated with the modified Lentz method (Thompson & Barnett 1986, "Coulomb and Bessel
/// functions of complex arguments and order", J. Comput. Phys. 64). Each branch is used
/// where it converges fast and where the quantity it returns does not cancel, so small
/// p-values keep their relative accuracy. Throws invalid_parameter for a <= 0 or x < 0.
[[nodiscard]] inline double regularized_gamma_q(double a, double x) {
    if (!(a > 0) || !std::isfinite(a)) throw invalid_parameter("a", "must be finite and > 0", shade::detail::to_text(a));
    if (!(x >= 0)) throw invalid_parameter("x", "must be >= 0", shade::detail::to_text(x));
    if (x == 0) return 1;
    if (std::isinf(x)) return 0;
    constexpr double eps = std::numeric_limits<double>::epsilon();
    const double log_prefactor = -x + a * std::log(x) - std::lgamma(a);
    if (x < a + 1) {
        // Series of P; its terms shrink by x / (a + n) < 1.
        double term = 1 / a;
        double sum = term;
        for (int n = 1; n < 100000; ++n) {
            term *= x / (a + n);
            sum += term;
            if (std::abs(term) < std::abs(sum) * eps) break;
        }
        return std::clamp(1 - sum * std::exp(log_prefactor), 0.0, 1.0);
    }
    // Continued fraction of Q, modified Lentz: b_n = x + 2n + 1 - a, a_n = -n (n - a).
    constexpr double tiny = std::numeric_limits<double>::min() / eps;
    double b = x + 1 - a;
    double c = 1 / tiny;
    double d = 1 / b;
    double h = d;
    for (int n = 1; n < 100000; ++n) {
        const double an = -n * (n - a);
        b += 2;
        d = an * d + b;
        if (std::abs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::abs(c) < tiny) c = tiny;
        d = 1 / d;
        const double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1) < eps) break;
    }
    return std::clamp(std::exp(log_prefactor) * h, 0.0, 1.0);
}

/// The p-value of a chi-square statistic with `dof` degrees of freedom: the probability
/// that a chi-square variable exceeds `statistic`, Q(dof/2, statistic/2) (A&S 26.4.19).
[[nodiscard]] inline double chi2_p_value(double statistic, double dof) {
    if (!(dof > 0)) throw invalid_parameter("dof", "must be > 0", shade::detail::to_text(dof));
    if (std::isnan(statistic)) return 0; // a NaN statistic comes from NaN counts: reject
    return regularized_gamma_q(dof / 2, std::max(statistic, 0.0) / 2);
}

/// The per-test significance level that keeps the chance of any false rejection among
/// `tests` independent tests at `alpha`: 1 - (1 - alpha)^(1/tests) (Šidák 1967,
/// "Rectangular confidence regions for the means of multivariate normal distributions",
/// JASA 62(318)). Computed as -expm1(log1p(-alpha) / tests), which keeps its digits when
/// the level is tiny.
[[nodiscard]] inline double sidak_significance(double alpha, std::size_t tests) {
    if (!(alpha > 0 && alpha < 1)) throw invalid_parameter("alpha", "must be in (0, 1)", shade::detail::to_text(alpha));
    if (tests == 0) throw invalid_parameter("tests", "must be >= 1", "0");
    return -std::expm1(std::log1p(-alpha) / double(tests));
}

/// A chi-square statistic over binned counts.
struct chi2_statistic {
    double statistic = 0;    ///< Σ (observed - expected)² / expected over the pooled bins
    std::size_t dof = 0;     ///< pooled bins - 1 (the counts' total is fixed)
    std::size_t bins = 0;    ///< bins after pooling
    std::size_t pooled = 0;  ///< input bins merged into the pool of low-expectation bins
};

/// Pearson's chi-square statistic for observed counts against expected counts (same
/// length; the totals should agree). The chi-square approximation of the statistic's
/// distribution needs enough expectation per bin; the classic rule (Cochran 1954, "Some
/// methods for strengthening the common χ² tests", Biometrics 10(4)) is an expected count
/// of at least 5, so every bin whose expectation is below `min_expected` is merged into one
/// pool (as pbrt-v4's and Mitsuba 3's BSDF tests do), and if the pool's own expectation is
/// still below `min_expected` it is merged with the smallest remaining bin. Bins with
/// expected and observed both 0 carry no information and are dropped.
[[nodiscard]] inline chi2_statistic pearson_chi2(std::span<const double> observed, std::span<const double> expected,
                                                 double min_expected = 5) {
    if (observed.size() != expected.size())
        throw invalid_parameter("observed", "must have as many bins as expected",
                                shade::detail::to_text(double(observed.size())));
    std::vector<std::size_t> order(observed.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return expected[i] < expected[j]; });
    chi2_statistic s;
    double pool_observed = 0;
    double pool_expected = 0;
    std::size_t k = 0;
    for (; k < order.size() && expected[order[k]] < min_expected; ++k) {
        pool_observed += observed[order[k]];
        pool_expected += std::max(expected[order[k]], 0.0);
        if (observed[order[k]] != 0 || expected[order[k]] != 0) ++s.pooled;
    }
    // Too little in the pool: take in the smallest remaining bins until it has enough.
    while (s.pooled > 0 && pool_expected < min_expected && k < order.size()) {
        pool_observed += observed[order[k]];
        pool_expected += expected[order[k]];
        ++s.pooled;
        ++k;
    }
    const auto add = [&](double o, double e) {
        ++s.bins;
        if (e > 0) s.statistic += (o - e) * (o - e) / e;
        else if (o > 0) s.statistic = std::numeric_limits<double>::infinity(); // counts where none may fall
    };
    if (s.pooled > 0) add(pool_observed, pool_expected);
    for (; k < order.size(); ++k) add(observed[order[k]], expected[order[k]]);
    s.dof = s.bins > 0 ? s.bins - 1 : 0;
    return s;
}

} // namespace shade::check
