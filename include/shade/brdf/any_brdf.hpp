#pragma once
// shade::any_brdf: one value that holds any BRDF of a given scalar type, for renderers
// whose materials are of several types (a std::vector<any_brdf<double>>).

#include <concepts>
#include <optional>
#include <type_traits>
#include <utility>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/detail/sampling.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// Any BRDF of scalar type T behind one type (type erasure, like shade::any_light for
/// lights): it owns a copy of the BRDF on the heap (copying an any_brdf copies the BRDF;
/// <memory> is left out to keep the header cheap). It is a shade::brdf, a
/// shade::sampled_brdf and a shade::split_brdf:
///   * f forwards to the held BRDF;
///   * sample and pdf forward to the held BRDF's when it is a shade::sampled_brdf; for a
///     BRDF with f only they fall back to cosine-weighted sampling about the shading
///     normal, density n·l / pi (Malley's method, shade::square_to_cosine_hemisphere),
///     with f evaluated at the drawn direction: unbiased for any BRDF (the density is
///     positive wherever f can be), exact for Lambert, noisy for sharp lobes;
///     has_own_sampler() says which;
///   * f_diffuse and f_specular forward to a shade::split_brdf; for any other BRDF
///     f_diffuse = f and f_specular = 0, which is how shade::lit lights an unsplit BRDF,
///     so wrapping never changes what lit computes.
template <std::floating_point T>
class any_brdf {
public:
    using scalar_type = T;

    /// Holds a copy of b. Implicit, so a BRDF converts where an any_brdf is expected.
    template <brdf B>
        requires(!std::same_as<std::remove_cvref_t<B>, any_brdf> && std::same_as<scalar_of<B>, T>)
    any_brdf(B b) // NOLINT: implicit by design
        : model_(new model<B>(std::move(b))) {}

    any_brdf(const any_brdf& other) : model_(other.model_->clone()) {}
    any_brdf(any_brdf&& other) noexcept : model_(std::exchange(other.model_, nullptr)) {}
    any_brdf& operator=(const any_brdf& other) {
        if (this != &other) {
            interface* copy = other.model_->clone();
            delete model_;
            model_ = copy;
        }
        return *this;
    }
    any_brdf& operator=(any_brdf&& other) noexcept {
        std::swap(model_, other.model_);
        return *this;
    }
    ~any_brdf() { delete model_; }

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

    /// The diffuse part (f itself for a BRDF that does not split).
    [[nodiscard]] rgb<T> f_diffuse(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const {
        return model_->f_diffuse(l, v, at);
    }

    /// The specular part (0 for a BRDF that does not split).
    [[nodiscard]] rgb<T> f_specular(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const {
        return model_->f_specular(l, v, at);
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
        virtual rgb<T> f_diffuse(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const = 0;
        virtual rgb<T> f_specular(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const = 0;
        virtual bool has_own_sampler() const noexcept = 0;
        virtual interface* clone() const = 0;
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
        rgb<T> f_diffuse(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const override {
            if constexpr (split_brdf<B>) {
                return held.f_diffuse(l, v, at);
            } else {
                return held.f(l, v, at);
            }
        }
        rgb<T> f_specular(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const override {
            if constexpr (split_brdf<B>) {
                return held.f_specular(l, v, at);
            } else {
                (void)l;
                (void)v;
                (void)at;
                return rgb<T>(0);
            }
        }
        bool has_own_sampler() const noexcept override { return sampled_brdf<B>; }
        interface* clone() const override { return new model(held); }

        B held;
    };

    interface* model_; // owned; null only in a moved-from any_brdf (which may only be
                       // assigned to or destroyed)
};

} // namespace shade
