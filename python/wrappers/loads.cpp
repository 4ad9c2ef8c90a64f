// Bindings: points on a crack's segments (2D), boundary facet bases, lip
// loads, loads in enriched cells (2D or 3D).
#include "array.h"
#include "dimension.h"

#include "assembly/enriched_loads.h"
#include "assembly/facet_basis.h"
#include "quadrature/crack_points_2d.h"

#include <pybind11/stl.h>

#include <optional>

namespace cracklip_wrappers
{
using namespace cracklip;

void declare_loads(py::module& m)
{
  m.def(
      "compute_crack_points",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const CrackGeometry& g, int n)
      {
        CrackPoints c = compute_crack_points(as_span(x), as_span(cells), g, n);
        const py::ssize_t np_ = c.weight.size();
        py::dict d;
        d["cell"] = as_pyarray(std::move(c.cell));
        d["ref"] = as_pyarray(std::move(c.ref), {np_, 2});
        d["x"] = as_pyarray(std::move(c.x), {np_, 2});
        d["weight"] = as_pyarray(std::move(c.weight));
        d["normal"] = as_pyarray(std::move(c.normal), {np_, 2});
        return d;
      },
      py::arg("x"), py::arg("cells"), py::arg("geometry"), py::arg("n"),
      "Gauss points on a crack's segments (tau^2 toward tips): cell, ref (n, 2), x (n, 2), weight, "
      "normal (n, 2) to the + side.");

  m.def(
      "compute_facet_basis",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout& layout,
         const py::sequence& cracks, const carray<std::int32_t>& facet_cells, const carray<std::int32_t>& facet_local,
         int degree)
      {
        const int dim = mesh_dimension(x, cells);
        FacetBasis fb = with_dimension(dim,
                                       [&](auto d)
                                       {
                                         constexpr int D = decltype(d)::value;
                                         return compute_facet_basis<D>(as_span(x), as_span(cells), layout,
                                                                       cracks_of<D>(cracks), as_span(facet_cells),
                                                                       as_span(facet_local), degree);
                                       });
        const auto np = static_cast<py::ssize_t>(fb.weights.size());
        const auto ne = static_cast<py::ssize_t>(fb.entry_point.size());
        py::dict d;
        d["points"] = as_pyarray(std::move(fb.points), {np, dim});
        d["normals"] = as_pyarray(std::move(fb.normals), {np, dim});
        d["weights"] = as_pyarray(std::move(fb.weights));
        d["entry_point"] = as_pyarray(std::move(fb.entry_point));
        d["entry_dof"] = as_pyarray(std::move(fb.entry_dof));
        d["entry_value"] = as_pyarray(std::move(fb.entry_value), {ne, dim});
        return d;
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("facet_cells"),
      py::arg("facet_local"), py::arg("degree"),
      "Quadrature points of boundary facets (points, outward normals, weights) and the basis values there "
      "(entries: COO by point).");
  m.attr("compute_facet_basis_3d") = m.attr("compute_facet_basis");

  m.def(
      "assemble_lip_load",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout& layout,
         const py::sequence& cracks, std::int32_t crack, const carray<std::int32_t>& point_cells,
         const carray<double>& ref, const carray<double>& weights, const carray<double>& traction)
      {
        const int dim = mesh_dimension(x, cells);
        std::vector<double> b(dim * static_cast<std::size_t>(layout.num_nodes_total()), 0.0);
        with_dimension(dim,
                       [&](auto d)
                       {
                         constexpr int D = decltype(d)::value;
                         assemble_lip_load<D>(as_span(x), as_span(cells), layout, cracks_of<D>(cracks), crack,
                                              as_span(point_cells), as_span(ref), as_span(weights),
                                              as_span(traction), b);
                       });
        return as_pyarray(std::move(b));
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("crack"), py::arg("point_cells"),
      py::arg("ref"), py::arg("weights"), py::arg("traction"),
      "Load vector (num_dofs) of + lip tractions (n, dim) at crack points (the - lip carries the opposite).");
  m.attr("assemble_lip_load_3d") = m.attr("assemble_lip_load");

  m.def(
      "assemble_cell_load",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout& layout,
         const py::sequence& cracks, const carray<std::int32_t>& point_cells, const carray<double>& ref,
         const carray<std::int8_t>& sides, const carray<double>& weights, const carray<double>& force,
         const std::optional<carray<double>>& stress)
      {
        const int dim = mesh_dimension(x, cells);
        std::vector<double> b(dim * static_cast<std::size_t>(layout.num_nodes_total()), 0.0);
        const std::span<const double> s = stress ? as_span(*stress) : std::span<const double>();
        with_dimension(dim,
                       [&](auto d)
                       {
                         constexpr int D = decltype(d)::value;
                         assemble_cell_load<D>(as_span(x), as_span(cells), layout, cracks_of<D>(cracks),
                                               as_span(point_cells), as_span(ref), as_span(sides), as_span(weights),
                                               as_span(force), s, b);
                       });
        return as_pyarray(std::move(b));
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("point_cells"), py::arg("ref"),
      py::arg("sides"), py::arg("weights"), py::arg("force"), py::arg("stress") = py::none(),
      "Enriched-dof load (num_dofs) of a body force (n, dim) and an initial stress (n, 3: xx, yy, xy in 2D; "
      "n, 6: xx, yy, zz, yz, xz, xy in 3D; or None) at quadrature points of enriched cells.");
  m.attr("assemble_cell_load_3d") = m.attr("assemble_cell_load");
}

} // namespace cracklip_wrappers
