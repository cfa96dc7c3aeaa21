// shade::rough_dielectric_albedo_grid and shade::compensated_rough_dielectric in its per-interface
// mode (issue #31: R + T in [0.99, 1.001] at 2:1 and 10:1 at every view azimuth and mu >= 0.1,
// both sides): the white furnace over views, the grid's quadrature against the model's own
// sampler, the lobe returning exactly 1 - E_s(v), symmetry, reciprocity and sampling in that
// mode, and bad input.
//
// The white furnace is that of tests/bsdf/anisotropic_furnace.hpp: R + T = 1 + E_true(v) -
// E_read(v), E_true the single-scattering R + T estimated with rough_dielectric's own sampler
// on stratified random numbers (independent of the grid's midpoint rule), E_read the grid's
// value; the lobe returning 1 - E_read(v) is checked below by integrating f_ms over l.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/brdf/thin_film.hpp>
#include <shade/bsdf/compensated_rough_dielectric.hpp>
#include <shade/bsdf/dielectric_anisotropic_reflection_albedo.hpp>
#include <shade/bsdf/rough_dielectric_albedo_grid.hpp>
#include <shade/check/doctest.hpp>
#include <shade/check/sampling.hpp>
#include <shade/core/error.hpp>
#include <shade/core/random.hpp>
#include <shade/core/sampling.hpp>

#include "bsdf/anisotropic_furnace.hpp"
#include "bsdf/support.hpp"

using namespace bsdf_test;
using namespace bsdf_test::anisotropic;
using brdf_test::close;
using shade::transport_mode;

TEST_CASE_TEMPLATE("rough_dielectric_albedo_grid: R + T in [0.99, 1.001] at 2:1, 10:1 and anisotropy 1 over azimuths, "
                   "mu >= 0.1, both sides", T, float, double) {
    // Pairs at 2:1 and 10:1 with the smoother axis along t and along b, and one at anisotropy 1
    // (the smaller alpha 1.2e-4, as float(1e-4) is below the lobe's floor: the grid's finer
    // azimuths and larger margin), eta 1.33 and 2.4 (seen from inside: 1 / 1.33 and 1 / 2.4,
    // with total internal reflection); azimuths off the grid's nodes. Each reading held to the
    // band widened by 4 standard errors of E_true (96^2 strata, standard error below 8e-4,
    // asserted).
    struct lobe {
        double a_x, a_y;
    };
    double low[2] = {2, 2}, high[2] = {0, 0};
    for (const lobe& r : {lobe{0.2, 0.4}, lobe{0.8, 0.08}, lobe{0.05, 0.5}, lobe{1.2e-4, 0.6}})
        for (const double eta : {1.33, 2.4}) {
            const shade::ggx<T> distribution(T(r.a_x), T(r.a_y));
            const shade::rough_dielectric_albedo_grid<T> grid(distribution, T(eta));
            const compensated<T> model{distribution, T(eta), grid};
            for (const int side : {0, 1})
                for (const double mu : {0.1, 0.35, 0.7, 1.0})
                    for (const double phi : {0.0, 25.0, 50.0, 77.0, 90.0}) {
                        if (mu == 1.0 && phi > 0) continue;
                        CAPTURE(r.a_x);
                        CAPTURE(r.a_y);
                        CAPTURE(eta);
                        CAPTURE(side);
                        CAPTURE(mu);
                        CAPTURE(phi);
                        const furnace e = table_furnace(model, view<T>(side == 0 ? mu : -mu, phi), 96);
                        const double total = e.total();
                        CAPTURE(total);
                        CHECK(e.error < 8e-4);
                        CHECK(total >= 0.99 - 4 * e.error);
                        CHECK(total <= 1.001 + 4 * e.error);
                        low[side] = std::min(low[side], total);
                        high[side] = std::max(high[side], total);
                    }
        }
    MESSAGE("per-interface grid, R + T at 2:1, 10:1 and anisotropy 1: v outside " << low[0] << " to " << high[0] << ", v inside " << low[1]
                                                                     << " to " << high[1]);
}

TEST_CASE("rough_dielectric_albedo_grid: the quadrature is rough_dielectric's own sampler, averaged (double)") {
    // detail::dielectric_visible_albedo takes the sampler's weight as G2(v, l) / G1(v) on
    // both branches (its comment derives it). Here the same midpoint visible normals go
    // through rough_dielectric::sample with uc choosing each branch, weighted by the Fresnel
    // factor with which the sampler would choose it: the two must agree to rounding.
    using T = double;
    const auto at = flat_frame<T>();
    for (const double eta : {1.5, 1 / 1.5, 2.4, 1 / 2.4})
        for (const auto& roughness : {std::pair{0.05, 1e-4}, std::pair{0.3, 0.9}, std::pair{1.0, 0.2}})
            for (const double mu : {0.05, 0.4, 0.9})
                for (const double phi : {10.0, 70.0}) {
                    const shade::rough_dielectric<shade::ggx<T>> model{shade::ggx<T>(roughness.first, roughness.second), eta};
                    const vec3<T> v = view<T>(mu, phi);
                    constexpr int cells = 24;
                    double sum = 0;
                    for (int i = 0; i < cells; ++i)
                        for (int j = 0; j < cells; ++j) {
                            const vec2<T> u((i + 0.5) / cells, (j + 0.5) / cells);
                            const vec3<T> m = model.distribution().sample_visible_normal(v, u);
                            const double F = shade::F_dielectric(glm::dot(v, m), eta);
                            const auto reflected = model.sample(v, 0, u, at, transport_mode::importance);
                            const auto refracted = model.sample(v, std::nextafter(1.0, 0.0), u, at, transport_mode::importance);
                            if (F > 0 && reflected) sum += F * reflected->weight.x;
                            if (F < 1 && refracted) sum += (1 - F) * refracted->weight.x;
                        }
                    CAPTURE(eta);
                    CAPTURE(roughness.first);
                    CAPTURE(mu);
                    CAPTURE(phi);
                    const double direct = shade::detail::dielectric_visible_albedo(model.distribution(), v, eta, cells);
                    CHECK(direct == doctest::Approx(sum / (cells * cells)).epsilon(1e-12));
                    CHECK(direct > 0.3);
                    CHECK(direct <= 1);
                }
}

TEST_CASE_TEMPLATE("rough_dielectric_albedo_grid: the lobe returns exactly 1 - E_s(v); E_s,avg is the average of its reads", T,
                   float, double) {
    // f_ms integrates over l to 1 - E_s(v) only if E_s,avg is the cosine-weighted average
    // of the E_s(l) the lobe reads at every l; integrated by the midpoint rule (32 x 64 cells
    // per hemisphere, whose own error is up to 2e-4 here), held to 4e-4 as the tables are.
    const auto at = flat_frame<T>();
    double worst = 0;
    for (const auto& roughness : {std::pair{0.05, 0.5}, std::pair{0.6, 0.3}})
        for (const double eta : {1.2, 2.5}) {
            const shade::ggx<T> distribution(T(roughness.first), T(roughness.second));
            const shade::rough_dielectric_albedo_grid<T> grid(distribution, T(eta));
            const compensated<T> model{distribution, T(eta), grid};
            REQUIRE(model.albedo_grid() == &grid);
            for (const double mu : {0.2, -0.2, 0.6, -0.6})
                for (const double phi : {0.0, 40.0, 90.0}) {
                    const vec3<T> v = view<T>(mu, phi);
                    const double read = double(model.single_scattering_albedo(v, at));
                    CHECK(read == doctest::Approx(double(grid.albedo(mu < 0, v))).epsilon(1e-6));
                    const double lost = 1 - read;
                    const double returned = multiple_scattering_albedo(model, v);
                    CAPTURE(roughness.first);
                    CAPTURE(eta);
                    CAPTURE(mu);
                    CAPTURE(phi);
                    CAPTURE(lost);
                    CHECK(lost > 0.01);
                    worst = std::max(worst, std::abs(returned - lost));
                    CHECK(std::abs(returned - lost) <= 4e-4);
                }
        }
    MESSAGE("per-interface grid: integral of f_ms against 1 - E_s(v): worst difference " << worst);
}

TEST_CASE("rough_dielectric_albedo_grid: symmetric about both axes; isotropic interfaces read the same at every azimuth (double)") {
    using T = double;
    // Mirror symmetry of the interface about t and about b: the grid reads w's squared
    // components, so the mirrored views read the same value exactly.
    const shade::rough_dielectric_albedo_grid<T> grid(shade::ggx<T>(0.05, 0.5), 1.5);
    for (const bool inside : {false, true})
        for (const double mu : {0.2, 0.7})
            for (const double phi : {20.0, 65.0}) {
                const T e = grid.albedo(inside, view<T>(mu, phi));
                for (const double mirrored : {180 - phi, 180 + phi, 360 - phi})
                    CHECK(grid.albedo(inside, view<T>(mu, mirrored)) == doctest::Approx(e).epsilon(1e-14));
                CHECK(grid.albedo(inside, view<T>(-mu, phi)) == doctest::Approx(e).epsilon(1e-14));
            }
    // An isotropic interface: E_s does not depend on the azimuth; the nodes' midpoint rules
    // (whose visible normals are not those of another azimuth rotated) agree within their own
    // error, a few 1e-4 at 48^2 cells.
    const shade::rough_dielectric_albedo_grid<T> isotropic(shade::ggx<T>(0.4), 1 / 1.5);
    for (const bool inside : {false, true})
        for (const double mu : {0.1, 0.5, 0.95}) {
            const T e = isotropic.albedo(inside, view<T>(mu, 0));
            for (const double phi : {17.0, 45.0, 90.0, 200.0})
                CHECK(std::abs(isotropic.albedo(inside, view<T>(mu, phi)) - e) <= 1e-3);
        }
    // Reads stay in [0, 1], also on the normal, on the surface and for a smooth interface
    // (which loses nothing: E_s = 1, so the margin is clamped away, but for the last row,
    // mu below 0.02, where masking takes a little even at alpha 1e-4).
    const shade::rough_dielectric_albedo_grid<T> smooth(shade::ggx<T>(1e-4), 1.5);
    for (const bool inside : {false, true}) {
        CHECK(smooth.albedo(inside, vec3<T>(0, 0, 1)) == 1);
        CHECK(smooth.albedo(inside, view<T>(0.3, 30)) == 1);
        CHECK(smooth.average(inside) == doctest::Approx(1).epsilon(1e-4));
        for (const vec3<T>& w : {vec3<T>(0, 0, 1), vec3<T>(1, 0, 0), vec3<T>(0, 1, 0), vec3<T>(0.6, 0, -0.8)}) {
            const T e = grid.albedo(inside, w);
            CHECK(e >= 0);
            CHECK(e <= 1);
        }
        CHECK(grid.average(inside) > 0.5);
        CHECK(grid.average(inside) < 1);
    }
}

TEST_CASE("rough_dielectric_albedo_grid: per-interface mode keeps adjoint reciprocity to 1e-6 and samples agree with f and pdf "
          "(double)") {
    using T = double;
    const auto at = brdf_test::tilted<T>();
    shade::rng random(31);
    for (const double eta : {1.5, 1 / 1.33}) {
        const shade::ggx<T> distribution(0.1, 0.6);
        const shade::rough_dielectric_albedo_grid<T> grid(distribution, eta);
        const compensated<T> model{distribution, eta, grid};
        int compared = 0;
        for (int i = 0; i < 3000; ++i) {
            const vec3<T> l = shade::square_to_uniform_sphere(vec2<T>(random.uniform<T>(), random.uniform<T>()));
            const vec3<T> v = shade::square_to_uniform_sphere(vec2<T>(random.uniform<T>(), random.uniform<T>()));
            const double eta_v = glm::dot(at.n(), v) > 0 ? 1.0 : eta;
            const double eta_l = glm::dot(at.n(), l) > 0 ? 1.0 : eta;
            const double a = model.f(l, v, at).x / (eta_v * eta_v);
            const double b = model.f(v, l, at).x / (eta_l * eta_l);
            CHECK(std::isfinite(a));
            CHECK(a >= 0);
            if (std::max(a, b) < 1e-12) continue;
            ++compared;
            CHECK(std::abs(a - b) <= 1e-6 * std::max(a, b));
        }
        CHECK(compared > 2500);
        for (const double deg : {0.0, 70.0, 180.0, 110.0}) {
            CAPTURE(eta);
            CAPTURE(deg);
            const vec3<T> v = view_deg(at, deg);
            for (int i = 0; i < 500; ++i) {
                const T uc = random.uniform<T>();
                const vec2<T> u(random.uniform<T>(), random.uniform<T>());
                const auto s = model.sample(v, uc, u, at, transport_mode::importance);
                if (!s) continue;
                check_sample(*s, v, at, T(1e-9));
                CHECK(close(s->f.x, model.f(v, s->l, at).x, T(1e-8))); // importance: the adjoint
                CHECK(close(s->pdf, model.pdf(s->l, v, at), T(1e-9)));
            }
            shade::check::chi2_options chi2{.samples = 40000, .alpha = 1e-3, .tests = 8};
            chi2.model = "compensated rough dielectric, per-interface grid";
            shade::check::doctest_expect(shade::check::chi2_goodness_of_fit(model, v, at, chi2));
            shade::check::doctest_expect(shade::check::pdf_normalization(model, v, at, chi2));
        }
    }
}

TEST_CASE_TEMPLATE("rough_dielectric_albedo_grid: bad eta throws; a model given another interface's grid throws", T, float,
                   double) {
    const shade::ggx<T> distribution(T(0.1), T(0.5));
    for (const T eta : {T(1), T(0), T(-1.5), T(2e4), std::numeric_limits<T>::quiet_NaN()}) {
        CAPTURE(eta);
        try {
            const shade::rough_dielectric_albedo_grid<T> grid(distribution, eta);
            FAIL("no exception");
        } catch (const shade::invalid_parameter& e) {
            CHECK(e.parameter() == "eta");
        }
    }
    const shade::rough_dielectric_albedo_grid<T> grid(distribution, T(1.5));
    CHECK(grid.built_for(distribution, T(1.5)));
    CHECK(grid.distribution().alpha_y() == T(0.5));
    CHECK(grid.eta() == T(1.5));
    const auto rejects = [&grid](const shade::ggx<T>& d, T eta) {
        try {
            const compensated<T> model{d, eta, grid};
            FAIL("no exception");
        } catch (const shade::invalid_parameter& e) {
            CHECK(e.parameter() == "grid");
            CHECK(std::string(e.what()).find("grid") != std::string::npos);
        }
    };
    rejects(shade::ggx<T>(T(0.1), T(0.5)), T(1.4));
    rejects(shade::ggx<T>(T(0.5), T(0.1)), T(1.5));
    rejects(shade::ggx<T>(T(0.1)), T(1.5));
    // The model's own eta is checked first, as without a grid.
    try {
        const compensated<T> model{distribution, T(1), grid};
        FAIL("no exception");
    } catch (const shade::invalid_parameter& e) {
        CHECK(e.parameter() == "eta");
    }
    // Table mode has no grid.
    const compensated<T> tables{distribution, T(1.5)};
    CHECK(tables.albedo_grid() == nullptr);
}

TEST_CASE_TEMPLATE("rough_dielectric_albedo_grid: one side integrated with R_ss in one pass; the model reads the tables on "
                   "the other",
                   T, float, double) {
    // detail::anisotropic_reflection_albedo_grid(..., with_total) fills E_s = R + T of the
    // denser side on the nodes of its R_ss grid, from the same visible normals (40^2); a grid
    // of that side alone then serves compensated_rough_dielectric, which reads the tables on
    // the other side. The white furnace from the grid's side, 1 + E_true(v) - E_read(v)
    // (table_furnace, 96^2 strata), is held to [0.99, 1.001] widened by 4 standard errors; the
    // lobe returns 1 - E_s(v) from both sides (each side's E_s,avg the average of its own
    // reads); R_ss reads the same with and without E_s.
    const auto at = flat_frame<T>();
    struct lobe {
        double a_x, a_y, eta; // eta = n_inside / n_outside < 1: the outside is the denser side
    };
    double low = 2, high = 0;
    for (const lobe& r : {lobe{0.3, 0.03, 0.5}, lobe{0.1, 0.01, 0.4}, lobe{1.2e-4, 1.0, 0.66}, lobe{0.0409, 1.2e-4, 0.608},
                          lobe{0.6, 0.3, 0.9}}) {
        CAPTURE(r.a_x);
        CAPTURE(r.a_y);
        CAPTURE(r.eta);
        const shade::ggx<T> distribution(T(r.a_x), T(r.a_y));
        const shade::detail::anisotropic_reflection_albedo_grid<T> with_total(T(r.a_x), T(r.a_y), T(r.eta), true);
        const shade::detail::anisotropic_reflection_albedo_grid<T> alone(T(r.a_x), T(r.a_y), T(r.eta));
        REQUIRE(with_total.total_albedo() != nullptr);
        CHECK(alone.total_albedo() == nullptr);
        const shade::rough_dielectric_albedo_grid<T> grid(distribution, T(r.eta), false, *with_total.total_albedo());
        CHECK(grid.integrated(false));
        CHECK_FALSE(grid.integrated(true));
        CHECK(grid.average(true) == T(1));
        CHECK(grid.albedo(true, view<T>(-0.5, 0.0)) == T(1));
        const compensated<T> model{distribution, T(r.eta), grid};
        const compensated<T> tables{distribution, T(r.eta)};
        for (const double mu : {0.1, 0.2, 0.35, 0.7, 1.0})
            for (const double phi : {0.0, 25.0, 50.0, 77.0, 90.0}) {
                if (mu == 1.0 && phi > 0) continue;
                CAPTURE(mu);
                CAPTURE(phi);
                const vec3<T> v = view<T>(mu, phi);
                CHECK(with_total.at(v) == alone.at(v));
                CHECK(model.single_scattering_albedo(v, at) == grid.albedo(false, v));
                CHECK(model.single_scattering_albedo(-v, at) == tables.single_scattering_albedo(-v, at));
                const furnace e = table_furnace(model, v, 96);
                const double total = e.total();
                CAPTURE(total);
                CHECK(e.error < 8e-4);
                CHECK(total >= 0.99 - 4 * e.error);
                CHECK(total <= 1.001 + 4 * e.error);
                low = std::min(low, total);
                high = std::max(high, total);
            }
        for (const double mu : {0.2, -0.2, 0.6, -0.6}) {
            const vec3<T> v = view<T>(mu, 40.0);
            const double lost = 1 - double(model.single_scattering_albedo(v, at));
            CAPTURE(mu);
            CAPTURE(lost);
            CHECK(std::abs(multiple_scattering_albedo(model, v) - lost) <= 4e-4);
        }
    }
    MESSAGE("one-sided grid from R_ss's pass, R + T from the denser side: " << low << " to " << high);
    // The one-sided constructor checks eta as the other does.
    const shade::detail::anisotropic_reflection_albedo_grid<T> side(T(0.3), T(0.03), T(0.5), true);
    for (const T eta : {T(1), T(0), std::numeric_limits<T>::quiet_NaN()}) {
        CAPTURE(eta);
        try {
            const shade::rough_dielectric_albedo_grid<T> grid(shade::ggx<T>(T(0.3), T(0.03)), eta, false, *side.total_albedo());
            FAIL("no exception");
        } catch (const shade::invalid_parameter& e) {
            CHECK(e.parameter() == "eta");
        }
    }
}

TEST_CASE("anisotropic_reflection_albedo_grid: another Fresnel term's difference, integrated in R_ss's pass (double)") {
    // With `other`, the pass that integrates R_ss also integrates D_k(v) = E_m[(F'_k(v·m) -
    // F(v·m)) G2/G1] per channel: OpenPBR's thin film on an anisotropic lobe, F' the film's
    // reflectance over the interface's index (shade::thin_film_fresnel; read here, as the
    // material reads it, from 4,097 tabulated cosines), which is 1 where F is (total internal
    // reflection). Channel 1 is F itself: D_1 is exactly 0 at every node, the read the margin
    // alone. Each read less the margin against a fresh 200^2 quadrature with the film's exact
    // F at random views and along the smoother axis, below 1 (rows dense at the critical
    // cosine) and above 1 at strong anisotropy (46 rows then): within 3e-3 (the rows' interpolation and the 40^2 or 32^2
    // visible normals per node), below the margin's 2e-3 by at most 1e-3.
    using T = double;
    using grid = shade::detail::anisotropic_reflection_albedo_grid<T>;
    shade::rng random(29);
    double lowest = 1, highest = -1;
    struct lobe {
        double a_x, a_y, eta_s, film_ior, thickness_nm;
    };
    for (const lobe& r : {lobe{0.3, 0.03, 0.6, 1.4, 500}, lobe{1.2e-4, 0.8, 0.75, 2.2, 1200}, lobe{0.509, 1.2e-4, 1.5, 1.05, 1000},
                          lobe{0.02, 0.7, 2.2, 3.0, 250}}) {
        const double eta = r.eta_s;
        const auto film = shade::thin_film_fresnel<double>::over_dielectric(eta, r.film_ior, r.thickness_nm);
        constexpr std::size_t nodes = 4096;
        std::vector<shade::rgb<double>> table(nodes + 1);
        for (std::size_t i = 0; i <= nodes; ++i) table[i] = film.F(double(i) / double(nodes));
        const auto other = [&table, eta](double c) {
            const double x = std::clamp(c, 0.0, 1.0) * double(nodes);
            const std::size_t i = std::min(std::size_t(x), nodes - 1);
            const shade::rgb<double> f = table[i] + (x - double(i)) * (table[i + 1] - table[i]);
            return std::array<double, 3>{f.x, shade::F_dielectric(c, eta), f.z};
        };
        const grid g(r.a_x, r.a_y, r.eta_s, false, other);
        REQUIRE(g.integrated());
        REQUIRE(g.has_difference());
        CHECK_FALSE(grid(r.a_x, r.a_y, r.eta_s).has_difference());
        const shade::ggx<double> d(shade::unchecked, r.a_x, r.a_y);
        for (int k = 0; k < 28; ++k) {
            // 20 random views, then 8 along the smoother axis where a thick film's fringes in
            // mu are sharpest (OpenPBR roughness 0.6, anisotropy 1: the 1 um film of index
            // 1.05 over 1.5 read 7.8e-3 low between 16 rows there).
            const bool smooth_axis = k >= 20;
            const double mu = smooth_axis ? 0.2 + 0.025 * (k - 20) : 0.05 + 0.95 * random.uniform<double>();
            const double phi = smooth_axis ? (r.a_x > r.a_y ? 1.5707963 : 0.0) : 1.5707963 * random.uniform<double>();
            const double s = std::sqrt((1 - mu) * (1 + mu));
            const vec3<T> v(s * std::cos(phi), s * std::sin(phi), mu);
            shade::rgb<double> fresh(0);
            (void)shade::detail::dielectric_visible_albedo_sums<false>(
                d, v, eta, 200, 200, [&](double c, double F, double w) { fresh += (film.F(c) - F) * w; });
            const double margin = grid::difference_margin;
            CAPTURE(r.a_x);
            CAPTURE(r.eta_s);
            CAPTURE(mu);
            CAPTURE(phi);
            CHECK(g.difference(1, v) == doctest::Approx(margin).epsilon(1e-6));
            // differences_at reads the three channels at once, as difference() reads each.
            const std::array<T, 3> all = g.differences_at(v);
            for (std::size_t c = 0; c < 3; ++c) CHECK(all[c] == g.difference(c, v));
            for (const std::size_t c : {std::size_t(0), std::size_t(2)}) {
                const double error = g.difference(c, v) - margin - fresh[int(c)];
                CAPTURE(c);
                CAPTURE(error);
                CHECK(std::abs(error) <= 3e-3);
                CHECK(error + margin >= -1e-3);
                lowest = std::min(lowest, error);
                highest = std::max(highest, error);
            }
        }
    }
    MESSAGE("film difference grid against fresh quadrature, before the margin: " << lowest << " to " << highest);
}
