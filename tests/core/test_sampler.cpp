// Samplers (shade/core/sampler.hpp, shade/core/sobol.hpp): the Owen-scrambled Sobol
// sampler's points form (0, k, 2)-nets for every pixel and dimension, its dimensions and
// pixels are decorrelated, and it integrates a smooth integrand with far less error than
// independent numbers; both samplers are deterministic and in [0, 1).

#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

#include <doctest/doctest.h>

#include <shade/check/chi2.hpp>
#include <shade/core/sampler.hpp>
#include <shade/core/sobol.hpp>

static_assert(shade::sampler<shade::independent_sampler<float>>);
static_assert(shade::sampler<shade::sobol_sampler<double>>);

TEST_CASE("sobol: the unscrambled generators give Sobol's first points") {
    // Dimension 0 is the van der Corput sequence: 0, 1/2, 1/4, 3/4, 1/8, ...
    const double vdc[] = {0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875};
    // Dimension 1 (x + 1), in index order (not Gray-code order): 0, 1/2, 3/4, 1/4,
    // 5/8 (v_2 = 0.101b), 1/8 (v_0 ^ v_2), 3/8 (v_1 ^ v_2), 7/8.
    const double second[] = {0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
    for (std::uint32_t i = 0; i < 8; ++i) {
        CHECK(double(shade::detail::sobol_dimension_0(i)) * 0x1p-32 == vdc[i]);
        CHECK(double(shade::detail::sobol_dimension_1(i)) * 0x1p-32 == second[i]);
    }
}

TEST_CASE("sobol: the nested uniform scramble is a bijection that keeps prefixes together") {
    // Scrambling maps numbers sharing their top b bits to numbers sharing their top b bits
    // (Owen's nested scramble permutes each elementary interval as a whole).
    const std::uint32_t seed = 0x12345678u;
    std::set<std::uint32_t> images;
    for (std::uint32_t i = 0; i < 4096; ++i) images.insert(shade::detail::nested_uniform_scramble(i << 20, seed) >> 20);
    CHECK(images.size() == 4096);
    for (std::uint32_t i = 0; i < 4096; ++i) {
        const std::uint32_t a = shade::detail::nested_uniform_scramble(i << 20, seed);
        const std::uint32_t b = shade::detail::nested_uniform_scramble((i << 20) | 0xfffffu, seed);
        CHECK((a >> 20) == (b >> 20));
    }
}

TEST_CASE_TEMPLATE("sobol_sampler: the first 2^k points of every pixel and dimension form a (0, k, 2)-net", T, float, double) {
    shade::sobol_sampler<T> s(42);
    for (std::uint32_t pixel = 0; pixel < 3; ++pixel)
        for (int k = 0; k <= 10; ++k) {
            const std::uint32_t n = 1u << k;
            constexpr int dims = 4; // two 1D and two 2D calls per sample
            std::vector<std::vector<shade::vec2<T>>> points(dims);
            for (std::uint32_t i = 0; i < n; ++i) {
                s.start_pixel_sample(pixel, 7 * pixel, i);
                const T a = s.next_1d();
                const auto b = s.next_2d();
                const T c = s.next_1d();
                const auto d = s.next_2d();
                points[0].push_back({a, T(0)});
                points[1].push_back(b);
                points[2].push_back({c, T(0)});
                points[3].push_back(d);
            }
            for (int dim = 0; dim < dims; ++dim) {
                const bool one_d = dim % 2 == 0;
                for (int i = 0; i <= (one_d ? 0 : k); ++i) {
                    // Boxes of 2^-(k - i) along x and 2^-i along y (1D: intervals of 2^-k).
                    const std::uint32_t nx = 1u << (k - i), ny = 1u << i;
                    std::vector<int> count(std::size_t(nx) * ny, 0);
                    for (const auto& p : points[std::size_t(dim)]) {
                        REQUIRE(p.x >= T(0));
                        REQUIRE(p.x < T(1));
                        REQUIRE(p.y < T(1));
                        const auto bx = std::uint32_t(p.x * T(nx)), by = std::uint32_t(p.y * T(ny));
                        ++count[std::size_t(by) * nx + bx];
                    }
                    int wrong = 0;
                    for (const int c : count) wrong += c != 1;
                    CHECK_MESSAGE(wrong == 0, "pixel ", pixel, " dimension ", dim, " k ", k, " boxes 2^", k - i,
                                  " x 2^", i);
                }
            }
        }
}

TEST_CASE("sobol_sampler: dimensions and pixels are decorrelated") {
    shade::sobol_sampler<double> s(3);
    // Two 1D dimensions of the same samples: correlation of N = 4096 pairs. For independent
    // uniforms its standard deviation is 1/sqrt(N) = 0.0156; 0.07 is 4.5 of them.
    const int n = 4096;
    double sx = 0, sy = 0, sxy = 0, sxx = 0, syy = 0;
    for (int i = 0; i < n; ++i) {
        s.start_pixel_sample(5, 9, std::uint32_t(i));
        const double x = s.next_1d(), y = s.next_1d();
        sx += x, sy += y, sxy += x * y, sxx += x * x, syy += y * y;
    }
    const double cov = sxy / n - (sx / n) * (sy / n);
    const double r = cov / std::sqrt((sxx / n - (sx / n) * (sx / n)) * (syy / n - (sy / n) * (sy / n)));
    CHECK(std::abs(r) < 0.07);
    // The first sample of 16384 different pixels: uniform over 64 bins (chi-square).
    std::vector<double> observed(64, 0), expected(64, 16384.0 / 64);
    for (std::uint32_t p = 0; p < 16384; ++p) {
        s.start_pixel_sample(p % 128, p / 128, 0);
        observed[std::size_t(s.next_1d() * 64)] += 1;
    }
    const auto chi2 = shade::check::pearson_chi2(observed, expected);
    CHECK(shade::check::chi2_p_value(chi2.statistic, double(chi2.dof)) > 1e-3);
}

TEST_CASE("sobol_sampler: a smooth integrand has RMSE at least 10x lower than with independent numbers") {
    // I = integral over [0,1]^2 of exp(-(x^2 + y^2)) = (sqrt(pi)/2 erf(1))^2.
    const double half = std::sqrt(3.141592653589793) / 2 * std::erf(1.0);
    const double exact = half * half;
    const auto f = [](shade::vec2<double> p) { return std::exp(-(p.x * p.x + p.y * p.y)); };
    // 64 pixels (independent scrambles or streams), N = 256 samples each, dimension 1 (the
    // 2D call after one 1D call). Independent numbers: RMSE = sigma / 16 with sigma^2 =
    // Var f ~ 0.018 (so about 8e-3). Scrambled nets: variance O(N^-3 log N) for this
    // smooth f (Owen 1997), so the ratio at N = 256 is of order 1/16 or smaller; 0.1 leaves
    // room for the constants and for the estimate of each RMSE from 64 errors (relative
    // standard error about 9%).
    const auto rmse = [&](auto sampler) {
        double sum = 0;
        for (std::uint32_t p = 0; p < 64; ++p) {
            double mean = 0;
            for (std::uint32_t i = 0; i < 256; ++i) {
                sampler.start_pixel_sample(p, 0, i);
                (void)sampler.next_1d();
                mean += f(sampler.next_2d());
            }
            mean /= 256;
            sum += (mean - exact) * (mean - exact);
        }
        return std::sqrt(sum / 64);
    };
    const double sobol = rmse(shade::sobol_sampler<double>(1));
    const double independent = rmse(shade::independent_sampler<double>(1));
    MESSAGE("RMSE at 256 samples: sobol ", sobol, ", independent ", independent, ", ratio ", sobol / independent);
    CHECK(independent > 4e-3); // the baseline is what its variance says (sigma/16 ~ 8e-3)
    CHECK(sobol < 0.1 * independent);
}

TEST_CASE_TEMPLATE("samplers: deterministic per (seed, pixel, index), different across indices", T, float, double) {
    shade::independent_sampler<T> a(9), b(9);
    a.start_pixel_sample(1, 2, 3);
    b.start_pixel_sample(1, 2, 3);
    CHECK(a.next_1d() == b.next_1d());
    CHECK(a.next_2d() == b.next_2d());
    b.start_pixel_sample(1, 2, 4);
    a.start_pixel_sample(1, 2, 3);
    CHECK(a.next_1d() != b.next_1d());
    shade::sobol_sampler<T> c(9), d(9);
    c.start_pixel_sample(4, 5, 6);
    d.start_pixel_sample(4, 5, 6);
    CHECK(c.next_2d() == d.next_2d());
    CHECK(c.next_1d() == d.next_1d());
    // Independent numbers are uniform: chi-square over 32 bins.
    std::vector<double> observed(32, 0), expected(32, 65536.0 / 32);
    for (std::uint32_t i = 0; i < 65536; ++i) {
        a.start_pixel_sample(i % 256, i / 256, 0);
        const T u = a.next_1d();
        REQUIRE(u < T(1));
        observed[std::size_t(u * T(32))] += 1;
    }
    const auto chi2 = shade::check::pearson_chi2(observed, expected);
    CHECK(shade::check::chi2_p_value(chi2.statistic, double(chi2.dof)) > 1e-3);
}
