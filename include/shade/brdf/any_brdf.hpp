#pragma once
// shade::any_brdf: one value that holds any BRDF of a given scalar type, for renderers
// whose materials are of several types (a std::vector<any_brdf<double>>).

#include <concepts>
#include <memory>
#include <optional>
#include <type_traits>
#include <utility>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/detail/sampling.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// Any BRDF of scalar type T behind one type (type erasure, like shade::any_light for
/// lights), in the physical interface a path tracer uses: f, sample and pdf. It owns a copy
/// of the BRDF through std::unique_ptr (copying an any_brdf copies the BRDF; moving moves
/// the pointer). It is a shade::brdf and a shade::sampled_brdf:
///   * f forwards to the held BRDF;
///   * sample and pdf forward to the held BRDF's when it is a shade::sampled_brdf; for a
///     BRDF with f only they fall back to cosine-weighted sampling about the shading
///     normal, density n·l / pi (Malley's method, shade::square_to_cosine_hemisphere),
///     with f evaluated at the drawn direction: unbiased for any BRDF (the density is
///     positive wherever f can be), exact for Lambert, noisy for sharp lobes;
///     has_own_sampler() says which.
/// The classic model's split into diffuse and specular parts (shade::split_brdf) is not part
/// of it: shade::lit lights an any_brdf as an unsplit BRDF, all of f with the light's
/// diffuse colour. Classic shading with separate specular colours uses the model's own type
/// (shade::lit<Model>), where the split is known at compile time.
template <std::floating_point T>
class any_brdf {
public:
    using scalar_type = T;

    /// Holds a copy of b. Implicit, so a BRDF converts where an any_brdf is expected.
    template <brdf B>
        requires(!std::same_as<std::remove_cvref_t<B>, any_brdf> && std::same_as<scalar_of<B>, T>)
    any_brdf(B b) // NOLINT: implicit by design
        : model_(std::make_unique<model<B>>(std::move(b))) {}

    any_brdf(const any_brdf& other) : model_(other.model_->clone()) {}
    any_brdf(any_brdf&& other) noexcept = default;
    any_brdf& operator=(const any_brdf& other) {
        if (this != &other) model_ = other.model_->clone();
        return *this;
    }
    any_brdf& operator=(any_brdf&& other) noexcept = default;
    ~any_brdf() = default;

    /// The held BRDF's value (1/sr, no cosine).
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const {
        return model_->f(l, v, at);
    }

    /// The held BRDF's sample, or the cosine-weighted fallback (see the class comment).
    [[nodiscard]] std::optional<brdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                       const surface_point<T>& at) const {
        return model_->sample(v, uc, u, at);
    }

    /// The density sample() draws l with (1/sr).
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const {
        return model_->pdf(l, v, at);
    }

    /// True when the held BRDF samples itself (a shade::sampled_brdf), false when the
    /// cosine-weighted fallback is used.
    [[nodiscard]] bool has_own_sampler() const noexcept { return model_->has_own_sampler(); }

private:
    struct interface {
        virtual ~interface() = default;
        virtual rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const = 0;
        virtual std::optional<brdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                     const surface_point<T>& at) const = 0;
        virtual T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const = 0;
        virtual bool has_own_sampler() const noexcept = 0;
        virtual std::unique_ptr<interface> clone() const = 0;
    };

    template <class B>
    struct model final : interface {
        explicit model(B b) : held(std::move(b)) {}

        rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const override {
            return held.f(l, v, at);
        }
        std::optional<brdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                             const surface_point<T>& at) const override {
            if constexpr (sampled_brdf<B>) {
                return held.sample(v, uc, u, at);
            } else {
                (void)uc;
                return detail::sample_cosine_brdf(v, u, at, [&](const vec3<T>& l) { return held.f(l, v, at); });
            }
        }
        T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const override {
            if constexpr (sampled_brdf<B>) {
                return held.pdf(l, v, at);
            } else {
                return detail::cosine_brdf_pdf(l, v, at);
            }
        }
        bool has_own_sampler() const noexcept override { return sampled_brdf<B>; }
        std::unique_ptr<interface> clone() const override { return std::make_unique<model>(held); }

        B held;
    };

    std::unique_ptr<interface> model_; // null only in a moved-from any_brdf (which may only be
                                       // assigned to or destroyed)
};

} // namespace shade
