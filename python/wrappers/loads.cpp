// Bindings: points on a crack's segments, lip loads, loads in enriched cells.
#include "array.h"

#include "quadrature/crack_points_2d.h"
#include "assembly/loads_2d.h"
#include <pybind11/stl.h>

namespace cracklip_wrappers
{
using namespace cracklip;
using Cracks = std::vector<const CrackGeometry*>;

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
      "assemble_lip_load",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout& layout,
         const Cracks& cracks, std::int32_t crack, const carray<std::int32_t>& point_cells,
         const carray<double>& ref, const carray<double>& weights, const carray<double>& traction)
      {
        std::vector<double> b(2 * static_cast<std::size_t>(layout.num_nodes_total()), 0.0);
        assemble_lip_load(as_span(x), as_span(cells), layout, cracks, crack, as_span(point_cells),
                          as_span(ref), as_span(weights), as_span(traction), b);
        return as_pyarray(std::move(b));
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("crack"),
      py::arg("point_cells"), py::arg("ref"), py::arg("weights"), py::arg("traction"),
      "Load vector (num_dofs) of + lip tractions (n, 2) at crack points (the - lip carries the opposite).");

  m.def(
      "assemble_cell_load",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout& layout,
         const Cracks& cracks, const carray<std::int32_t>& point_cells, const carray<double>& ref,
         const carray<std::int8_t>& sides, const carray<double>& weights, const carray<double>& force,
         const carray<double>& stress)
      {
        std::vector<double> b(2 * static_cast<std::size_t>(layout.num_nodes_total()), 0.0);
        assemble_cell_load(as_span(x), as_span(cells), layout, cracks, as_span(point_cells), as_span(ref),
                           as_span(sides), as_span(weights), as_span(force), as_span(stress), b);
        return as_pyarray(std::move(b));
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("point_cells"),
      py::arg("ref"), py::arg("sides"), py::arg("weights"), py::arg("force"), py::arg("stress"),
      "Enriched-dof load (num_dofs) of a body force (n, 2) and an initial stress (n, 3: xx, yy, xy) at "
      "quadrature points of enriched cells.");
}

} // namespace cracklip_wrappers
