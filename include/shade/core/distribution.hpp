#pragma once
// Piecewise-constant distributions on [0,1) and [0,1)^2, sampled by inverting their
// cumulative distribution: shade::piecewise_constant_1d and shade::piecewise_constant_2d
// (the second drives shade::environment_map_light).
//
// The idea, as in Pharr, Jakob, Humphreys 2023, "Physically Based Rendering", 4th ed.,
// §A.4 "Sampling 1D Functions" (piecewise-constant functions, inverted through their CDF)
// and §A.5 "Sampling Multidimensional Functions" (piecewise-constant 2D distributions,
// drawn from the marginal density of the rows and the conditional density of a column
// within the chosen row): n non-negative weights f_0 .. f_{n-1} define the density
// p(x) = f_i / (sum_k f_k / n) for x in [i/n, (i+1)/n), whose cumulative distribution
// at the bin edges is c_i = sum_{k<i} f_k / sum_k f_k. A uniform u in [0,1) falls between
// c_i and c_{i+1} with probability c_{i+1} - c_i, which selects bin i; the offset of u
// within that step places x inside the bin.
//
// What "exact" means here: the stored edges c_i are rounded to T, and every density and
// probability these classes report is computed from the stored edges
// (probability of bin i = c_{i+1} - c_i, density = n (c_{i+1} - c_i)), so the reported
// values are those of the sampling actually done, up to the resolution of u, and the
// probabilities sum to c_n - c_0 = 1 up to the rounding of each difference in T.

#include <cmath>
#include <concepts>
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <shade/core/config.hpp>
#include <shade/core/error.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// A point drawn from a piecewise-constant density on [0,1).
template <std::floating_point T>
struct distribution_sample_1d {
    T x = T(0);              ///< the point, in [0, 1)
    T pdf = T(0);            ///< its density (per unit length of [0,1)), > 0
    std::size_t index = 0;   ///< the bin x lies in: x in [index/n, (index+1)/n) up to rounding
    T offset = T(0);         ///< where x lies within its bin, in [0, 1): x = (index + offset) / n
};

/// A bin drawn from a piecewise-constant distribution, with its probability.
template <std::floating_point T>
struct discrete_sample {
    std::size_t index = 0;   ///< the bin
    T probability = T(0);    ///< the probability of drawing it, > 0
    T offset = T(0);         ///< u's position within the bin's step of the CDF, in [0, 1)
};

namespace detail {

/// The largest T below 1: where u in [0,1) is clamped so that it never reaches 1.
template <std::floating_point T>
inline constexpr T one_minus_ulp = T(1) - std::numeric_limits<T>::epsilon() / T(2);

/// Fills cdf (n + 1 entries) with cdf[i] = sum_{k<i} w_k / sum_k w_k (sums in double),
/// cdf[n] = 1 exactly, or i / n when every weight is 0 (the documented fallback); returns
/// the sum. Throws invalid_parameter naming `parameter` if a weight is negative or not
/// finite, or if their sum overflows.
template <std::floating_point T>
double fill_cdf(std::span<const T> weights, std::span<T> cdf, std::string_view parameter,
                std::size_t first_index = 0) {
    const std::size_t n = weights.size();
    double sum = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const T w = weights[i];
        if (!std::isfinite(w) || !(w >= T(0))) {
            std::string got = to_text(w);
            got += " at index ";
            got += std::to_string(first_index + i);
            throw invalid_parameter(parameter, "must be finite and >= 0", got);
        }
        sum += double(w);
    }
    if (!std::isfinite(sum)) throw invalid_parameter(parameter, "must have a finite sum", to_text(sum));
    cdf[0] = T(0);
    double running = 0;
    for (std::size_t i = 0; i < n; ++i) {
        running += sum > 0 ? double(weights[i]) : 1.0;
        cdf[i + 1] = T(running / (sum > 0 ? sum : double(n)));
    }
    // The running sum may round to a little under or over the total: pin the last edge to 1,
    // and keep the edges non-decreasing (rounding to T is monotone, so they already are).
    cdf[n] = T(1);
    return sum;
}

/// u clamped to [0, 1 - ulp]; NaN gives 0.
template <std::floating_point T>
[[nodiscard]] constexpr T clamp_to_unit_interval(T u) noexcept {
    if (!(u >= T(0))) return T(0);
    return u < one_minus_ulp<T> ? u : one_minus_ulp<T>;
}

/// The length of the leading run of a on which pred holds, for a pred that holds on a
/// prefix of a and nowhere after it: binary search, as std::partition_point (written out
/// to keep <algorithm> and its ranges out of the header).
template <class T, class Pred>
[[nodiscard]] inline std::size_t count_leading(std::span<const T> a, Pred pred) noexcept {
    std::size_t lo = 0, count = a.size();
    while (count > 0) {
        const std::size_t half = count / 2;
        if (pred(a[lo + half])) {
            lo += half + 1;
            count -= half + 1;
        } else {
            count = half;
        }
    }
    return lo;
}

/// The discrete sample of the CDF for u in [0,1): the bin i with cdf[i] <= u < cdf[i+1]
/// (never one of probability 0: its step is empty), its probability, and u rescaled to
/// [0, 1) within the step. u, and the rescaled u (the division may round up to 1), are
/// clamped to [0, 1 - ulp], so u = 1 (outside the precondition) gives the last non-empty bin.
template <std::floating_point T>
[[nodiscard]] inline discrete_sample<T> sample_cdf(std::span<const T> cdf, T u) noexcept {
    const T uc = clamp_to_unit_interval(u);
    // The edges up to u: at least cdf[0] = 0 and never cdf[n] = 1 > u.
    const std::size_t i = count_leading(cdf, [uc](T c) { return c <= uc; }) - 1;
    discrete_sample<T> s;
    s.index = i;
    s.probability = cdf[i + 1] - cdf[i];
    s.offset = clamp_to_unit_interval((uc - cdf[i]) / s.probability);
    return s;
}

/// The bin of x in [0,1) among n equal bins: floor(x n), clamped to [0, n - 1] (x n may
/// round up to n for x just below 1; x outside [0,1) is clamped).
template <std::floating_point T>
[[nodiscard]] inline std::size_t bin_of(T x, std::size_t n) noexcept {
    const T scaled = x * T(n);
    if (!(scaled >= T(0))) return 0; // negative or NaN
    const auto i = std::size_t(scaled);
    return i < n ? i : n - 1;
}

/// The continuous sample over n = cdf.size() - 1 equal bins of [0,1): x = (i + offset) / n,
/// with the density n (cdf[i+1] - cdf[i]) of bin i. x is then moved by at most a few ulps
/// so that bin_of(x) == i (the division may round across the bin's edge, or up to 1), so
/// that the density evaluated at x is the one returned.
template <std::floating_point T>
[[nodiscard]] inline distribution_sample_1d<T> sample_continuous(std::span<const T> cdf, T u) noexcept {
    const std::size_t n = cdf.size() - 1;
    const discrete_sample<T> d = sample_cdf(cdf, u);
    distribution_sample_1d<T> s;
    s.index = d.index;
    s.offset = d.offset;
    s.pdf = d.probability * T(n);
    T x = clamp_to_unit_interval((T(d.index) + d.offset) / T(n));
    // Bounded: the rounding of (i + offset) / n and of x n is a few ulps at most.
    for (int k = 0; k < 8 && bin_of(x, n) > d.index; ++k) x = std::nextafter(x, T(0));
    for (int k = 0; k < 8 && bin_of(x, n) < d.index; ++k) x = std::nextafter(x, T(1));
    s.x = x;
    return s;
}

/// Throws invalid_parameter naming `parameter` unless 1 <= n <= 2^(digits of T - 2)
/// (float: 4194304): bins are counted exactly in T, and x n must resolve every bin.
template <std::floating_point T>
std::size_t require_bin_count(std::string_view parameter, std::size_t n) {
    constexpr int digits = std::numeric_limits<T>::digits < 62 ? std::numeric_limits<T>::digits : 62;
    constexpr std::size_t most = std::size_t(1) << (digits - 2);
    if (n < 1 || n > most)
        throw invalid_parameter(parameter, "must have between 1 and " + std::to_string(most) + " entries",
                                std::to_string(n));
    return n;
}

} // namespace detail

/// A piecewise-constant density on [0,1) with n equal bins, bin i weighted by weights[i]
/// (pbrt-v4 §A.4, see the top of this header): density p(x) = n P_i for x in bin i, where
/// P_i = c_{i+1} - c_i is the bin's probability, proportional to its weight. Weights that
/// are all zero give the uniform density (p = 1 everywhere; the documented fallback, so
/// that a black environment map still has a valid sampler). Bins of weight zero are never
/// drawn and have density 0.
template <std::floating_point T>
class piecewise_constant_1d {
public:
    using scalar_type = T;

    /// From the bins' weights (any scale; at least one, at most 2^(digits of T - 2)).
    /// Throws shade::invalid_parameter naming `parameter` if there are no weights or too
    /// many, if a weight is negative or not finite, or if their sum overflows.
    explicit piecewise_constant_1d(std::span<const T> weights, std::string_view parameter = "weights")
        : cdf_(detail::require_bin_count<T>(parameter, weights.size()) + 1) {
        (void)detail::fill_cdf(weights, std::span<T>(cdf_), parameter);
    }

    /// The number of bins n.
    [[nodiscard]] std::size_t size() const noexcept { return cdf_.size() - 1; }
    /// The cumulative distribution at the n + 1 bin edges: 0 = c_0 <= ... <= c_n = 1.
    [[nodiscard]] std::span<const T> cdf() const noexcept { return cdf_; }

    /// The probability P_i of drawing bin i (0 outside [0, n)).
    [[nodiscard]] T probability(std::size_t i) const noexcept {
        return i < size() ? cdf_[i + 1] - cdf_[i] : T(0);
    }
    /// The density at x in [0,1): n P_i for the bin i containing x (x outside [0,1) is
    /// clamped to it).
    [[nodiscard]] T pdf(T x) const noexcept {
        return probability(detail::bin_of(x, size())) * T(size());
    }

    /// A point x in [0,1) with density pdf(x), from u in [0,1) (inversion of the CDF;
    /// monotone in u). The returned pdf equals pdf(x) exactly, and x < 1 for every u,
    /// including 1 - ulp. Precondition: u in [0,1) (SHADE_ASSERT; outside it u is clamped).
    [[nodiscard]] distribution_sample_1d<T> sample_continuous(T u) const noexcept {
        SHADE_ASSERT(u >= T(0) && u < T(1));
        return detail::sample_continuous(cdf(), u);
    }

    /// A bin i with probability P_i, from u in [0,1), and u rescaled to [0,1) within the
    /// bin's step (reusable as a fresh uniform number). Precondition: u in [0,1) (SHADE_ASSERT;
    /// outside it u is clamped).
    [[nodiscard]] discrete_sample<T> sample_discrete(T u) const noexcept {
        SHADE_ASSERT(u >= T(0) && u < T(1));
        return detail::sample_cdf(cdf(), u);
    }

private:
    std::vector<T> cdf_;
};

/// A point drawn from a piecewise-constant density on [0,1)^2.
template <std::floating_point T>
struct distribution_sample_2d {
    vec2<T> uv{0, 0};        ///< the point, in [0,1)^2: uv.x along a row (column), uv.y across rows
    T pdf = T(0);            ///< its density (per unit area of [0,1)^2), > 0
    std::size_t column = 0;  ///< the cell's column, in [0, width)
    std::size_t row = 0;     ///< the cell's row, in [0, height)
    vec2<T> offset{0, 0};    ///< where uv lies within its cell, in [0,1)^2
};

/// A piecewise-constant density on [0,1)^2 over a grid of width x height equal cells,
/// cell (column i, row j) weighted by weights[j * width + i] (rows one after another). It
/// is drawn as in pbrt-v4 §A.5 (see the top of this header): the row j from the marginal
/// distribution of the rows (weight of a row = sum of its weights) with u.y, then the
/// column from the conditional distribution within row j with u.x. The probability of
/// cell (i, j) is P(j) P(i | j) and the density p(uv) = width height P(j) P(i | j). A row
/// whose weights are all zero gets a uniform conditional distribution (it is never drawn
/// unless every weight is zero, when the whole density is uniform).
template <std::floating_point T>
class piecewise_constant_2d {
public:
    using scalar_type = T;

    /// From width x height weights, row after row. Throws shade::invalid_parameter naming
    /// "width" or "height" if either is 0 or above 2^(digits of T - 2), `parameter` if the
    /// weights are not width x height many, negative, not finite, or their sum overflows.
    piecewise_constant_2d(std::span<const T> weights, std::size_t width, std::size_t height,
                          std::string_view parameter = "weights")
        : width_(detail::require_bin_count<T>("width", width)),
          height_(detail::require_bin_count<T>("height", height)), marginal_(height + 1) {
        if (weights.size() != width * height)
            throw invalid_parameter(parameter, "must hold width x height = " + std::to_string(width * height) +
                                                   " entries", std::to_string(weights.size()));
        conditional_.resize(height * (width + 1));
        std::vector<T> row_weights(height);
        for (std::size_t j = 0; j < height; ++j) {
            const double row_sum = detail::fill_cdf(weights.subspan(j * width, width),
                                                    std::span<T>(conditional_).subspan(j * (width + 1), width + 1),
                                                    parameter, j * width);
            // Row sums are formed in double and can exceed T's range when T is float.
            if (!(row_sum <= double(std::numeric_limits<T>::max())))
                throw invalid_parameter(parameter, "must have a finite sum in every row", detail::to_text(row_sum));
            row_weights[j] = T(row_sum);
        }
        (void)detail::fill_cdf(std::span<const T>(row_weights), std::span<T>(marginal_), parameter);
    }

    /// The number of columns (cells along uv.x).
    [[nodiscard]] std::size_t width() const noexcept { return width_; }
    /// The number of rows (cells along uv.y).
    [[nodiscard]] std::size_t height() const noexcept { return height_; }

    /// The probability P(j) P(i | j) of drawing cell (column i, row j); 0 outside the grid.
    [[nodiscard]] T probability(std::size_t column, std::size_t row) const noexcept {
        if (column >= width_ || row >= height_) return T(0);
        const std::span<const T> c = row_cdf(row);
        return (marginal_[row + 1] - marginal_[row]) * (c[column + 1] - c[column]);
    }
    /// The density at uv in [0,1)^2: width height P(j) P(i | j) for the cell containing uv
    /// (uv outside [0,1)^2 is clamped to it).
    [[nodiscard]] T pdf(const vec2<T>& uv) const noexcept {
        return probability(detail::bin_of(uv.x, width_), detail::bin_of(uv.y, height_)) * T(width_) *
               T(height_);
    }

    /// A point uv in [0,1)^2 with density pdf(uv) (which the sample's pdf equals exactly),
    /// its cell, and its offset within the cell: the row from u.y, the column from u.x.
    /// Precondition: u in [0,1)^2 (SHADE_ASSERT; outside it u is clamped).
    [[nodiscard]] distribution_sample_2d<T> sample_continuous(const vec2<T>& u) const noexcept {
        SHADE_ASSERT(u.x >= T(0) && u.x < T(1) && u.y >= T(0) && u.y < T(1));
        const distribution_sample_1d<T> r = detail::sample_continuous(std::span<const T>(marginal_), u.y);
        const distribution_sample_1d<T> c = detail::sample_continuous(row_cdf(r.index), u.x);
        distribution_sample_2d<T> s;
        s.uv = vec2<T>(c.x, r.x);
        // The same expression as pdf(uv), so that the two agree to the last bit.
        s.pdf = probability(c.index, r.index) * T(width_) * T(height_);
        s.column = c.index;
        s.row = r.index;
        s.offset = vec2<T>(c.offset, r.offset);
        return s;
    }

private:
    [[nodiscard]] std::span<const T> row_cdf(std::size_t j) const noexcept {
        return std::span<const T>(conditional_).subspan(j * (width_ + 1), width_ + 1);
    }
    std::size_t width_;
    std::size_t height_;
    std::vector<T> marginal_;    ///< the CDF of the rows, height + 1 edges
    std::vector<T> conditional_; ///< height CDFs of width + 1 edges, one per row
};

} // namespace shade
