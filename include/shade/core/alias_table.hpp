#pragma once
// shade::alias_table: draws an index i with probability w_i / sum(w) in constant time
// (Walker 1977, "An Efficient Method for Generating Discrete Random Variables with General
// Distributions", ACM TOMS 3(3); built in linear time by Vose 1991, "A Linear Algorithm for
// Generating Random Numbers with a Given Distribution", IEEE TSE 17(9)).
//
// Each of the n bins holds a threshold q_i and an alias a_i: u in [0, 1) picks bin
// i = floor(n u), and the remaining fraction of n u chooses i itself when below q_i, a_i
// otherwise. Vose's construction fills every bin to exactly 1/n of probability, so the
// draw is exact up to the rounding of the thresholds.

#include <cmath>
#include <concepts>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <shade/core/error.hpp>

namespace shade {

namespace detail {

/// floor(x) as an index below n, for x > 0 (x >= n, which u = 1 or the rounding of u n up
/// to n gives, maps to n - 1). Used instead of std::min to keep <algorithm> out.
template <std::floating_point T>
[[nodiscard]] inline std::size_t clamped_index(T x, std::size_t n) noexcept {
    if (!(x < static_cast<T>(n))) return n - 1;
    const auto i = static_cast<std::size_t>(x);
    return i < n ? i : n - 1; // T(n) may round above n
}

} // namespace detail

template <std::floating_point T>
class alias_table {
public:
    using scalar_type = T;

    /// One draw: the index and the probability with which it is drawn (w_i / sum(w)).
    struct choice {
        std::size_t index = 0;
        T probability = 0;
    };

    /// A table over the weights (any non-negative scale). Throws invalid_parameter naming
    /// "weights" when there is none, when one is negative, NaN or infinite, or when they
    /// sum to 0. A weight of 0 is never drawn.
    explicit alias_table(std::span<const T> weights) {
        const std::size_t n = weights.size();
        if (n == 0) throw invalid_parameter("weights", "must not be empty", "0 weights");
        // The sum and the scaled weights in long double: the thresholds then carry less
        // rounding than T can show, whatever n is.
        long double sum = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const T w = weights[i];
            if (!std::isfinite(w) || !(w >= T(0)))
                throw invalid_parameter("weights", "must each be finite and >= 0",
                                        "weights[" + std::to_string(i) + "] = " + detail::to_text(w));
            sum += w;
        }
        if (!(sum > 0)) throw invalid_parameter("weights", "must not all be 0", detail::to_text(static_cast<double>(sum)));
        bins_.resize(n);
        std::vector<long double> scaled(n);
        std::vector<std::size_t> small, large;
        for (std::size_t i = 0; i < n; ++i) {
            bins_[i].probability = static_cast<T>(static_cast<long double>(weights[i]) / sum);
            scaled[i] = static_cast<long double>(weights[i]) * static_cast<long double>(n) / sum;
            (scaled[i] < 1 ? small : large).push_back(i);
        }
        // Vose: pair a bin below 1 with one above, which gives it the missing mass and
        // becomes its alias.
        while (!small.empty() && !large.empty()) {
            const std::size_t s = small.back();
            small.pop_back();
            const std::size_t l = large.back();
            bins_[s].threshold = static_cast<T>(scaled[s]);
            bins_[s].alias = l;
            scaled[l] -= 1 - scaled[s];
            if (scaled[l] < 1) {
                large.pop_back();
                small.push_back(l);
            }
        }
        // What is left is 1 up to rounding and keeps its whole bin; a zero weight left
        // over by rounding goes to the heaviest entry instead, so that it is never drawn.
        std::size_t heaviest = 0;
        for (std::size_t i = 1; i < n; ++i)
            if (weights[i] > weights[heaviest]) heaviest = i;
        for (const auto* rest : {&small, &large})
            for (const std::size_t i : *rest) {
                const bool empty = weights[i] == T(0);
                bins_[i].threshold = empty ? T(0) : T(1);
                bins_[i].alias = empty ? heaviest : i;
            }
    }

    /// The number of entries.
    [[nodiscard]] std::size_t size() const noexcept { return bins_.size(); }

    /// The probability of drawing index i (w_i / sum(w)). Precondition: i < size().
    [[nodiscard]] T probability(std::size_t i) const noexcept { return bins_[i].probability; }

    /// Draws an index with u in [0, 1) (values outside are clamped into the table).
    [[nodiscard]] choice sample(T u) const noexcept {
        const std::size_t n = bins_.size();
        const T scaled = u * static_cast<T>(n);
        const std::size_t i = scaled > T(0) ? detail::clamped_index(scaled, n) : 0;
        const T fraction = scaled - static_cast<T>(i);
        const std::size_t k = fraction < bins_[i].threshold ? i : bins_[i].alias;
        return {k, bins_[k].probability};
    }

private:
    struct bin {
        T probability = 0; ///< w_i / sum(w)
        T threshold = 1;   ///< fractions below it choose this bin's own index
        std::size_t alias = 0;
    };
    std::vector<bin> bins_;
};

} // namespace shade
