#pragma once
// bench/legacy/ holds the reflection models' headers as they were before the sampling
// redesign (git show 7b9c61a:include/shade/brdf/<name>.hpp), copied verbatim except for
// three mechanical edits, so that bench/brdf.cpp can time the old f next to the new one in
// the same binary: namespace shade becomes shade_legacy, the includes of other model
// headers point at the copies here, and each copy includes this file, which makes the rest
// of shade (types, core helpers, the brdf concept) visible inside shade_legacy.

namespace shade {
namespace detail {}
} // namespace shade

namespace shade_legacy {
using namespace ::shade;
namespace detail {
using namespace ::shade::detail;
} // namespace detail
} // namespace shade_legacy
