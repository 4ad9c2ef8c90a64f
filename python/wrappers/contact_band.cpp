// Bindings: the multiplier spaces of a gathered crack band (python/cracklip/
// contact/band.py, issue 40) and a space restricted to a process's owned cells.
//
// Under MPI no process holds the whole crack, yet the stable (P1-) groups are
// a graph computation over all of it. contact/band.py gathers every
// process's lip pieces (cells by input index, their nodes by input index,
// level set, piece coordinates, which nodes are enriched) onto every
// process; the crack geometries are rebuilt here from those arrays, with
// only the fields the spaces read, and the unchanged
// create_multiplier_space(_3d) runs on them: the same groups on every
// process, and in serial (the same path on one process).
#include "array.h"

#include "contact/multiplier_space_2d.h"
#include "contact/multiplier_space_3d.h"
#include "enrichment/enrichment_selection.h"
#include <pybind11/stl.h>

namespace cracklip_wrappers
{
using namespace cracklip;

namespace
{
MultiplierKind kind_of(const std::string& kind)
{
  if (kind != "naive" and kind != "stable")
    throw std::invalid_argument("multiplier space must be 'stable' or 'naive', got '" + kind + "'");
  return kind == "naive" ? MultiplierKind::naive : MultiplierKind::stable;
}

/// The layout's enriched (crack, node) pairs and their kinds: all the spaces read of it.
EnrichmentLayout band_layout(int dim, std::size_t num_nodes, const carray<std::int32_t>& node,
                             const carray<std::int32_t>& crack, const carray<std::int8_t>& kind)
{
  EnrichmentLayout layout;
  layout.dim = dim;
  layout.num_std_nodes = static_cast<std::int32_t>(num_nodes);
  layout.node.assign(node.data(), node.data() + node.size());
  layout.crack.assign(crack.data(), crack.data() + crack.size());
  layout.kind.assign(kind.data(), kind.data() + kind.size());
  if (layout.crack.size() != layout.node.size() or layout.kind.size() != layout.node.size())
    throw std::invalid_argument("band layout: node, crack and kind must have one entry per pseudo-node");
  return layout;
}

/// phi of crack ic: row ic of phi (num_cracks, num_nodes).
std::vector<double> phi_row(const carray<double>& phi, std::size_t ic, std::size_t num_nodes)
{
  if (static_cast<std::size_t>(phi.size()) < (ic + 1) * num_nodes)
    throw std::invalid_argument("band space: phi must be (num_cracks, num_nodes)");
  return std::vector<double>(phi.data() + ic * num_nodes, phi.data() + (ic + 1) * num_nodes);
}

/// A copy of a space whose pieces are those on cells below num_cells (the
/// process's owned cells, first in its cell order).
template <class Space, class Pieces>
Space on_cells(const Space& space, Pieces Space::*pieces, std::int32_t num_cells)
{
  Space out = space;
  (out.*pieces).clear();
  for (const auto& p : space.*pieces)
    if (p.cell < num_cells)
      (out.*pieces).push_back(p);
  return out;
}
} // namespace

void declare_contact_band(py::module& m)
{
  m.def(
      "create_band_multiplier_space",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const carray<double>& phi,
         const carray<double>& tips, const carray<std::int32_t>& tip_offsets, const carray<std::int32_t>& cc_crack,
         const carray<std::int32_t>& cc_cell, const carray<std::int8_t>& cc_cls, const carray<double>& cc_segment,
         const carray<std::int32_t>& tc_crack, const carray<std::int32_t>& tc_cell, const carray<std::int32_t>& tc_tip,
         const carray<double>& tc_segment, const carray<std::int32_t>& layout_node,
         const carray<std::int32_t>& layout_crack, const carray<std::int8_t>& layout_kind, const std::string& kind,
         bool with_tip_segments)
      {
        require_columns(x, 2, "x (node coordinates)");
        require_columns(cells, 3, "cells (node indices per triangle)");
        const std::size_t nn = x.shape(0), nc = cells.shape(0), ncr = tip_offsets.size() - 1;
        std::vector<CrackGeometry> g(ncr);
        for (std::size_t ic = 0; ic < ncr; ++ic)
        {
          g[ic].phi = phi_row(phi, ic, nn);
          g[ic].tips.assign(tips.data() + 2 * tip_offsets.data()[ic], tips.data() + 2 * tip_offsets.data()[ic + 1]);
          g[ic].cell_class.assign(nc, static_cast<std::int8_t>(CellClass::plain));
          g[ic].crack_cell_index.assign(nc, -1);
          g[ic].tip_cell_index.assign(nc, -1);
        }
        for (py::ssize_t i = 0; i < cc_cell.size(); ++i) // (sorted by cell per crack)
        {
          CrackGeometry& gi = g.at(cc_crack.data()[i]);
          CrackCell c;
          c.cell = cc_cell.data()[i];
          c.cls = static_cast<CellClass>(cc_cls.data()[i]);
          c.owns_segment = true;
          std::copy(cc_segment.data() + 4 * i, cc_segment.data() + 4 * i + 4, c.segment.begin());
          gi.crack_cell_index.at(c.cell) = static_cast<std::int32_t>(gi.crack_cells.size());
          gi.cell_class[c.cell] = cc_cls.data()[i];
          gi.crack_cells.push_back(c);
        }
        for (py::ssize_t i = 0; i < tc_cell.size(); ++i)
        {
          CrackGeometry& gi = g.at(tc_crack.data()[i]);
          TipCell t;
          t.cell = tc_cell.data()[i];
          t.tip = tc_tip.data()[i];
          std::copy(tc_segment.data() + 4 * i, tc_segment.data() + 4 * i + 4, t.segment.begin());
          gi.tip_cell_index.at(t.cell) = static_cast<std::int32_t>(gi.tip_cells.size());
          gi.cell_class[t.cell] = static_cast<std::int8_t>(CellClass::tip);
          gi.tip_cells.push_back(t);
        }
        std::vector<const CrackGeometry*> cracks;
        for (const auto& gi : g)
          cracks.push_back(&gi);
        const EnrichmentLayout layout = band_layout(2, nn, layout_node, layout_crack, layout_kind);
        return create_multiplier_space(as_span(x), as_span(cells), cracks, layout, kind_of(kind), with_tip_segments);
      },
      py::arg("x"), py::arg("cells"), py::arg("phi"), py::arg("tips"), py::arg("tip_offsets"), py::arg("cc_crack"),
      py::arg("cc_cell"), py::arg("cc_cls"), py::arg("cc_segment"), py::arg("tc_crack"), py::arg("tc_cell"),
      py::arg("tc_tip"), py::arg("tc_segment"), py::arg("layout_node"), py::arg("layout_crack"),
      py::arg("layout_kind"), py::arg("kind"), py::arg("with_tip_segments"),
      "The 2D multiplier space of a gathered band: x (n, 2), cells (m, 3); phi (num_cracks, n); tips (k, 2) "
      "with tip_offsets (num_cracks + 1); the segment-owning crack cells (crack, cell, class, segment (., 4)) "
      "sorted by cell per crack; the tip cells (crack, cell, tip, segment (., 4)); the enriched (node, crack, "
      "kind) pseudo-nodes.");

  m.def(
      "create_band_multiplier_space_3d",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const carray<double>& phi, std::size_t num_cracks,
         const carray<std::int32_t>& cc_crack, const carray<std::int32_t>& cc_cell, const carray<std::int8_t>& cc_cls,
         const carray<std::int32_t>& facet_offsets, const carray<double>& facets, const carray<double>& facet_area,
         const carray<std::int32_t>& layout_node, const carray<std::int32_t>& layout_crack,
         const carray<std::int8_t>& layout_kind, const std::string& kind, bool with_front_pieces)
      {
        require_columns(x, 3, "x (node coordinates)");
        require_columns(cells, 4, "cells (node indices per tetrahedron)");
        const std::size_t nn = x.shape(0), nc = cells.shape(0);
        std::vector<CrackGeometry3D> g(num_cracks);
        for (std::size_t ic = 0; ic < num_cracks; ++ic)
        {
          g[ic].phi = phi_row(phi, ic, nn);
          g[ic].cell_class.assign(nc, static_cast<std::int8_t>(CellClass3D::plain));
          g[ic].crack_cell_index.assign(nc, -1);
        }
        for (py::ssize_t i = 0; i < cc_cell.size(); ++i) // (sorted by cell per crack)
        {
          CrackGeometry3D& gi = g.at(cc_crack.data()[i]);
          CrackCell3D c;
          c.cell = cc_cell.data()[i];
          c.cls = static_cast<CellClass3D>(cc_cls.data()[i]);
          const std::int32_t f0 = facet_offsets.data()[i], f1 = facet_offsets.data()[i + 1];
          c.facets.assign(facets.data() + 9 * f0, facets.data() + 9 * f1);
          c.facet_area.assign(facet_area.data() + f0, facet_area.data() + f1);
          gi.crack_cell_index.at(c.cell) = static_cast<std::int32_t>(gi.crack_cells.size());
          gi.cell_class[c.cell] = cc_cls.data()[i];
          gi.crack_cells.push_back(std::move(c));
        }
        std::vector<const CrackGeometry3D*> cracks;
        for (const auto& gi : g)
          cracks.push_back(&gi);
        const EnrichmentLayout layout = band_layout(3, nn, layout_node, layout_crack, layout_kind);
        return create_multiplier_space_3d(as_span(x), as_span(cells), cracks, layout, kind_of(kind), with_front_pieces);
      },
      py::arg("x"), py::arg("cells"), py::arg("phi"), py::arg("num_cracks"), py::arg("cc_crack"), py::arg("cc_cell"),
      py::arg("cc_cls"), py::arg("facet_offsets"), py::arg("facets"), py::arg("facet_area"), py::arg("layout_node"),
      py::arg("layout_crack"), py::arg("layout_kind"), py::arg("kind"), py::arg("with_front_pieces"),
      "The 3D multiplier space of a gathered band: x (n, 3), cells (m, 4); phi (num_cracks, n); the crack cells "
      "holding lip facets (crack, cell, class; facets (F, 9) reference coordinates and their areas, those of "
      "cell i at facet_offsets[i]:facet_offsets[i + 1]) sorted by cell per crack; the enriched (node, crack, kind) "
      "pseudo-nodes.");

  m.def(
      "multiplier_space_on_cells",
      [](const MultiplierSpace& s, std::int32_t num_cells) { return on_cells(s, &MultiplierSpace::segments, num_cells); },
      py::arg("space"), py::arg("num_cells"),
      "A copy of a 2D space whose segments are those on cells below num_cells (the owned cells).");
  m.def(
      "multiplier_space_on_cells",
      [](const MultiplierSpace3D& s, std::int32_t num_cells)
      { return on_cells(s, &MultiplierSpace3D::pieces, num_cells); },
      py::arg("space"), py::arg("num_cells"),
      "A copy of a 3D space whose pieces are those on cells below num_cells (the owned cells).");
}

} // namespace cracklip_wrappers
