// Collapsed (Duffy-type) quadrature rules for integrands singular at a crack
// front in 3D (layer a: no DOLFINx).
//
// Near a front line the enriched integrands behave like r^(1/2) (front
// functions), r^(-1/2) (their gradients, and products with standard
// gradients) and r^(-1) (products of two gradients), r the distance to the
// front line. The rules below make r linear in a collapsed variable rho and
// take rho = tau^2, so that the Jacobian cancels r^(-1) and sqrt(r) becomes
// polynomial in tau; the remaining angular variable is smoothed by a sinh
// substitution. Every rule is given on the simplex's own coordinates:
//   tetrahedron ABCD: x = A + alpha (B - A) + beta (C - A) + gamma (D - A),
//     points (n, 3) = (alpha, beta, gamma), weights summing to 1/6, so
//     int_T f = 6 |T| sum_q w_q f(x_q);
//   triangle ABC: x = A + alpha (B - A) + beta (C - A), points (n, 2),
//     weights summing to 1/2: int_T f = 2 |T| sum_q w_q f(x_q).
// The physical vertices enter only through the angular substitution and the
// point rules' decomposition; r is the distance to the front LINE (within a
// cell the P1 front is straight).
#pragma once

#include "quadrature/rules.h"

#include <array>
#include <span>

namespace cracklip::quadrature
{

/// Edge-collapsed rule on the tetrahedron ABCD (physical vertices xv (4, 3))
/// with the edge AB on the front:
///   beta = rho (1 - eta), gamma = rho eta, alpha = (1 - rho) t, rho = tau^2,
///   d(alpha, beta, gamma) = rho (1 - rho) drho deta dt = 2 tau^3 (1 - tau^2) dtau deta dt,
/// and r = rho |P(eta)|, P(eta) = (1 - eta) C' + eta D' (C', D' the parts of
/// C - A, D - A normal to AB): r^(-1) and r^(-1/2) times polynomials are
/// polynomial in tau and t. Across (eta) the factor 1 / |P(eta)|, nearly
/// singular for a flat or obtuse tetrahedron, is made constant by
/// s0 + eta L = h0 sinh(u) (h0 the distance from the front to the line C'D',
/// L = |D' - C'|). n_tau x n_eta x n_t Gauss-Legendre points in (tau, u, t).
Rule tetrahedron_edge_collapsed(std::span<const double, 12> xv, int n_tau, int n_eta, int n_t);

/// Point-collapsed rule on the tetrahedron ABCD with the vertex A on the
/// front, whose direction at A is `front` (physical, any length > 0; the
/// front line must not enter the tetrahedron). Where the front line meets
/// the plane of BCD at F = b_B B + b_C C + b_D D (max |b| <= 1000), ABCD is
/// the signed sum of the tetrahedra AFCD, AFDB, AFBC with weights b_B, b_C,
/// b_D (cones from A over the pieces of BCD seen from F), each with the edge
/// AF on the front line: the edge-collapsed rule there. This is exact for
/// r^(-1) and r^(-1/2) times polynomials however close the front passes to
/// BCD; a front nearly parallel to BCD puts F far (b = 62 on a penny mesh's
/// sub-tetrahedra), where the plain collapse below needs three times the
/// angular points. Round-off grows with max |b|. Points of the pieces lie
/// outside ABCD (weights may be negative) but inside the same wedge of the
/// front (the convex hull of A, F and ABCD's vertices lies on the same side
/// of phi = 0 and of psi = 0), where integrands built from the cell's P1
/// level sets are analytic: evaluate them from the cell's data, not from a
/// point-wise nearest-front frame. Otherwise (F farther, or the front
/// parallel to BCD) x = A + rho Q(sigma) over the triangle BCD, rho = tau^2:
/// weight 2 tau^5, sigma by an n x n conical rule, n = max(n_eta, n_t).
Rule tetrahedron_point_collapsed(std::span<const double, 12> xv, std::span<const double, 3> front, int n_tau,
                                 int n_eta, int n_t);

/// The plain collapse of the tetrahedron ABCD onto its vertex A:
/// x = A + rho Q(sigma) over the triangle BCD, rho = tau^2 (weight 2 tau^5),
/// sigma by an n x n conical rule. Weights positive, points inside: a
/// positive semi-definite integrand gets a positive semi-definite sum. For
/// a front through A that stays away from BCD, r^(-1) becomes rho^(-1)
/// times a smooth function of sigma (nearly singular if the front passes
/// close to BCD: then the signed decomposition above is exact).
Rule tetrahedron_vertex_collapsed(int n_tau, int n);

/// Edge-collapsed rule on the triangle ABC with the edge AB on the front:
/// beta = tau^2, alpha = (1 - beta) t, weight 2 tau (1 - tau^2); r = beta
/// dist(C, AB), so r^(1/2) and r^(-1/2) times polynomials are polynomial.
Rule triangle_edge_collapsed(int n_tau, int n_t);

/// Point-collapsed rule on the triangle ABC (physical vertices xv (3, 3))
/// with the vertex A on the front and the front direction `front` in the
/// triangle's plane: where the front line meets the line BC at
/// F = (1 - s) B + s C (|s|, |1 - s| <= 1000), ABC is the signed sum of AFC
/// (weight 1 - s) and AFB (weight s), each with the edge AF on the front (the
/// rule above; points outside ABC as for the tetrahedron); otherwise the fan
/// from A with rho = tau^2.
Rule triangle_point_collapsed(std::span<const double, 9> xv, std::span<const double, 3> front, int n_tau, int n_t);

/// A tetrahedron near a front line it does not touch (the line through
/// `origin` along `front`, physical): the signed sum of the cones from O,
/// the point of the line nearest the tetrahedron's centroid, over its four
/// faces (sum of signed cone volumes = the volume), each integrated by the
/// point-collapsed rule at O. Points of the cones lie between the line and
/// the tetrahedron, inside the same wedge of the front if the tetrahedron
/// is; weights carry the cones' signs. The nearly singular integrand then
/// gets the accuracy of the collapsed rules.
Rule tetrahedron_near_front(std::span<const double, 12> xv, std::span<const double, 3> origin,
                            std::span<const double, 3> front, int n_tau, int n_eta, int n_t);

/// A triangle near a front line in its plane: the signed sum of the fans
/// from O (the line's point nearest the centroid) over its three edges,
/// each point-collapsed at O.
Rule triangle_near_front(std::span<const double, 9> xv, std::span<const double, 3> origin,
                         std::span<const double, 3> front, int n_tau, int n_t);

} // namespace cracklip::quadrature
