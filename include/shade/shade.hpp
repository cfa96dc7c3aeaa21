#pragma once
// shade: header-only C++20 shading, BRDF and ray-intersection library on GLM.
// This umbrella header includes every public header except the property kit,
// shade/check/*.hpp (for testing models: containers, streams and statistics a renderer does
// not need; include shade/check/properties.hpp for all of it, shade/check/doctest.hpp with
// doctest), shade/geometry/triangle_batch.hpp (platform-specific SIMD code and
// run-time CPU detection), the hierarchies shade/geometry/bvh.hpp and triangle_bvh.hpp
// (SIMD box tests, and the batch), and shade/light/environment_map.hpp with the
// distributions it samples by, shade/core/distribution.hpp (they would take this header
// past its preprocessed-line budget, tests/headers/budget.cmake), the path tracer's light
// selection (shade/light/light_sampler.hpp with shade/core/alias_table.hpp, and
// bvh_light_sampler.hpp with light_bounds.hpp and light_bounds_of.hpp), and
// shade/light/classic_light.hpp (the classic mode of an emitter of yours): include them
// where you use them.
// Conventions: shade/core/frame.hpp and docs/conventions.md.

#include <shade/version.hpp>

#include <shade/core/config.hpp>
#include <shade/core/error.hpp>
#include <shade/core/frame.hpp>
#include <shade/core/math.hpp>
#include <shade/core/mis.hpp>
#include <shade/core/random.hpp>
#include <shade/core/sampler.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/sobol.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

#include <shade/geometry/aabb.hpp>
#include <shade/geometry/camera.hpp>
#include <shade/geometry/hit.hpp>
#include <shade/geometry/plane.hpp>
#include <shade/geometry/ray.hpp>
#include <shade/geometry/spawn.hpp>
#include <shade/geometry/sphere.hpp>
#include <shade/geometry/triangle.hpp>

#include <shade/brdf/aliases.hpp>
#include <shade/brdf/any_brdf.hpp>
#include <shade/brdf/ashikhmin_shirley.hpp>
#include <shade/brdf/blinn_phong.hpp>
#include <shade/brdf/brdf.hpp>
#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/coupled_plastic.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/brdf/metals.hpp>
#include <shade/brdf/microfacet.hpp>
#include <shade/brdf/multiple_scattering.hpp>
#include <shade/brdf/oren_nayar.hpp>
#include <shade/brdf/phong.hpp>

#include <shade/bsdf/bsdf.hpp>
#include <shade/bsdf/refract.hpp>
#include <shade/bsdf/rough_dielectric.hpp>
#include <shade/bsdf/smooth_conductor.hpp>
#include <shade/bsdf/smooth_dielectric.hpp>
#include <shade/bsdf/thin_dielectric.hpp>

#include <shade/light/any_light.hpp>
#include <shade/light/area.hpp>
#include <shade/light/area_emitter.hpp>
#include <shade/light/delta_light.hpp>
#include <shade/light/directional.hpp>
#include <shade/light/disk.hpp>
#include <shade/light/emission.hpp>
#include <shade/light/environment.hpp>
#include <shade/light/falloff.hpp>
#include <shade/light/incident_sample.hpp>
#include <shade/light/light.hpp>
#include <shade/light/light_sample.hpp>
#include <shade/light/point.hpp>
#include <shade/light/sample_context.hpp>
#include <shade/light/sphere.hpp>
#include <shade/light/spot.hpp>
#include <shade/light/triangle.hpp>

#include <shade/shading/checker.hpp>
#include <shade/shading/gooch.hpp>
#include <shade/shading/gradient.hpp>
#include <shade/shading/shader.hpp>
#include <shade/shading/sum_over_lights.hpp>
#include <shade/shading/toon.hpp>

#include <shade/color/convert.hpp>
#include <shade/color/delta_e.hpp>
#include <shade/color/lab.hpp>
#include <shade/color/srgb.hpp>
#include <shade/color/xyz.hpp>
