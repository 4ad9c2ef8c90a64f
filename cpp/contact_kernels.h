// Crack-lip contact integrals (layer a): coupling B = int lambda [[v]].n,
// multiplier mass M = int lambda mu, pressure sampling, and the crack-lip
// term of the interaction integral.
#pragma once

#include "crack_geometry.h"
#include "enrichment.h"
#include "multiplier_space.h"
#include "tip_functions.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// Triplets (row, col, value); rows are full multipliers.
struct Triplets
{
  std::vector<std::int32_t> row, col;
  std::vector<double> value;
};

/// Quadrature points on every segment of the space: n Gauss points per
/// segment, in the variable t = tau^2 from an end that is a crack tip (the
/// jump of tip functions grows like sqrt(r) there, the auxiliary SIF fields
/// like 1/sqrt(r): both become polynomial in tau).
struct SegmentPoints
{
  std::vector<std::int32_t> segment; ///< (n) segment index
  std::vector<std::int32_t> cell;    ///< (n)
  std::vector<double> ref;           ///< (n, 2)
  std::vector<double> x;             ///< (n, 2)
  std::vector<double> weight;        ///< (n) length measure
  std::vector<double> normal;        ///< (n, 2) unit normal pointing to the + side
  /// COO of multiplier basis values: point, full multiplier, value.
  std::vector<std::int32_t> entry_point, entry_mult;
  std::vector<double> entry_value;
};
SegmentPoints compute_segment_points(std::span<const double> x, std::span<const std::int32_t> cells,
                                     std::span<const CrackGeometry* const> cracks,
                                     const MultiplierSpace& space, int n);

/// B (full multipliers x dofs) with [[v]] . n from the Heaviside and tip
/// functions (standard functions do not jump), and M (full x full).
void assemble_coupling(std::span<const double> x, std::span<const std::int32_t> cells,
                       const EnrichmentLayout& layout, std::span<const CrackGeometry* const> cracks,
                       const MultiplierSpace& space, int n, Triplets& B, Triplets& M);

/// Crack-lip term of the interaction integral for a frictionless pressure
/// p = -lambda on both lips (lambda_full: full multiplier values):
///   I_lip,m = - int_crack p q n . [[ d u_aux,m / d x_1 ]] ds   (m = I, II)
/// (n towards the + side): the lip tractions p n (+ lip) and -p n (- lip)
/// times d u_aux / d x_1, with the sign of the domain form. Without it a
/// pressed crack shows K_I < 0 (the paper's block test).
/// with the plateau q of `radius` around the tip.
std::array<double, 2> lip_interaction_integral(std::span<const double> x,
                                               std::span<const std::int32_t> cells,
                                               std::span<const CrackGeometry* const> cracks,
                                               const MultiplierSpace& space,
                                               std::span<const double> lambda_full,
                                               const TipFrame& tip, std::int32_t crack, double radius,
                                               double E, double nu, int n);

} // namespace cracklip
