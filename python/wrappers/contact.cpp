// Bindings: multiplier spaces, contact coupling, lip term of the interaction integral.
#include "array.h"

#include "contact/contact_kernels_2d.h"
#include "contact/multiplier_space_2d.h"
#include "solvers/saddle_matrix.h"
#include <pybind11/stl.h>

namespace cracklip_wrappers
{
using namespace cracklip;
using Cracks = std::vector<const CrackGeometry*>;

void declare_contact(py::module& m)
{
  py::class_<MultiplierSpace>(m, "MultiplierSpace", "Lagrange multipliers on the crack")
      .def_property_readonly("kind", [](const MultiplierSpace& s) { return s.kind == MultiplierKind::naive ? "naive" : "stable"; })
      .def_property_readonly("num_full", &MultiplierSpace::num_full)
      .def_property_readonly("num_reduced", [](const MultiplierSpace& s) { return s.num_reduced; })
      .def_property_readonly("num_segments", [](const MultiplierSpace& s) { return s.segments.size(); })
      .def_property_readonly("full_to_reduced", [](const MultiplierSpace& s)
                             { return carray<std::int32_t>(s.full_to_reduced.size(), s.full_to_reduced.data()); })
      .def_property_readonly("full_node", [](const MultiplierSpace& s)
                             { return carray<std::int32_t>(s.full_node.size(), s.full_node.data()); })
      .def_property_readonly("full_cell", [](const MultiplierSpace& s)
                             { return carray<std::int32_t>(s.full_cell.size(), s.full_cell.data()); })
      .def_property_readonly("full_crack", [](const MultiplierSpace& s)
                             { return carray<std::int32_t>(s.full_crack.size(), s.full_crack.data()); })
      .def_property_readonly("segment_crack", [](const MultiplierSpace& s)
                             {
                               std::vector<std::int32_t> c;
                               for (const auto& seg : s.segments)
                                 c.push_back(seg.crack);
                               return as_pyarray(std::move(c));
                             })
      .def_property_readonly("vital_edges", [](const MultiplierSpace& s)
                             {
                               return carray<std::int32_t>({py::ssize_t(s.vital_edges.size() / 2), py::ssize_t(2)},
                                                           s.vital_edges.data());
                             });

  m.def(
      "create_multiplier_space",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const Cracks& cracks,
         const EnrichmentLayout& layout, const std::string& kind, bool with_tip_segments)
      {
        if (kind != "naive" and kind != "stable")
          throw std::invalid_argument("multiplier space must be 'stable' or 'naive', got '" + kind + "'");
        return create_multiplier_space(as_span(x), as_span(cells), cracks, layout,
                                       kind == "naive" ? MultiplierKind::naive : MultiplierKind::stable,
                                       with_tip_segments);
      },
      py::arg("x"), py::arg("cells"), py::arg("cracks"), py::arg("layout"), py::arg("kind"),
      py::arg("with_tip_segments"));

  m.def(
      "assemble_coupling",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout& layout,
         const Cracks& cracks, const MultiplierSpace& space, int n, bool tangential)
      {
        Triplets B, M, Bt;
        assemble_coupling(as_span(x), as_span(cells), layout, cracks, space, n, B, M,
                          tangential ? &Bt : nullptr);
        auto out = py::make_tuple(as_pyarray(std::move(B.row)), as_pyarray(std::move(B.col)),
                                  as_pyarray(std::move(B.value)), as_pyarray(std::move(M.row)),
                                  as_pyarray(std::move(M.col)), as_pyarray(std::move(M.value)));
        if (!tangential)
          return out;
        return py::tuple(out + py::make_tuple(as_pyarray(std::move(Bt.row)), as_pyarray(std::move(Bt.col)),
                                              as_pyarray(std::move(Bt.value))));
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("space"), py::arg("n"),
      py::arg("tangential") = false,
      "Coupling B (full multipliers x dofs) and multiplier mass M as COO triplets (B rows, cols, "
      "values, M rows, cols, values); with tangential, then the tangential coupling Bt's triplets.");

  m.def(
      "compute_segment_points",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const Cracks& cracks,
         const MultiplierSpace& space, int n)
      {
        SegmentPoints s = compute_segment_points(as_span(x), as_span(cells), cracks, space, n);
        const py::ssize_t np_ = s.weight.size();
        py::dict d;
        d["segment"] = as_pyarray(std::move(s.segment));
        d["cell"] = as_pyarray(std::move(s.cell));
        d["ref"] = as_pyarray(std::move(s.ref), {np_, 2});
        d["x"] = as_pyarray(std::move(s.x), {np_, 2});
        d["weight"] = as_pyarray(std::move(s.weight));
        d["normal"] = as_pyarray(std::move(s.normal), {np_, 2});
        d["entry_point"] = as_pyarray(std::move(s.entry_point));
        d["entry_mult"] = as_pyarray(std::move(s.entry_mult));
        d["entry_value"] = as_pyarray(std::move(s.entry_value));
        return d;
      },
      py::arg("x"), py::arg("cells"), py::arg("cracks"), py::arg("space"), py::arg("n"));

  m.def(
      "evaluate_multipliers",
      [](const MultiplierSpace& space, std::int32_t crack, const carray<std::int32_t>& point_cells,
         const carray<double>& ref, const carray<double>& lambda_full)
      {
        return as_pyarray(evaluate_multipliers(space, crack, as_span(point_cells), as_span(ref),
                                               as_span(lambda_full)));
      },
      py::arg("space"), py::arg("crack"), py::arg("point_cells"), py::arg("ref"), py::arg("lambda_full"),
      "Values (n) of a full multiplier field at points (cell, reference) of a crack.");

  m.def(
      "saddle_csr",
      [](const carray<std::int32_t>& k_indptr, const carray<std::int32_t>& k_indices,
         const carray<double>& k_data, const carray<std::int32_t>& b_indptr,
         const carray<std::int32_t>& b_indices, const carray<double>& b_data,
         const carray<std::int8_t>& active)
      {
        SaddleCsr s = saddle_csr(as_span(k_indptr), as_span(k_indices), as_span(k_data), as_span(b_indptr),
                                 as_span(b_indices), as_span(b_data), as_span(active));
        return py::make_tuple(as_pyarray(std::move(s.indptr)), as_pyarray(std::move(s.indices)),
                              as_pyarray(std::move(s.data)));
      },
      py::arg("k_indptr"), py::arg("k_indices"), py::arg("k_data"), py::arg("b_indptr"),
      py::arg("b_indices"), py::arg("b_data"), py::arg("active"),
      "CSR (indptr, indices, data) of [K B_a^T; B_a D] (cpp/solvers/saddle_matrix.h).");
}

} // namespace cracklip_wrappers
