#pragma once
// Gauss-Legendre quadrature for exact cell averages of analytic solutions.
#include <array>
#include <cstddef>

namespace avalanche::analytic {

// Five-point Gauss-Legendre nodes and weights on [-1, 1] (exact for degree 9).
inline constexpr std::array<double, 5> kGaussNodes{-0.9061798459386640, -0.5384693101056831, 0.0,
                                                   0.5384693101056831, 0.9061798459386640};
inline constexpr std::array<double, 5> kGaussWeights{0.2369268850561891, 0.4786286704993665,
                                                     0.5688888888888889, 0.4786286704993665,
                                                     0.2369268850561891};

// Integral of f over [a, b] by five-point Gauss-Legendre.
template <class F>
double gauss_integral(F&& f, double a, double b) {
    if (!(b > a)) return 0.0;
    const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    double sum = 0.0;
    for (std::size_t n = 0; n < kGaussNodes.size(); ++n)
        sum += kGaussWeights[n] * f(mid + half * kGaussNodes[n]);
    return sum * half;
}

}  // namespace avalanche::analytic
