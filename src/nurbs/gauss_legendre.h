// Internal to src/nurbs: Gauss-Legendre rules on [0, 1].
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

namespace hm {

struct GaussRule {
  std::vector<double> nodes;    // in (0, 1), ascending
  std::vector<double> weights;  // summing to 1
};

// The n-point rule (exact for polynomials of degree 2n - 1), by Newton's method on the Legendre
// polynomial from Chebyshev starting guesses. Deterministic; accurate to a few ulps.
inline GaussRule gauss_legendre_01(int n) {
  GaussRule r;
  r.nodes.resize(n);
  r.weights.resize(n);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 1;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1;
      double p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    // x descends with i, so (1 - x) / 2 ascends.
    r.nodes[i] = 0.5 * (1 - x);
    r.weights[i] = 1.0 / ((1 - x * x) * dp * dp);
  }
  return r;
}

}  // namespace hm
