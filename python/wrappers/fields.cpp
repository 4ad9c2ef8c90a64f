// Bindings: point values and quadrature-point fields (2D or 3D), sub-cell
// fields (2D), rasterised pictures.
#include "array.h"
#include "dimension.h"

#include "post/displacement.h"
#include "post/fields_2d.h"
#include "post/raster.h"
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
         const py::sequence& cracks, const carray<double>& u, const carray<std::int32_t>& point_cells,
         const carray<double>& ref_points, const carray<std::int8_t>& sides)
      {
        const int dim = mesh_dimension(x, cells);
        std::vector<double> grad;
        auto out = with_dimension(dim,
                                  [&](auto d)
                                  {
                                    constexpr int D = decltype(d)::value;
                                    return evaluate_displacement<D>(as_span(x), as_span(cells), layout,
                                                                    cracks_of<D>(cracks), as_span(u),
                                                                    as_span(point_cells), as_span(ref_points),
                                                                    as_span(sides), &grad);
                                  });
        const auto n = static_cast<py::ssize_t>(point_cells.size());
        return py::make_tuple(as_pyarray(std::move(out), {n, dim}), as_pyarray(std::move(grad), {n, dim, dim}));
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("u"),
      py::arg("point_cells"), py::arg("ref_points"), py::arg("sides"),
      "Displacement (n, dim) and its gradient (n, dim, dim) at (cell, reference point, side).");

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
        return d;
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("u"),
      py::arg("E"), py::arg("nu"));

  m.def(
      "rasterize_triangles",
      [](const carray<double>& triangles, const carray<double>& values, double x0, double x1, double y0,
         double y1, int ny, int nx)
      {
        auto img = rasterize_triangles(as_span(triangles), as_span(values), x0, x1, y0, y1, ny, nx);
        return as_pyarray(std::move(img), {py::ssize_t(ny), py::ssize_t(nx)});
      },
      py::arg("triangles"), py::arg("values"), py::arg("x0"), py::arg("x1"), py::arg("y0"), py::arg("y1"),
      py::arg("ny"), py::arg("nx"),
      "Image (ny, nx), row 0 at y0, of values constant on triangles (n, 3, 2); NaN outside.");

  m.def(
      "compute_field_points",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout& layout,
         const py::sequence& cracks, const carray<double>& u, const carray<std::int32_t>& cell_list,
         const py::object& options)
      {
        const int dim = mesh_dimension(x, cells);
        FieldPoints f = with_dimension(dim,
                                       [&](auto d)
                                       {
                                         constexpr int D = decltype(d)::value;
                                         return compute_field_points<D>(as_span(x), as_span(cells), layout,
                                                                        cracks_of<D>(cracks), as_span(u),
                                                                        as_span(cell_list), options_of<D>(options));
                                       });
        const py::ssize_t n = f.weight.size();
        py::dict d;
        d["cell"] = as_pyarray(std::move(f.cell));
        d["ref"] = as_pyarray(std::move(f.ref), {n, dim});
        d["x"] = as_pyarray(std::move(f.x), {n, dim});
        d["weight"] = as_pyarray(std::move(f.weight));
        d["side"] = as_pyarray(std::move(f.side));
        d["grad_u"] = as_pyarray(std::move(f.grad_u), {n, dim, dim});
        return d;
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("u"),
      py::arg("cell_list"), py::arg("options"),
      "Quadrature points of cells (all if cell_list is empty; the enriched stiffness's rules) with grad u there: "
      "cell, ref (n, dim), x (n, dim), weight, side, grad_u (n, dim, dim).");
}

} // namespace cracklip_wrappers
