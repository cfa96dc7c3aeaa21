#pragma once
// All BRDF property checks: positivity, Helmholtz reciprocity and energy conservation,
// for any type satisfying shade::brdf, and the sampling checks (chi-square goodness of fit,
// sample consistency, pdf normalization and coverage) for any shade::sampled_bsdf.
// Framework-neutral: each returns a shade::check::result that converts to bool, carries a
// pass / fail / inconclusive verdict and prints as a sentence.
//
//   auto r = shade::check::reciprocity(my_brdf, at, {.model = "my BRDF"});
//   if (!r) std::cerr << r << '\n';

#include <shade/check/directions.hpp>
#include <shade/check/energy.hpp>
#include <shade/check/positivity.hpp>
#include <shade/check/reciprocity.hpp>
#include <shade/check/result.hpp>
#include <shade/check/sampling.hpp>
