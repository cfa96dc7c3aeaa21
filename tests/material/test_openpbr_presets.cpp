// shade::openpbr's named presets (shade/material/openpbr_presets.hpp): the ACEScg
// conversion, that every preset is a valid parameter set with the character it is named
// for, and the white-furnace variant.

#include <cmath>
#include <set>
#include <string>

#include <doctest/doctest.h>

#include <shade/material/openpbr_presets.hpp>

namespace {

using shade::rgb;

template <class T>
void check_rgb(const rgb<T>& got, double r, double g, double b, double tolerance) {
    CHECK(std::abs(double(got.x) - r) <= tolerance);
    CHECK(std::abs(double(got.y) - g) <= tolerance);
    CHECK(std::abs(double(got.z) - b) <= tolerance);
}

} // namespace

TEST_CASE_TEMPLATE("openpbr::from_acescg: grey stays grey, primaries and gold by hand, clamped to [0, 1]", T, float,
                   double) {
    // The rows of the AP1-to-Rec.709 matrix sum to 1 (both spaces' white is (1, 1, 1)).
    check_rgb(shade::openpbr::from_acescg(rgb<T>(T(0.5))), 0.5, 0.5, 0.5, 1e-6);
    check_rgb(shade::openpbr::from_acescg(rgb<T>(T(1))), 1, 1, 1, 1e-6);
    // The green primary of ACEScg is the matrix's middle column (-0.621792, 1.140805,
    // -0.128969), clamped: (0, 1, 0).
    check_rgb(shade::openpbr::from_acescg(rgb<T>(0, 1, 0)), 0, 1, 0, 0);
    // A tenth of the blue primary: (-0.0083259, -0.0010548, 0.1152972), clamped.
    check_rgb(shade::openpbr::from_acescg(rgb<T>(0, 0, T(0.1))), 0, 0, 0.1152972, 1e-6);
    // Gold's base_color (0.929, 0.788, 0.374) in ACEScg:
    //   r = 1.705051 * 0.929 - 0.621792 * 0.788 - 0.083259 * 0.374 = 1.062859 -> 1 (clamped)
    //   g = -0.130256 * 0.929 + 1.140805 * 0.788 - 0.010548 * 0.374 = 0.774002
    //   b = -0.024003 * 0.929 - 0.128969 * 0.788 + 1.152972 * 0.374 = 0.307284
    check_rgb(shade::openpbr::from_acescg(rgb<T>(T(0.929), T(0.788), T(0.374))), 1, 0.774002, 0.307285, 2e-6);
}

TEST_CASE_TEMPLATE("openpbr presets: twelve distinct names, each a valid parameter set", T, float, double) {
    const auto all = shade::openpbr::presets<T>();
    std::set<std::string> names;
    for (const auto& m : all) {
        CAPTURE(std::string(m.name));
        names.insert(std::string(m.name));
        CHECK_NOTHROW(m.parameters.validate());
        CHECK_NOTHROW(shade::openpbr::white_furnace_variant(m.parameters).validate());
    }
    CHECK(names.size() == all.size());
}

TEST_CASE_TEMPLATE("openpbr presets: each has the character it is named for", T, float, double) {
    namespace o = shade::openpbr;
    const shade::openpbr_parameters<T> defaults;
    const auto d = o::default_material<T>();
    CHECK(d.base_color == defaults.base_color);
    CHECK(d.specular_roughness == defaults.specular_roughness);
    for (const auto& metal : {o::gold<T>(), o::brushed_aluminium<T>(), o::copper<T>(), o::car_paint<T>()})
        CHECK(metal.base_metalness == T(1));
    // Gold reflects red most and blue least at normal incidence.
    const auto gold = o::gold<T>();
    CHECK(gold.base_color.x > gold.base_color.y);
    CHECK(gold.base_color.y > gold.base_color.z);
    CHECK(o::brushed_aluminium<T>().specular_roughness_anisotropy > T(0));
    CHECK(o::car_paint<T>().coat_weight == T(1));
    CHECK(o::coated_plastic<T>().coat_weight == T(1));
    CHECK(o::coated_plastic<T>().base_metalness == T(0));
    CHECK(o::velvet<T>().fuzz_weight > T(0));
    CHECK(o::rubber<T>().base_diffuse_roughness == T(1));
    CHECK(o::glass<T>().transmission_weight == T(1));
    CHECK(o::glass<T>().specular_roughness == T(0));
    CHECK(o::frosted_glass<T>().transmission_weight == T(1));
    CHECK(o::frosted_glass<T>().specular_roughness > T(0));
    const auto bubble = o::soap_bubble<T>();
    CHECK(bubble.geometry_thin_walled);
    CHECK(bubble.thin_film_weight == T(1));
    CHECK(o::marble<T>().subsurface_weight == T(1));
    // Marble's mean free path is longest in red (radius scale ACEScg (0.851, 0.557, 0.395)).
    const auto scale = o::marble<T>().subsurface_radius_scale;
    CHECK(scale.x > scale.y);
    CHECK(scale.y > scale.z);
}

TEST_CASE_TEMPLATE("openpbr::white_furnace_variant: white colours, no medium, no emission, the rest kept", T, float,
                   double) {
    auto p = shade::openpbr::marble<T>();
    p.base_weight = T(0.5);
    p.base_color = rgb<T>(T(0.2));
    p.transmission_depth = T(2);
    p.transmission_color = rgb<T>(T(0.3));
    p.transmission_scatter = rgb<T>(T(0.1));
    p.coat_weight = T(0.7);
    p.coat_color = rgb<T>(T(0.4));
    p.fuzz_color = rgb<T>(T(0.6));
    p.emission_luminance = T(100);
    const auto w = shade::openpbr::white_furnace_variant(p);
    const rgb<T> white(1);
    CHECK(w.base_weight == T(1));
    CHECK(w.base_color == white);
    CHECK(w.specular_color == white);
    CHECK(w.transmission_color == white);
    CHECK(w.transmission_depth == T(0));
    CHECK(w.transmission_scatter == rgb<T>(0));
    CHECK(w.subsurface_color == white);
    CHECK(w.coat_color == white);
    CHECK(w.fuzz_color == white);
    CHECK(w.emission_luminance == T(0));
    // Kept: the layers' weights, roughnesses and the mean free path.
    CHECK(w.coat_weight == T(0.7));
    CHECK(w.subsurface_weight == p.subsurface_weight);
    CHECK(w.subsurface_radius_scale == p.subsurface_radius_scale);
    CHECK(w.specular_roughness == p.specular_roughness);
    CHECK_FALSE(shade::openpbr::transmission_medium(w).present);
}
