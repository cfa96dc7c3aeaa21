#pragma once
// shade::environment_map_light: radiance from every direction, infinitely far away, read
// from a latitude-longitude (equirectangular) image, and importance-sampled by the image's
// luminance.

#include <cmath>
#include <concepts>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/core/distribution.hpp>
#include <shade/core/error.hpp>
#include <shade/core/frame.hpp>
#include <shade/core/math.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/types.hpp>
#include <shade/light/classic_light.hpp>
#include <shade/light/incident_sample.hpp>
#include <shade/light/light_sample.hpp>
#include <shade/light/sample_context.hpp>

namespace shade {

namespace detail {

/// The luminance Y of a linear RGB colour with the Rec. 709 / sRGB primaries and D65
/// white: Y = 0.2126 R + 0.7152 G + 0.0722 B (ITU-R BT.709-6 2015, "Parameter values for
/// the HDTV standards", item 3.2; the middle row of shade's linear_srgb_to_xyz_d65 matrix
/// rounded to 4 decimals). Every coefficient is positive, so Y > 0 whenever a channel is.
template <std::floating_point T>
[[nodiscard]] constexpr double luminance_709(const rgb<T>& c) noexcept {
    return 0.2126 * double(c.r) + 0.7152 * double(c.g) + 0.0722 * double(c.b);
}

} // namespace detail

/// An environment map: radiance arriving from infinitely far away, from every direction,
/// given by a latitude-longitude (equirectangular) image of linear RGB radiance, looked up
/// without interpolation (each texel is a patch of constant radiance on the sphere).
///
/// The mapping, in the map's frame (`orientation()`: t, b, n; by default x, y, z), with a
/// direction w = (sin theta cos phi, sin theta sin phi, cos theta) in that frame:
///   * "up" is n (+z by default): row 0 is the top of the image, at theta = 0 (w = n), and
///     the last row the bottom, at theta = pi; image coordinate v = theta / pi, so row j
///     covers theta in [pi j / H, pi (j+1) / H);
///   * the image's horizontal coordinate u = 1/2 - phi / (2 pi) with phi = atan2(w.b, w.t)
///     in [-pi, pi], so column i covers u in [i / W, (i+1) / W). The image's centre
///     column looks along t (+x), u = 1/4 along b (+y) and the left and right edges along
///     -t. Standing at the centre with n up and looking along t, one sees the image
///     unmirrored, its left half to the left, as a panorama photograph is meant to be seen.
/// Rotate the map by passing another right-handed orthonormal frame (e.g.
/// frame<T>::from_normal_tangent({0, 1, 0}, {0, 0, -1}) for a y-up scene, the image's centre
/// along -z).
///
/// Radiance: texel (i, j) times scale(), in W/(m^2 sr) (incident_radiance).
///
/// Sampling (sample_incident). A texel is drawn with probability proportional to its
/// luminance (detail::luminance_709) times its solid angle
/// Omega_j = (2 pi / W)(cos theta_j - cos theta_{j+1}) = (2 pi / W) (pi / H) times the mean of
/// sin theta over the row, by a piecewise-constant 2D distribution over the image (rows
/// from the marginal, the column from the conditional; shade::piecewise_constant_2d) --
/// the scheme of Pharr, Jakob, Humphreys 2023, "Physically Based Rendering", 4th ed.,
/// §12.5.2 (image infinite lights), with the sin theta weighting of the latitude-longitude
/// parameterisation from the 3rd edition (2016), §14.2.4. The direction is then placed
/// uniformly in solid angle within the texel: phi uniform across the column and cos theta
/// uniform across the row (Archimedes' hat-box theorem: equal steps of cos theta bound
/// equal areas of the sphere). Its density is therefore constant over each texel,
///   pdf(w) = P_ij / Omega_ij   (1/sr),
/// where P_ij is the texel's probability; it is finite everywhere, poles included, and 0
/// on texels of zero radiance. (Probabilities are differences of a CDF stored in T: in
/// float, a texel whose share of the map's luminance x solid angle is below about 1e-7
/// can round to probability 0; it is then never drawn and its pdf is 0, which MIS with
/// BRDF sampling accounts for.) (Placing the direction uniformly in theta instead,
/// as pbrt-v3 does, gives p(u, v) / (2 pi^2 sin theta), which diverges at the poles.) For
/// a constant map P_ij is proportional to Omega_ij, so the density is 1 / (4 pi)
/// everywhere and the map is shade::environment_light. L / pdf is constant within a texel.
///
/// What the sampler reports is what sample_incident does: the returned radiance and pdf
/// are incident_radiance(p, l) and pdf_incident(p, l) at the returned direction l.
template <std::floating_point T>
class environment_map_light {
public:
    using scalar_type = T;

    /// A map of width x height texels of linear RGB (row after row, row 0 at the top, see
    /// the class comment), each multiplied by `scale` to give radiance in W/(m^2 sr), in the
    /// frame `orientation` (its n is up, its t the direction of the image's centre).
    /// Throws shade::invalid_parameter naming "width" or "height" (< 1, too large for the
    /// sampler, or so many rows that the thinnest one's solid angle rounds to 0 in T),
    /// "texels" (not width x height many, or a channel negative or not finite: the message
    /// gives the texel's column and row), "scale" (negative, not finite, or overflowing a
    /// texel's radiance) or "orientation" (not orthonormal and right-handed).
    environment_map_light(int width, int height, std::span<const rgb<T>> texels, T scale = T(1),
                          const frame<T>& orientation = frame<T>{})
        : width_(require_size("width", width)), height_(require_size("height", height)),
          scale_(require_non_negative("scale", scale)), orientation_(require_orientation(orientation)),
          radiance_(scaled(texels, width_, height_, scale)), edges_(row_edges(height_)),
          distribution_(weights(), width_, height_, "texels") {
        for (const rgb<T>& c : radiance_) black_ = black_ && c == rgb<T>(0);
        // Omega_j from the edges in T that the sampler uses, the difference formed in double.
        for (std::size_t j = 0; j < height_; ++j)
            texel_solid_angle_.push_back(
                T(2.0 * pi<double> / double(width_) * (double(edges_[j]) - double(edges_[j + 1]))));
        // The integral of the radiance over the sphere, sum of L_ij Omega_j, in double.
        double sum[3] = {0, 0, 0};
        for (std::size_t j = 0; j < height_; ++j)
            for (std::size_t i = 0; i < width_; ++i)
                for (int c = 0; c < 3; ++c)
                    sum[c] += double(radiance_[j * width_ + i][c]) * double(texel_solid_angle_[j]);
        radiance_integral_ = rgb<T>(T(sum[0]), T(sum[1]), T(sum[2]));
    }

    /// The number of columns W.
    [[nodiscard]] std::size_t width() const noexcept { return width_; }
    /// The number of rows H.
    [[nodiscard]] std::size_t height() const noexcept { return height_; }
    /// The factor texel values were multiplied by.
    [[nodiscard]] T scale() const noexcept { return scale_; }
    /// The map's frame: n is up (theta = 0), t the direction of the image's centre column.
    [[nodiscard]] const frame<T>& orientation() const noexcept { return orientation_; }
    /// The radiance of texel (column, row) in W/(m^2 sr): the texel's value times scale().
    /// Precondition: column < width(), row < height().
    [[nodiscard]] const rgb<T>& texel(std::size_t column, std::size_t row) const noexcept {
        SHADE_ASSERT(column < width_ && row < height_);
        return radiance_[row * width_ + column];
    }
    /// The solid angle Omega_j of each texel of row j, in sr (every texel of a row has the
    /// same): (2 pi / W)(cos theta_j - cos theta_{j+1}), from the row edges in T that the
    /// sampler uses. Precondition: row < height().
    [[nodiscard]] T texel_solid_angle(std::size_t row) const noexcept {
        SHADE_ASSERT(row < height_);
        return texel_solid_angle_[row];
    }

    /// The image coordinates (u, v) in [0, 1]^2 of the unit world direction l (see the
    /// class comment): u = 1/2 - phi / (2 pi), v = theta / pi.
    [[nodiscard]] vec2<T> image_coordinates(const vec3<T>& l) const noexcept {
        const vec3<T> w = orientation_.to_local(l);
        const T phi = std::atan2(w.y, w.x);
        const T theta = std::acos(glm::clamp(w.z, T(-1), T(1)));
        return {T(0.5) - phi / (T(2) * pi<T>), theta / pi<T>};
    }

    /// The radiant power in W the map sends into a scene that fits in a sphere of radius
    /// scene_radius: pi r^2 times the integral of the radiance over all directions
    /// (sum of texel x Omega_j), the flux each direction sends through the sphere's
    /// cross-section pi r^2; 4 pi r^2 x pi L for a constant map of radiance L, as
    /// shade::environment_light::power. Throws shade::invalid_parameter naming
    /// "scene_radius" unless it is finite and >= 0.
    [[nodiscard]] rgb<T> power(T scene_radius) const {
        const T r = detail::require_scene_radius(scene_radius);
        return (pi<T> * r * r) * radiance_integral_;
    }

    /// Always false: the environment is sampled many times.
    [[nodiscard]] static constexpr bool is_delta() noexcept { return false; }

    /// The radiance in W/(m^2 sr) a ray from p along the unit direction l sees: the texel
    /// l falls in, times scale() (p is ignored: the map is infinitely far away).
    [[nodiscard]] rgb<T> incident_radiance(const vec3<T>& p, const vec3<T>& l) const noexcept {
        (void)p;
        const texel_index t = texel_of(l);
        return radiance_[t.row * width_ + t.column];
    }

    /// The density in 1/sr with which sample_incident draws the unit direction l:
    /// P_ij / Omega_ij for the texel l falls in (see the class comment); 0 on texels of
    /// zero radiance (p is ignored).
    [[nodiscard]] T pdf_incident(const vec3<T>& p, const vec3<T>& l) const noexcept {
        (void)p;
        if (black_) return T(0); // the sampler's uniform fallback is never used
        const texel_index t = texel_of(l);
        const T probability = distribution_.probability(t.column, t.row);
        if (!(probability > T(0))) return T(0);
        const T pdf = probability / texel_solid_angle_[t.row];
        return std::isfinite(pdf) ? pdf : T(0);
    }

    /// The physical sample at p: a direction l drawn as the class comment says, at
    /// infinity, with radiance incident_radiance(p, l) and pdf pdf_incident(p, l).
    /// Nothing when the map is black (or, for a direction that rounding put on the edge
    /// of a black texel, when that texel's radiance or density is 0). u.y chooses the row,
    /// u.x the column. Precondition: u in [0,1)^2 (SHADE_ASSERT; outside it u is clamped).
    [[nodiscard]] std::optional<incident_sample<T>> sample_incident(const vec3<T>& p,
                                                                    const vec2<T>& u) const noexcept {
        if (black_) return std::nullopt;
        const distribution_sample_2d<T> d = distribution_.sample_continuous(u);
        // cos theta uniform across row j: from edge j (top) toward edge j + 1 (bottom).
        const T z = edges_[d.row] + (edges_[d.row + 1] - edges_[d.row]) * d.offset.y;
        const T sin_theta = safe_sqrt((T(1) - z) * (T(1) + z));
        // phi = pi - 2 pi u: cos phi = -cos(2 pi u), sin phi = sin(2 pi u).
        const detail::sin_cos<T> a = detail::sin_cos_two_pi(d.uv.x);
        incident_sample<T> s;
        s.l = orientation_.to_world(vec3<T>(-sin_theta * a.cos, sin_theta * a.sin, z));
        s.pdf = pdf_incident(p, s.l);
        s.radiance = incident_radiance(p, s.l);
        if (!(s.pdf > T(0)) || s.radiance == rgb<T>(0)) return std::nullopt;
        return s;
    }

    /// sample_incident(ctx.p, u): the map is sampled by its luminance whatever surface
    /// ctx.p lies on (shade::emitter).
    [[nodiscard]] std::optional<incident_sample<T>> sample_incident(const light_sample_context<T>& ctx,
                                                                    const vec2<T>& u) const noexcept {
        return sample_incident(ctx.p, u);
    }

    /// pdf_incident(ctx.p, l), the density of sample_incident(ctx, .).
    [[nodiscard]] T pdf_incident(const light_sample_context<T>& ctx, const vec3<T>& l) const noexcept {
        return pdf_incident(ctx.p, l);
    }

    /// The classic light sample along the direction sample_incident draws: diffuse and
    /// specular colours L / (pi pdf), one Monte Carlo sample of the map in the units of
    /// the classic model (a light's colour is the radiance a white Lambertian surface
    /// facing it reflects, E / pi), no ambient: shade::classic_sample with the default
    /// colours. An empty sample (no colour) where sample_incident returns nothing.
    [[nodiscard]] light_sample<T> sample(const vec3<T>& p, const vec2<T>& u) const noexcept {
        return classic_sample(*this, classic_colours<T>{}, p, u);
    }

private:
    struct texel_index {
        std::size_t column;
        std::size_t row;
    };

    /// The texel of the unit world direction l: row j with cos theta in (edge_{j+1}, edge_j]
    /// (and -1 in the last), column floor(u W) with u = 1/2 - atan2(w.b, w.t) / (2 pi).
    [[nodiscard]] texel_index texel_of(const vec3<T>& l) const noexcept {
        const vec3<T> w = orientation_.to_local(l);
        const T z = glm::clamp(w.z, T(-1), T(1));
        // k = the number of edges >= z (they decrease from 1 to -1): row k - 1, clamped.
        const std::size_t k = detail::count_leading(std::span<const T>(edges_), [z](T e) { return e >= z; });
        const std::size_t above = k == 0 ? 0 : k - 1;
        const std::size_t row = above < height_ ? above : height_ - 1;
        const T u = T(0.5) - std::atan2(w.y, w.x) / (T(2) * pi<T>);
        return {detail::bin_of(u, width_), row};
    }

    /// The sampler's weights: luminance times the row's cos theta step (the solid angle up to
    /// 2 pi / W), in double, divided by the largest so that T cannot underflow bright ones.
    [[nodiscard]] std::vector<T> weights() const {
        std::vector<double> w(radiance_.size());
        double largest = 0;
        for (std::size_t j = 0; j < height_; ++j)
            for (std::size_t i = 0; i < width_; ++i) {
                const std::size_t k = j * width_ + i;
                w[k] = detail::luminance_709(radiance_[k]) * (double(edges_[j]) - double(edges_[j + 1]));
                largest = w[k] > largest ? w[k] : largest;
            }
        std::vector<T> out(w.size(), T(0));
        if (largest > 0)
            for (std::size_t k = 0; k < w.size(); ++k) out[k] = T(w[k] / largest);
        return out;
    }

    static std::size_t require_size(const char* name, int n) {
        if (n < 1) throw invalid_parameter(name, "must be >= 1", std::to_string(n));
        return std::size_t(n);
    }

    static frame<T> require_orientation(const frame<T>& f) {
        const T tolerance = T(1e-3); // as shade::is_unit_length: frames built in float pass
        const bool unit = is_unit_length(f.t) && is_unit_length(f.b) && is_unit_length(f.n);
        const bool orthogonal = std::abs(glm::dot(f.t, f.b)) < tolerance && std::abs(glm::dot(f.t, f.n)) < tolerance &&
                                std::abs(glm::dot(f.b, f.n)) < tolerance;
        const bool right_handed = glm::dot(glm::cross(f.t, f.b), f.n) > T(0);
        if (!(unit && orthogonal && right_handed))
            throw invalid_parameter("orientation", "must be an orthonormal right-handed frame (t, b, n)",
                                    "t = " + detail::to_text(f.t) + ", b = " + detail::to_text(f.b) +
                                        ", n = " + detail::to_text(f.n));
        return f;
    }

    static std::vector<rgb<T>> scaled(std::span<const rgb<T>> texels, std::size_t width, std::size_t height,
                                      T scale) {
        if (texels.size() != width * height)
            throw invalid_parameter("texels", "must hold width x height = " + std::to_string(width * height) + " texels",
                                    std::to_string(texels.size()));
        std::vector<rgb<T>> out(texels.size());
        for (std::size_t k = 0; k < texels.size(); ++k) {
            const rgb<T>& c = texels[k];
            out[k] = scale * c;
            const bool bad_texel = !is_finite(c) || !(c.r >= T(0) && c.g >= T(0) && c.b >= T(0));
            if (!bad_texel && is_finite(out[k])) continue;
            std::string got = bad_texel ? detail::to_text(c) : detail::to_text(scale) + " times " + detail::to_text(c);
            got += " at column " + std::to_string(k % width) + ", row " + std::to_string(k / width);
            throw invalid_parameter(bad_texel ? "texels" : "scale",
                                    bad_texel ? "must be finite and >= 0 in every channel"
                                              : "times every texel must be finite",
                                    got);
        }
        return out;
    }

    /// cos theta at the H + 1 row edges theta_k = pi k / H, from 1 down to -1, as
    /// sin(pi (H - 2k) / (2H)): odd in H - 2k, so the edges are exactly symmetric about the
    /// equator and the middle one (H even) is exactly 0. Throws invalid_parameter naming
    /// "height" if two edges round to the same T (a row of zero solid angle).
    static std::vector<T> row_edges(std::size_t height) {
        std::vector<T> e(height + 1);
        for (std::size_t k = 0; k <= height; ++k)
            e[k] = T(std::sin(pi<double> * (double(height) - 2.0 * double(k)) / (2.0 * double(height))));
        for (std::size_t k = 0; k < height; ++k)
            if (!(e[k] > e[k + 1]))
                throw invalid_parameter("height", "must leave every row a non-zero solid angle in this scalar type",
                                        std::to_string(height));
        return e;
    }

    std::size_t width_;
    std::size_t height_;
    T scale_;
    frame<T> orientation_;
    std::vector<rgb<T>> radiance_;        ///< texels times scale, row after row
    std::vector<T> edges_;                ///< cos theta at the row edges, height + 1, decreasing
    piecewise_constant_2d<T> distribution_;
    std::vector<T> texel_solid_angle_;    ///< Omega_j per row, sr
    rgb<T> radiance_integral_{0, 0, 0};   ///< sum of L_ij Omega_j, W/m^2
    bool black_ = true;
};

} // namespace shade
