// Bindings: the 3D X-FEM model on tetrahedra (enrichment layout, sparsity,
// enriched stiffness into PETSc or COO, point values of the displacement).
#include "array.h"

#include "assembly/dolfinx_glue.h"
#include "assembly/enriched_kernels_3d.h"
#include "assembly/loads_3d.h"
#include "assembly/sparsity.h"
#include "enrichment/enrichment_layout_3d.h"

#include <pybind11/stl.h>

namespace cracklip_wrappers
{
using namespace cracklip;
using Cracks3D = std::vector<const CrackGeometry3D*>;

namespace
{
template <typename T>
py::array_t<T> view(const std::vector<T>& v)
{
  return carray<T>(static_cast<py::ssize_t>(v.size()), v.data());
}

void check_mesh(const carray<double>& x, const carray<std::int32_t>& cells)
{
  if (x.ndim() != 2 or x.shape(1) != 3 or cells.ndim() != 2 or cells.shape(1) != 4)
    throw std::invalid_argument("a tetrahedral mesh needs x (n, 3) and cells (m, 4)");
}
} // namespace

void declare_model_3d(py::module& m)
{
  py::class_<QuadratureOptions3D>(m, "QuadratureOptions3D", "Quadrature rules of the enriched kernels on tetrahedra")
      .def(py::init<>())
      .def_readwrite("degree", &QuadratureOptions3D::degree)
      .def_property(
          "front_rule", [](const QuadratureOptions3D& o) { return o.front_rule == FrontQuadrature::collapsed ? "collapsed" : "gauss"; },
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

  py::class_<EnrichmentLayout3D>(m, "EnrichmentLayout3D", "Enriched pseudo-nodes of a tetrahedral mesh")
      .def_property_readonly("num_std_nodes", [](const EnrichmentLayout3D& l) { return l.num_std_nodes; })
      .def_property_readonly("num_enriched", &EnrichmentLayout3D::num_enriched)
      .def_property_readonly("num_nodes_total", &EnrichmentLayout3D::num_nodes_total)
      .def_property_readonly("node", [](const EnrichmentLayout3D& l) { return view(l.node); })
      .def_property_readonly("crack", [](const EnrichmentLayout3D& l) { return view(l.crack); })
      .def_property_readonly("kind", [](const EnrichmentLayout3D& l) { return view(l.kind); })
      .def_property_readonly("function", [](const EnrichmentLayout3D& l) { return view(l.function); })
      .def_property_readonly("piece", [](const EnrichmentLayout3D& l) { return view(l.piece); })
      .def_property_readonly("core", [](const EnrichmentLayout3D& l) { return view(l.core); })
      .def_property_readonly("node_side", [](const EnrichmentLayout3D& l) { return view(l.node_side); })
      .def_property_readonly("cells", [](const EnrichmentLayout3D& l) { return view(l.cells); })
      .def_property_readonly("cell_offsets", [](const EnrichmentLayout3D& l) { return view(l.cell_offsets); })
      .def_property_readonly("cell_enr", [](const EnrichmentLayout3D& l) { return view(l.cell_enr); })
      .def_property_readonly("frame_node", [](const EnrichmentLayout3D& l) { return view(l.frame_node); });

  m.def(
      "create_enrichment_layout_3d",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const Cracks3D& cracks, const std::string& front,
         double radius, double kappa, bool corrected)
      {
        check_mesh(x, cells);
        EnrichmentOptions3D o;
        o.front = front == "none" ? TipEnrichment::none : front == "scalar" ? TipEnrichment::scalar
                : front == "vector" ? TipEnrichment::vector
                                    : throw std::invalid_argument("front enrichment must be 'none', 'scalar' or "
                                                                  "'vector', got '" + front + "'");
        o.radius = radius;
        o.kappa = kappa;
        o.corrected = corrected;
        return create_enrichment_layout_3d(as_span(x), as_span(cells), cracks, o);
      },
      py::arg("x"), py::arg("cells"), py::arg("cracks"), py::arg("front") = "vector", py::arg("radius") = 0.0,
      py::arg("kappa") = 1.8, py::arg("corrected") = true,
      "Heaviside and front enrichment of every crack on a tetrahedral mesh.");

  m.def(
      "create_sparsity_3d",
      [](const carray<std::int32_t>& cells, const EnrichmentLayout3D& layout)
      {
        CSR s = expand_blocks(create_block_sparsity(as_span(cells), 4, layout.num_std_nodes, layout.num_enriched(),
                                                    layout),
                              3);
        return py::make_tuple(as_pyarray(std::move(s.offsets)), as_pyarray(std::move(s.indices)));
      },
      py::arg("cells"), py::arg("layout"), "Scalar CSR (indptr, indices) of the enriched stiffness, block size 3.");

  m.def(
      "assemble_enriched_stiffness_3d_petsc",
      [](std::uintptr_t mat_handle, const carray<double>& x, const carray<std::int32_t>& cells,
         const EnrichmentLayout3D& layout, const Cracks3D& cracks, double E, double nu,
         const QuadratureOptions3D& options)
      {
        check_mesh(x, cells);
        const MatrixSink sink = petsc_add_sink(reinterpret_cast<Mat>(mat_handle));
        return assemble_enriched_stiffness_3d(sink, as_span(x), as_span(cells), layout, cracks, E, nu, options);
      },
      py::arg("mat"), py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("E"),
      py::arg("nu"), py::arg("options"),
      "Add the enriched cells' stiffness (standard-standard block excluded) into a PETSc Mat (handle).");

  m.def(
      "assemble_enriched_stiffness_3d_coo",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout3D& layout,
         const Cracks3D& cracks, double E, double nu, const QuadratureOptions3D& options)
      {
        check_mesh(x, cells);
        Triplets coo;
        const auto n = assemble_enriched_stiffness_3d(coo_sink(coo), as_span(x), as_span(cells), layout, cracks, E,
                                                      nu, options);
        return py::make_tuple(as_pyarray(std::move(coo.row)), as_pyarray(std::move(coo.col)),
                              as_pyarray(std::move(coo.value)), n);
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("E"), py::arg("nu"),
      py::arg("options"), "The enriched stiffness as COO triplets (rows, cols, values, cells integrated).");

  m.def(
      "evaluate_displacement_3d",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout3D& layout,
         const Cracks3D& cracks, const carray<double>& u, const carray<std::int32_t>& point_cells,
         const carray<double>& ref, const carray<std::int8_t>& sides)
      {
        check_mesh(x, cells);
        std::vector<double> grad;
        auto val = evaluate_displacement_3d(as_span(x), as_span(cells), layout, cracks, as_span(u),
                                            as_span(point_cells), as_span(ref), as_span(sides), &grad);
        const auto np = static_cast<py::ssize_t>(point_cells.size());
        return py::make_tuple(as_pyarray(std::move(val), {np, 3}), as_pyarray(std::move(grad), {np, 3, 3}));
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("u"), py::arg("point_cells"),
      py::arg("ref"), py::arg("sides"), "Displacement (n, 3) and its gradient (n, 3, 3) at points (cell, ref, side).");

  m.def(
      "compute_enriched_cell_quadrature_3d",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout3D& layout,
         const Cracks3D& cracks, const carray<std::int32_t>& cell_list, const QuadratureOptions3D& options)
      {
        check_mesh(x, cells);
        std::vector<std::int32_t> pc;
        std::vector<double> ref, weight;
        std::vector<std::int8_t> side;
        CellQuadrature3D q;
        for (const std::int32_t c : as_span(cell_list))
        {
          compute_enriched_cell_quadrature_3d(as_span(x), as_span(cells), layout, cracks, c, options, q);
          pc.insert(pc.end(), q.size(), c);
          ref.insert(ref.end(), q.ref.begin(), q.ref.end());
          weight.insert(weight.end(), q.weight.begin(), q.weight.end());
          side.insert(side.end(), q.side.begin(), q.side.end());
        }
        const auto np = static_cast<py::ssize_t>(pc.size());
        py::dict d;
        d["cell"] = as_pyarray(std::move(pc));
        d["ref"] = as_pyarray(std::move(ref), {np, 3});
        d["weight"] = as_pyarray(std::move(weight));
        d["side"] = as_pyarray(std::move(side));
        return d;
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("cell_list"),
      py::arg("options"), "The stiffness's quadrature points of the given cells: cell, ref (n, 3), weight, side.");

  m.def(
      "compute_facet_basis_3d",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout3D& layout,
         const Cracks3D& cracks, const carray<std::int32_t>& facet_cells, const carray<std::int32_t>& facet_local,
         int degree)
      {
        check_mesh(x, cells);
        FacetBasis3D fb = compute_facet_basis_3d(as_span(x), as_span(cells), layout, cracks, as_span(facet_cells),
                                                 as_span(facet_local), degree);
        const auto np = static_cast<py::ssize_t>(fb.weights.size());
        const auto ne = static_cast<py::ssize_t>(fb.entry_point.size());
        py::dict d;
        d["points"] = as_pyarray(std::move(fb.points), {np, 3});
        d["normals"] = as_pyarray(std::move(fb.normals), {np, 3});
        d["weights"] = as_pyarray(std::move(fb.weights));
        d["entry_point"] = as_pyarray(std::move(fb.entry_point));
        d["entry_dof"] = as_pyarray(std::move(fb.entry_dof));
        d["entry_value"] = as_pyarray(std::move(fb.entry_value), {ne, 3});
        return d;
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("facet_cells"),
      py::arg("facet_local"), py::arg("degree"),
      "Quadrature points of boundary facets (points, normals, weights) and the basis values there (entries).");

  m.def(
      "assemble_lip_load_3d",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout3D& layout,
         const Cracks3D& cracks, std::int32_t crack, const carray<std::int32_t>& point_cells,
         const carray<double>& ref, const carray<double>& weights, const carray<double>& traction)
      {
        check_mesh(x, cells);
        std::vector<double> b(3 * static_cast<std::size_t>(layout.num_nodes_total()), 0.0);
        assemble_lip_load_3d(as_span(x), as_span(cells), layout, cracks, crack, as_span(point_cells), as_span(ref),
                             as_span(weights), as_span(traction), b);
        return as_pyarray(std::move(b));
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("crack"), py::arg("point_cells"),
      py::arg("ref"), py::arg("weights"), py::arg("traction"),
      "Load vector of lip tractions (n, 3) on the + lip (their opposite on the - lip).");

  m.def(
      "assemble_cell_load_3d",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout3D& layout,
         const Cracks3D& cracks, const carray<std::int32_t>& point_cells, const carray<double>& ref,
         const carray<std::int8_t>& sides, const carray<double>& weights, const carray<double>& force)
      {
        check_mesh(x, cells);
        std::vector<double> b(3 * static_cast<std::size_t>(layout.num_nodes_total()), 0.0);
        assemble_cell_load_3d(as_span(x), as_span(cells), layout, cracks, as_span(point_cells), as_span(ref),
                              as_span(sides), as_span(weights), as_span(force), b);
        return as_pyarray(std::move(b));
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("point_cells"), py::arg("ref"),
      py::arg("sides"), py::arg("weights"), py::arg("force"),
      "Load vector of a body force (n, 3) at the enriched cells' quadrature points (enriched dofs only).");
}

} // namespace cracklip_wrappers
