// Bindings: 3D crack surfaces, level sets, crack geometry on tetrahedra, the
// front and its nearest-point queries, near-front quadrature. Thin: every
// function converts arrays and calls one C++ function; results are numpy
// arrays (dicts of them for per-cell data, flattened with offsets).
#include "array.h"

#include <optional>

#include "geometry/crack_geometry_3d.h"
#include "geometry/crack_surface_3d.h"
#include "quadrature/cell_quadrature_3d.h"
#include "quadrature/front_rules_3d.h"
#include "quadrature/rules.h"

#include <pybind11/stl.h>

namespace cracklip_wrappers
{
using namespace cracklip;

namespace
{
Point3 point3(const carray<double>& a, const std::string& name)
{
  if (a.size() != 3)
    throw std::invalid_argument(name + " must have 3 components, got " + std::to_string(a.size()));
  return {a.data()[0], a.data()[1], a.data()[2]};
}

template <typename T>
py::array_t<T> copy_array(const std::vector<T>& v, std::vector<py::ssize_t> shape)
{
  std::vector<T> c(v);
  return as_pyarray(std::move(c), std::move(shape));
}

py::ssize_t n(std::size_t v) { return static_cast<py::ssize_t>(v); }

py::dict rule_dict(const quadrature::Rule& r)
{
  py::dict d;
  d["points"] = copy_array(r.points, {n(r.weights.size()), r.dim});
  d["weights"] = copy_array(r.weights, {n(r.weights.size())});
  return d;
}

/// Per-cell data of the crack cells, flattened: one row per crack cell and
/// offsets into the sub-tetrahedra and facets.
py::dict crack_cells_dict(const CrackGeometry3D& g)
{
  const std::size_t m = g.crack_cells.size();
  std::vector<std::int32_t> cell(m), sub_offsets = {0}, facet_offsets = {0};
  std::vector<std::int8_t> cls(m), side, psi_side, num_front, facet_num_front;
  std::vector<double> sub, dropped(m), facets, area, normal, segment(6 * m), length(m);
  for (std::size_t i = 0; i < m; ++i)
  {
    const CrackCell3D& c = g.crack_cells[i];
    cell[i] = c.cell;
    cls[i] = static_cast<std::int8_t>(c.cls);
    sub.insert(sub.end(), c.sub.begin(), c.sub.end());
    side.insert(side.end(), c.side.begin(), c.side.end());
    psi_side.insert(psi_side.end(), c.psi_side.begin(), c.psi_side.end());
    num_front.insert(num_front.end(), c.num_front.begin(), c.num_front.end());
    sub_offsets.push_back(static_cast<std::int32_t>(side.size()));
    dropped[i] = c.dropped_volume;
    facets.insert(facets.end(), c.facets.begin(), c.facets.end());
    area.insert(area.end(), c.facet_area.begin(), c.facet_area.end());
    normal.insert(normal.end(), c.facet_normal.begin(), c.facet_normal.end());
    facet_num_front.insert(facet_num_front.end(), c.facet_num_front.begin(), c.facet_num_front.end());
    facet_offsets.push_back(static_cast<std::int32_t>(area.size()));
    std::copy(c.front_segment.begin(), c.front_segment.end(), segment.begin() + 6 * i);
    length[i] = c.front_length;
  }
  const py::ssize_t ns = n(side.size()), nf = n(area.size());
  py::dict d;
  d["cell"] = as_pyarray(std::move(cell));
  d["cls"] = as_pyarray(std::move(cls));
  d["sub_offsets"] = as_pyarray(std::move(sub_offsets));
  d["sub"] = as_pyarray(std::move(sub), {ns, 4, 3});
  d["side"] = as_pyarray(std::move(side));
  d["psi_side"] = as_pyarray(std::move(psi_side));
  d["num_front"] = as_pyarray(std::move(num_front));
  d["dropped_volume"] = as_pyarray(std::move(dropped));
  d["facet_offsets"] = as_pyarray(std::move(facet_offsets));
  d["facets"] = as_pyarray(std::move(facets), {nf, 3, 3});
  d["facet_area"] = as_pyarray(std::move(area));
  d["facet_normal"] = as_pyarray(std::move(normal), {nf, 3});
  d["facet_num_front"] = as_pyarray(std::move(facet_num_front));
  d["front_segment"] = as_pyarray(std::move(segment), {n(m), 2, 3});
  d["front_length"] = as_pyarray(std::move(length));
  return d;
}

py::dict front_dict(const CrackFront3D& f)
{
  const py::ssize_t np = f.num_points(), ns = f.num_segments();
  py::dict d;
  d["x"] = copy_array(f.x, {np, 3});
  d["s"] = copy_array(f.s, {np});
  d["frame"] = copy_array(f.frame, {np, 3, 3});
  d["cell"] = copy_array(f.cell, {np});
  d["on_boundary"] = copy_array(f.on_boundary, {np});
  d["piece_offsets"] = copy_array(f.piece_offsets, {n(f.piece_offsets.size())});
  d["closed"] = copy_array(f.closed, {n(f.closed.size())});
  d["segments"] = copy_array(f.segments, {ns, 2});
  d["segment_cell"] = copy_array(f.segment_cell, {ns});
  d["num_branch_points"] = f.num_branch_points;
  return d;
}

QuadratureOptions3D quadrature_options(int degree, const std::string& front_rule, int front_radial,
                                       int front_angular, int front_axial, int front_degree, double near_factor,
                                       bool signed_point_rule)
{
  QuadratureOptions3D o;
  o.degree = degree;
  if (front_rule == "collapsed")
    o.front_rule = FrontQuadrature::collapsed;
  else if (front_rule == "gauss")
    o.front_rule = FrontQuadrature::gauss;
  else
    throw std::invalid_argument("front_rule must be 'collapsed' or 'gauss', got '" + front_rule + "'");
  o.front_radial = front_radial;
  o.front_angular = front_angular;
  o.front_axial = front_axial;
  o.front_degree = front_degree;
  o.near_factor = near_factor;
  o.signed_point_rule = signed_point_rule;
  if (degree < 0 or front_degree < 0 or front_radial < 1 or front_angular < 1 or front_axial < 1 or near_factor < 0)
    throw std::invalid_argument("quadrature options: degrees must be >= 0, numbers of points >= 1 and "
                                "near_factor >= 0");
  return o;
}
} // namespace

void declare_geometry_3d(py::module& m)
{
  py::class_<CrackSurface3D>(m, "CrackSurface3D", "A crack surface in 3D (ellipse, polygon or triangulated)")
      .def_property_readonly("kind",
                             [](const CrackSurface3D& s)
                             {
                               static const char* names[] = {"ellipse", "polygon", "triangulated"};
                               return std::string(names[static_cast<int>(s.kind())]);
                             })
      .def_property_readonly("bounding_box",
                             [](const CrackSurface3D& s)
                             {
                               const auto b = s.bounding_box();
                               return copy_array(std::vector<double>(b.begin(), b.end()), {2, 3});
                             })
      .def("__repr__", &CrackSurface3D::describe)
      .def(
          "level_sets",
          [](const CrackSurface3D& s, const carray<double>& p)
          {
            require_columns(p, 3, "points");
            const LevelSets3D ls = compute_level_sets_3d(as_span(p), s);
            return py::make_tuple(copy_array(ls.phi, {p.shape(0)}), copy_array(ls.psi, {p.shape(0)}));
          },
          py::arg("points"), "(phi, psi) at points (n, 3).")
      .def(
          "front_directions",
          [](const CrackSurface3D& s, const carray<double>& p)
          {
            require_columns(p, 3, "points");
            const py::ssize_t np = p.shape(0);
            std::vector<double> e1(3 * np), e2(3 * np);
            for (py::ssize_t i = 0; i < np; ++i)
            {
              const auto [a, b] = s.front_directions({p.data()[3 * i], p.data()[3 * i + 1], p.data()[3 * i + 2]});
              std::copy(a.begin(), a.end(), e1.begin() + 3 * i);
              std::copy(b.begin(), b.end(), e2.begin() + 3 * i);
            }
            return py::make_tuple(as_pyarray(std::move(e1), {np, 3}), as_pyarray(std::move(e2), {np, 3}));
          },
          py::arg("points"), "(e1, e2) (n, 3) each: propagation direction and normal at the nearest front point.");

  m.def(
      "create_ellipse_crack",
      [](const carray<double>& center, const carray<double>& normal, const carray<double>& axis, double a, double b)
      { return create_ellipse_crack(point3(center, "center"), point3(normal, "normal"), point3(axis, "axis"), a, b); },
      py::arg("center"), py::arg("normal"), py::arg("axis"), py::arg("a"), py::arg("b"),
      "Elliptical (a = b: circular) planar crack: normal to the phi > 0 side, semi-axis a along axis, b along "
      "normal x axis.");
  m.def(
      "create_polygon_crack",
      [](const carray<double>& v)
      {
        require_columns(v, 3, "vertices");
        return create_polygon_crack(as_span(v));
      },
      py::arg("vertices"), "Planar polygonal crack, vertices (n, 3) counter-clockwise seen from the + side.");
  m.def(
      "create_triangulated_crack",
      [](const carray<double>& v, const carray<std::int32_t>& t)
      {
        require_columns(v, 3, "vertices");
        require_columns(t, 3, "triangles");
        return create_triangulated_crack(as_span(v), as_span(t));
      },
      py::arg("vertices"), py::arg("triangles"),
      "Triangulated crack surface: vertices (nv, 3), consistently oriented triangles (nt, 3).");
  m.def(
      "compute_level_sets_3d",
      [](const carray<double>& x, const CrackSurface3D& s)
      {
        require_columns(x, 3, "x (node coordinates)");
        LevelSets3D ls = compute_level_sets_3d(as_span(x), s);
        return py::make_tuple(as_pyarray(std::move(ls.phi)), as_pyarray(std::move(ls.psi)));
      },
      py::arg("x"), py::arg("surface"), "Nodal level sets (phi, psi) of a crack surface.");

  py::class_<CrackGeometry3D>(m, "CrackGeometry3D", "Geometry of one crack on a tetrahedral mesh")
      .def_property_readonly("phi", [](const CrackGeometry3D& g) { return copy_array(g.phi, {n(g.phi.size())}); })
      .def_property_readonly("psi", [](const CrackGeometry3D& g) { return copy_array(g.psi, {n(g.psi.size())}); })
      .def_property_readonly("cell_class",
                             [](const CrackGeometry3D& g) { return copy_array(g.cell_class, {n(g.cell_class.size())}); })
      .def_property_readonly("cell_side",
                             [](const CrackGeometry3D& g) { return copy_array(g.cell_side, {n(g.cell_side.size())}); })
      .def_property_readonly("crack_cell_index", [](const CrackGeometry3D& g)
                             { return copy_array(g.crack_cell_index, {n(g.crack_cell_index.size())}); })
      .def_property_readonly("num_snapped", [](const CrackGeometry3D& g) { return g.num_snapped; })
      .def_property_readonly("num_degenerate_front_cells",
                             [](const CrackGeometry3D& g) { return g.num_degenerate_front_cells; })
      .def_property_readonly(
          "class_counts",
          [](const CrackGeometry3D& g)
          {
            std::array<std::int64_t, 5> c = {0, 0, 0, 0, 0};
            for (std::int8_t k : g.cell_class)
              ++c[k];
            py::dict d;
            const char* names[] = {"plain", "cut", "face", "front", "extension"};
            for (int k = 0; k < 5; ++k)
              d[names[k]] = c[k];
            return d;
          },
          "Number of cells of each class (plain, cut, face, front, extension).")
      .def_property_readonly("crack_cells", &crack_cells_dict,
                             "Cut, face and front cells (sorted by cell), flattened: cell (m), cls (m), "
                             "sub_offsets (m + 1) into sub (N, 4, 3) reference coordinates, side (N), psi_side (N), "
                             "num_front (N); dropped_volume (m); facet_offsets (m + 1) into facets (F, 3, 3) "
                             "reference coordinates, facet_area (F), facet_normal (F, 3), facet_num_front (F); "
                             "front_segment (m, 2, 3) reference coordinates, front_length (m).")
      .def_property_readonly(
          "front_segments",
          [](const CrackGeometry3D& g)
          {
            const py::ssize_t m = n(g.front_segments.size());
            std::vector<double> p(3 * m), q(3 * m), gphi(3 * m), gpsi(3 * m);
            std::vector<std::int32_t> cell(m);
            for (py::ssize_t i = 0; i < m; ++i)
            {
              const FrontSegment& sg = g.front_segments[i];
              std::copy(sg.p.begin(), sg.p.end(), p.begin() + 3 * i);
              std::copy(sg.q.begin(), sg.q.end(), q.begin() + 3 * i);
              std::copy(sg.grad_phi.begin(), sg.grad_phi.end(), gphi.begin() + 3 * i);
              std::copy(sg.grad_psi.begin(), sg.grad_psi.end(), gpsi.begin() + 3 * i);
              cell[i] = sg.cell;
            }
            py::dict d;
            d["p"] = as_pyarray(std::move(p), {m, 3});
            d["q"] = as_pyarray(std::move(q), {m, 3});
            d["cell"] = as_pyarray(std::move(cell));
            d["grad_phi"] = as_pyarray(std::move(gphi), {m, 3});
            d["grad_psi"] = as_pyarray(std::move(gpsi), {m, 3});
            d["cell_size"] = g.front_cell_size;
            return d;
          },
          "The segments the front was joined from: p, q (m, 3) physical end points (P -> Q along e3), cell (m), "
          "grad_phi, grad_psi (m, 3); cell_size the smallest front cell's largest edge (inf without front).")
      .def(
          "set_front",
          [](CrackGeometry3D& g, const carray<double>& p, const carray<double>& q, const carray<std::int32_t>& cell,
             const carray<double>& grad_phi, const carray<double>& grad_psi, const carray<double>& boundary_faces,
             double h_front, const CrackSurface3D* surface)
          {
            for (const auto* a : {&p, &q, &grad_phi, &grad_psi})
              require_columns(*a, 3, "front segment arrays");
            const py::ssize_t m = p.shape(0);
            if (q.shape(0) != m or grad_phi.shape(0) != m or grad_psi.shape(0) != m or cell.size() != m)
              throw std::invalid_argument("set_front: the segment arrays differ in length");
            std::vector<FrontSegment> segs(m);
            for (py::ssize_t i = 0; i < m; ++i)
              for (int k = 0; k < 3; ++k)
              {
                segs[i].p[k] = p.data()[3 * i + k], segs[i].q[k] = q.data()[3 * i + k];
                segs[i].grad_phi[k] = grad_phi.data()[3 * i + k], segs[i].grad_psi[k] = grad_psi.data()[3 * i + k];
                segs[i].cell = cell.data()[i];
              }
            set_crack_front_3d(g, segs, as_span(boundary_faces), h_front, surface);
          },
          py::arg("p"), py::arg("q"), py::arg("cell"), py::arg("grad_phi"), py::arg("grad_psi"),
          py::arg("boundary_faces"), py::arg("h_front"), py::arg("surface") = nullptr,
          "Replace the front by the one joined from these segments, in this order (set_crack_front_3d): "
          "boundary_faces (n, 3, 3) the part's boundary faces near the front; frames from surface if given.")
      .def_property_readonly(
          "front", [](const CrackGeometry3D& g) { return front_dict(g.front); },
          "The front: x (n, 3), s (n), frame (n, 3, 3) rows e1 e2 e3, cell (n), on_boundary (n), "
          "piece_offsets (pieces + 1), closed (pieces), segments (k, 2), segment_cell (k), num_branch_points.");

  m.def(
      "compute_crack_geometry_3d",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const CrackSurface3D& s, double snap_tol,
         std::optional<carray<std::int64_t>> node_keys, bool require_crack)
      {
        require_columns(x, 3, "x (node coordinates)");
        require_columns(cells, 4, "cells (node indices per tetrahedron)");
        return compute_crack_geometry_3d(as_span(x), as_span(cells), s, snap_tol,
                                         node_keys ? as_span(*node_keys) : std::span<const std::int64_t>(),
                                         require_crack);
      },
      py::arg("x"), py::arg("cells"), py::arg("surface"), py::arg("snap_tol") = 1e-6, py::arg("node_keys") = py::none(),
      py::arg("require_crack") = true,
      "Level sets, cell classes, sub-tetrahedra, lip facets and front of a crack surface; node_keys (n) int64: the "
      "order each cell's vertices are cut in (default the node indices; the mesh's input indices give the same "
      "sub-tetrahedra on any number of processes); require_crack False: no error when no cell is cut (one "
      "process's part of a mesh).");
  m.def(
      "compute_crack_geometry_3d",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const carray<double>& phi,
         const carray<double>& psi, double snap_tol)
      {
        require_columns(x, 3, "x (node coordinates)");
        require_columns(cells, 4, "cells (node indices per tetrahedron)");
        return compute_crack_geometry_3d(as_span(x), as_span(cells), as_span(phi), as_span(psi), snap_tol);
      },
      py::arg("x"), py::arg("cells"), py::arg("phi"), py::arg("psi"), py::arg("snap_tol") = 1e-6,
      "The same from nodal level sets (front frames from the P1 polyline).");
  m.def(
      "compute_front_projection_3d",
      [](const CrackGeometry3D& g, const carray<double>& p, std::optional<carray<double>> frames)
      {
        require_columns(p, 3, "points");
        const FrontLocator loc(g.front);
        const std::span<const double> fr = frames ? as_span(*frames) : std::span<const double>();
        const py::ssize_t np = p.shape(0);
        std::vector<std::int32_t> seg(np), piece(np), nearest(np);
        std::vector<double> t(np), xp(3 * np), dist(np), s(np), frame(9 * np);
        for (py::ssize_t i = 0; i < np; ++i)
        {
          const FrontProjection r = loc.project({p.data()[3 * i], p.data()[3 * i + 1], p.data()[3 * i + 2]}, fr);
          seg[i] = r.segment, piece[i] = r.piece, nearest[i] = r.nearest_point;
          t[i] = r.t, dist[i] = r.distance, s[i] = r.s;
          std::copy(r.x.begin(), r.x.end(), xp.begin() + 3 * i);
          for (int k = 0; k < 3; ++k)
            std::copy(r.frame[k].begin(), r.frame[k].end(), frame.begin() + 9 * i + 3 * k);
        }
        py::dict d;
        d["segment"] = as_pyarray(std::move(seg));
        d["t"] = as_pyarray(std::move(t));
        d["x"] = as_pyarray(std::move(xp), {np, 3});
        d["distance"] = as_pyarray(std::move(dist));
        d["s"] = as_pyarray(std::move(s));
        d["piece"] = as_pyarray(std::move(piece));
        d["nearest_point"] = as_pyarray(std::move(nearest));
        d["frame"] = as_pyarray(std::move(frame), {np, 3, 3});
        return d;
      },
      py::arg("geometry"), py::arg("points"), py::arg("frames") = py::none(),
      "Nearest point of the front polyline to each point (n, 3), with arc length and interpolated frame (of "
      "the front's points, or of frames (num_front_points, 3, 3) if given).");
  m.def(
      "compute_cell_quadrature_3d",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const CrackGeometry3D& g, std::int32_t cell,
         int degree, const std::string& front_rule, int front_radial, int front_angular, int front_axial,
         int front_degree, double near_factor, bool signed_point_rule)
      {
        require_columns(x, 3, "x (node coordinates)");
        require_columns(cells, 4, "cells (node indices per tetrahedron)");
        const QuadratureOptions3D o = quadrature_options(degree, front_rule, front_radial, front_angular,
                                                         front_axial, front_degree, near_factor, signed_point_rule);
        CellQuadrature3D q;
        compute_cell_quadrature_3d(as_span(x), as_span(cells), g, cell, o, q);
        const py::ssize_t nq = q.size();
        py::dict d;
        d["ref"] = as_pyarray(std::move(q.ref), {nq, 3});
        d["weight"] = as_pyarray(std::move(q.weight));
        d["side"] = as_pyarray(std::move(q.side));
        d["front_vertices"] = as_pyarray(std::move(q.front_vertices));
        return d;
      },
      py::arg("x"), py::arg("cells"), py::arg("geometry"), py::arg("cell"), py::arg("degree") = 2,
      py::arg("front_rule") = "collapsed", py::arg("front_radial") = 4, py::arg("front_angular") = 6,
      py::arg("front_axial") = 2, py::arg("front_degree") = 5, py::arg("near_factor") = 0.0,
      py::arg("signed_point_rule") = false,
      "Quadrature points of one cell (defaults: QuadratureOptions3D's): ref (n, 3), weight (n), side (n), "
      "front_vertices (n).");
  m.def(
      "tetrahedron_rule", [](int degree) { return rule_dict(quadrature::tetrahedron(degree)); }, py::arg("degree"),
      "Gauss rule on the reference tetrahedron exact to a degree: points (n, 3), weights (n) summing to 1/6.");
  m.def(
      "tetrahedron_edge_collapsed_rule",
      [](const carray<double>& xv, int n_tau, int n_eta, int n_t)
      {
        require_columns(xv, 3, "xv (vertices A, B, C, D)");
        if (xv.shape(0) != 4)
          throw std::invalid_argument("xv must be (4, 3)");
        return rule_dict(
            quadrature::tetrahedron_edge_collapsed(std::span<const double, 12>(xv.data(), 12), n_tau, n_eta, n_t));
      },
      py::arg("xv"), py::arg("n_tau") = 6, py::arg("n_eta") = 8, py::arg("n_t") = 3,
      "Edge-collapsed rule for a tetrahedron ABCD with AB on the front, in its own coordinates.");
  m.def(
      "tetrahedron_point_collapsed_rule",
      [](const carray<double>& xv, const carray<double>& front, int n_tau, int n_eta, int n_t)
      {
        require_columns(xv, 3, "xv (vertices A, B, C, D)");
        if (xv.shape(0) != 4)
          throw std::invalid_argument("xv must be (4, 3)");
        const Point3 d = point3(front, "front");
        return rule_dict(quadrature::tetrahedron_point_collapsed(std::span<const double, 12>(xv.data(), 12), d,
                                                                 n_tau, n_eta, n_t));
      },
      py::arg("xv"), py::arg("front"), py::arg("n_tau") = 6, py::arg("n_eta") = 8, py::arg("n_t") = 3,
      "Point-collapsed rule for a tetrahedron ABCD with A on the front (direction `front`).");
}

} // namespace cracklip_wrappers
