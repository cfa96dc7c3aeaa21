// shade::environment_map_light: the documented latitude-longitude mapping and frame, a
// sampler that draws directions with the density pdf_incident reports (chi-square against
// exact integrals of pdf_incident over bins finer than the texels), a density that
// integrates to 1, the constant map equal to shade::environment_light, the variance it
// saves over cosine sampling on a high-dynamic-range map, and the validation of its inputs.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/check/chi2.hpp>
#include <shade/core/frame.hpp>
#include <shade/core/random.hpp>
#include <shade/core/sampling.hpp>
#include <shade/light/environment.hpp>
#include <shade/light/environment_map.hpp>
#include <shade/light/light.hpp>

namespace {

template <class T>
using v3 = shade::vec3<T>;
template <class T>
using v2 = shade::vec2<T>;
template <class T>
using map_light = shade::environment_map_light<T>;

constexpr double pi = std::numbers::pi;

template <class T>
constexpr T below_one = T(1) - std::numeric_limits<T>::epsilon() / T(2);

// Significance of each chi-square test, as in the BRDF tests (tests/brdf/sampling.hpp).
constexpr double significance = 1e-5;

// A width x height map whose texel (i, j) is f(i, j).
template <class T, class F>
std::vector<shade::rgb<T>> texels_of(int width, int height, F&& f) {
    std::vector<shade::rgb<T>> t(std::size_t(width) * std::size_t(height));
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i) t[std::size_t(j) * std::size_t(width) + std::size_t(i)] = f(i, j);
    return t;
}

// The documented mapping, written out here independently of the header: the unit
// direction in the map's frame at image coordinate u (1/2 - phi / 2 pi) and cos theta = z.
glm::dvec3 local_direction(double u, double z) {
    const double phi = pi - 2 * pi * u;
    const double s = std::sqrt(std::max(0.0, (1 - z) * (1 + z)));
    return {s * std::cos(phi), s * std::sin(phi), z};
}

// (u, z) of a unit direction in the map's frame, the inverse of local_direction.
glm::dvec2 u_and_z(const glm::dvec3& w) {
    double u = 0.5 - std::atan2(w.y, w.x) / (2 * pi);
    u = std::clamp(u, 0.0, std::nextafter(1.0, 0.0));
    return {u, std::clamp(w.z, -1.0, 1.0)};
}

// The world direction of (u, z) for a map in frame f.
template <class T>
v3<T> world_direction(const shade::frame<T>& f, double u, double z) {
    const shade::frame<double> fd{glm::dvec3(f.t), glm::dvec3(f.b), glm::dvec3(f.n)};
    return v3<T>(glm::normalize(fd.to_world(local_direction(u, z))));
}

// Sorted union of two lists of edges in [lo, hi].
std::vector<double> merged(std::vector<double> a, const std::vector<double>& b) {
    a.insert(a.end(), b.begin(), b.end());
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end(), [](double x, double y) { return std::abs(x - y) < 1e-14; }), a.end());
    return a;
}

std::vector<double> uniform_edges(double lo, double hi, int n) {
    std::vector<double> e(std::size_t(n) + 1);
    for (int k = 0; k <= n; ++k) e[std::size_t(k)] = lo + (hi - lo) * k / n;
    return e;
}

// What the chi-square test of a light found.
struct chi2_outcome {
    double statistic = 0;
    std::size_t dof = 0;
    double p_value = 1;
    double pdf_integral = 0; // sum of the bins' exact integrals of pdf
    std::size_t lost = 0;    // draws that returned nothing
};

// Chi-square test of light.sample_incident against `pdf` (a solid-angle density of world
// directions). Bins: n_z bands of equal width in z = cos theta times n_u sectors of equal
// width in u, in the map's frame (solid angle 2 pi dz du): bins of equal solid angle,
// finer than the texels. The expected count of a bin is N times the integral of pdf over
// it, computed exactly for a density that is constant over each texel: the bin is cut at
// the texels' documented edges (z = cos(pi j / H), u = i / W) and pdf is read at the
// centre of each piece. One more bin counts the draws that return nothing, expected
// N (1 - integral of pdf).
template <class T, class Pdf>
chi2_outcome light_chi2(const map_light<T>& light, Pdf&& pdf, std::size_t n, int n_z, int n_u, std::uint64_t seed) {
    const shade::frame<double> fd{glm::dvec3(light.orientation().t), glm::dvec3(light.orientation().b),
                                  glm::dvec3(light.orientation().n)};
    const int W = int(light.width()), H = int(light.height());
    std::vector<double> texel_z(std::size_t(H) + 1);
    for (int j = 0; j <= H; ++j) texel_z[std::size_t(j)] = std::cos(pi * j / H);
    const std::vector<double> bin_z = uniform_edges(-1, 1, n_z), bin_u = uniform_edges(0, 1, n_u);
    const std::vector<double> z_cuts = merged(bin_z, texel_z), u_cuts = merged(bin_u, uniform_edges(0, 1, W));
    const auto bin_of = [&](double u, double z) {
        const int bz = std::min(n_z - 1, int((z + 1) / 2 * n_z));
        const int bu = std::min(n_u - 1, int(u * n_u));
        return std::size_t(bz) * std::size_t(n_u) + std::size_t(bu);
    };
    std::vector<double> expected(std::size_t(n_z) * std::size_t(n_u) + 1, 0.0);
    chi2_outcome out;
    for (std::size_t a = 0; a + 1 < z_cuts.size(); ++a)
        for (std::size_t b = 0; b + 1 < u_cuts.size(); ++b) {
            const double z = 0.5 * (z_cuts[a] + z_cuts[a + 1]), u = 0.5 * (u_cuts[b] + u_cuts[b + 1]);
            const v3<T> l(glm::normalize(fd.to_world(local_direction(u, z))));
            const double mass = double(pdf(l)) * 2 * pi * (z_cuts[a + 1] - z_cuts[a]) * (u_cuts[b + 1] - u_cuts[b]);
            expected[bin_of(u, z)] += double(n) * mass;
            out.pdf_integral += mass;
        }
    expected.back() = double(n) * std::max(0.0, 1 - out.pdf_integral);
    std::vector<double> observed(expected.size(), 0.0);
    shade::rng random(seed);
    for (std::size_t k = 0; k < n; ++k) {
        const auto s = light.sample_incident(v3<T>(0), v2<T>(random.uniform<T>(), random.uniform<T>()));
        if (!s) {
            ++out.lost;
            observed.back() += 1;
            continue;
        }
        const glm::dvec2 uz = u_and_z(fd.to_local(glm::normalize(glm::dvec3(s->l))));
        observed[bin_of(uz.x, uz.y)] += 1;
    }
    const auto c = shade::check::pearson_chi2(observed, expected);
    out.statistic = c.statistic;
    out.dof = c.dof;
    out.p_value = c.dof > 0 ? shade::check::chi2_p_value(c.statistic, double(c.dof)) : 1.0;
    return out;
}

template <class T>
chi2_outcome light_chi2(const map_light<T>& light, std::size_t n = 400000, int n_z = 40, int n_u = 40,
                        std::uint64_t seed = 1) {
    return light_chi2(light, [&](const v3<T>& l) { return light.pdf_incident(v3<T>(0), l); }, n, n_z, n_u, seed);
}

// A map of random colours (each channel in [0.05, 1.05)), one black texel.
template <class T>
std::vector<shade::rgb<T>> random_texels(int width, int height, std::uint64_t seed) {
    shade::rng random(seed);
    auto t = texels_of<T>(width, height, [&](int, int) {
        return shade::rgb<T>(T(0.05) + random.uniform<T>(), T(0.05) + random.uniform<T>(),
                             T(0.05) + random.uniform<T>());
    });
    t[std::size_t(width) + 2] = shade::rgb<T>(0);
    return t;
}

// The high-dynamic-range test map: a white sky of radiance 1 and a sun of 2 x 2 texels
// 10^4 brighter, at rows 7-8 (theta from 39.4 to 50.6 degrees) and columns 10-11 of a
// 64 x 32 map.
constexpr int hdr_width = 64, hdr_height = 32;
template <class T>
std::vector<shade::rgb<T>> sun_and_sky() {
    return texels_of<T>(hdr_width, hdr_height, [](int i, int j) {
        const bool sun = (j == 7 || j == 8) && (i == 10 || i == 11);
        return shade::rgb<T>(sun ? T(1e4) : T(1));
    });
}

template <class T>
shade::frame<T> tilted_frame() {
    return shade::frame<T>::from_normal_tangent(v3<T>(T(0.3), T(-0.5), T(0.8)), v3<T>(1, T(0.2), 0));
}

} // namespace

TEST_CASE_TEMPLATE("environment_map_light is a shade::emitter", T, float, double) {
    static_assert(shade::emitter<map_light<T>>);
    static_assert(shade::light<map_light<T>>);
    CHECK_FALSE(map_light<T>::is_delta());
}

TEST_CASE_TEMPLATE("environment map: the documented mapping (row 0 up, centre column along t, unmirrored)", T, float,
                   double) {
    // A 8 x 4 map whose texel (i, j) has radiance (i, j, 1) times 2.
    const int W = 8, H = 4;
    const auto t = texels_of<T>(W, H, [](int i, int j) { return shade::rgb<T>(T(i), T(j), T(1)); });
    for (const auto& f : {shade::frame<T>{}, tilted_frame<T>(),
                          shade::frame<T>::from_normal_tangent(v3<T>(0, 1, 0), v3<T>(0, 0, -1))}) {
        const map_light<T> light(W, H, t, T(2), f);
        const v3<T> p(T(3), T(-1), T(7)); // an infinitely far map looks the same from anywhere
        const auto at = [&](const v3<T>& l) { return light.incident_radiance(p, glm::normalize(l)); };
        // Straight up: row 0. Straight down: row H - 1.
        CHECK(at(f.n).y == T(0));
        CHECK(at(-f.n).y == T(2 * (H - 1)));
        // Just above the horizon along t: the centre column (u = 1/2), row H/2 - 1.
        const v3<T> ahead = f.t + T(0.01) * f.n;
        CHECK(at(ahead) == T(2) * shade::rgb<T>(T(W / 2), T(H / 2 - 1), 1));
        // Along b (phi = pi/2): u = 1/4, column W/4, just below the horizon: row H/2.
        CHECK(at(f.b - T(0.01) * f.n) == T(2) * shade::rgb<T>(T(W / 4), T(H / 2), 1));
        // Along -b: u = 3/4. Looking along t with n up, -b is to the right: the image's right half.
        CHECK(at(-f.b + T(0.01) * f.n).x == T(2 * (3 * W / 4)));
        // Along -t: the image's left and right edges meet.
        const T edge = at(-f.t + T(0.3) * f.b + T(0.01) * f.n).x; // phi just below pi: u just above 0
        CHECK(edge == T(0));
        CHECK(at(-f.t - T(0.3) * f.b + T(0.01) * f.n).x == T(2 * (W - 1)));
        // image_coordinates agrees with the formula.
        const v3<T> l = world_direction(f, 0.37, -0.2);
        const v2<T> uv = light.image_coordinates(l);
        CHECK(uv.x == doctest::Approx(0.37).epsilon(1e-5));
        CHECK(uv.y == doctest::Approx(std::acos(-0.2) / pi).epsilon(1e-5));
        CHECK(light.texel(2, 1) == T(2) * shade::rgb<T>(2, 1, 1));
    }
}

TEST_CASE_TEMPLATE("environment map: sampling passes chi-square against pdf_incident, which integrates to 1", T, float,
                   double) {
    struct map_case {
        const char* name;
        map_light<T> light;
    };
    const std::vector<map_case> cases{
        {"constant 12 x 6", map_light<T>(12, 6, texels_of<T>(12, 6, [](int, int) { return shade::rgb<T>(T(0.7)); }))},
        {"random 12 x 6", map_light<T>(12, 6, random_texels<T>(12, 6, 5))},
        {"random 12 x 6, tilted frame", map_light<T>(12, 6, random_texels<T>(12, 6, 9), T(3), tilted_frame<T>())},
        {"random 5 x 3 (odd sizes)", map_light<T>(5, 3, random_texels<T>(5, 3, 13))},
        {"one row, one column", map_light<T>(1, 1, texels_of<T>(1, 1, [](int, int) { return shade::rgb<T>(1, 2, 3); }))},
        {"sun and sky 64 x 32", map_light<T>(hdr_width, hdr_height, sun_and_sky<T>())},
    };
    for (const auto& c : cases) {
        CAPTURE(c.name);
        const chi2_outcome r = light_chi2(c.light);
        MESSAGE(std::string(c.name) << ": chi2 = " << r.statistic << ", dof " << r.dof << ", p = " << r.p_value
                       << ", integral of pdf " << r.pdf_integral);
        CHECK(r.p_value > significance);
        CHECK(r.pdf_integral == doctest::Approx(1.0).epsilon(sizeof(T) == 4 ? 1e-5 : 1e-12));
        CHECK(r.lost == 0);
    }
}

TEST_CASE_TEMPLATE("environment map: pdf_incident integrates to 1 on a grid that ignores the texels", T, float, double) {
    // 4 pi times the mean of pdf over the cell centres of a stratified grid mapped uniformly
    // onto the sphere: the texel edges cut the grid's cells anywhere, so the error is that of
    // the cells the edges cross (about 1e-4 here).
    for (const auto& light : {map_light<T>(12, 6, random_texels<T>(12, 6, 21)),
                              map_light<T>(12, 6, random_texels<T>(12, 6, 22), T(1), tilted_frame<T>())}) {
        const int n = 400;
        double sum = 0;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const v3<T> l = shade::square_to_uniform_sphere(v2<T>(T((i + 0.5) / n), T((j + 0.5) / n)));
                sum += double(light.pdf_incident(v3<T>(0), l));
            }
        CHECK(4 * pi * sum / (double(n) * n) == doctest::Approx(1.0).epsilon(2e-3));
    }
}

TEST_CASE_TEMPLATE("environment map: the chi-square test rejects a density that is not the sampler's", T, float,
                   double) {
    // The density pbrt-v3's placement (uniform in theta within a texel) would have,
    // P_ij / (dphi dtheta sin theta): it integrates to 1 like the true one but is spread
    // differently within each row, which the bins, finer than the texels, see.
    const map_light<T> light(12, 6, random_texels<T>(12, 6, 5));
    const auto wrong = [&](const v3<T>& l) {
        const double z = std::clamp(double(l.z), -1.0, 1.0);
        const double theta = std::acos(z);
        const auto row = std::size_t(std::min(5.0, std::floor(theta / pi * 6)));
        const double omega = double(light.texel_solid_angle(row));
        const double dphi_dtheta = (2 * pi / 12) * (pi / 6);
        return T(double(light.pdf_incident(v3<T>(0), l)) * omega / (dphi_dtheta * std::sin(theta)));
    };
    const chi2_outcome r = light_chi2(light, wrong, 400000, 40, 40, 1);
    MESSAGE("wrong density: chi2 = " << r.statistic << ", dof " << r.dof << ", p = " << r.p_value);
    CHECK(r.p_value < significance);
}

TEST_CASE_TEMPLATE("environment map: each sample carries pdf_incident and incident_radiance of its direction", T,
                   float, double) {
    const map_light<T> light(hdr_width, hdr_height, sun_and_sky<T>(), T(0.5), tilted_frame<T>());
    shade::rng random(17);
    const v3<T> p(1, 2, 3);
    int disagreements = 0, invalid = 0, lost = 0;
    for (int k = 0; k < 20000; ++k) {
        const auto s = light.sample_incident(p, v2<T>(random.uniform<T>(), random.uniform<T>()));
        if (!s) {
            ++lost;
            continue;
        }
        if (s->pdf != light.pdf_incident(p, s->l) || s->radiance != light.incident_radiance(p, s->l)) ++disagreements;
        if (!shade::is_unit_length(s->l) || !(s->pdf > T(0)) || !std::isfinite(s->pdf) || s->delta ||
            s->distance != shade::infinity<T>)
            ++invalid;
    }
    CHECK(disagreements == 0);
    CHECK(invalid == 0);
    CHECK(lost == 0);
}

TEST_CASE_TEMPLATE("environment map: u at the edges of the unit square gives finite unit directions", T, float, double) {
    for (const auto& light : {map_light<T>(hdr_width, hdr_height, sun_and_sky<T>()),
                              map_light<T>(7, 5, random_texels<T>(7, 5, 2), T(1), tilted_frame<T>()),
                              map_light<T>(1, 1, texels_of<T>(1, 1, [](int, int) { return shade::rgb<T>(1); }))}) {
        for (const T a : {T(0), T(0.5), below_one<T>})
            for (const T b : {T(0), T(0.5), below_one<T>}) {
                CAPTURE(a);
                CAPTURE(b);
                const auto s = light.sample_incident(v3<T>(0), v2<T>(a, b));
                if (!s) continue; // a pole direction may land where the density is 0: worth nothing
                CHECK(shade::is_finite(s->l));
                CHECK(shade::is_unit_length(s->l));
                CHECK(std::isfinite(s->pdf));
                CHECK(s->pdf > T(0));
                CHECK(shade::is_finite(s->radiance));
                const auto classic = light.sample(v3<T>(0), v2<T>(a, b));
                CHECK(shade::is_finite(classic.diffuse));
            }
        // Poles and the seam at u = 0 / 1.
        for (const v3<T>& l : {v3<T>(0, 0, 1), v3<T>(0, 0, -1), v3<T>(-1, 0, 0), v3<T>(-1, T(-0.0), 0)}) {
            CHECK(std::isfinite(light.pdf_incident(v3<T>(0), l)));
            CHECK(shade::is_finite(light.incident_radiance(v3<T>(0), l)));
        }
    }
}

TEST_CASE_TEMPLATE("environment map: a constant map is the constant environment_light", T, float, double) {
    const T L = T(2.5);
    const shade::environment_light<T> constant(shade::emission<T>::from_physical(shade::rgb<T>(L)));
    const map_light<T> map(16, 8, texels_of<T>(16, 8, [&](int, int) { return shade::rgb<T>(L); }));
    shade::rng random(23);
    const double tolerance = sizeof(T) == 4 ? 1e-4 : 1e-10;
    for (int k = 0; k < 1000; ++k) {
        const v3<T> l = shade::square_to_uniform_sphere(v2<T>(random.uniform<T>(), random.uniform<T>()));
        CHECK(map.incident_radiance(v3<T>(0), l) == constant.incident_radiance(v3<T>(0), l));
        CHECK(map.pdf_incident(v3<T>(0), l) == doctest::Approx(constant.pdf_incident(v3<T>(0), l)).epsilon(tolerance));
    }
    // Irradiance on a surface facing +y (across the map's rows and columns), E = pi L: both
    // lights' estimators agree with it and, having the same density, the same spread of
    // values: X = 4 pi L cos on the upper half of the sphere, 0 below, so E[X^2] =
    // (4 pi L)^2 / 6 and the variance of X is (8/3 - 1) (pi L)^2 = (5/3) E^2.
    const v3<T> n(0, 1, 0);
    const auto estimate = [&](const auto& light) {
        double sum = 0, sum2 = 0, classic = 0;
        constexpr int side = 300;
        for (int j = 0; j < side; ++j)
            for (int i = 0; i < side; ++i) {
                const v2<T> u = shade::stratified_u(i, j, side, v2<T>(random.uniform<T>(), random.uniform<T>()));
                const auto s = light.sample_incident(v3<T>(0), u);
                if (!s) continue;
                const double x = double(s->radiance.x) * std::max(0.0, double(glm::dot(n, s->l))) / double(s->pdf);
                sum += x;
                sum2 += x * x;
                const auto c = light.sample(v3<T>(0), u);
                classic += pi * double(c.diffuse.x) * std::max(0.0, double(glm::dot(n, c.l)));
            }
        const double count = double(side) * side;
        return std::array<double, 3>{sum / count, sum2 / count - (sum / count) * (sum / count), classic / count};
    };
    const std::array<double, 3> by_map = estimate(map);
    const std::array<double, 3> by_constant = estimate(constant);
    const double mean_map = by_map[0], var_map = by_map[1], classic_map = by_map[2];
    const double mean_constant = by_constant[0], var_constant = by_constant[1], classic_constant = by_constant[2];
    const double E = pi * double(L);
    // The standard error of an i.i.d. mean bounds the stratified one's.
    const double se = std::sqrt(var_constant / (300.0 * 300.0));
    MESSAGE("E = " << E << ": map " << mean_map << ", environment_light " << mean_constant << " (se " << se << ")");
    CHECK(std::abs(mean_map - E) < 4 * se);
    CHECK(std::abs(mean_constant - E) < 4 * se);
    CHECK(var_map == doctest::Approx(var_constant).epsilon(0.02));
    CHECK(var_map == doctest::Approx(5.0 / 3 * E * E).epsilon(0.02));
    CHECK(classic_map == doctest::Approx(mean_map).epsilon(1e-5));
    CHECK(classic_constant == doctest::Approx(mean_constant).epsilon(1e-5));
}

TEST_CASE_TEMPLATE("environment map: on a sun 10^4 brighter than the sky, map sampling beats cosine sampling >= 10x in "
                   "variance",
                   T, float, double) {
    const map_light<T> light(hdr_width, hdr_height, sun_and_sky<T>());
    // The irradiance at a point facing up (n = +z) and both estimators' variances, exactly:
    // over texel (i, j) of the upper half, with radiance L_ij, dphi = 2 pi / W and
    // theta_j = pi j / H,
    //   int cos dw = dphi (sin^2 theta_{j+1} - sin^2 theta_j) / 2,
    //   int cos^2 dw = dphi (cos^3 theta_j - cos^3 theta_{j+1}) / 3.
    // Cosine sampling (pdf cos / pi): X = pi L, E[X^2] = pi sum L^2 int cos dw.
    // Map sampling (pdf = P_ij / Omega_ij with P_ij = L_ij Omega_ij / S, S = sum L Omega):
    // X = S cos for directions above the surface, 0 below, E[X^2] = S sum L int cos^2 dw.
    const double dphi = 2 * pi / hdr_width;
    double E = 0, S = 0, cos_moment = 0, map_moment = 0;
    for (int j = 0; j < hdr_height; ++j) {
        const double t0 = pi * j / hdr_height, t1 = pi * (j + 1) / hdr_height;
        const double omega = dphi * (std::cos(t0) - std::cos(t1));
        for (int i = 0; i < hdr_width; ++i) {
            const double L = double(light.texel(std::size_t(i), std::size_t(j)).x);
            S += L * omega;
            if (j >= hdr_height / 2) continue; // below the surface
            const double int_cos = dphi * (std::sin(t1) * std::sin(t1) - std::sin(t0) * std::sin(t0)) / 2;
            const double int_cos2 = dphi * (std::pow(std::cos(t0), 3) - std::pow(std::cos(t1), 3)) / 3;
            E += L * int_cos;
            cos_moment += pi * L * L * int_cos;
            map_moment += L * int_cos2;
        }
    }
    map_moment *= S;
    const double var_cos = cos_moment - E * E, var_map = map_moment - E * E;

    // The same measured, with 2^21 samples each: mean, variance and the standard error of the
    // variance, sqrt((m4 - var^2) / N) from the fourth central moment.
    struct moments {
        double mean, variance, variance_se;
    };
    const auto measure = [](auto&& draw, std::uint64_t seed) {
        shade::rng random(seed);
        constexpr std::size_t N = std::size_t(1) << 21;
        std::vector<double> x(N);
        double sum = 0;
        for (auto& v : x) {
            v = draw(v2<T>(random.uniform<T>(), random.uniform<T>()));
            sum += v;
        }
        const double mean = sum / double(N);
        double m2 = 0, m4 = 0;
        for (const double v : x) {
            const double d2 = (v - mean) * (v - mean);
            m2 += d2;
            m4 += d2 * d2;
        }
        m2 /= double(N);
        m4 /= double(N);
        return moments{mean, m2, std::sqrt(std::max(0.0, m4 - m2 * m2) / double(N))};
    };
    const moments by_map = measure(
        [&](const v2<T>& u) {
            const auto s = light.sample_incident(v3<T>(0), u);
            return s ? double(s->radiance.x) * std::max(0.0, double(s->l.z)) / double(s->pdf) : 0.0;
        },
        31);
    const moments by_cosine = measure(
        [&](const v2<T>& u) {
            return pi * double(light.incident_radiance(v3<T>(0), shade::square_to_cosine_hemisphere(u)).x);
        },
        37);
    const double ratio = by_cosine.variance / by_map.variance;
    const double ratio_relative_se = std::hypot(by_cosine.variance_se / by_cosine.variance,
                                                by_map.variance_se / by_map.variance);
    MESSAGE("E = " << E << "; map sampling: mean " << by_map.mean << ", variance " << by_map.variance << " +- "
                   << by_map.variance_se << " (exact " << var_map << "); cosine sampling: mean " << by_cosine.mean
                   << ", variance " << by_cosine.variance << " +- " << by_cosine.variance_se << " (exact " << var_cos
                   << "); ratio " << ratio << " +- " << ratio * ratio_relative_se << " (exact " << var_cos / var_map
                   << ")");
    const double n = double(std::size_t(1) << 21);
    CHECK(std::abs(by_map.mean - E) < 5 * std::sqrt(by_map.variance / n));
    CHECK(std::abs(by_cosine.mean - E) < 5 * std::sqrt(by_cosine.variance / n));
    CHECK(std::abs(by_map.variance - var_map) < 5 * by_map.variance_se + 1e-4 * var_map);
    CHECK(std::abs(by_cosine.variance - var_cos) < 5 * by_cosine.variance_se);
    // The bar, with the ratio's uncertainty taken off: >= 10x.
    CHECK(ratio * (1 - 5 * ratio_relative_se) >= 10);
}

TEST_CASE_TEMPLATE("environment map: a black map draws nothing and has density 0", T, float, double) {
    const map_light<T> black(4, 2, texels_of<T>(4, 2, [](int, int) { return shade::rgb<T>(0); }));
    CHECK_FALSE(black.sample_incident(v3<T>(0), v2<T>(T(0.3), T(0.6))));
    CHECK(black.pdf_incident(v3<T>(0), v3<T>(0, 0, 1)) == T(0));
    CHECK(black.incident_radiance(v3<T>(0), v3<T>(0, 0, 1)) == shade::rgb<T>(0));
    CHECK(black.sample(v3<T>(0), v2<T>(T(0.3), T(0.6))).diffuse == shade::rgb<T>(0));
}

TEST_CASE_TEMPLATE("environment map: bad inputs throw invalid_parameter naming the parameter", T, float, double) {
    const auto t = texels_of<T>(4, 2, [](int, int) { return shade::rgb<T>(1); });
    const auto names = [](auto&& make, const char* name, const char* part) {
        try {
            make();
            FAIL("no exception");
        } catch (const shade::invalid_parameter& e) {
            CHECK(e.parameter() == name);
            CHECK(std::string(e.what()).find(part) != std::string::npos);
        }
    };
    names([&] { (void)map_light<T>(4, 3, t); }, "texels", "width x height = 12");
    names([&] { (void)map_light<T>(0, 2, t); }, "width", ">= 1");
    names([&] { (void)map_light<T>(4, -1, t); }, "height", "got -1");
    auto bad = t;
    bad[5] = shade::rgb<T>(1, T(-0.5), 1);
    names([&] { (void)map_light<T>(4, 2, bad); }, "texels", "at column 1, row 1");
    bad[5] = shade::rgb<T>(std::numeric_limits<T>::quiet_NaN());
    names([&] { (void)map_light<T>(4, 2, bad); }, "texels", "nan");
    bad[5] = shade::rgb<T>(std::numeric_limits<T>::infinity());
    names([&] { (void)map_light<T>(4, 2, bad); }, "texels", "finite");
    names([&] { (void)map_light<T>(4, 2, t, T(-1)); }, "scale", "got -1");
    auto huge = t;
    huge[0] = shade::rgb<T>(std::numeric_limits<T>::max());
    names([&] { (void)map_light<T>(4, 2, huge, T(4)); }, "scale", "times every texel");
    shade::frame<T> skew;
    skew.b = v3<T>(1, 0, 0);
    names([&] { (void)map_light<T>(4, 2, t, T(1), skew); }, "orientation", "orthonormal");
    shade::frame<T> mirrored;
    mirrored.b = v3<T>(0, -1, 0);
    names([&] { (void)map_light<T>(4, 2, t, T(1), mirrored); }, "orientation", "right-handed");
    const std::vector<shade::rgb<T>> none;
    names([&] { (void)map_light<T>(0, 0, none); }, "width", ">= 1");
}
