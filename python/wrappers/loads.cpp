// Bindings: points on a crack's lips (segments in 2D, lip facets in 3D),
// boundary facet bases, lip loads, loads in enriched cells (2D or 3D).
#include "array.h"
#include "dimension.h"

#include "assembly/enriched_loads.h"
#include "assembly/facet_basis.h"
#include "quadrature/crack_points_2d.h"
#include "quadrature/crack_points_3d.h"

#include <pybind11/stl.h>

#include <optional>

namespace cracklip_wrappers
{
using namespace cracklip;

namespace
{
/// cell, ref, x, weight, normal of crack points (2D CrackPoints, 3D LipPoints3D).
template <typename Points>
py::dict lip_points_dict(Points&& p, py::ssize_t dim)
{
  const auto np_ = static_cast<py::ssize_t>(p.weight.size());
  py::dict d;
  d["cell"] = as_pyarray(std::move(p.cell));
  d["ref"] = as_pyarray(std::move(p.ref), {np_, dim});
  d["x"] = as_pyarray(std::move(p.x), {np_, dim});
  d["weight"] = as_pyarray(std::move(p.weight));
  d["normal"] = as_pyarray(std::move(p.normal), {np_, dim});
  return d;
}
} // namespace

void declare_loads(py::module& m)
{
  m.def(
      "compute_lip_points",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const py::object& geometry, int n,
         double near_factor, bool signed_point_rule)
      {
        const int dim = mesh_dimension(x, cells);
        if (dim == 2)
        {
          if (near_factor != 0.0 or signed_point_rule)
            throw std::invalid_argument("near_factor and signed_point_rule choose the rules of lip facets near a 3D "
                                        "front; a 2D crack's segments take n only");
          return lip_points_dict(compute_crack_points(as_span(x), as_span(cells), crack_of<2>(geometry), n), 2);
        }
        LipPoints3D lp = compute_lip_points_3d(as_span(x), as_span(cells), crack_of<3>(geometry), n, near_factor,
                                               signed_point_rule);
        auto front_vertices = std::move(lp.front_vertices);
        py::dict d = lip_points_dict(std::move(lp), 3);
        d["front_vertices"] = as_pyarray(std::move(front_vertices));
        return d;
      },
      py::arg("x"), py::arg("cells"), py::arg("geometry"), py::arg("n"), py::arg("near_factor") = 0.0,
      py::arg("signed_point_rule") = false,
      "Quadrature points on one crack's lips, inside the cells: cell, ref (n, dim), x (n, dim), weight, "
      "normal (n, dim) to the + side; 3D also front_vertices (the facet's vertices on the front). 2D: n Gauss "
      "points per segment (tau^2 toward tips); 3D: n per direction on each lip facet (collapsed on facets touching "
      "the front, signed fans from it on facets within near_factor diameters of it; signed_point_rule: the signed "
      "point-collapsed rule).");

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
}

} // namespace cracklip_wrappers
