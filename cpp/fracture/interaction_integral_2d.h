// Stress intensity factors at a 2D crack tip by the domain interaction
// integral (layer a): the density and its sum are the same in 3D
// (interaction_density.h); here the auxiliary fields live in the tip's
// frame and the domain is a disc (or ring) of cells around the tip.
//
//   I_m = int_A ( sigma_ij u^aux_i,1 + sigma^aux_ij u_i,1 - sigma_kl eps^aux_kl delta_1j ) q,_j dA
//   K_m = (E* / 2) I_m,   E* = E / (1 - nu^2) (plane strain)
//
// with the auxiliary Williams field of mode m (K^aux_m = 1) and direction 1 =
// e1 of the tip frame, written frame-free:
//   (sigma grad q) . (grad u_aux e1) + (sigma_aux grad q) . (grad u e1)
//   - (sigma : eps_aux) (e1 . grad q).
// q is the plateau function: 1 at the nodes within the domain radius, 0
// outside, interpolated by P1, so grad q lives on the ring of cells the
// circle crosses. With an inner radius r_in < r_out, q is the ring function
// of code_aster (R_INF, R_SUP) and MOOSE's geometric rings instead: 1 at the
// nodes within r_in, 0 beyond r_out, linear in the distance between, so
// grad q lives on the annulus. Lip tractions and body forces add terms that
// the caller integrates (python/cracklip/fracture/sif.py).
#pragma once

#include "quadrature/cell_quadrature_2d.h"
#include "geometry/crack_geometry_2d.h"
#include "enrichment/enrichment_layout.h"
#include "enrichment/tip_functions_2d.h"

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace cracklip
{

/// I (mode I, mode II) from values at points: points (n, 2), weights (n),
/// grad_q (n, 2), grad_u (n, 2, 2) of the field whose SIFs are sought,
/// sides (n) lip branch of the auxiliary field (+1 / -1 / 0).
std::array<double, 2> interaction_integral(const TipFrame& tip, double E, double nu,
                                           std::span<const double> points,
                                           std::span<const double> weights,
                                           std::span<const double> grad_q,
                                           std::span<const double> grad_u,
                                           std::span<const std::int8_t> sides);

/// q at a node `distance` from the tip: the plateau (1 below `radius`, else
/// 0) without an inner radius or with inner_radius >= radius; else the ring
/// function 1 up to inner_radius, 0 from radius on, linear between.
double domain_q(double distance, double radius, std::optional<double> inner_radius = std::nullopt);

/// Quadrature points of the ring of cells where grad q != 0, for the q of
/// `radius` (and `inner_radius`, see domain_q) around the tip, interpolated
/// by P1 from its nodal values (with `interior`, of every cell where q != 0,
/// for domain terms weighted by q such as body forces): cell (n), reference
/// (n, 2) and physical points (n, 2), weights (n), sides (n), q (n),
/// grad_q (n, 2).
struct DomainPoints
{
  std::vector<std::int32_t> cell;
  std::vector<double> ref, x, weight, q, grad_q;
  std::vector<std::int8_t> side;
};
DomainPoints compute_domain_points(std::span<const double> x, std::span<const std::int32_t> cells,
                                   const EnrichmentLayout& layout,
                                   std::span<const CrackGeometry* const> cracks,
                                   const TipFrame& tip, double radius,
                                   const QuadratureOptions& options, bool interior = false,
                                   std::optional<double> inner_radius = std::nullopt);

} // namespace cracklip
