// libFuzzer target: shade::cook_torrance in every composition: distribution (beckmann,
// ggx) x Fresnel (schlick, dielectric_fresnel) x masking (v_groove, matching Smith) x form
// (walter, course, paper_1982). Input: byte 0 float/double, a composition byte,
// the roughness (m or alpha), f0 (rgb) and eta, k_s, k_d, then a
// situation (brdf_target.hpp, which also says what is checked).

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <optional>

#include <shade/brdf/cook_torrance.hpp>

#include "brdf_target.hpp"

namespace {

using namespace shade;
using fuzz::build;
using fuzz::decode_rgb;

template <class D, class F, class G, class Form, std::floating_point T>
void check(const D& d, const F& f, const rgb<T>& k_s, const rgb<T>& k_d,
           const std::optional<fuzz::brdf_situation<T>>& s) {
    const auto b = build<cook_torrance<D, F, G, Form>>(d, f, k_s, k_d);
    if (b && s) fuzz::check_brdf(*b, *s);
}

template <class D, class F, class G, std::floating_point T>
void with_form(unsigned form, const D& d, const F& f, const rgb<T>& k_s, const rgb<T>& k_d,
               const std::optional<fuzz::brdf_situation<T>>& s) {
    using namespace cook_torrance_form;
    if (form == 0) check<D, F, G, walter>(d, f, k_s, k_d, s);
    if (form == 1) check<D, F, G, course>(d, f, k_s, k_d, s);
    if (form == 2) check<D, F, G, paper_1982>(d, f, k_s, k_d, s);
}

template <class D, class F, class Smith, std::floating_point T>
void with_masking(unsigned masking, unsigned form, const D& d, const F& f, const rgb<T>& k_s,
                  const rgb<T>& k_d, const std::optional<fuzz::brdf_situation<T>>& s) {
    if (masking == 0)
        with_form<D, F, v_groove<T>>(form, d, f, k_s, k_d, s);
    else
        with_form<D, F, Smith>(form, d, f, k_s, k_d, s);
}

template <class D, class Smith, std::floating_point T>
void with_fresnel(unsigned fresnel, unsigned masking, unsigned form, const D& d,
                  const rgb<T>& f0, T eta, const rgb<T>& k_s, const rgb<T>& k_d,
                  const std::optional<fuzz::brdf_situation<T>>& s) {
    if (fresnel == 0) {
        if (const auto f = build<schlick<T>>(f0))
            with_masking<D, schlick<T>, Smith>(masking, form, d, *f, k_s, k_d, s);
    } else {
        if (const auto f = build<dielectric_fresnel<T>>(eta))
            with_masking<D, dielectric_fresnel<T>, Smith>(masking, form, d, *f, k_s, k_d, s);
    }
}

template <std::floating_point T>
void run(fuzz::input& in) {
    const unsigned composition = in.byte();
    const T roughness = in.scalar<T>();
    const rgb<T> f0 = decode_rgb<T>(in);
    const T eta = in.scalar<T>();
    const rgb<T> k_s = decode_rgb<T>(in);
    const rgb<T> k_d = decode_rgb<T>(in);
    const auto s = fuzz::decode_situation<T>(in);
    const unsigned fresnel = (composition >> 1u) & 1u;
    const unsigned masking = (composition >> 2u) & 1u;
    const unsigned form = ((composition >> 3u) & 3u) % 3u;
    if ((composition & 1u) == 0) {
        if (const auto d = build<beckmann<T>>(roughness))
            with_fresnel<beckmann<T>, smith_beckmann<T>>(fresnel, masking, form, *d, f0, eta,
                                                         k_s, k_d, s);
    } else {
        if (const auto d = build<ggx<T>>(roughness))
            with_fresnel<ggx<T>, smith_ggx<T>>(fresnel, masking, form, *d, f0, eta, k_s, k_d, s);
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return shade::fuzz::dispatch(data, size, &run<float>, &run<double>);
}
