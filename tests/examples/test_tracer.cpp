// Tests of the reference tracer (examples/tracer): every scene renders finite pixels, the
// image does not depend on the thread count, and targeted checks of the things a tracer
// gets wrong: shadows, faceting across mesh edges, noise on the checker floor at y = 0,
// BVH traversal against brute force, shadow acne; plus the tone map.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <vector>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/blinn_phong.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/core/random.hpp>
#include <shade/geometry/triangle.hpp>
#include <shade/geometry/triangle_bvh.hpp>
#include <shade/light/area.hpp>
#include <shade/light/directional.hpp>
#include <shade/light/point.hpp>
#include <shade/shading/checker.hpp>

#include "tracer/mesh.hpp"
#include "tracer/render.hpp"
#include "tracer/scenes.hpp"

namespace {

using tracer::real;
using tracer::rgb;
using tracer::vec3;

constexpr real pi = shade::pi<real>;

/// Rec. 709 luminance, the same weights as tracer::tone_map.
real luminance(const rgb& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

bool finite(const rgb& c) { return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z); }

/// The camera ray of scene s from its pinhole through world point target.
shade::ray<real> ray_toward(const tracer::scene& s, const vec3& target) {
    const vec3 o = s.camera->position();
    return {o, glm::normalize(target - o)};
}

/// Radiance that the camera of s sees along r, with a fixed random stream so that two calls
/// with the same arguments draw the same area-light samples.
rgb radiance_along(const tracer::scene& s, const shade::ray<real>& r, std::uint64_t stream = 7) {
    shade::rng random(1, stream);
    return tracer::trace(s, r, random, tracer::lighting_options{});
}

/// The shaded radiance at hit h seen along r (same fixed stream as radiance_along).
rgb shade_at(const tracer::scene& s, const tracer::scene_hit& h, const shade::ray<real>& r) {
    shade::rng random(1, 7);
    return s.shade_hit(h, -glm::normalize(r.direction), random);
}

bool same_bits(const tracer::radiance_image& a, const tracer::radiance_image& b) {
    return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(rgb)) == 0;
}

constexpr real aspect_16_9 = real(48) / real(27);

} // namespace

// ---------------------------------------------------------------------------------------
// Every scene: finite, non-negative, thread-count independent.

TEST_CASE("every scene renders finite, non-negative radiance with some pixels hitting objects") {
    for (const char* name : {"gallery", "mesh", "lights"}) {
        CAPTURE(name);
        const auto s = tracer::make_scene(name, aspect_16_9);
        tracer::render_options o;
        o.width = 48;
        o.height = 27;
        o.spp = 2;
        o.threads = 2;
        const auto img = tracer::render(s, o);
        REQUIRE(img.pixels.size() == std::size_t(48 * 27));
        int bad = 0;
        int not_background = 0;
        for (const rgb& c : img.pixels) {
            if (!finite(c) || c.x < 0 || c.y < 0 || c.z < 0) ++bad;
            if (c != s.background) ++not_background;
        }
        CHECK(bad == 0);
        // Every scene has a floor filling the lower half of the frame at least.
        CHECK(not_background > 48 * 27 / 2);
    }
}

TEST_CASE("rendering is bit-for-bit identical with 1 and 3 threads, in radiance and in 8-bit output") {
    for (const char* name : {"gallery", "mesh", "lights"}) {
        CAPTURE(name);
        const auto s = tracer::make_scene(name, aspect_16_9);
        tracer::render_options o;
        o.width = 48;
        o.height = 27;
        o.spp = 2;
        o.threads = 1;
        const auto one = tracer::render(s, o);
        o.threads = 3;
        const auto three = tracer::render(s, o);
        CHECK(same_bits(one, three));
        const auto a = tracer::to_srgb8(one);
        const auto b = tracer::to_srgb8(three);
        CHECK(a.pixels == b.pixels);
    }
}

TEST_CASE("the seed matters: scenes with an area light differ between seeds, and spp 1 does not jitter") {
    // The lights scene's soft shadow is sampled with random strata, so another seed gives
    // other samples (a test that the seed reaches the generators at all).
    const auto s = tracer::make_scene("lights", aspect_16_9);
    tracer::render_options o;
    o.width = 48;
    o.height = 27;
    o.spp = 1;
    o.threads = 2;
    o.seed = 1;
    const auto a = tracer::render(s, o);
    o.seed = 2;
    const auto b = tracer::render(s, o);
    CHECK_FALSE(same_bits(a, b));
    // With spp = 1 the sample is the pixel centre, so the primary ray is the camera's
    // ray_for_pixel ray and pixel (x, y) equals trace() along it with that pixel's stream.
    const int x = 30;
    const int y = 20;
    const std::uint64_t index = std::uint64_t(y) * 48 + std::uint64_t(x);
    shade::rng random(o.seed, index);
    const auto r = s.camera->ray_for_raster(real(x) + 0.5, real(y) + 0.5, 48, 27);
    CHECK(tracer::trace(s, r, random, o.lighting) == b.at(x, y));
}

TEST_CASE("render rejects a scene without camera and non-positive sizes") {
    tracer::scene s;
    tracer::render_options o;
    CHECK_THROWS_AS((void)tracer::render(s, o), std::invalid_argument);
    const auto g = tracer::make_scene("lights", 1);
    o.width = 0;
    CHECK_THROWS_AS((void)tracer::render(g, o), std::invalid_argument);
    o.width = 4;
    o.spp = 0;
    CHECK_THROWS_AS((void)tracer::render(g, o), std::invalid_argument);
    CHECK_THROWS_AS((void)tracer::make_scene("nope", 1), std::invalid_argument);
    CHECK(tracer::is_scene_name("mesh"));
    CHECK_FALSE(tracer::is_scene_name("Mesh"));
}

// ---------------------------------------------------------------------------------------
// (a) Shadows.

TEST_CASE("lights scene: a floor point in the left sphere's shadow gets nothing from the point light, one beside it the derived amount") {
    // The lights scene: floor y = 0 (Lambert 0.8), left sphere centre (-2, 0.6, 0) radius
    // 0.6, point light at (-2, 2.5, 0) with intensity 2.5, colour (1, 0.8, 0.6), 1/r^2.
    //
    // Shadowed point S = (-2, 0, 0.7). The segment from S to the light has direction
    // (0, 2.5, -0.7)/2.5962; the sphere centre minus S is (0, 0.6, -0.7), whose projection
    // on it is (1.5 + 0.49)/2.5962 = 0.7665, so the segment passes the centre at distance
    // sqrt(0.85 - 0.7665^2) = 0.512 < 0.6 (the projection lies between 0 and 2.5962): the
    // sphere blocks the point light at S.
    //
    // Lit point L = (-3.2, 0, 0.7): direction to the light (1.2, 2.5, -0.7)/2.8601, centre
    // minus L = (1.2, 0.6, -0.7), projection 1.1993, distance sqrt(2.29 - 1.4383) = 0.923
    // > 0.6; the other spheres (x = 0 and 2) are farther still: unblocked.
    //
    // Check: replace the point light by the same light with intensity 0 (the random stream
    // is consumed identically, so the area-light samples are the same). At S nothing
    // changes, bit for bit. At L the radiance drops by exactly the lit Lambert term
    //   pi (0.8/pi) E_d (n·l) = 0.8 * 2.5 (1, 0.8, 0.6) / r^2 * (2.5 / r)     (n·l = 2.5/r).
    auto with = tracer::make_scene("lights", 16.0 / 9.0);
    auto without = with;
    without.lights[0] = shade::point_light<real>({-2, 2.5, 0}, tracer::detail::light_colour(0, rgb(1, 0.8, 0.6), rgb(1)),
                                                 shade::falloff::inverse_square);
    const vec3 S(-2, 0, 0.7);
    const vec3 L(-3.2, 0, 0.7);
    for (const vec3& target : {S, L}) {
        const auto h = with.intersect(ray_toward(with, target));
        REQUIRE(h);
        CHECK(h->object == 0); // the camera sees the floor there, not a sphere
        CHECK(glm::length(h->p - target) < 1e-9);
    }
    const rgb s_with = radiance_along(with, ray_toward(with, S));
    const rgb s_without = radiance_along(without, ray_toward(without, S));
    const rgb l_with = radiance_along(with, ray_toward(with, L));
    const rgb l_without = radiance_along(without, ray_toward(without, L));
    CHECK(s_with == s_without);
    CHECK(luminance(s_with) > 0); // lit by the sun and the area light: not trivially black

    const real r = glm::length(vec3(-2, 2.5, 0) - L);
    const rgb expected = real(0.8) * real(2.5) * rgb(1, 0.8, 0.6) / (r * r) * (real(2.5) / r);
    const rgb got = l_with - l_without;
    for (int c = 0; c < 3; ++c) CHECK(got[c] == doctest::Approx(expected[c]).epsilon(1e-12));
    // And so the lit point is clearly brighter: the point light alone gives L a
    // luminance of 0.8 * 2.5 * Y(1, 0.8, 0.6) * 2.5 / 2.8601^3 = 0.8 * 2.5 * 0.828 * 2.5 /
    // 23.396 = 0.177.
    CHECK(luminance(l_with) > luminance(s_with) + 0.15);
}

TEST_CASE("lights scene: hard shadow of the point light in a rendered image") {
    // The same shadowed and lit floor points as above, found in an image: the pixel
    // whose centre ray passes nearest each point. Rendering with spp 1 uses exactly that
    // centre ray, so the shadow shows in the image as it does in the direct trace.
    const auto s = tracer::make_scene("lights", 16.0 / 9.0);
    tracer::render_options o;
    o.width = 160;
    o.height = 90;
    o.spp = 1;
    o.threads = 2;
    const auto img = tracer::render(s, o);
    const auto pixel_of = [&](const vec3& target) {
        const vec3 d = glm::normalize(target - s.camera->position());
        int best_x = 0;
        int best_y = 0;
        real best = -2;
        for (int y = 0; y < o.height; ++y)
            for (int x = 0; x < o.width; ++x) {
                const auto r = s.camera->ray_for_raster(real(x) + 0.5, real(y) + 0.5, o.width, o.height);
                const real c = glm::dot(glm::normalize(r.direction), d);
                if (c > best) {
                    best = c;
                    best_x = x;
                    best_y = y;
                }
            }
        return img.at(best_x, best_y);
    };
    CHECK(luminance(pixel_of({-3.2, 0, 0.7})) > luminance(pixel_of({-2, 0, 0.7})) + 0.1);
}

// ---------------------------------------------------------------------------------------
// (b) Faceting: flat shading jumps across a mesh edge, Phong and Gouraud do not.

TEST_CASE("mesh scene: across a torus edge the flat normal and radiance jump, the Phong and Gouraud ones do not") {
    const auto s = tracer::make_scene("mesh", 16.0 / 9.0);
    // Objects: 0 floor, 1 flat torus, 2 Gouraud torus, 3 Phong torus (make_mesh_scene).
    REQUIRE(s.objects.size() == 4);
    const tracer::mesh& m = *s.objects[1].mesh;
    const int rings = 28;
    const int sides = 14;
    REQUIRE(m.triangle_count() == std::size_t(2 * rings * sides));

    // The edge: quad (i, j) = (7, 2) of make_torus is triangles 2 (i sides + j) = (a, c, b)
    // and +1 = (a, d, c), a = vertex (i, j), b = (i + 1, j). Ring 7 of 28 is u = pi/2 (the
    // side facing the camera at z = 6.5), side 2 of 14 is w = 51 deg (upper front). The edge
    // a-b is shared with the quad (i, j - 1); find that triangle in the index data.
    const std::uint32_t t1 = 2 * (7 * sides + 2);
    const std::uint32_t a = m.indices[3 * t1];
    const std::uint32_t b = m.indices[3 * t1 + 2];
    const std::uint32_t third1 = m.indices[3 * t1 + 1];
    std::optional<std::uint32_t> t2;
    std::uint32_t third2 = 0;
    for (std::uint32_t t = 0; t < m.triangle_count(); ++t) {
        if (t == t1) continue;
        int shared = 0;
        std::uint32_t other = 0;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t v = m.indices[3 * std::size_t(t) + std::size_t(k)];
            if (v == a || v == b) ++shared;
            else other = v;
        }
        if (shared == 2) {
            REQUIRE_FALSE(t2); // a closed manifold: exactly one neighbour per edge
            t2 = t;
            third2 = other;
        }
    }
    REQUIRE(t2);

    // The two faces belong to neighbouring quads along the tube. Each quad is an isosceles
    // trapezoid, planar and symmetric about the meridian plane u = u_{i+1/2}: its edges
    // a-b and d-c are both perpendicular to that plane. In the meridian plane (coordinates
    // rho from the axis, y) the quad's side from mid(a, b) to mid(d, c) runs from
    // ((R + r cos w_j) C, r sin w_j) to ((R + r cos w_{j+1}) C, r sin w_{j+1}), C =
    // cos(pi/28) (the chord midpoints sit at C times the ring radius), i.e. along
    // (-C sin w_{j+1/2}, cos w_{j+1/2}). The dihedral angle is the angle between those
    // directions for w = 2 pi 2.5/14 and 2 pi 1.5/14 (2 pi/14 if C were 1).
    const real C = std::cos(pi / rings);
    const real w_hi = 2 * pi * 2.5 / sides;
    const real w_lo = 2 * pi * 1.5 / sides;
    const tracer::vec2 d_hi(-C * std::sin(w_hi), std::cos(w_hi));
    const tracer::vec2 d_lo(-C * std::sin(w_lo), std::cos(w_lo));
    const real dihedral = std::atan2(std::abs(d_hi.x * d_lo.y - d_hi.y * d_lo.x), glm::dot(d_hi, d_lo));

    // Points on either side of the edge at barycentric weight eps of the third vertex:
    // P_k = m + eps (third_k - m), m the edge midpoint, i.e. about eps * 0.16 from the edge.
    const real eps = 1e-7;
    struct side_result {
        vec3 shading_n;
        rgb radiance;
    };
    const auto probe = [&](std::size_t object, std::uint32_t tri, std::uint32_t third) {
        const tracer::mesh& mm = *s.objects[object].mesh;
        const vec3 mid = (mm.positions[a] + mm.positions[b]) * real(0.5);
        const vec3 p = mid + eps * (mm.positions[third] - mid);
        const auto r = ray_toward(s, p);
        const auto h = s.intersect(r);
        REQUIRE(h);
        REQUIRE(h->object == object);
        REQUIRE(h->triangle == tri);
        return side_result{h->shading_n, shade_at(s, *h, r)};
    };
    const auto angle = [](const vec3& x, const vec3& y) {
        return std::atan2(glm::length(glm::cross(x, y)), glm::dot(x, y));
    };
    const auto jump = [](const rgb& x, const rgb& y) {
        return std::abs(luminance(x) - luminance(y)) / (real(0.5) * (luminance(x) + luminance(y)));
    };

    const auto flat1 = probe(1, t1, third1);
    const auto flat2 = probe(1, *t2, third2);
    const auto gouraud1 = probe(2, t1, third1);
    const auto gouraud2 = probe(2, *t2, third2);
    const auto phong1 = probe(3, t1, third1);
    const auto phong2 = probe(3, *t2, third2);

    // Normals: flat jumps by the dihedral angle. Phong's normal is b_a n_a + b_b n_b + eps
    // n_third, normalised, with b_a = b_b = (1 - eps)/2 on both sides: the two unnormalised
    // normals differ by eps |n_third1 - n_third2| <= 2 eps, and their length is ~cos(pi/28),
    // so the angle between them is at most ~2.1 eps.
    CHECK(angle(flat1.shading_n, flat2.shading_n) == doctest::Approx(dihedral).epsilon(1e-9));
    CHECK(angle(phong1.shading_n, phong2.shading_n) < 2.2 * eps);

    // Radiance: a first-order function of the normal (and of the position, which moves by
    // ~eps * 0.3 across the edge). Flat shading jumps by a visible amount; Phong and
    // Gouraud (whose colours interpolate the same two vertex colours with weight eps for
    // the third) change by a fraction ~angle ratio (2.2e-7 / 0.45 ~ 5e-7) of it; require
    // at least 1000 times less, leaving room for the nonlinearity of the specular lobe.
    const real flat_jump = jump(flat1.radiance, flat2.radiance);
    const real phong_jump = jump(phong1.radiance, phong2.radiance);
    const real gouraud_jump = jump(gouraud1.radiance, gouraud2.radiance);
    CAPTURE(flat_jump);
    CAPTURE(phong_jump);
    CAPTURE(gouraud_jump);
    CHECK(flat_jump > 0.02);
    CHECK(phong_jump < 1e-3 * flat_jump);
    CHECK(gouraud_jump < 1e-3 * flat_jump);
}

// ---------------------------------------------------------------------------------------
// (c) The checker floor at y = 0.

namespace {

/// The gallery's camera and floor, lit by one directional light only (no shadows possible,
/// the same irradiance everywhere), so the radiance of a floor point depends only on the
/// checker cell it lies in: 0.75 or 0.25 times E (n·l).
tracer::scene checker_floor_scene(tracer::material floor) {
    tracer::scene s;
    s.name = "checker floor";
    s.camera = tracer::detail::camera({0, 4.6, 8}, {0, 0.2, 0}, 38, 16.0 / 9.0);
    s.add_plane(shade::plane<real>({0, 0, 0}, {0, 1, 0}), std::move(floor));
    s.lights.push_back(shade::directional_light<real>({0.3, 1, 0.2}, tracer::detail::light_colour(1, rgb(1), rgb(1))));
    return s;
}

} // namespace

TEST_CASE("checker floor: every point within one cell gets the same colour, also far away and at grazing angles") {
    const auto s = checker_floor_scene(tracer::detail::checker_floor());
    // Directional light l = (0.3, 1, 0.2)/|.|, so n·l = 1/sqrt(1.13); a Lambert cell of
    // albedo k reflects k * E * n·l (lit's pi cancels the BRDF's 1/pi).
    const real n_dot_l = 1 / std::sqrt(1.13);
    // With cell size 1 and bias 1/2 the cells are [k - 1/2, k + 1/2) in each coordinate and
    // the parity is (k_x + k_y + k_z) mod 2; on the floor k_y = 0 however y rounds.
    const struct {
        int kx;
        int kz;
    } cells[] = {{0, 2}, {1, 2}, {-3, 1}, {2, -5}, {0, -40}, {7, -60}};
    int hits_off_plane = 0;
    for (const auto& cell : cells) {
        const real k = ((cell.kx + cell.kz) & 1) == 0 ? 0.75 : 0.25;
        const rgb expected = rgb(k * n_dot_l);
        CAPTURE(cell.kx);
        CAPTURE(cell.kz);
        // 201 points on a diagonal across the cell, stopping 1% short of its edges (so
        // only y, not x or z, could put a point into another cell).
        int wrong = 0;
        for (int i = 0; i <= 200; ++i) {
            const real f = -0.49 + 0.98 * real(i) / 200;
            const vec3 target(real(cell.kx) + f, 0, real(cell.kz) + 0.7 * f);
            const auto r = ray_toward(s, target);
            const auto h = s.intersect(r);
            REQUIRE(h);
            if (h->p.y != 0) ++hits_off_plane;
            const rgb c = shade_at(s, *h, r);
            if (glm::length(c - expected) > 1e-12) ++wrong;
        }
        CHECK(wrong == 0);
    }
    // The hits do land off y = 0 by rounding (o.y + t d.y is rarely exactly 0), which is
    // why the bias is needed: with bias 0 the cell boundary y = 0 runs through the floor
    // and those points flip to the neighbouring cell.
    CHECK(hits_off_plane > 0);
    using L = shade::lambert<real>;
    const auto biased0 = checker_floor_scene(
        tracer::make_material(shade::checker<L, L>(L(rgb(0.75)), L(rgb(0.25)), real(1), real(0))));
    int below = 0;
    int above = 0;
    for (int i = 0; i <= 200; ++i) {
        const real f = -0.49 + 0.98 * real(i) / 200;
        const vec3 target(7.5 + f, 0, -60.5 + 0.7 * f); // one cell of the bias-0 lattice
        const auto r = ray_toward(biased0, target);
        const auto h = biased0.intersect(r);
        REQUIRE(h);
        (luminance(shade_at(biased0, *h, r)) > 0.5 * n_dot_l ? above : below)++;
    }
    CAPTURE(below);
    CAPTURE(above);
    CHECK((below > 0 && above > 0)); // the noise the bias removes
}

TEST_CASE("a checker material chooses its cell once per point and lights it as the whole checker would") {
    // tracer::light_with lights lit<checker> through the child of the point's cell. Lit
    // whole, a checker of a Lambert (not a split BRDF) and a Blinn-Phong (split) is not
    // split either, so its specular part is weighted by the light's diffuse colour; the
    // chosen child must be lit the same way. The lights' specular colours differ from their
    // diffuse ones, so lighting the Blinn-Phong cell as a split BRDF would show.
    using L = shade::lambert<real>;
    using B = shade::blinn_phong<real>;
    tracer::scene s;
    s.name = "checker materials";
    s.add_plane(shade::plane<real>({0, 0, 0}, {0, 1, 0}), tracer::make_material(L(rgb(0.5))));
    s.lights.push_back(shade::directional_light<real>({0.3, 1, 0.2}, tracer::detail::light_colour(1, rgb(1, 0.6, 0.3), rgb(0.2, 0.4, 1), rgb(0.05))));
    s.lights.push_back(shade::area_light<real>({-1, 3, -1}, {2, 0, 0}, {0, 0, 2}, tracer::detail::light_colour(1, rgb(0.9, 1, 0.7), rgb(1, 0.1, 0.1))));
    const shade::lit mixed(shade::checker<L, B>(L(rgb(0.9)), B(rgb(0.3, 0.1, 0.1), rgb(0.6), 30), real(0.25)), rgb(0.1));
    const shade::lit lamberts(shade::checker<L, L>(L(rgb(0.75)), L(rgb(0.25)), real(0.25)), rgb(0.1));
    const auto pattern_shader = shade::checker<shade::lit<L>, shade::lit<B>>(
        shade::lit<L>(L(rgb(0.9))), shade::lit<B>(B(rgb(0.3, 0.1, 0.1), rgb(0.6), 30)), real(0.25));
    int first_cells = 0;
    int second_cells = 0;
    for (int i = 0; i < 64; ++i) {
        const vec3 p(-1 + real(i % 8) * 0.27, 0, -1 + real(i / 8) * 0.27);
        const auto at = shade::surface_point<real>::at(p, {0, 1, 0});
        const vec3 v = glm::normalize(vec3(0.2, 1, 0.7));
        const vec3 n(0, 1, 0);
        // p is exactly on the floor (y = 0); a bound of a few ulps of its coordinates starts
        // shadow rays off it, as a computed hit's p_error does.
        const vec3 p_error(1e-15);
        const tracer::lighting_options options{};
        const auto both = [&](const auto& shader) {
            shade::rng r1(3, std::uint64_t(i));
            shade::rng r2(3, std::uint64_t(i));
            const tracer::lighting_query q1{s, at, n, p_error, v, r1, options, true};
            const tracer::lighting_query q2{s, at, n, p_error, v, r2, options, true};
            const rgb chosen = tracer::light_with(shader, q1);
            const rgb whole = s.sum_lights(shader, q2);
            CHECK(chosen == whole); // bit for bit
            CHECK(r1.next_u32() == r2.next_u32());
            return chosen;
        };
        (void)both(mixed);
        (void)both(lamberts);
        (void)both(pattern_shader);
        (mixed.brdf().parity(at) == 0 ? first_cells : second_cells)++;
    }
    CHECK(first_cells > 0);
    CHECK(second_cells > 0);
}

// ---------------------------------------------------------------------------------------
// (d) The BVH against brute force.

namespace {

std::optional<shade::triangle_hit<real>> brute_force(const tracer::mesh& m, shade::ray<real> r) {
    std::optional<shade::triangle_hit<real>> best;
    for (std::size_t i = 0; i < m.triangle_count(); ++i) {
        const shade::triangle<real> t{m.positions[m.indices[3 * i]], m.positions[m.indices[3 * i + 1]],
                                      m.positions[m.indices[3 * i + 2]]};
        if (auto h = shade::intersect<shade::watertight>(r, t)) {
            r.t_max = h->t;
            best = h;
        }
    }
    return best;
}

using mesh_bvh = shade::triangle_bvh<real, shade::watertight>;

std::optional<shade::triangle_hit<real>> through_bvh(const mesh_bvh& b, const shade::ray<real>& r) {
    const auto h = b.closest(r);
    if (!h) return std::nullopt;
    return h->hit;
}

} // namespace

TEST_CASE("BVH: closest hit and any-hit equal brute force over all triangles for random rays") {
    const tracer::mesh meshes[] = {
        tracer::make_torus({0.1, 0.2, -0.3}, 0.75, 0.35, 28, 14),
        tracer::make_icosphere({0, 0, 0}, 1, 3),
        tracer::make_torus({5, -2, 1}, 2, 0.2, 64, 6), // thin tube: many slivers
    };
    for (const auto& m : meshes) {
        const mesh_bvh b(m.triangles());
        CHECK(b.size() > 1);
        const shade::aabb<real> box = m.bounds();
        const vec3 centre = box.center();
        const real size = glm::length(box.hi - box.lo);
        shade::rng random(42, 3);
        const auto u = [&] { return random.uniform<real>(); };
        int hits = 0;
        int mismatches = 0;
        int ties = 0;
        for (int k = 0; k < 3000; ++k) {
            // Origins in a box twice the mesh's size; directions toward a random point of
            // the mesh box, or toward a vertex (rays through vertices and edges stress
            // the traversal's conservative slab test), or fully random.
            const vec3 o = centre + size * vec3(u() - 0.5, u() - 0.5, u() - 0.5);
            vec3 target;
            if (k % 3 == 0) target = box.lo + (box.hi - box.lo) * vec3(u(), u(), u());
            else if (k % 3 == 1) target = m.positions[std::size_t(u() * real(m.positions.size()))];
            else target = o + vec3(u() - 0.5, u() - 0.5, u() - 0.5);
            if (target == o) continue;
            shade::ray<real> r{o, target - o};
            if (k % 5 == 0) r.t_max = u() * 1.5; // shortened rays: the interval must be honoured
            const auto fast = through_bvh(b, r);
            const auto slow = brute_force(m, r);
            const bool any = b.any(r);
            if (slow) ++hits;
            // Same triangle test, same interval: the same closest t exactly. Except for a
            // ray through a vertex or along an edge: several triangles report the same
            // point, each rounding t on its own (they differ by an ulp), and which of them
            // the traversal meets first decides which t it keeps; there t agrees to 4 ulps.
            bool same_t = true;
            if (fast && slow && fast->t != slow->t) {
                const vec3 w = slow->barycentric;
                const bool on_edge = std::min({w.x, w.y, w.z}) <= 1e-12;
                same_t = on_edge && std::abs(fast->t - slow->t) <= 4 * std::numeric_limits<real>::epsilon() * slow->t;
                if (same_t) ++ties;
            }
            if (fast.has_value() != slow.has_value() || any != slow.has_value() || !same_t) ++mismatches;
        }
        CHECK(mismatches == 0);
        CHECK(ties < hits / 20); // ties are the rare vertex rays, not the rule
        CHECK(hits > 500); // the test exercises hits, not only misses
    }
}

TEST_CASE("scene::intersect on a mesh equals brute force, and the reported triangle is the one hit") {
    tracer::scene s;
    s.add_mesh(tracer::make_torus({0, 0, 0}, 0.75, 0.35, 28, 14), tracer::mesh_shading::phong,
               tracer::make_material(shade::lambert<real>(rgb(0.5))));
    const tracer::mesh& m = *s.objects[0].mesh;
    shade::rng random(5, 9);
    const auto u = [&] { return random.uniform<real>(); };
    int hits = 0;
    for (int k = 0; k < 2000; ++k) {
        const vec3 o = 3.0 * vec3(u() - 0.5, u() - 0.5, u() - 0.5);
        const vec3 target = vec3(1.1 * (u() - 0.5), 0.35 * (u() - 0.5), 1.1 * (u() - 0.5)) * 2.0;
        const shade::ray<real> r{o, target - o};
        const auto h = s.intersect(r);
        const auto slow = brute_force(m, r);
        REQUIRE(h.has_value() == slow.has_value());
        if (!h) continue;
        ++hits;
        CHECK(h->t == slow->t);
        // The reported triangle contains the hit point with the reported barycentrics.
        const std::size_t q = 3 * std::size_t(h->triangle);
        const vec3 p = h->barycentric.x * m.positions[m.indices[q]] + h->barycentric.y * m.positions[m.indices[q + 1]] +
                       h->barycentric.z * m.positions[m.indices[q + 2]];
        CHECK(glm::length(p - h->p) < 1e-12);
    }
    CHECK(hits > 500);
}

// ---------------------------------------------------------------------------------------
// (e) No shadow acne: surfaces facing the only light, with nothing else in the scene, are
// fully lit at every pixel.

namespace {

/// Renders s (one directional light, no occluders but the object itself) at spp 1 and
/// counts the pixels whose camera hit faces the light (geometric n·l > min_n_dot_l) and
/// the ones among them that got the full unshadowed Lambert radiance albedo E (n_s·l).
struct lit_count {
    int facing = 0;
    int fully_lit = 0;
};

lit_count count_lit(const tracer::scene& s, real albedo, real min_n_dot_l) {
    tracer::render_options o;
    o.width = 96;
    o.height = 54;
    o.spp = 1;
    o.threads = 2;
    const auto img = tracer::render(s, o);
    const vec3 l = s.lights[0].sample(vec3(0), tracer::vec2(0.5)).l;
    lit_count n;
    for (int y = 0; y < o.height; ++y)
        for (int x = 0; x < o.width; ++x) {
            // spp 1 renders exactly the pixel-centre ray.
            const auto r = s.camera->ray_for_raster(real(x) + 0.5, real(y) + 0.5, o.width, o.height);
            const auto h = s.intersect(r);
            if (!h || !(glm::dot(h->geometric_n, l) > min_n_dot_l)) continue;
            ++n.facing;
            const real expected = albedo * glm::dot(h->shading_n, l);
            if (std::abs(img.at(x, y).x - expected) <= 1e-12) ++n.fully_lit;
        }
    return n;
}

tracer::scene acne_scene(vec3 light_direction) {
    tracer::scene s;
    s.camera = tracer::detail::camera({0, 3, 6}, {0, 0.4, 0}, 40, 16.0 / 9.0);
    s.lights.push_back(shade::directional_light<real>(light_direction, tracer::detail::light_colour(1, rgb(1), rgb(1))));
    return s;
}

} // namespace

TEST_CASE("no shadow acne on a floor under a grazing sun: every floor pixel is fully lit") {
    // A sun 3 degrees above the horizon: shadow rays leave the floor almost along it,
    // where an origin left on (or below) the plane by rounding re-hits the floor.
    const real elevation = 3 * pi / 180;
    auto s = acne_scene({std::cos(elevation), std::sin(elevation), 0.3});
    s.add_plane(shade::plane<real>({0, 0, 0}, {0, 1, 0}), tracer::make_material(shade::lambert<real>(rgb(0.8))));
    const auto n = count_lit(s, 0.8, 0);
    CHECK(n.facing > 96 * 54 / 3);
    CHECK(n.fully_lit == n.facing);
}

TEST_CASE("no shadow acne on a sphere and on a flat-shaded icosphere facing the sun") {
    // A convex object never shadows its own points that face the light: it lies behind
    // the tangent plane (for the polyhedron: the face's plane), and the light direction
    // points away from that plane. So every pixel with geometric n·l > 0 must be fully
    // lit. The threshold 1e-9 only skips pixels where n·l itself is at rounding level.
    for (const vec3 sun : {vec3(1, 1, 0.5), vec3(-1, 0.2, -0.3)}) {
        {
            auto s = acne_scene(sun);
            s.add_sphere(shade::sphere<real>({0.2, 0.5, 0}, 1.2), tracer::make_material(shade::lambert<real>(rgb(0.6))));
            const auto n = count_lit(s, 0.6, 1e-9);
            CHECK(n.facing > 200);
            CHECK(n.fully_lit == n.facing);
        }
        {
            auto s = acne_scene(sun);
            s.add_mesh(tracer::make_icosphere({0.2, 0.5, 0}, 1.2, 2), tracer::mesh_shading::flat,
                       tracer::make_material(shade::lambert<real>(rgb(0.6))));
            const auto n = count_lit(s, 0.6, 1e-9);
            CHECK(n.facing > 200);
            CHECK(n.fully_lit == n.facing);
        }
    }
}

// ---------------------------------------------------------------------------------------
// Tone map.

TEST_CASE("tone_map: 0 maps to 0, values land in [0, 1], hand-derived values") {
    CHECK(tracer::tone_map(rgb(0), 1) == rgb(0));
    // Negative or NaN luminance has nothing to show: black, not NaN.
    CHECK(tracer::tone_map(rgb(-1), 1) == rgb(0));
    CHECK(tracer::tone_map(rgb(std::numeric_limits<real>::quiet_NaN()), 1) == rgb(0));
    // Grey L = 1, white 4: L_d = 1 (1 + 1/16) / 2 = 17/32.
    CHECK(tracer::tone_map(rgb(1), 1).x == doctest::Approx(17.0 / 32.0).epsilon(1e-15));
    // L = L_white = 4 maps to exactly 1: 4 (1 + 4/16) / 5 = 1.
    CHECK(tracer::tone_map(rgb(4), 1).y == doctest::Approx(1).epsilon(1e-15));
    // Exposure scales the input: tone_map(c, 2) == tone_map(2c, 1).
    CHECK(tracer::tone_map(rgb(0.3, 0.2, 0.1), 2) == tracer::tone_map(rgb(0.6, 0.4, 0.2), 1));
    // Hue is kept below clipping: the output is the input scaled by L_d / L.
    const rgb c(0.4, 0.2, 0.1);
    const rgb t = tracer::tone_map(c, 1);
    CHECK(t.x / t.z == doctest::Approx(4).epsilon(1e-12));
    CHECK(t.y / t.z == doctest::Approx(2).epsilon(1e-12));
    for (const real v : {1e-300, 1e-6, 0.5, 3.0, 1e3, 1e300}) {
        const rgb m = tracer::tone_map(rgb(v, 2 * v, 0.5 * v), 1);
        for (int k = 0; k < 3; ++k) {
            CHECK(m[k] >= 0);
            CHECK(m[k] <= 1);
        }
    }
}

TEST_CASE("tone_map is monotonic in the input and in the exposure") {
    real previous = 0;
    for (int i = 1; i <= 4000; ++i) {
        const real v = 1e-4 * std::pow(1.005, real(i)); // 1e-4 .. ~48
        const real y = luminance(tracer::tone_map(rgb(v), 1));
        CHECK(y >= previous);
        previous = y;
    }
    // Up to the white point (L_white = 4) it is strictly increasing.
    CHECK(luminance(tracer::tone_map(rgb(3.9), 1)) < luminance(tracer::tone_map(rgb(3.95), 1)));
    CHECK(luminance(tracer::tone_map(rgb(0.5), 1)) < luminance(tracer::tone_map(rgb(0.5), 1.01)));
}

TEST_CASE("to_srgb8: black stays black, radiance at the white point becomes 255, sizes are kept") {
    tracer::radiance_image r;
    r.width = 3;
    r.height = 2;
    r.pixels = {rgb(0), rgb(4), rgb(100), rgb(1), rgb(0.01), rgb(0)};
    const auto img = tracer::to_srgb8(r);
    CHECK(img.width == 3);
    CHECK(img.height == 2);
    CHECK(img.at(0, 0).r == 0);
    CHECK(img.at(1, 0).g == 255);
    CHECK(img.at(2, 0).b == 255);
    // L = 1 -> 17/32 = 0.53125 linear -> sRGB 1.055 * 0.53125^(1/2.4) - 0.055 = 0.75558,
    // times 255 = 192.67, rounded to the nearest code: 193.
    CHECK(img.at(0, 1).r == 193);
    // Exposure 4 takes radiance 1 to the white point.
    CHECK(tracer::to_srgb8(r, 4).at(0, 1).r == 255);
}
