// Stress intensity factors along a 3D crack front by the domain
// interaction integral (layer a).
//
// For a front point k with the virtual crack extension q (x) d, d = e1 of
// the point's frame, q a weight 1 near the point and 0 outside its domain:
//
//   I_m int q_s ds = int_V ( sigma_ij u^aux_i,d + sigma^aux_ij u_i,d
//                            - sigma_kl eps^aux_kl d_j ) q,_j dV
//
// written frame-free as (sigma grad q) . (grad u_aux d) + (sigma_aux grad q) .
// (grad u d) - (sigma : eps_aux) (d . grad q), with the auxiliary field of
// mode m (K^aux_m = 1: the Williams fields of front_functions_3d.h times
// 1 / (2 mu sqrt(2 pi))) in the frame the caller gives per point (the frame
// of the point's nearest front point: fields that follow a curved front).
// The terms of the non-gradient volume integral that a curved front or a
// curved crack adds (sigma^aux_ij,j u_i,1 + sigma_ij (u^aux_i,1j -
// eps^aux_ij,1)) q are not included; lip tractions and body forces add
// terms the caller integrates (aux_derivative_3d gives what they need).
// Conversion: K_I = E' I_I / 2, K_II = E' I_II / 2 with E' = E / (1 - nu^2),
// K_III = mu I_III.
//
// Curved fronts and curved crack surfaces (interaction_integrand_3d,
// auxiliary_fields_3d). The auxiliary field of a point follows the front and
// the crack's surface: its nearest front point p(s) (s the arc length) has
// the Darboux frame of the front on the surface, e3 the front's tangent, e2
// the surface's normal (+ side), e1 = e2 x e3 in the surface away from the
// crack, turning along the front as
//   e1' = kappa_f e3 + tau e2,  e2' = -kappa_33 e3 - tau e1,  e3' = -kappa_f e1 + kappa_33 e2
// (' = d/ds): kappa_f the front's curvature within the surface (> 0 when the
// front bends around the crack, 1 / a on a penny of radius a), kappa_33 the
// surface's normal curvature along the front, tau its geodesic torsion; and
// kappa_11 the surface's normal curvature across the front (the surface is
// x2 = kappa_11 x1^2 / 2 + O(x1^3) in the front point's normal plane;
// normal curvatures > 0 when the surface bends toward e2). A planar crack has
// kappa_11 = kappa_33 = tau = 0. Tube coordinates x = p(s) + x1 e1 + x2 e2:
//   h = 1 + kappa_f x1 - kappa_33 x2,  grad s = e3 / h,
//   grad x1 = e1 + (tau x2 / h) e3,   grad x2 = e2 - (tau x1 / h) e3,
// and coordinates that follow the surface, xi1 = x1, xi2 = x2 - kappa_11
// x1^2 / 2 (the lips are xi2 = 0, xi1 < 0, to O(x1^3)). The field is the
// plane-strain / anti-plane Williams field of (xi1, xi2) carried by the
// frame,
//   u_aux = sum_k U_k(xi1, xi2) e_k(s),
//   grad u_aux = sum_k e_k (x) (U_k,xi1 grad xi1 + U_k,xi2 grad xi2) + U_k e_k' (x) grad s,
// its angle atan2(xi2, xi1) continued (not mirrored) across xi2 = 0 behind
// the front for a point of a given side (front_functions_3d.h
// continued_front_angle), so that it is analytic in the material of each
// side up to the real lips. The field is compatible (its true gradient) and
// not in equilibrium: div sigma_aux, with sigma_ab (frame components) a
// function of (x1, x2) only for curvatures constant along the front,
//   div sigma_aux = sum_ab (sigma_ab,1 (e_b . grad x1) + sigma_ab,2 (e_b . grad x2)) e_a
//                   + (sigma_a3 e_a' + sigma_ab (e_b' . e3) e_a) / h,
// the partial derivatives by central differences (relative step 1e-4 of
// the distance to the front) on a curved surface, in closed form on a
// planar crack (kappa_11 = kappa_33 = tau = 0: R = h / kappa_f the distance
// to the osculating circle's axis):
//   div sigma_aux = (lambda + 2 mu) (u_1,1 - u_1 / R) / R e1
//                 + (mu u_2,1 + (lambda + mu) u_1,2) / R e2
//                 + mu (u_3,1 - u_3 / R) / R e3.
// The domain integral then reads, for a constant virtual extension d,
//   I int q_s (e1 . d) ds = int_V (grad q)_j T_jl d_l dV + int_V q D_l d_l dV
//                           + int_lips ((sigma : eps_aux) (n . d) - t . grad u_aux d - t_aux . grad u d) q dA
// with n the outward normal of each lip's material, t = sigma n the lip's
// traction, t_aux = sigma_aux n, T_jl = sigma_ij G_il + sigma_aux_ij g_il -
// (sigma : eps_aux) delta_jl (G = grad u_aux, g = grad u) and D_l = (div
// sigma_aux)_i g_il - b_i G_il (b the body force). The first lip term
// vanishes on a planar crack (n . d = 0); on a curved one n . d = O(kappa_11
// r). Exact for any field with K and the curvatures constant along the
// front (the tube identity of the unit tests); the rates of change of K are
// what the hat along the front averages, those of the curvatures are not
// kept. All curvatures 0 gives the straight-front fields above.
#pragma once

#include "enrichment/front_functions_3d.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace cracklip
{

/// (I_I, I_II, I_III) times int q_s ds: E, nu the isotropic material;
/// direction d (3) the virtual extension; per point (n): frames (n, 12):
/// origin, e1, e2, e3 of the auxiliary fields' frame, weights (volume
/// measure), grad_q (n, 3), grad_u (n, 3, 3) (d u_i / d x_j) of the field
/// whose K is sought, sides (n) lip branch of the auxiliary fields (+1 /
/// -1 / 0), points x (n, 3).
std::array<double, 3> interaction_integral_3d(double E, double nu, const Point3& d, std::span<const double> frames,
                                              std::span<const double> x, std::span<const double> weights,
                                              std::span<const double> grad_q, std::span<const double> grad_u,
                                              std::span<const std::int8_t> sides);

/// d u^aux / d x_d (n, mode, component) of the unit-K auxiliary fields at
/// points x (n, 3) in per-point frames (n, 12), lip branch sides (n).
void aux_derivative_3d(double E, double nu, const Point3& d, std::span<const double> frames,
                       std::span<const double> x, std::span<const std::int8_t> sides, std::span<double> out);

/// The curvatures of a front point (header): kappa_f, kappa_11, kappa_33,
/// tau.
struct FrontCurvatures
{
  double front = 0.0, across = 0.0, along = 0.0, torsion = 0.0;
};

/// The unit-K auxiliary fields of curved fronts and crack surfaces (header)
/// at points x (n, 3) in per-point frames (n, 12) with the curvatures (n, 4)
/// kappa_f, kappa_11, kappa_33, tau at the frame's front point, lip branch
/// sides (n): U (n, mode, component) the displacement, G (n, mode, i, j) = d
/// U_i / d x_j its true gradient, local (n, mode, 3) its components along
/// e1, e2, e3, div_sigma (n, mode, 3) the divergence of its stress (global
/// components). Throws for a point beyond the centre of curvature (h =
/// 1 + kappa_f x1 - kappa_33 x2 <= 0.05).
void auxiliary_fields_3d(double E, double nu, std::span<const double> frames, std::span<const double> curvatures,
                         std::span<const double> x, std::span<const std::int8_t> sides, std::span<double> U,
                         std::span<double> G, std::span<double> local, std::span<double> div_sigma);

/// The integrands of the curved-front interaction integral (header) at
/// points x (n, 3): frames (n, 12), curvatures (n, 4), grad_u (n, 3, 3) of
/// the field whose K is sought, sides (n), body (3) a constant body force,
/// (n, 3) one per point (an initial stress's divergence), or empty: none.
/// Output T (n, mode, j, l) and D (n, mode, l), so that
/// for a virtual extension d and a weight q
///   I_m int q_s (e1 . d) ds = sum_p w_p (grad q_p . T_m,p d + q_p D_m,p . d)
/// (plus the lip terms). Work O(n), no allocation per point.
void interaction_integrand_3d(double E, double nu, std::span<const double> frames, std::span<const double> curvatures,
                              std::span<const double> x, std::span<const double> grad_u,
                              std::span<const std::int8_t> sides, std::span<const double> body, std::span<double> T,
                              std::span<double> D);

/// K_I, K_II, K_III of a front point from its interaction integrals I (3)
/// with a constant virtual extension d: q_e1 = int q (e1 . d) ds and q_e2 =
/// int q (e2 . d) ds along the front. Where the crack surface bends along
/// the front (kappa_33, tau) e2 turns away from d along the hat, and the
/// contour limit carries the e2 component's interaction, the mixed-mode
/// J2 = -2 K_I K_II / E' linearised:
///   I_I q_e1 E' / 2 = K_I q_e1 - K_II q_e2,  I_II q_e1 E' / 2 = K_II q_e1 - K_I q_e2
/// (mode III has no such term; the component along e3 has no contour
/// limit), solved here (rho = q_e2 / q_e1 = 0 on a planar crack:
/// K_I = E' I_I / 2, K_II = E' I_II / 2, K_III = mu I_III, each divided by
/// q_e1).
std::array<double, 3> front_sifs_3d(double E, double nu, const std::array<double, 3>& I, double q_e1, double q_e2);

/// Which front points' domains reach each cell, for the one-pass sums
/// below: the entries of cell c are [offsets[c], offsets[c + 1]), each with
/// its front point (point) and that point's q at the cell's 4 nodes for each
/// of its num_domains domains (q (m, 4, num_domains)).
struct FrontDomainTable
{
  std::span<const std::int32_t> offsets;
  std::span<const std::int32_t> point;
  std::span<const double> q;
  int num_domains = 1;
};

/// The volume part of the interaction integrals of many front points at
/// once (one pass over the quadrature points of all their domains: each
/// point's auxiliary fields and integrands are computed once): for every
/// point p (as interaction_integrand_3d, with weights (n), its cell
/// point_cell (n) in the table, its P1 shape values shape (n, 4)) and every
/// table entry (front point k, domain d) of its cell, with q and grad q from
/// the entry's nodal q and the cell's shape gradients cell_gradients (c, 4,
/// 3),
///   I[k, d, m] += w_p (grad q . T_m d_k + q D_m . d_k),
/// d_k = directions (K, 3). I (K, num_domains, 3) is added to.
void front_domain_integrals_3d(double E, double nu, std::span<const double> frames,
                               std::span<const double> curvatures, std::span<const double> x,
                               std::span<const double> grad_u, std::span<const std::int8_t> sides,
                               std::span<const double> body, std::span<const double> weights,
                               std::span<const std::int32_t> point_cell, std::span<const double> shape,
                               std::span<const double> cell_gradients, const FrontDomainTable& table,
                               std::span<const double> directions, std::span<double> I);

/// I[k, d, m] += w_p q_kd(p) values_p[m] . d_k over points p (weights (n),
/// point_cell (n) among num_cells, shape (n, 4)) and the table entries of
/// their cells: the lip terms, values (n, mode, l) per unit q and extension.
void front_domain_sums_3d(std::span<const double> values, std::span<const double> weights,
                          std::span<const std::int32_t> point_cell, std::span<const double> shape,
                          std::size_t num_cells, const FrontDomainTable& table, std::span<const double> directions,
                          std::span<double> I);

} // namespace cracklip
