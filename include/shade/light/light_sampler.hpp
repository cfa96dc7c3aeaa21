#pragma once
// Choosing one light among many for next-event estimation: shade::uniform_light_sampler
// (every light alike) and shade::power_light_sampler (in proportion to each light's
// emitted power, through an alias table). Both return the index and the probability of the
// choice; the light's sample is then divided by that probability (its solid-angle pdf times
// it), and the same probability enters the multiple-importance weights (shade/core/mis.hpp)
// when a BSDF-sampled ray hits that light. Pharr, Jakob, Humphreys 2023, "Physically Based
// Rendering", 4th ed., sec. 12.6 (light samplers).

#include <cmath>
#include <concepts>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <shade/core/alias_table.hpp>
#include <shade/core/error.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// A light chosen by a light sampler: its index in the caller's list and the probability
/// with which it was chosen (> 0).
template <std::floating_point T>
struct light_choice {
    std::size_t index = 0;
    T probability = 0;
};

/// Every light with probability 1 / count.
template <std::floating_point T>
class uniform_light_sampler {
public:
    using scalar_type = T;

    /// A sampler over `count` lights (0 allowed: sample() then returns nothing).
    explicit uniform_light_sampler(std::size_t count) noexcept : count_(count) {}

    [[nodiscard]] std::size_t size() const noexcept { return count_; }

    /// The light of u in [0, 1): index floor(u count), probability 1 / count; nothing when
    /// there are no lights.
    [[nodiscard]] std::optional<light_choice<T>> sample(T u) const noexcept {
        if (count_ == 0) return std::nullopt;
        const T scaled = u * static_cast<T>(count_);
        const std::size_t i = scaled > T(0) ? detail::clamped_index(scaled, count_) : 0;
        return light_choice<T>{i, T(1) / static_cast<T>(count_)};
    }

    /// The probability of choosing light i: 1 / count (0 when i >= count).
    [[nodiscard]] T probability(std::size_t i) const noexcept {
        return i < count_ ? T(1) / static_cast<T>(count_) : T(0);
    }

private:
    std::size_t count_;
};

/// Lights in proportion to their emitted power Phi_i (watts, or any common scale), so a
/// bright light gets the samples its contribution deserves on average over the scene. A
/// light of power 0 is never chosen; when every power is 0 the choice is uniform (every
/// light contributes nothing, and the estimator stays defined).
template <std::floating_point T>
class power_light_sampler {
public:
    using scalar_type = T;

    /// A sampler over lights of the given powers (one per light). Throws invalid_parameter
    /// naming "powers" for a negative, NaN or infinite power.
    explicit power_light_sampler(std::span<const T> powers) : count_(powers.size()) {
        bool any_positive = false;
        for (std::size_t i = 0; i < powers.size(); ++i) {
            if (!std::isfinite(powers[i]) || !(powers[i] >= T(0)))
                throw invalid_parameter("powers", "must each be finite and >= 0",
                                        "powers[" + std::to_string(i) + "] = " + detail::to_text(powers[i]));
            any_positive = any_positive || powers[i] > T(0);
        }
        if (any_positive) table_.emplace(powers);
    }

    /// A sampler weighting each light by the luminance of its RGB power (Rec. 709 / sRGB
    /// weights 0.2126, 0.7152, 0.0722: the Y row of IEC 61966-2-1's RGB-to-XYZ matrix). The
    /// same errors as above, naming "powers".
    [[nodiscard]] static power_light_sampler from_rgb(std::span<const rgb<T>> powers) {
        std::vector<T> luminance(powers.size());
        for (std::size_t i = 0; i < powers.size(); ++i) {
            const rgb<T>& p = powers[i];
            if (!is_finite(p) || !(p.x >= T(0) && p.y >= T(0) && p.z >= T(0)))
                throw invalid_parameter("powers", "must each be finite and >= 0 in every channel",
                                        "powers[" + std::to_string(i) + "] = " + detail::to_text(p));
            luminance[i] = T(0.2126) * p.x + T(0.7152) * p.y + T(0.0722) * p.z;
        }
        return power_light_sampler(std::span<const T>(luminance));
    }

    /// A sampler weighting each light by its power, light.power(scene_radius) (RGB, by
    /// luminance as from_rgb; shade::any_light::power says what the radius is for), for
    /// any range of lights that have such a power(). The same errors as from_rgb.
    template <class Light>
        requires requires(const Light& l, T r) {
            { l.power(r) } -> std::same_as<rgb<T>>;
        }
    [[nodiscard]] static power_light_sampler from_lights(std::span<const Light> lights, T scene_radius) {
        std::vector<rgb<T>> powers;
        powers.reserve(lights.size());
        for (const Light& l : lights) powers.push_back(l.power(scene_radius));
        return from_rgb(std::span<const rgb<T>>(powers));
    }

    [[nodiscard]] std::size_t size() const noexcept { return count_; }

    /// The light of u in [0, 1), with its probability; nothing when there are no lights.
    [[nodiscard]] std::optional<light_choice<T>> sample(T u) const noexcept {
        if (count_ == 0) return std::nullopt;
        if (!table_) return uniform_light_sampler<T>(count_).sample(u);
        const auto c = table_->sample(u);
        return light_choice<T>{c.index, c.probability};
    }

    /// The probability of choosing light i (0 when i >= size()).
    [[nodiscard]] T probability(std::size_t i) const noexcept {
        if (i >= count_) return T(0);
        if (!table_) return T(1) / static_cast<T>(count_);
        return table_->probability(i);
    }

private:
    std::size_t count_;
    std::optional<alias_table<T>> table_; ///< absent when every power is 0
};

} // namespace shade
