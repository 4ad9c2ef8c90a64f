// Crack-lip contact integrals on tetrahedra (layer a): the 3D counterpart of
// contact_kernels_2d. On the lip pieces of a multiplier space
// (multiplier_space_3d.h):
//   B  = int lambda_k [[v_j]] . n         (normal coupling)
//   Bt = int lambda_k [[v_j]] . t_c, c = 1, 2 (tangential coupling)
//   M  = int lambda_k lambda_l            (multiplier mass)
// over the lip facets with the rules of crack_points_3d (Gauss away from the
// front, collapsed with rho = tau^2 on the facets touching it: the jump of
// the front functions grows like sqrt(r) there and becomes polynomial).
// [[v]] = v(+ lip) - v(- lip); n the facet's unit normal to the + side.
//
// Tangent basis: t1 = the part of a per-crack reference direction a
// tangent to the facet, normalised, t2 = n x t1 ((t1, t2, n)
// right-handed), at every quadrature point. For a planar crack the basis
// is constant, so a uniform shear traction is exactly representable by
// the multipliers; it turns smoothly with a curved crack. The default a is
// the coordinate axis least aligned with the crack's mean normal (the area
// weighted sum of its facet normals). Where a is within 1e-3 of the normal
// (a crack folding back on itself), the axis least aligned with the local
// normal replaces it.
#pragma once

#include "assembly/matrix_sink.h"
#include "contact/multiplier_space_3d.h"
#include "enrichment/enrichment_layout.h"
#include "geometry/crack_geometry_3d.h"

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// The lip rule: n points per direction (Gauss of degree 2 n - 1 on facets
/// away from the front, n x n collapsed points on facets touching it); with
/// signed_point_rule the facets touching the front at a vertex take the
/// signed decomposition, exact for sqrt(r) and r^(-1/2) times polynomials
/// (else the plain fan from that vertex); near_factor: facets within that
/// many diameters of their cell's front line take the near-front signed
/// fans (0: never). compute_lip_points_3d's arguments. The defaults
/// integrate the sqrt(r) jumps of a penny's front functions (a / h = 3) to
/// 6e-11 of B's largest entry (n = 4: 5e-3; near_factor 0, Gauss on the
/// facets near the front that do not touch it: 3e-6; near_factor 2, longer
/// signed fans: 9e-10). M is exact with any of them (polynomial).
struct LipRule3D
{
  int n = 6;
  double near_factor = 1.0;
  bool signed_point_rule = true;
};

/// Quadrature points on every piece of the space, with the multiplier
/// values and the local bases.
struct ContactPoints3D
{
  std::vector<std::int32_t> piece;  ///< (n) index into space.pieces
  std::vector<std::int32_t> cell;   ///< (n)
  std::vector<double> ref;          ///< (n, 3) reference coordinates in the cell
  std::vector<double> x;            ///< (n, 3) physical points
  std::vector<double> weight;       ///< (n) area measure (may be negative on signed pieces)
  std::vector<double> normal;       ///< (n, 3) unit normal to the + side
  std::vector<double> t1, t2;       ///< (n, 3) unit tangents, (t1, t2, normal) right-handed
  /// COO of multiplier basis values: point, full multiplier, value (points ascending).
  std::vector<std::int32_t> entry_point, entry_mult;
  std::vector<double> entry_value;
};

/// The default tangent reference of a crack (file header): the coordinate
/// axis least aligned with the area-weighted mean of its facet normals
/// (ties within 1e-12 of its length: the first axis; a crack normal to z
/// gets t1 = e_x, t2 = e_y).
Point3 default_tangent_reference(const CrackGeometry3D& g);

/// The tangent basis at a point with unit normal n from the reference a
/// (file header).
void tangent_basis(const Point3& n, const Point3& a, Point3& t1, Point3& t2);

/// tangent_reference: (num_cracks, 3) reference directions, or empty for
/// the defaults.
ContactPoints3D compute_contact_points_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                          std::span<const CrackGeometry3D* const> cracks,
                                          const MultiplierSpace3D& space, const LipRule3D& rule,
                                          std::span<const double> tangent_reference = {});

/// Where the contact integrals go: blocks with rows = full multipliers and
/// columns = global scalar dofs (normal, tangent1, tangent2), or rows and
/// columns = full multipliers (mass). An empty tangent sink is skipped.
struct ContactSinks3D
{
  MatrixSink normal, mass, tangent1, tangent2;
};

/// B, M and (with non-empty tangent sinks) Bt1, Bt2 of the space (file
/// header), one block per cell and set of multipliers (its consecutive
/// quadrature points summed): the multipliers non-zero there times the
/// enriched dofs of the cell (standard functions do not jump).
void assemble_coupling_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                          const EnrichmentLayout& layout, std::span<const CrackGeometry3D* const> cracks,
                          const MultiplierSpace3D& space, const LipRule3D& rule, const ContactSinks3D& sinks,
                          std::span<const double> tangent_reference = {});

/// Values of a full multiplier field (lambda_full, (num_full)) at points of
/// crack `crack` given by cell (n) and reference coordinates (n, 3): the
/// multipliers active on the crack's piece in that cell (P1, or a front
/// cell's P0); 0 in a cell without a piece of the space.
std::vector<double> evaluate_multipliers_3d(const MultiplierSpace3D& space, std::int32_t crack,
                                            std::span<const std::int32_t> point_cells, std::span<const double> ref,
                                            std::span<const double> lambda_full);

} // namespace cracklip
