// What a crack's geometry decides about its enrichment (layer a): the part
// of create_enrichment_layout that differs between a curve with tips (2D)
// and a surface with fronts (3D). The rest (one crack per cell, the
// selection rules, the numbering, the enriched cells) is the same in every
// dimension (enrichment_layout.cpp).
//
// CrackEnrichment<dim>, for crack ic:
//   - registers its tips (2D: frames) / front pieces in the layout
//     (tip_crack, tip_local) and finds its core nodes: within the radius of
//     a tip / the front, and the nodes of the cells holding it;
//   - selection(): the selection input with the geometric predicates
//     (distance to the crack's line / plane; in 3D which cut cells open a
//     node's Heaviside function and whether the ramp leaves it a share of
//     the jump);
//   - shift(): the values of the tip functions of a pseudo-node at its base
//     node (2D: in the tip's frame; 3D: from the node's level sets and the
//     frame of its nearest front point);
//   - complete(): after every crack (3D: the nodal frames the front functions
//     interpolate).
#pragma once

#include "enrichment/enrichment_layout.h"
#include "enrichment/enrichment_selection.h"
#include "geometry/crack_front_3d.h"

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace cracklip
{

/// What every dimension's part holds: the crack's tips (front pieces),
/// each node's core tip (-1 for others) and the selection input made of
/// them.
class CrackEnrichmentBase
{
public:
  CrackEnrichmentBase() = default;
  CrackEnrichmentBase(const CrackEnrichmentBase&) = delete;
  const SelectionInput& selection() const { return input_; }

protected:
  std::vector<std::int32_t> core_tip_, tips_;
  SelectionInput input_;
};

template <int dim>
class CrackEnrichment;

/// A curve with tips on triangles (crack_enrichment_2d.cpp).
template <>
class CrackEnrichment<2> : public CrackEnrichmentBase
{
public:
  CrackEnrichment(std::span<const double> x, std::span<const std::int32_t> cells, const CrackGeometry& g,
                  std::int32_t ic, const EnrichmentOptions& options, EnrichmentLayout& layout);
  /// The dim * dim shift values of a tip pseudo-node at its base node.
  void shift(const PseudoNode& pn, int side, std::span<double> out) const;
  static void complete(EnrichmentLayout&, std::span<const double>, std::span<const std::int32_t>,
                       std::span<const CrackGeometry* const>)
  {
  }

private:
  std::span<const double> x_;
  const EnrichmentLayout& layout_;
};

/// A surface with fronts on tetrahedra (crack_enrichment_3d.cpp).
template <>
class CrackEnrichment<3> : public CrackEnrichmentBase
{
public:
  CrackEnrichment(std::span<const double> x, std::span<const std::int32_t> cells, const CrackGeometry3D& g,
                  std::int32_t ic, const EnrichmentOptions& options, EnrichmentLayout& layout);
  void shift(const PseudoNode& pn, int side, std::span<double> out) const;
  /// The nodal frames of every node of every cell carrying front functions.
  static void complete(EnrichmentLayout& layout, std::span<const double> x, std::span<const std::int32_t> cells,
                       std::span<const CrackGeometry3D* const> cracks);

private:
  /// The shares of the jump the ramp leaves each node's Heaviside function
  /// (keep_heaviside), measured when the selection first asks.
  void measure_shares(std::span<const std::int8_t> is_core);

  std::span<const double> x_;
  std::span<const std::int32_t> cells_;
  const CrackGeometry3D& g_;
  const EnrichmentOptions& options_;
  std::unique_ptr<FrontLocator> locator_;
  std::vector<double> bare_, ramped_, jump_share_;
};

} // namespace cracklip
