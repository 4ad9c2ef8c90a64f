// Crack-lip contact integrals (layer a): coupling B = int lambda [[v]].n,
// multiplier mass M = int lambda mu, and multiplier values at crack points.
#pragma once

#include "assembly/matrix_sink.h"
#include "geometry/crack_geometry_2d.h"
#include "enrichment/enrichment_layout.h"
#include "contact/multiplier_space_2d.h"
#include "enrichment/tip_functions_2d.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{


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
/// functions (standard functions do not jump), and M (full x full); with Bt,
/// also the tangential coupling [[v]] . t, t = n turned by -90 degrees (the
/// crack's direction: slip > 0 when the + lip moves along t).
void assemble_coupling(std::span<const double> x, std::span<const std::int32_t> cells,
                       const EnrichmentLayout& layout, std::span<const CrackGeometry* const> cracks,
                       const MultiplierSpace& space, int n, Triplets& B, Triplets& M,
                       Triplets* Bt = nullptr);

/// Values of a full multiplier field (lambda_full, (num_full)) at points of
/// crack `crack` given by cell (n) and reference coordinates (n, 2): the
/// multipliers active on the crack's segment in that cell (P1 or the tip
/// cell's P0); 0 in a cell without a segment of the space.
std::vector<double> evaluate_multipliers(const MultiplierSpace& space, std::int32_t crack,
                                         std::span<const std::int32_t> point_cells,
                                         std::span<const double> ref,
                                         std::span<const double> lambda_full);

} // namespace cracklip
