#pragma once
// Gauss-Legendre quadrature: the 5-point rule (Abramowitz, Stegun 1964, "Handbook of
// Mathematical Functions", 25.4.29; exact for polynomials of degree <= 9) and its composite
// form on equal intervals, shared by the albedo averages of the tables and the Fresnel
// averages.

namespace shade {

/// The nodes of the 5-point Gauss-Legendre rule on [-1, 1].
inline constexpr double gauss_legendre_5_nodes[5] = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                                     0.5384693101056831, 0.9061798459386640};

/// The weights of the 5-point Gauss-Legendre rule on [-1, 1] (they sum to 2).
inline constexpr double gauss_legendre_5_weights[5] = {0.2369268850561891, 0.4786286704993665,
                                                       0.5688888888888889, 0.4786286704993665,
                                                       0.2369268850561891};

/// integral_a^b f(x) dx by the 5-point rule on `intervals` equal intervals. f takes a double
/// and returns a double or any type with + and * by double (e.g. glm::dvec3); so does this.
template <class F>
[[nodiscard]] auto gauss_legendre_integral(const F& f, double a, double b, int intervals) {
    using R = decltype(f(a));
    const double width = (b - a) / double(intervals);
    R sum = R(0);
    for (int i = 0; i < intervals; ++i)
        for (int k = 0; k < 5; ++k)
            sum += f(a + width * (double(i) + 0.5 * (1.0 + gauss_legendre_5_nodes[k]))) * gauss_legendre_5_weights[k];
    return sum * (0.5 * width);
}

} // namespace shade
