#include <cmath>
#include <limits>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/core/math.hpp>
#include <shade/geometry/camera.hpp>

namespace {

template <class T>
using v3 = shade::vec3<T>;

template <class T>
constexpr T eps = std::numeric_limits<T>::epsilon();

template <class T>
bool near_vec(const v3<T>& a, const v3<T>& b, T tol) {
    return std::abs(a.x - b.x) <= tol && std::abs(a.y - b.y) <= tol && std::abs(a.z - b.z) <= tol;
}

// Angle between two directions, via atan2(|a x b|, a·b) (accurate also for small angles).
template <class T>
T angle_between(const v3<T>& a, const v3<T>& b) {
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

template <class T>
shade::pinhole_camera<T> test_camera() {
    // At (1,2,3) looking at (4,6,3): forward = (3,4,0)/5 = (0.6, 0.8, 0), distance 5.
    // up hint +z: right = forward x z = (0.8, -0.6, 0), up = right x forward = (0,0,1).
    // fov_y = 60 degrees, aspect 2.
    return shade::pinhole_camera<T>({1, 2, 3}, {4, 6, 3}, {0, 0, 1}, shade::pi<T> / 3, 2);
}

} // namespace

TEST_CASE_TEMPLATE("camera: basis and centre ray point at the look-at point", T, float, double) {
    const auto cam = test_camera<T>();
    const T tol = 8 * eps<T>;
    CHECK(near_vec(cam.forward(), v3<T>(T(0.6), T(0.8), 0), tol));
    CHECK(near_vec(cam.right(), v3<T>(T(0.8), T(-0.6), 0), tol));
    CHECK(near_vec(cam.up(), v3<T>(0, 0, 1), tol));
    CHECK(near_vec(cam.look_at(), v3<T>(4, 6, 3), 8 * tol));
    const auto r = cam.ray_for_ndc(0, 0);
    CHECK(r.origin == v3<T>(1, 2, 3));
    CHECK(near_vec(r.direction, v3<T>(T(0.6), T(0.8), 0), tol));
    CHECK(r.t_min == T(0));
    CHECK(r.t_max == shade::infinity<T>);
    CHECK(r.valid());
    // With an odd image size the centre pixel's centre, (50 + 0.5, 25 + 0.5) in a 101 x 51
    // image, is the image centre: its ray reaches the look-at point at t = 5 (unit
    // direction, so t is the distance).
    const auto p = cam.ray_for_pixel(50, 25, 101, 51);
    CHECK(near_vec(p.at(T(5)), v3<T>(4, 6, 3), 64 * eps<T>));
    CHECK(std::abs(glm::length(p.direction) - T(1)) <= tol);
}

TEST_CASE_TEMPLATE("camera: edge and corner rays span the field of view", T, float, double) {
    const auto cam = test_camera<T>();
    const v3<T> f = cam.forward();
    const T tol = 64 * eps<T>;
    const T t = std::tan(shade::pi<T> / 6); // tan(fov_y / 2) = tan(30 deg) = 1/sqrt(3)
    // Top and bottom edge centres are fov_y/2 = 30 degrees from the view axis, 60 apart.
    const auto top = cam.ray_for_ndc(0, 1).direction;
    const auto bottom = cam.ray_for_ndc(0, -1).direction;
    CHECK(std::abs(angle_between(top, f) - shade::pi<T> / 6) <= tol);
    CHECK(std::abs(angle_between(top, bottom) - shade::pi<T> / 3) <= tol);
    CHECK(glm::dot(top, cam.up()) > 0);
    // Left and right edge centres: the image half-width at unit distance is aspect * t, so
    // each is atan(2 / sqrt(3)) ~ 49.1 degrees from the axis.
    const auto right = cam.ray_for_ndc(1, 0).direction;
    const auto left = cam.ray_for_ndc(-1, 0).direction;
    CHECK(std::abs(angle_between(right, f) - std::atan(2 * t)) <= tol);
    CHECK(std::abs(angle_between(left, right) - 2 * std::atan(2 * t)) <= tol);
    CHECK(glm::dot(right, cam.right()) > 0);
    // A corner lies at (aspect t, t) in the unit-distance image plane, at distance
    // t sqrt(aspect^2 + 1) = sqrt(5/3) from the axis: atan(sqrt(5/3)) ~ 52.2 degrees.
    const auto corner = cam.ray_for_ndc(1, 1).direction;
    CHECK(std::abs(angle_between(corner, f) - std::atan(std::sqrt(T(5) / T(3)))) <= tol);
    // Pixel centres of a 200 x 100 image: pixel (0,0) is top-left, its centre at raster
    // (0.5, 0.5), i.e. NDC (-1 + 1/200, 1 - 1/100) = (-0.995, 0.99); pixel (199, 99) is
    // the mirror image (0.995, -0.99). Both are offsets +-w from the axis in the image
    // plane, |w| = t sqrt((2 * 0.995)^2 + 0.99^2), so they are 2 atan(|w|) apart.
    const auto tl = cam.ray_for_pixel(0, 0, 200, 100).direction;
    const auto br = cam.ray_for_pixel(199, 99, 200, 100).direction;
    CHECK(glm::dot(tl, cam.up()) > 0);
    CHECK(glm::dot(tl, cam.right()) < 0);
    const T w = t * std::sqrt(shade::sqr(T(2) * T(0.995)) + shade::sqr(T(0.99)));
    CHECK(std::abs(angle_between(tl, br) - 2 * std::atan(w)) <= tol);
    // ray_for_raster at the top edge's midpoint is the NDC (0, 1) ray.
    CHECK(near_vec(cam.ray_for_raster(100, 0, 200, 100).direction, top, tol));
}

TEST_CASE_TEMPLATE("camera: in_frustum", T, float, double) {
    const auto cam = test_camera<T>();
    CHECK(cam.in_frustum(cam.look_at()));
    CHECK_FALSE(cam.in_frustum(v3<T>(1, 2, 3) - cam.forward())); // behind
    // 10 units ahead the half-height is 10 tan(30 deg) = 5.77: 5.5 above the axis is in, 6
    // is out; the half-width is twice that.
    const v3<T> ahead = v3<T>(1, 2, 3) + T(10) * cam.forward();
    CHECK(cam.in_frustum(ahead + T(5.5) * cam.up()));
    CHECK_FALSE(cam.in_frustum(ahead + T(6) * cam.up()));
    CHECK(cam.in_frustum(ahead - T(11) * cam.right()));
    CHECK_FALSE(cam.in_frustum(ahead - T(12) * cam.right()));
}

TEST_CASE_TEMPLATE("camera: translate moves rays, not their directions", T, float, double) {
    auto cam = test_camera<T>();
    const auto before = cam.ray_for_pixel(13, 7, 200, 100);
    cam.translate({T(0.5), -1, 2});
    const auto after = cam.ray_for_pixel(13, 7, 200, 100);
    CHECK(after.origin == v3<T>(T(1.5), 1, 5));
    CHECK(after.direction == before.direction);
    CHECK(near_vec(cam.look_at(), v3<T>(T(4.5), 5, 5), 64 * eps<T>));
}

TEST_CASE_TEMPLATE("camera: rotate turns the view about the camera position", T, float, double) {
    const T tol = 8 * eps<T>;
    // Camera at (0,0,5) looking at the origin (forward -z), up +y, right +x.
    const shade::pinhole_camera<T> start({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, shade::pi<T> / 2, 1);
    // Yaw by +90 degrees about +y (right-hand rule): (x, z) -> (x cos + z sin, -x sin + z cos)
    // sends forward (0,0,-1) to (-1,0,0) (a left turn) and right (1,0,0) to (0,0,-1).
    auto yawed = start;
    yawed.rotate({0, 1, 0}, shade::pi<T> / 2);
    CHECK(yawed.position() == v3<T>(0, 0, 5));
    CHECK(near_vec(yawed.ray_for_ndc(0, 0).direction, v3<T>(-1, 0, 0), tol));
    CHECK(near_vec(yawed.right(), v3<T>(0, 0, -1), tol));
    CHECK(near_vec(yawed.up(), v3<T>(0, 1, 0), tol));
    CHECK(near_vec(yawed.look_at(), v3<T>(-5, 0, 5), 8 * tol));
    // Pitch by +90 degrees about right (+x): (y, z) -> (y cos - z sin, y sin + z cos) sends
    // forward (0,0,-1) to (0,1,0) (looking up) and up (0,1,0) to (0,0,1).
    auto pitched = start;
    pitched.rotate(pitched.right(), shade::pi<T> / 2);
    CHECK(near_vec(pitched.forward(), v3<T>(0, 1, 0), tol));
    CHECK(near_vec(pitched.up(), v3<T>(0, 0, 1), tol));
    // 1000 turns of 2 pi / 1000 about a skew axis come back to the start, orthonormal.
    auto spun = start;
    for (int i = 0; i < 1000; ++i) spun.rotate({1, 2, 3}, 2 * shade::pi<T> / 1000);
    const T loose = std::is_same_v<T, float> ? T(1e-4) : T(1e-12); // 1000 accumulated turns
    CHECK(near_vec(spun.forward(), start.forward(), loose));
    CHECK(near_vec(spun.up(), start.up(), loose));
    CHECK(std::abs(glm::dot(spun.forward(), spun.up())) <= tol);
    CHECK(std::abs(glm::length(spun.right()) - 1) <= tol);
}

TEST_CASE_TEMPLATE("camera: orbit circles the look-at point and keeps looking at it", T, float, double) {
    const T tol = 8 * eps<T>;
    shade::pinhole_camera<T> cam({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, shade::pi<T> / 2, 1);
    // +90 degrees about +y through the target sends the offset (0,0,5) to (5,0,0) and
    // forward (0,0,-1) to (-1,0,0).
    cam.orbit({0, 1, 0}, shade::pi<T> / 2);
    CHECK(near_vec(cam.position(), v3<T>(5, 0, 0), 8 * tol));
    CHECK(near_vec(cam.forward(), v3<T>(-1, 0, 0), tol));
    CHECK(near_vec(cam.look_at(), v3<T>(0, 0, 0), 8 * tol));
    const auto r = cam.ray_for_ndc(0, 0);
    CHECK(near_vec(r.at(T(5)), v3<T>(0, 0, 0), 8 * tol));
}

TEST_CASE_TEMPLATE("camera: invalid parameters throw naming the parameter", T, float, double) {
    using cam = shade::pinhole_camera<T>;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const T inf = std::numeric_limits<T>::infinity();
    const v3<T> p(0, 0, 5), at(0, 0, 0), up(0, 1, 0);
    const T fov = T(1), aspect = T(1.5);
    for (const T bad : {T(0), shade::pi<T>, T(-1), T(4), nan})
        CHECK_THROWS_WITH_AS((void)cam(p, at, up, bad, aspect), doctest::Contains("'fov_y'"),
                             shade::invalid_parameter);
    for (const T bad : {T(0), T(-2), nan, inf})
        CHECK_THROWS_WITH_AS((void)cam(p, at, up, fov, bad), doctest::Contains("'aspect'"),
                             shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)cam(p, p, up, fov, aspect), doctest::Contains("'look_at' must differ"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)cam({inf, 0, 0}, at, up, fov, aspect), doctest::Contains("'position'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)cam(p, {0, nan, 0}, up, fov, aspect), doctest::Contains("'look_at'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)cam(p, at, {0, 0, 0}, fov, aspect), doctest::Contains("'up'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)cam(p, at, {0, 0, 1}, fov, aspect), doctest::Contains("'up' must not be parallel"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)cam(p, at, {0, 0, -3}, fov, aspect), doctest::Contains("'up' must not be parallel"),
                         shade::invalid_parameter);
    const T big = std::numeric_limits<T>::max();
    CHECK_THROWS_WITH_AS((void)cam({-big, 0, 0}, {big, 0, 0}, up, fov, aspect),
                         doctest::Contains("'look_at'"), shade::invalid_parameter);

    auto c = cam(p, at, up, fov, aspect);
    CHECK_THROWS_WITH_AS((void)c.ray_for_pixel(0, 0, 0, 10), doctest::Contains("'width'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)c.ray_for_pixel(0, 0, 10, -1), doctest::Contains("'height'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(c.rotate({0, 0, 0}, T(1)), doctest::Contains("'axis'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(c.rotate({0, 1, 0}, nan), doctest::Contains("'angle'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(c.orbit({0, 1, 0}, inf), doctest::Contains("'angle'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(c.translate({nan, 0, 0}), doctest::Contains("'offset'"), shade::invalid_parameter);
    // A failed call leaves the camera unchanged.
    CHECK(c.position() == p);
    // Barely valid: fov just inside (0, pi), up 0.01 rad off the view axis.
    CHECK_NOTHROW((void)cam(p, at, up, std::nextafter(shade::pi<T>, T(0)), aspect));
    CHECK_NOTHROW((void)cam(p, at, {T(0.01), 0, 1}, fov, aspect));
}
