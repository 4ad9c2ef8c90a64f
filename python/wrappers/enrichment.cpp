// Bindings: the enrichment layout (2D or 3D) and the sparsity of its
// enriched stiffness.
#include "array.h"
#include "dimension.h"

#include "assembly/sparsity.h"
#include "enrichment/enrichment_layout.h"

#include <pybind11/stl.h>

namespace cracklip_wrappers
{
using namespace cracklip;

namespace
{
template <typename T>
py::array_t<T> view(const std::vector<T>& v)
{
  return carray<T>(static_cast<py::ssize_t>(v.size()), v.data());
}

TipEnrichment tip_enrichment(const std::string& tip)
{
  if (tip == "none")
    return TipEnrichment::none;
  if (tip == "scalar")
    return TipEnrichment::scalar;
  if (tip == "vector")
    return TipEnrichment::vector;
  throw std::invalid_argument("tip enrichment must be 'none', 'scalar' or 'vector', got '" + tip + "'");
}
} // namespace

void declare_enrichment(py::module& m)
{
  using L = EnrichmentLayout;
  py::class_<L>(m, "EnrichmentLayout", "Enriched pseudo-nodes and enriched cells (triangles or tetrahedra)")
      .def_readonly("dim", &L::dim, "Space dimension: 2 or 3 (dofs per node)")
      .def_property_readonly("num_std_nodes", [](const L& l) { return l.num_std_nodes; })
      .def_property_readonly("num_enriched", &L::num_enriched)
      .def_property_readonly("num_nodes_total", &L::num_nodes_total)
      .def_property_readonly("node", [](const L& l) { return view(l.node); })
      .def_property_readonly("crack", [](const L& l) { return view(l.crack); })
      .def_property_readonly("kind", [](const L& l) { return view(l.kind); })
      .def_property_readonly("function", [](const L& l) { return view(l.function); })
      .def_property_readonly("tip", [](const L& l) { return view(l.tip); },
                             "Per pseudo-node: its tip (2D) / front piece (3D), -1 for Heaviside")
      .def_property_readonly("core", [](const L& l) { return view(l.core); })
      .def_property_readonly("node_side", [](const L& l) { return view(l.node_side); })
      .def_property_readonly("tip_crack", [](const L& l) { return view(l.tip_crack); })
      .def_property_readonly("tip_local", [](const L& l) { return view(l.tip_local); })
      .def_property_readonly("cells", [](const L& l) { return view(l.cells); })
      .def_property_readonly("cell_offsets", [](const L& l) { return view(l.cell_offsets); })
      .def_property_readonly("cell_enr", [](const L& l) { return view(l.cell_enr); })
      .def_property_readonly("frame_node", [](const L& l) { return view(l.frame_node); })
      .def("with_cells_below", &with_cells_below, py::arg("num_cells"),
           "The same layout with only the enriched cells below num_cells (a process's owned cells under MPI): "
           "the pseudo-nodes and their numbering are kept");

  m.def(
      "create_enrichment_layout",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const py::sequence& cracks, const std::string& tip,
         double radius, double kappa, bool corrected)
      {
        EnrichmentOptions o;
        o.tip = tip_enrichment(tip);
        o.radius = radius;
        o.kappa = kappa;
        o.corrected = corrected;
        return with_dimension(mesh_dimension(x, cells),
                              [&](auto d)
                              {
                                return create_enrichment_layout(as_span(x), as_span(cells),
                                                                cracks_of<decltype(d)::value>(cracks), o);
                              });
      },
      py::arg("x"), py::arg("cells"), py::arg("cracks"), py::arg("tip") = "none", py::arg("radius") = 0.0,
      py::arg("kappa") = 1.8, py::arg("corrected") = true,
      "Heaviside and tip (2D) / front (3D) enrichment of every crack on a triangle or tetrahedral mesh "
      "(x (n, dim), cells (m, dim + 1)).");

  m.def(
      "create_sparsity",
      [](const carray<std::int32_t>& cells, const EnrichmentLayout& layout)
      {
        const int dim = layout.dim;
        require_columns(cells, dim + 1, "cells (node indices per cell)");
        CSR s = expand_blocks(
            create_block_sparsity(as_span(cells), dim + 1, layout.num_std_nodes, layout.num_enriched(), layout), dim);
        return py::make_tuple(as_pyarray(std::move(s.offsets)), as_pyarray(std::move(s.indices)));
      },
      py::arg("cells"), py::arg("layout"),
      "Scalar CSR (indptr, indices) of the enriched stiffness, block size = the dimension.");
}

} // namespace cracklip_wrappers
