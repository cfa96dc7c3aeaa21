#pragma once
// shade::pinhole_camera: primary rays through pixels of an image, and the view frustum.
//
// Image convention: raster coordinates (x, y) run from the image's top-left corner, x to
// the right and y DOWN, in pixels; pixel (i, j) covers [i, i+1) x [j, j+1) and its centre
// is (i + 0.5, j + 0.5). Normalised device coordinates (NDC) run from -1 to 1 across the
// image, x to the right and y UP, so (0, 0) is the image centre and (1, 1) its top-right
// corner. The camera looks along `forward`, `right` = forward × up (right-handed), and
// the vertical field of view is the full angle between the top and bottom image edges.

#include <cmath>
#include <concepts>
#include <string>

#include <glm/geometric.hpp>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/hit.hpp>
#include <shade/geometry/ray.hpp>

namespace shade {

/// A pinhole camera: every primary ray starts at `position`.
template <std::floating_point T>
class pinhole_camera {
public:
    using scalar_type = T;

    /// A camera at `position` looking at `look_at`, with `up` giving the roll (it only has
    /// to be non-parallel to the view direction; the camera's own up is made orthogonal),
    /// vertical field of view `fov_y` in radians and `aspect` = image width / height.
    /// Throws shade::invalid_parameter naming the parameter when position, look_at or up is
    /// not finite, up is zero, look_at == position (or so far that the distance is not
    /// finite), up is parallel to the view direction, fov_y is not in (0, pi) or aspect is
    /// not finite and > 0.
    pinhole_camera(const vec3<T>& position, const vec3<T>& look_at, const vec3<T>& up, T fov_y,
                   T aspect)
        : position_(require_finite("position", position)), aspect_(require_positive("aspect", aspect)) {
        require_finite("look_at", look_at);
        const vec3<T> up_hat = require_direction("up", up);
        if (!(fov_y > T(0) && fov_y < pi<T>))
            throw invalid_parameter("fov_y", "must lie in (0, pi) radians", detail::to_text(fov_y));
        fov_y_ = fov_y;
        tan_half_fov_ = std::tan(fov_y / T(2));

        const vec3<T> to_target = look_at - position;
        if (to_target == vec3<T>(0, 0, 0))
            throw invalid_parameter("look_at", "must differ from position", detail::to_text(look_at));
        if (!is_finite(to_target))
            throw invalid_parameter("look_at", "must be a finite distance from position",
                                    detail::to_text(look_at));
        forward_ = detail::normalize_or_zero(to_target);
        // |forward x up_hat| = sin(angle between them). Below 1e-3 (up within ~0.06 degrees
        // of the view axis) the rounding errors of the two inputs dominate the cross
        // product's direction, so the camera's roll would be noise: reject.
        const vec3<T> side = glm::cross(forward_, up_hat);
        if (!(glm::length(side) > T(1e-3)))
            throw invalid_parameter("up", "must not be parallel to the view direction",
                                    detail::to_text(up));
        right_ = glm::normalize(side);
        up_ = glm::cross(right_, forward_);
        distance_ = glm::dot(to_target, forward_);
    }

    /// The pinhole (origin of every primary ray).
    [[nodiscard]] const vec3<T>& position() const noexcept { return position_; }
    /// Unit view direction (toward the look-at point).
    [[nodiscard]] const vec3<T>& forward() const noexcept { return forward_; }
    /// Unit vector toward the image's right edge: forward × up.
    [[nodiscard]] const vec3<T>& right() const noexcept { return right_; }
    /// Unit vector toward the image's top edge, orthogonal to forward.
    [[nodiscard]] const vec3<T>& up() const noexcept { return up_; }
    /// The look-at point: position + distance * forward (moves with the camera).
    [[nodiscard]] vec3<T> look_at() const noexcept { return position_ + distance_ * forward_; }
    /// Vertical field of view in radians, in (0, pi).
    [[nodiscard]] T fov_y() const noexcept { return fov_y_; }
    /// Image width / height.
    [[nodiscard]] T aspect() const noexcept { return aspect_; }

    /// The primary ray through the NDC point (x_ndc, y_ndc) (see the header comment): from
    /// position, with unit direction
    ///     normalize(forward + x_ndc tan(fov_y/2) aspect right + y_ndc tan(fov_y/2) up),
    /// t_min = 0 and t_max = +infinity; t is therefore a distance. |x_ndc|, |y_ndc| <= 1
    /// covers the image; larger values give rays outside the frustum, which is allowed.
    /// A NaN coordinate gives a ray with zero direction, which is not valid() and hits
    /// nothing.
    [[nodiscard]] ray<T> ray_for_ndc(T x_ndc, T y_ndc) const noexcept {
        const vec3<T> d = forward_ + (x_ndc * tan_half_fov_ * aspect_) * right_ +
                          (y_ndc * tan_half_fov_) * up_;
        return ray<T>{position_, detail::normalize_or_zero(d), T(0), infinity<T>};
    }

    /// The primary ray through raster point (x, y) of a width x height image (x right, y
    /// down, (0, 0) the top-left corner, see the header comment): the NDC point
    /// (2x/width - 1, 1 - 2y/height). Throws shade::invalid_parameter naming "width" or
    /// "height" unless both are > 0.
    [[nodiscard]] ray<T> ray_for_raster(T x, T y, int width, int height) const {
        require_image_size(width, height);
        return ray_for_ndc(T(2) * x / T(width) - T(1), T(1) - T(2) * y / T(height));
    }

    /// The primary ray through the CENTRE of pixel (x, y), i.e. raster point
    /// (x + 0.5, y + 0.5); pixel (0, 0) is the top-left one. Throws like ray_for_raster.
    [[nodiscard]] ray<T> ray_for_pixel(int x, int y, int width, int height) const {
        return ray_for_raster(T(x) + T(0.5), T(y) + T(0.5), width, height);
    }

    /// True when point p lies inside the (infinite) view frustum: in front of the camera
    /// and within the image rectangle's angles, boundary included.
    [[nodiscard]] bool in_frustum(const vec3<T>& p) const noexcept {
        const vec3<T> w = p - position_;
        const T z = glm::dot(w, forward_);
        if (!(z > T(0))) return false;
        const T x = glm::dot(w, right_);
        const T y = glm::dot(w, up_);
        return std::abs(x) <= z * tan_half_fov_ * aspect_ && std::abs(y) <= z * tan_half_fov_;
    }

    /// Moves the camera (and its look-at point) by offset; orientation is unchanged.
    /// Throws shade::invalid_parameter naming "offset" if it, or the new position, is not
    /// finite.
    pinhole_camera& translate(const vec3<T>& offset) {
        const vec3<T> moved = require_finite("offset", offset) + position_;
        require_finite("offset", moved);
        position_ = moved;
        return *this;
    }

    /// Turns the camera by `angle` radians about `axis` through its position (right-hand
    /// rule: positive angles turn counter-clockwise seen from the axis tip); the look-at
    /// point turns with it. E.g. axis = up turns left for positive angles (yaw), axis =
    /// right pitches up. Throws shade::invalid_parameter naming "axis" (zero or not
    /// finite) or "angle" (not finite).
    pinhole_camera& rotate(const vec3<T>& axis, T angle) {
        const vec3<T> k = require_direction("axis", axis);
        require_finite("angle", angle);
        set_basis(rotated(forward_, k, angle), rotated(up_, k, angle));
        return *this;
    }

    /// Moves the camera by `angle` radians about `axis` through its look-at point (right-hand
    /// rule), keeping its orientation relative to that point, so it keeps looking at it.
    /// Throws like rotate.
    pinhole_camera& orbit(const vec3<T>& axis, T angle) {
        const vec3<T> k = require_direction("axis", axis);
        require_finite("angle", angle);
        const vec3<T> target = look_at();
        const vec3<T> moved = target + rotated(position_ - target, k, angle);
        set_basis(rotated(forward_, k, angle), rotated(up_, k, angle));
        position_ = moved;
        return *this;
    }

private:
    static void require_image_size(int width, int height) {
        if (width <= 0) throw invalid_parameter("width", "must be > 0", std::to_string(width));
        if (height <= 0) throw invalid_parameter("height", "must be > 0", std::to_string(height));
    }

    /// v rotated by angle about the unit axis k (Rodrigues 1840):
    ///     v cos(angle) + (k × v) sin(angle) + k (k·v) (1 - cos(angle)).
    static vec3<T> rotated(const vec3<T>& v, const vec3<T>& k, T angle) noexcept {
        const T c = std::cos(angle);
        const T s = std::sin(angle);
        return v * c + glm::cross(k, v) * s + k * (glm::dot(k, v) * (T(1) - c));
    }

    /// Re-orthonormalises after a rotation so rounding cannot accumulate over many turns.
    void set_basis(const vec3<T>& forward, const vec3<T>& up) noexcept {
        forward_ = glm::normalize(forward);
        right_ = glm::normalize(glm::cross(forward_, up));
        up_ = glm::cross(right_, forward_);
    }

    vec3<T> position_;
    vec3<T> forward_{0, 0, -1};
    vec3<T> right_{1, 0, 0};
    vec3<T> up_{0, 1, 0};
    T distance_ = T(1);
    T fov_y_ = T(1);
    T tan_half_fov_ = T(0.5);
    T aspect_;
};

} // namespace shade
