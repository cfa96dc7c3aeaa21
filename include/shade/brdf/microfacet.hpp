#pragma once
// The terms of the microfacet models (shade::cook_torrance is composed from them), all
// evaluated in the local shading frame (n = +z, t = +x, b = +y):
//
//   shade/brdf/microfacet/distribution.hpp  the contracts (microfacet_distribution,
//                                           sampled_microfacet_distribution), D_visible,
//                                           the roughness bounds [1e-4, 1e4]
//   shade/brdf/microfacet/ggx.hpp           ggx<T>: D, Lambda, G1, visible-normal sampling
//   shade/brdf/microfacet/beckmann.hpp      beckmann<T>: D, exact Lambda and G1, sampling
//   shade/brdf/microfacet/masking.hpp       v_groove, smith_ggx, smith_beckmann,
//                                           smith_separable, smith_height_correlated
//
// Free functions per term, named term_model: D_beckmann, D_ggx (of a cosine, or of a local
// normal with two roughnesses), Lambda_beckmann, Lambda_ggx, G1_smith_beckmann (rational),
// G1_smith_beckmann_exact, G1_smith_ggx, G_v_groove.
//
// Roughness parameters: Beckmann's `m` is the RMS slope of the microfacets (Cook and
// Torrance's m, Walter et al.'s alpha_b); GGX's `alpha` is Walter et al.'s alpha_g; the
// anisotropic pairs (m_x, m_y) and (alpha_x, alpha_y) are those along t and b. None is a
// "perceptual roughness" (shade does not use that name). All must lie in
// [microfacet_parameter_min, microfacet_parameter_max] = [1e-4, 1e4].
//
// Fresnel terms live in shade/brdf/fresnel.hpp.

#include <shade/brdf/microfacet/beckmann.hpp>
#include <shade/brdf/microfacet/distribution.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/brdf/microfacet/masking.hpp>
