#pragma once
// shade::has_scalar_type and shade::scalar_of: how a BRDF, shader or light names the
// floating-point type it computes in.

#include <concepts>

namespace shade {

/// X names its scalar type as X::scalar_type, and that type is float or double.
template <class X>
concept has_scalar_type =
    requires { typename X::scalar_type; } && std::floating_point<typename X::scalar_type>;

/// The scalar type of a BRDF, shader or light.
template <has_scalar_type X>
using scalar_of = typename X::scalar_type;

} // namespace shade
