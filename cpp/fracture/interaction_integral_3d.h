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

} // namespace cracklip
