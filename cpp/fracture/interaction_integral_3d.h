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
// Curved fronts (interaction_integrand_3d, auxiliary_fields_3d): the
// auxiliary field of a point follows the front, u_aux = sum_k u_k(x1, x2)
// e_k(s) in the frame of the point's nearest front point (s its arc
// length, x1 = (x - p(s)) . e1, x2 = (x - p(s)) . e2), for a planar crack
// whose front has the in-plane curvature kappa_f (d e3 / ds = -kappa_f e1,
// > 0 when the front bends around the crack, 1 / a on a penny of radius a).
// Its true gradient is the straight-front one plus the hoop terms
//   grad u_aux = sum_k e_k (x) grad u_k + (u_1 e3 (x) e3 - u_3 e1 (x) e3) / R,
// R = (1 + kappa_f x1) / kappa_f the distance to the osculating circle's
// axis (d e1 / ds = kappa_f e3, grad s = e3 / (1 + kappa_f x1)), so that the
// field is compatible; locally axisymmetric about that axis, it is not in
// equilibrium: with the plane-strain Navier equations of the 2D fields,
//   div sigma_aux = (lambda + 2 mu) (u_1,1 - u_1 / R) / R e1
//                 + (mu u_2,1 + (lambda + mu) u_1,2) / R e2
//                 + mu (u_3,1 - u_3 / R) / R e3,
// and its traction on the lips is lambda (u_1 / R) n (mode II only: u_1 = 0
// on the lips in modes I and III). The domain integral then reads
//   I int q_s (e1 . d) ds = int_V (grad q)_j T_jl d_l dV + int_V q D_l d_l dV
//                           - int_lips (t . grad u_aux d + t_aux . grad u d) q dA
// with T_jl = sigma_ij G_il + sigma_aux_ij g_il - (sigma : eps_aux) delta_jl
// (G = grad u_aux, g = grad u) and D_l = (div sigma_aux)_i g_il - b_i G_il
// (b the body force), exact for any field with K(s) smooth along the front
// (up to the terms of d kappa_f / ds and of a curved crack surface, not
// kept). kappa_f = 0 gives the straight-front fields above.
#pragma once

#include "enrichment/front_functions_3d.h"

#include <array>
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

/// The unit-K auxiliary fields of curved fronts (header) at points x (n, 3)
/// in per-point frames (n, 12) with the front's curvature kappa_f (n) at the
/// frame's front point, lip branch sides (n): U (n, mode, component) the
/// displacement, G (n, mode, i, j) = d U_i / d x_j its true gradient, local
/// (n, mode, 3) its components along e1, e2, e3, div_sigma (n, mode, 3) the
/// divergence of its stress (global components). Throws for a point beyond
/// the osculating circle's axis (1 + kappa_f x1 <= 0.05).
void auxiliary_fields_3d(double E, double nu, std::span<const double> frames, std::span<const double> curvature,
                         std::span<const double> x, std::span<const std::int8_t> sides, std::span<double> U,
                         std::span<double> G, std::span<double> local, std::span<double> div_sigma);

/// The integrands of the curved-front interaction integral (header) at
/// points x (n, 3): frames (n, 12), curvature (n), grad_u (n, 3, 3) of the
/// field whose K is sought, sides (n), body (3) a constant body force (or
/// empty: none). Output T (n, mode, j, l) and D (n, mode, l), so that for a
/// virtual extension d and a weight q
///   I_m int q_s (e1 . d) ds = sum_p w_p (grad q_p . T_m,p d + q_p D_m,p . d)
/// (plus the lip terms). Work O(n), no allocation per point.
void interaction_integrand_3d(double E, double nu, std::span<const double> frames, std::span<const double> curvature,
                              std::span<const double> x, std::span<const double> grad_u,
                              std::span<const std::int8_t> sides, std::span<const double> body, std::span<double> T,
                              std::span<double> D);

} // namespace cracklip
