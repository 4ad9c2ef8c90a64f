// Bindings: the node mesh of a P1 space, the crack geometry of a polyline on
// triangles.
#include "array.h"

#include "geometry/crack_geometry_2d.h"
#include <dolfinx/fem/FunctionSpace.h>
#include "assembly/dolfinx_glue.h"
#include <pybind11/stl.h>

namespace cracklip_wrappers
{
using namespace cracklip;

void declare_geometry(py::module& m)
{
  m.def(
      "extract_node_mesh",
      [](const dolfinx::fem::FunctionSpace& V)
      {
        NodeMesh nm = extract_node_mesh(V);
        const py::ssize_t d = nm.gdim;
        const auto n = static_cast<py::ssize_t>(nm.x.size()) / d;
        const auto nc = static_cast<py::ssize_t>(nm.cells.size()) / (d + 1);
        return py::make_tuple(as_pyarray(std::move(nm.x), {n, d}),
                              as_pyarray(std::move(nm.cells), {nc, d + 1}));
      },
      py::arg("V"), "Node coordinates (n, gdim) and cells (m, gdim + 1) of a P1 vector space "
                    "(triangles or tetrahedra); under MPI the local ones (owned, then ghost).");

  py::class_<CrackGeometry>(m, "CrackGeometry", "Geometry of one crack on the mesh")
      .def_property_readonly("phi", [](const CrackGeometry& g) { return carray<double>(g.phi.size(), g.phi.data()); })
      .def_property_readonly("psi",
                             [](const CrackGeometry& g)
                             {
                               const py::ssize_t nt = g.tips.size() / 2;
                               const py::ssize_t n = g.phi.size();
                               return carray<double>({nt, n}, g.psi.data());
                             })
      .def_property_readonly("tips", [](const CrackGeometry& g)
                             { return carray<double>({py::ssize_t(g.tips.size() / 2), py::ssize_t(2)}, g.tips.data()); })
      .def_property_readonly("tip_tangents", [](const CrackGeometry& g)
                             { return carray<double>({py::ssize_t(g.tips.size() / 2), py::ssize_t(2)}, g.tip_tangents.data()); })
      .def_property_readonly("cell_class", [](const CrackGeometry& g)
                             { return carray<std::int8_t>(g.cell_class.size(), g.cell_class.data()); })
      .def_property_readonly("cell_side", [](const CrackGeometry& g)
                             { return carray<std::int8_t>(g.cell_side.size(), g.cell_side.data()); })
      .def_property_readonly("tip_orientation", [](const CrackGeometry& g)
                             { return carray<int>(g.tip_orientation.size(), g.tip_orientation.data()); })
      .def_property_readonly("num_snapped", [](const CrackGeometry& g) { return g.num_snapped; })
      .def_property_readonly(
          "crack_cells",
          [](const CrackGeometry& g)
          {
            // cell (n), class (n), segment (n, 2, 2) reference coordinates,
            // owns_segment (n), num_sub (n), sub (n, 3, 3, 2), side (n, 3)
            const py::ssize_t n = g.crack_cells.size();
            std::vector<std::int32_t> cell(n), num_sub(n);
            std::vector<std::int8_t> cls(n), owns(n), side(3 * n);
            std::vector<double> seg(4 * n), sub(18 * n);
            for (py::ssize_t i = 0; i < n; ++i)
            {
              const CrackCell& c = g.crack_cells[i];
              cell[i] = c.cell;
              cls[i] = static_cast<std::int8_t>(c.cls);
              owns[i] = c.owns_segment;
              num_sub[i] = c.num_sub;
              std::copy(c.segment.begin(), c.segment.end(), seg.begin() + 4 * i);
              std::copy(c.sub.begin(), c.sub.end(), sub.begin() + 18 * i);
              std::copy(c.side.begin(), c.side.end(), side.begin() + 3 * i);
            }
            py::dict d;
            d["cell"] = as_pyarray(std::move(cell));
            d["cls"] = as_pyarray(std::move(cls));
            d["segment"] = as_pyarray(std::move(seg), {n, 2, 2});
            d["owns_segment"] = as_pyarray(std::move(owns));
            d["num_sub"] = as_pyarray(std::move(num_sub));
            d["sub"] = as_pyarray(std::move(sub), {n, 3, 3, 2});
            d["side"] = as_pyarray(std::move(side), {n, 3});
            return d;
          },
          "Cut and edge cells: dict of arrays (cell, cls, segment (n,2,2), owns_segment, "
          "num_sub, sub (n,3,3,2), side (n,3)).")
      .def_property_readonly(
          "tip_cells",
          [](const CrackGeometry& g)
          {
            const py::ssize_t n = g.tip_cells.size();
            std::vector<std::int32_t> cell(n), tip(n);
            std::vector<double> seg(4 * n);
            for (py::ssize_t i = 0; i < n; ++i)
            {
              cell[i] = g.tip_cells[i].cell;
              tip[i] = g.tip_cells[i].tip;
              std::copy(g.tip_cells[i].segment.begin(), g.tip_cells[i].segment.end(), seg.begin() + 4 * i);
            }
            py::dict d;
            d["cell"] = as_pyarray(std::move(cell));
            d["tip"] = as_pyarray(std::move(tip));
            d["segment"] = as_pyarray(std::move(seg), {n, 2, 2});
            return d;
          },
          "Tip cells: dict (cell, tip, segment (n,2,2) entry point -> tip, reference coordinates).");

  m.def(
      "compute_crack_geometry",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const carray<double>& points,
         std::array<bool, 2> tips, double snap_tol)
      {
        require_columns(x, 2, "x (node coordinates)");
        require_columns(cells, 3, "cells (node indices per triangle)");
        require_columns(points, 2, "points (crack polyline)");
        CrackPath path;
        path.points.assign(points.data(), points.data() + points.size());
        path.tip = tips;
        return compute_crack_geometry(as_span(x), as_span(cells), path, snap_tol);
      },
      py::arg("x"), py::arg("cells"), py::arg("points"), py::arg("tips"), py::arg("snap_tol"),
      "Level sets, cell classes and cut-cell data of one polyline crack.");

  m.def(
      "signed_distance",
      [](const carray<double>& points, const carray<double>& p)
      {
        CrackPath path;
        path.points.assign(points.data(), points.data() + points.size());
        const py::ssize_t n = p.size() / 2;
        std::vector<double> out(n);
        for (py::ssize_t i = 0; i < n; ++i)
          out[i] = signed_distance(path, {p.data()[2 * i], p.data()[2 * i + 1]});
        return as_pyarray(std::move(out));
      },
      py::arg("crack_points"), py::arg("points"));
}

} // namespace cracklip_wrappers
