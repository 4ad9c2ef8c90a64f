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

/// The same, computed once per n and kept (single-threaded callers).
const Rule& gauss_legendre_cached(int n);

/// Gauss-Legendre rule with n points on [0, 1] (a segment P-Q, t = 0 at P)
/// in the variable rho = sqrt(r), where r is the distance from a point (a
/// crack tip) on the segment's line, r0 at P and r1 at Q (r linear in t):
/// exact for f(r) r^(-1/2) and f(r) r^(1/2) with f a polynomial of degree up
/// to n - 2 (the 1/sqrt(r) of crack-tip gradients and the sqrt(r) of tip
/// functions along a crack), also when the tip lies just beyond the segment
/// (r0 small but not 0), where plain Gauss sees a near-singularity. With
/// r0 = r1 it is plain Gauss-Legendre.
Rule line_toward_tip(int n, double r0, double r1);

/// Rule on the reference triangle (0,0), (1,0), (0,1), exact for polynomials
/// of total degree `degree` (collapsed Gauss-Legendre product rule; weights
/// sum to 1/2). Degree 1 returns the one-point centroid rule.
Rule triangle(int degree);

/// Conical product rule with n x n points on the reference triangle (the
/// paper's plain rule uses n = (p + 3) / 2 for degree p); exact to degree
/// 2n - 2.
Rule triangle_product(int n);

/// Rule on the reference tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1),
/// exact for polynomials of total degree `degree` (collapsed Gauss-Legendre
/// product rule: x = u, y = (1 - u) v, z = (1 - u)(1 - v) w, Jacobian
/// (1 - u)^2 (1 - v), with (degree + 4) / 2, (degree + 3) / 2 and
/// (degree + 2) / 2 points in u, v, w; weights sum to 1/6). Degree 1 returns
/// the one-point centroid rule.
Rule tetrahedron(int degree);

/// The same, computed once per degree and kept (single-threaded callers).
const Rule& tetrahedron_cached(int degree);

/// Quasi-polar rule for integrands with a 1/r (and sqrt(r)) singularity at
/// vertex 0 of the reference triangle: x = rho ((1 - eta), eta) with
/// rho = t^2, n_t x n_eta Gauss-Legendre points in (t, eta), weight
/// 2 t^3 w_t w_eta. The rho factor of the polar Jacobian cancels 1/r, and
/// t^2 turns sqrt(r) into a polynomial; the eta direction stays analytic,
/// and converges fast when the triangle's angle at vertex 0 is small.
Rule tip_fan(int n_t, int n_eta);

} // namespace cracklip::quadrature
