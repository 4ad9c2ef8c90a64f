// Bindings: quadrature options (tip rules in 2D, front rules in 3D), the
// enriched stiffness (into PETSc or COO) and its quadrature points, block
// rescaling.
#include "array.h"
#include "dimension.h"

#include "assembly/dolfinx_glue.h"
#include "assembly/enriched_stiffness.h"
#include "solvers/rescaling.h"

#include <pybind11/stl.h>

namespace cracklip_wrappers
{
using namespace cracklip;

namespace
{
/// Stiffness of the enriched cells through a sink, in the mesh's dimension.
std::int32_t assemble(const MatrixSink& sink, const carray<double>& x, const carray<std::int32_t>& cells,
                      const EnrichmentLayout& layout, const py::sequence& cracks, double E, double nu,
                      const py::object& options)
{
  return with_dimension(mesh_dimension(x, cells),
                        [&](auto d)
                        {
                          constexpr int dim = decltype(d)::value;
                          return assemble_enriched_stiffness<dim>(sink, as_span(x), as_span(cells), layout,
                                                                  cracks_of<dim>(cracks), E, nu,
                                                                  options_of<dim>(options));
                        });
}
} // namespace

void declare_assembly(py::module& m)
{
  py::enum_<TipQuadrature>(m, "TipQuadrature")
      .value("collapsed", TipQuadrature::collapsed)
      .value("gauss", TipQuadrature::gauss);
  py::class_<QuadratureOptions>(m, "QuadratureOptions", "Quadrature rules of the enriched kernels on triangles")
      .def(py::init<>())
      .def_readwrite("degree", &QuadratureOptions::degree)
      .def_readwrite("tip_rule", &QuadratureOptions::tip_rule)
      .def_readwrite("tip_radial", &QuadratureOptions::tip_radial)
      .def_readwrite("tip_angular", &QuadratureOptions::tip_angular)
      .def_readwrite("tip_max_angle", &QuadratureOptions::tip_max_angle)
      .def_readwrite("tip_degree", &QuadratureOptions::tip_degree);
  py::class_<QuadratureOptions3D>(m, "QuadratureOptions3D", "Quadrature rules of the enriched kernels on tetrahedra")
      .def(py::init<>())
      .def_readwrite("degree", &QuadratureOptions3D::degree)
      .def_property(
          "front_rule",
          [](const QuadratureOptions3D& o) { return o.front_rule == FrontQuadrature::collapsed ? "collapsed" : "gauss"; },
          [](QuadratureOptions3D& o, const std::string& v)
          {
            if (v != "collapsed" and v != "gauss")
              throw std::invalid_argument("front_rule must be 'collapsed' or 'gauss', got '" + v + "'");
            o.front_rule = v == "collapsed" ? FrontQuadrature::collapsed : FrontQuadrature::gauss;
          })
      .def_readwrite("front_radial", &QuadratureOptions3D::front_radial)
      .def_readwrite("front_angular", &QuadratureOptions3D::front_angular)
      .def_readwrite("front_axial", &QuadratureOptions3D::front_axial)
      .def_readwrite("front_degree", &QuadratureOptions3D::front_degree)
      .def_readwrite("near_factor", &QuadratureOptions3D::near_factor)
      .def_readwrite("far_degree", &QuadratureOptions3D::far_degree)
      .def_readwrite("signed_point_rule", &QuadratureOptions3D::signed_point_rule)
      .def_readwrite("front_functions", &QuadratureOptions3D::front_functions);

  m.def(
      "assemble_enriched_stiffness_petsc",
      [](std::uintptr_t mat_handle, const carray<double>& x, const carray<std::int32_t>& cells,
         const EnrichmentLayout& layout, const py::sequence& cracks, double E, double nu, const py::object& options,
         bool local)
      {
        const Mat A = reinterpret_cast<Mat>(mat_handle);
        return assemble(local ? petsc_add_local_sink(A) : petsc_add_sink(A), x, cells, layout, cracks, E, nu, options);
      },
      py::arg("mat_handle"), py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("E"),
      py::arg("nu"), py::arg("options"), py::arg("local") = false,
      "Add the enriched cells' stiffness (standard-standard block excluded) into a PETSc Mat (petsc4py Mat.handle). "
      "Returns the number of cells integrated. options: QuadratureOptions (2D) or QuadratureOptions3D. local: "
      "the kernels' indices are local ones, mapped by the matrix's local-to-global map (MatSetValuesLocal; MPI).");

  m.def(
      "assemble_enriched_stiffness_coo",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout& layout,
         const py::sequence& cracks, double E, double nu, const py::object& options)
      {
        Triplets coo;
        const auto n = assemble(coo_sink(coo), x, cells, layout, cracks, E, nu, options);
        return py::make_tuple(as_pyarray(std::move(coo.row)), as_pyarray(std::move(coo.col)),
                              as_pyarray(std::move(coo.value)), n);
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("E"), py::arg("nu"),
      py::arg("options"), "The enriched stiffness as COO triplets (rows, cols, values, cells integrated).");

  m.def(
      "compute_enriched_cell_quadrature",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout& layout,
         const py::sequence& cracks, const carray<std::int32_t>& cell_list, const py::object& options)
      {
        return with_dimension(
            mesh_dimension(x, cells),
            [&](auto d)
            {
              constexpr int dim = decltype(d)::value;
              const auto cr = cracks_of<dim>(cracks);
              const auto& o = options_of<dim>(options);
              std::vector<std::int32_t> pc;
              std::vector<double> ref, weight;
              std::vector<std::int8_t> side;
              CellQuadratureOf<dim> q;
              for (const std::int32_t c : as_span(cell_list))
              {
                compute_enriched_cell_quadrature(as_span(x), as_span(cells), layout, cr, c, o, q);
                pc.insert(pc.end(), q.size(), c);
                ref.insert(ref.end(), q.ref.begin(), q.ref.end());
                weight.insert(weight.end(), q.weight.begin(), q.weight.end());
                side.insert(side.end(), q.side.begin(), q.side.end());
              }
              const auto np = static_cast<py::ssize_t>(pc.size());
              py::dict out;
              out["cell"] = as_pyarray(std::move(pc));
              out["ref"] = as_pyarray(std::move(ref), {np, dim});
              out["weight"] = as_pyarray(std::move(weight));
              out["side"] = as_pyarray(std::move(side));
              return out;
            });
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("cell_list"), py::arg("options"),
      "The stiffness's quadrature points of the given cells: cell, ref (n, dim), weight, side.");

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
