#pragma once
// shade::check::detail::model_ref: the property kit's view of the model it checks. Every
// public check is a thin template over the model's type that wraps the model in a model_ref
// and calls the check's body, which is a template over the scalar type only. The bodies
// (quadrature, binning, stratified estimators, message text) are therefore compiled once
// per scalar type and translation unit however many models a program checks, instead of
// once per model; only the model's own f, sample and pdf are compiled per model, once each,
// behind a function pointer.

#include <concepts>
#include <optional>

#include <shade/brdf/brdf.hpp>
#include <shade/bsdf/bsdf.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade::check::detail {

/// A non-owning reference to a BRDF or BSDF of scalar type T: f, and sample and pdf when
/// the referenced type is a shade::sampled_bsdf (a shade::sampled_brdf, or a BSDF with its
/// own sampler, shade::bsdf_sampler, for which two_sided() is true). Samples are
/// bsdf_samples as shade::sample_bsdf returns them (a BRDF's with flags glossy_reflection
/// and eta 1). sampled() says whether it samples. It refers to the model, so the model
/// must outlive it; the kit makes one per call and drops it on return. Calling sample or
/// pdf when sampled() is false is a precondition violation (the public checks that sample
/// require shade::sampled_bsdf at compile time).
template <std::floating_point T>
class model_ref {
public:
    using scalar_type = T;

    template <brdf B>
        requires(!std::same_as<B, model_ref> && std::same_as<scalar_of<B>, T>)
    explicit model_ref(const B& model) noexcept : model_(&model), f_(&call_f<B>) {
        if constexpr (sampled_bsdf<B>) {
            sample_ = &call_sample<B>;
            pdf_ = &call_pdf<B>;
            two_sided_ = !sampled_brdf<B>;
        }
    }

    /// The model's f(l, v, at) (1/sr, no cosine).
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const {
        return f_(model_, l, v, at);
    }

    /// shade::sample_bsdf(model, v, uc, u, at, mode): the model's own sample in that mode,
    /// or for a BRDF its sample(v, uc, u, at) as a bsdf_sample. Requires sampled().
    [[nodiscard]] std::optional<bsdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                       const surface_point<T>& at,
                                                       transport_mode mode = transport_mode::radiance) const {
        return sample_(model_, v, uc, u, at, mode);
    }

    /// The model's pdf(l, v, at) (1/sr). Requires sampled().
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const {
        return pdf_(model_, l, v, at);
    }

    /// True when the referenced model is a shade::sampled_bsdf.
    [[nodiscard]] bool sampled() const noexcept { return sample_ != nullptr; }

    /// True when the referenced model has a BSDF's own sampler (shade::bsdf_sampler) and is
    /// not a shade::sampled_brdf: v may be on either side, and sample draws over the whole
    /// sphere.
    [[nodiscard]] bool two_sided() const noexcept { return two_sided_; }

private:
    template <class B>
    static rgb<T> call_f(const void* model, const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) {
        return static_cast<const B*>(model)->f(l, v, at);
    }
    template <class B>
    static std::optional<bsdf_sample<T>> call_sample(const void* model, const vec3<T>& v, T uc, const vec2<T>& u,
                                                     const surface_point<T>& at, transport_mode mode) {
        return sample_bsdf(*static_cast<const B*>(model), v, uc, u, at, mode);
    }
    template <class B>
    static T call_pdf(const void* model, const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) {
        return static_cast<const B*>(model)->pdf(l, v, at);
    }

    const void* model_;
    rgb<T> (*f_)(const void*, const vec3<T>&, const vec3<T>&, const surface_point<T>&);
    std::optional<bsdf_sample<T>> (*sample_)(const void*, const vec3<T>&, T, const vec2<T>&,
                                             const surface_point<T>&, transport_mode) = nullptr;
    T (*pdf_)(const void*, const vec3<T>&, const vec3<T>&, const surface_point<T>&) = nullptr;
    bool two_sided_ = false;
};

} // namespace shade::check::detail
