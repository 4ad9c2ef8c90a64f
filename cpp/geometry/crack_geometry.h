// The crack geometry of a dimension (layer a): a curve with tips on
// triangles (crack_geometry_2d.h) or a surface with fronts on tetrahedra
// (crack_geometry_3d.h), and what both answer alike, so that code written
// once for any dimension (template <int dim>) can ask it.
//
// Both classify every cell with the same codes: 0 plain, 1 cut, 2 the crack
// along an edge (2D) / a face (3D), 3 tip (2D) / front (3D), 4 extension;
// cell_side is the side of a cell that lies on one side of the crack (0 for
// cells the crack crosses and for extension cells), phi the normal level set
// at the nodes.
#pragma once

#include "geometry/crack_geometry_2d.h"
#include "geometry/crack_geometry_3d.h"

#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

namespace cracklip
{

/// CrackGeometry (dim 2) or CrackGeometry3D (dim 3).
template <int dim>
using CrackGeometryOf = std::conditional_t<dim == 2, CrackGeometry, CrackGeometry3D>;

/// The crack crosses cell c: cut, along an edge / a face, or holding a tip
/// / the front (classes 1, 2, 3).
template <typename Crack>
bool crosses(const Crack& g, std::int32_t c)
{
  const std::int8_t cls = g.cell_class[c];
  return cls == 1 or cls == 2 or cls == 3;
}

/// The crack (index) that splits cell c into sub-cells, or -1: the one whose
/// crack_cells hold c (cut and edge cells in 2D; cut, face and front cells
/// in 3D).
template <typename Crack>
int crossing_crack(std::span<const Crack* const> cracks, std::int32_t c)
{
  for (std::size_t ic = 0; ic < cracks.size(); ++ic)
    if (cracks[ic]->crack_cell_index[c] >= 0)
      return static_cast<int>(ic);
  return -1;
}

/// Side of every crack at a point of cell c. For the crack that crosses the
/// cell (if any) the side is `crossing_side` (the point's sub-cell); every
/// other crack has a constant side on the cell (0 on its extension cells).
template <typename Crack>
void region_sides(std::span<const Crack* const> cracks, std::int32_t c, int crossing_side, std::vector<int>& side)
{
  side.resize(cracks.size());
  for (std::size_t ic = 0; ic < cracks.size(); ++ic)
    side[ic] = crosses(*cracks[ic], c) ? crossing_side : cracks[ic]->cell_side[c];
}

} // namespace cracklip
