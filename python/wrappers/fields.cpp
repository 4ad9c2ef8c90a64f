// Bindings: point evaluation and sub-cell fields.
#include "array.h"

#include <fields.h>
#include <pybind11/stl.h>

namespace cracklip_wrappers
{
using namespace cracklip;
using Cracks = std::vector<const CrackGeometry*>;

void declare_fields(py::module& m)
{
  m.def(
      "evaluate_displacement",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout& layout,
         const Cracks& cracks, const carray<double>& u, const carray<std::int32_t>& point_cells,
         const carray<double>& ref_points, const carray<std::int8_t>& sides)
      {
        auto out = evaluate_displacement(as_span(x), as_span(cells), layout, cracks, as_span(u),
                                         as_span(point_cells), as_span(ref_points), as_span(sides));
        const py::ssize_t n = out.size() / 2;
        return as_pyarray(std::move(out), {n, 2});
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("u"),
      py::arg("point_cells"), py::arg("ref_points"), py::arg("sides"));

  m.def(
      "compute_subcell_fields",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout& layout,
         const Cracks& cracks, const carray<double>& u, double E, double nu)
      {
        SubcellFields f = compute_subcell_fields(as_span(x), as_span(cells), layout, cracks,
                                                 as_span(u), E, nu);
        const py::ssize_t ns = f.parent.size();
        py::dict d;
        d["points"] = as_pyarray(std::move(f.points), {3 * ns, 2});
        d["displacement"] = as_pyarray(std::move(f.displacement), {3 * ns, 2});
        d["stress"] = as_pyarray(std::move(f.stress), {ns, 3});
        d["parent"] = as_pyarray(std::move(f.parent));
        d["side"] = as_pyarray(std::move(f.side));
        d["strain_energy"] = f.strain_energy;
        return d;
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("u"),
      py::arg("E"), py::arg("nu"));
}

} // namespace cracklip_wrappers
