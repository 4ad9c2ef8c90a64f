// Quadrature rules on plain arrays (layer a: no DOLFINx).
#pragma once

#include <vector>

namespace cracklip::quadrature
{

/// A quadrature rule: `points` is row-major (num_points, dim), `weights` is
/// (num_points).
struct Rule
{
  int dim = 0;
  std::vector<double> points;
  std::vector<double> weights;
  int size() const { return static_cast<int>(weights.size()); }
};

/// Gauss-Legendre rule with n points on [0, 1] (exact to degree 2n - 1).
Rule gauss_legendre(int n);

/// Rule on the reference triangle (0,0), (1,0), (0,1), exact for polynomials
/// of total degree `degree` (collapsed Gauss-Legendre product rule; weights
/// sum to 1/2). Degree 1 returns the one-point centroid rule.
Rule triangle(int degree);

} // namespace cracklip::quadrature
