// Bindings: sparsity, enriched stiffness (into PETSc or COO), facet basis.
#include "array.h"

#include "assembly/dolfinx_glue.h"
#include "assembly/enriched_kernels_2d.h"
#include "solvers/rescaling.h"
#include <pybind11/stl.h>
#include "assembly/sparsity.h"

namespace cracklip_wrappers
{
using namespace cracklip;
using Cracks = std::vector<const CrackGeometry*>;

void declare_assembly(py::module& m)
{
  py::enum_<TipQuadrature>(m, "TipQuadrature")
      .value("collapsed", TipQuadrature::collapsed)
      .value("gauss", TipQuadrature::gauss);
  py::class_<QuadratureOptions>(m, "QuadratureOptions", "Quadrature rules of the enriched kernels")
      .def(py::init<>())
      .def_readwrite("degree", &QuadratureOptions::degree)
      .def_readwrite("tip_rule", &QuadratureOptions::tip_rule)
      .def_readwrite("tip_radial", &QuadratureOptions::tip_radial)
      .def_readwrite("tip_angular", &QuadratureOptions::tip_angular)
      .def_readwrite("tip_max_angle", &QuadratureOptions::tip_max_angle)
      .def_readwrite("tip_degree", &QuadratureOptions::tip_degree);

  m.def(
      "create_sparsity",
      [](const carray<std::int32_t>& cells, const EnrichmentLayout& layout)
      {
        CSR s = expand_blocks(create_block_sparsity(as_span(cells), 3, layout.num_std_nodes, layout.num_enriched(), layout), 2);
        return py::make_tuple(as_pyarray(std::move(s.offsets)), as_pyarray(std::move(s.indices)));
      },
      py::arg("cells"), py::arg("layout"),
      "Scalar CSR (indptr, indices) of the enriched stiffness, block size 2.");

  m.def(
      "assemble_enriched_stiffness_petsc",
      [](std::uintptr_t mat_handle, const carray<double>& x, const carray<std::int32_t>& cells,
         const EnrichmentLayout& layout, const Cracks& cracks, double E, double nu,
         const QuadratureOptions& options)
      {
        const MatrixSink sink = petsc_add_sink(reinterpret_cast<Mat>(mat_handle));
        return assemble_enriched_stiffness(sink, as_span(x), as_span(cells), layout, cracks, E, nu, options);
      },
      py::arg("mat_handle"), py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"),
      py::arg("E"), py::arg("nu"), py::arg("options"),
      "Add the enriched blocks into a PETSc Mat (petsc4py Mat.handle). Returns the number "
      "of cells integrated.");

  m.def(
      "assemble_enriched_stiffness_coo",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout& layout,
         const Cracks& cracks, double E, double nu, const QuadratureOptions& options)
      {
        Triplets coo;
        const MatrixSink sink = coo_sink(coo);
        const auto n = assemble_enriched_stiffness(sink, as_span(x), as_span(cells), layout, cracks, E, nu, options);
        return py::make_tuple(as_pyarray(std::move(coo.row)), as_pyarray(std::move(coo.col)),
                              as_pyarray(std::move(coo.value)), n);
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("E"),
      py::arg("nu"), py::arg("options"),
      "Enriched blocks as COO (rows, cols, values, num_cells); for tests.");

  m.def(
      "compute_facet_basis",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout& layout,
         const Cracks& cracks, const carray<std::int32_t>& facet_cells,
         const carray<std::int32_t>& facet_local, int degree)
      {
        FacetBasis fb = compute_facet_basis(as_span(x), as_span(cells), layout, cracks,
                                            as_span(facet_cells), as_span(facet_local), degree);
        const py::ssize_t n = fb.weights.size();
        py::dict d;
        d["points"] = as_pyarray(std::move(fb.points), {n, 2});
        d["weights"] = as_pyarray(std::move(fb.weights));
        d["entry_point"] = as_pyarray(std::move(fb.entry_point));
        const py::ssize_t ne = fb.entry_dof.size();
        d["entry_dof"] = as_pyarray(std::move(fb.entry_dof));
        d["entry_value"] = as_pyarray(std::move(fb.entry_value), {ne, 2});
        return d;
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("facet_cells"),
      py::arg("facet_local"), py::arg("degree"),
      "Quadrature points on boundary facets and the basis values there (COO by point).");

  m.def(
      "nodal_block_transform",
      [](const carray<std::int32_t>& indptr, const carray<std::int32_t>& indices, const carray<double>& data,
         const carray<std::int32_t>& group_offsets, const carray<std::int32_t>& group_dofs)
      {
        BlockTransform T = nodal_block_transform(as_span(indptr), as_span(indices), as_span(data),
                                                 as_span(group_offsets), as_span(group_dofs));
        return py::make_tuple(as_pyarray(std::move(T.rows)), as_pyarray(std::move(T.cols)),
                              as_pyarray(std::move(T.values)));
      },
      py::arg("indptr"), py::arg("indices"), py::arg("data"), py::arg("group_offsets"), py::arg("group_dofs"),
      "COO (rows, cols, values) of the block rescaling T: T^T K T has identity blocks on the groups "
      "and a unit diagonal elsewhere.");
}

} // namespace cracklip_wrappers
