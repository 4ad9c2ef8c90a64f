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

/// Rule on the reference simplex of dimension dim (1, 2 or 3: [0, 1], the
/// triangle (0,0), (1,0), (0,1), the tetrahedron (0,0,0), (1,0,0), (0,1,0),
/// (0,0,1)), exact for polynomials of total degree `degree`: the collapsed
/// Gauss-Legendre product rule x_0 = u_0, x_k = (1 - u_0) ... (1 - u_{k-1})
/// u_k, Jacobian prod_k (1 - u_k)^(dim - 1 - k), with (degree + 1 + dim - k)
/// / 2 points in u_k (a monomial of degree p is of degree p + dim - 1 - k in
/// u_k with the Jacobian); weights sum to 1 / dim!. Degree 1 returns the
/// one-point centroid rule. Computed once per (dim, degree) and kept
/// (single-threaded callers, as the kernels that call it).
const Rule& simplex(int dim, int degree);

/// simplex(2, degree): the reference triangle (weights sum to 1/2).
Rule triangle(int degree);

/// Conical product rule with n x n points on the reference triangle (the
/// paper's plain rule uses n = (p + 3) / 2 for degree p); exact to degree
/// 2n - 2.
Rule triangle_product(int n);

/// simplex(3, degree): the reference tetrahedron (weights sum to 1/6).
Rule tetrahedron(int degree);

/// The same, without a copy.
const Rule& tetrahedron_cached(int degree);

/// Quasi-polar rule for integrands with a 1/r (and sqrt(r)) singularity at
/// vertex 0 of the reference triangle: x = rho ((1 - eta), eta) with
/// rho = t^2, n_t x n_eta Gauss-Legendre points in (t, eta), weight
/// 2 t^3 w_t w_eta. The rho factor of the polar Jacobian cancels 1/r, and
/// t^2 turns sqrt(r) into a polynomial; the eta direction stays analytic,
/// and converges fast when the triangle's angle at vertex 0 is small.
Rule tip_fan(int n_t, int n_eta);

} // namespace cracklip::quadrature
