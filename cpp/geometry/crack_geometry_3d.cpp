#include "geometry/crack_geometry_3d.h"

#include "geometry/mesh_arrays.h"
#include "geometry/p1_simplex.h"
#include "geometry/snapping.h"
#include "geometry/vec3.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>
#include <string>

namespace cracklip
{
using namespace vec3;

namespace
{
constexpr std::array<Point3, 4> ref_vertex = {Point3{0, 0, 0}, Point3{1, 0, 0}, Point3{0, 1, 0}, Point3{0, 0, 1}};
/// Sub-tetrahedra below this fraction of the cell's volume are dropped.
constexpr double sliver_tol = 1e-12;
/// A level set interpolated at a cut point (psi at a cut by phi, phi at a
/// cut by psi) below this fraction of the cell's largest nodal |value| is 0:
/// points within round-off of the front are on it.
constexpr double zero_tol = 1e-12;

/// A point of a cell's sub-division: reference coordinates and both level
/// sets (exact zeros where the point lies on phi = 0 or psi = 0 by
/// construction).
struct Vertex
{
  Point3 r;
  double phi, psi;
  bool on_front() const { return phi == 0.0 and psi == 0.0; }
};

std::string fmt_box(const std::array<double, 6>& b)
{
  std::ostringstream s;
  s.precision(6);
  s << "[" << b[0] << ", " << b[3] << "] x [" << b[1] << ", " << b[4] << "] x [" << b[2] << ", " << b[5] << "]";
  return s.str();
}

/// Put the front vertices first (keeping at most two: the farthest pair if
/// round-off marked more), return their number.
template <std::size_t N>
int front_first(std::array<Vertex, N>& v, std::array<bool, N>& front)
{
  std::array<int, N> idx;
  std::iota(idx.begin(), idx.end(), 0);
  int nf = 0;
  for (std::size_t i = 0; i < N; ++i)
    nf += front[i];
  if (nf > 2)
  {
    double best = -1.0;
    std::size_t bi = 0, bj = 0;
    for (std::size_t i = 0; i < N; ++i)
      for (std::size_t j = i + 1; j < N; ++j)
        if (front[i] and front[j] and dist(v[i].r, v[j].r) > best)
          best = dist(v[i].r, v[j].r), bi = i, bj = j;
    for (std::size_t i = 0; i < N; ++i)
      front[i] = i == bi or i == bj;
    nf = 2;
  }
  std::stable_partition(idx.begin(), idx.end(), [&](int i) { return front[i]; });
  std::array<Vertex, N> w;
  for (std::size_t i = 0; i < N; ++i)
    w[i] = v[idx[i]];
  v = w;
  return nf;
}

/// Everything the crack does in one cell.
class CellCutter
{
public:
  CellCutter(const P1Tetrahedron& T, std::int32_t c, const std::array<double, 4>& f, const std::array<double, 4>& g,
             std::span<const std::int64_t> node_keys)
      : T_(T), c_(c)
  {
    for (int a = 0; a < 4; ++a)
    {
      fmax_ = std::max(fmax_, std::abs(f[a]));
      gmax_ = std::max(gmax_, std::abs(g[a]));
    }
    grad_phi_ = T.gradient(f);
    grad_psi_ = T.gradient(g);
    // Vertices in ascending node order (node_keys' if given): cut points on
    // an edge shared by several cells are then computed from the same
    // numbers in each, and the sub-tetrahedra do not depend on how the
    // nodes are numbered locally.
    std::array<std::int64_t, 4> key;
    for (int a = 0; a < 4; ++a)
      key[a] = node_keys.empty() ? T.nodes[a] : node_keys[T.nodes[a]];
    std::array<int, 4> perm = {0, 1, 2, 3};
    std::sort(perm.begin(), perm.end(), [&](int a, int b) { return key[a] < key[b]; });
    for (int k = 0; k < 4; ++k)
    {
      for (int d = 0; d < 3; ++d)
        xin_[3 * k + d] = ref_vertex[perm[k]][d];
      fin_[k] = f[perm[k]];
      gin_[k] = g[perm[k]];
    }
    cut_tetrahedron(xin_, fin_, cut_);
    for (int p = 0; p < cut_.num_points; ++p)
      pts_[p] = {cut_.x[p], p < 4 ? fin_[p] : 0.0, p < 4 ? gin_[p] : zero_psi(cut_.from[p].interpolate(gin_))};
  }

  ZeroSet kind() const { return cut_.kind; }

  /// The zero set of phi in the closed cell as triangles (cut: the
  /// interface; face: the face), oriented to + in reference coordinates.
  std::vector<std::array<Vertex, 3>> zero_triangles() const
  {
    std::vector<std::array<Vertex, 3>> out;
    for (int k = 0; k < cut_.num_interface; ++k)
      out.push_back({pts_[cut_.interface[k][0]], pts_[cut_.interface[k][1]], pts_[cut_.interface[k][2]]});
    return out;
  }

  /// Points of the zero set of phi: the interface's (cut, face) or the zero
  /// vertices (vertex, edge kinds).
  std::vector<Vertex> zero_points() const
  {
    std::vector<Vertex> out;
    if (cut_.kind == ZeroSet::cut or cut_.kind == ZeroSet::face)
    {
      for (int p = 0; p < cut_.num_points; ++p)
        if (pts_[p].phi == 0.0)
          out.push_back(pts_[p]);
    }
    else
      for (int p = 0; p < 4; ++p)
        if (fin_[p] == 0.0)
          out.push_back(pts_[p]);
    return out;
  }

  /// Sub-tetrahedra of the cut by phi (or the cell), with their side.
  void phi_pieces(std::vector<std::array<Vertex, 4>>& tets, std::vector<int>& sides) const
  {
    for (int k = 0; k < cut_.num_tets; ++k)
    {
      const auto& t = cut_.tets[k];
      tets.push_back({pts_[t[0]], pts_[t[1]], pts_[t[2]], pts_[t[3]]});
      sides.push_back(cut_.side[k]);
    }
  }

  /// Add sub-tetrahedra to cc: the phi pieces, cut again by psi if
  /// `second_cut` (front cells).
  void add_sub_tetrahedra(CrackCell3D& cc, bool second_cut) const
  {
    std::vector<std::array<Vertex, 4>> tets;
    std::vector<int> sides;
    phi_pieces(tets, sides);
    for (std::size_t k = 0; k < tets.size(); ++k)
    {
      if (!second_cut)
      {
        add_tet(cc, tets[k], sides[k], 0);
        continue;
      }
      const auto& t = tets[k];
      std::array<double, 12> xs;
      std::array<double, 4> ps, fs;
      for (int i = 0; i < 4; ++i)
      {
        for (int d = 0; d < 3; ++d)
          xs[3 * i + d] = t[i].r[d];
        ps[i] = t[i].psi;
        fs[i] = t[i].phi;
      }
      if (ps[0] == 0.0 and ps[1] == 0.0 and ps[2] == 0.0 and ps[3] == 0.0)
      {
        // psi vanishes on the whole cell (every node on psi = 0, e.g. around
        // a polygon's corner at a node): the piece stays whole, on the
        // crack's side (psi <= 0); its front vertices are its phi = 0 ones.
        add_tet(cc, t, sides[k], -1);
        continue;
      }
      TetrahedronCut c2;
      cut_tetrahedron(xs, ps, c2);
      std::array<Vertex, 8> v;
      for (int p = 0; p < c2.num_points; ++p)
        v[p] = p < 4 ? t[p] : Vertex{c2.x[p], zero_phi(c2.from[p].interpolate(fs)), 0.0};
      for (int j = 0; j < c2.num_tets; ++j)
      {
        const auto& q = c2.tets[j];
        add_tet(cc, {v[q[0]], v[q[1]], v[q[2]], v[q[3]]}, sides[k], c2.side[j]);
      }
    }
  }

  /// Add the lip facets held by this cell: the zero triangles of phi (for a
  /// face only on the + side cell), where psi <= 0 (cut by psi in front
  /// cells).
  void add_facets(CrackCell3D& cc, int cell_side, bool second_cut) const
  {
    if (cut_.kind == ZeroSet::face and cell_side < 0)
      return;
    for (const auto& tri : zero_triangles())
    {
      if (!second_cut)
      {
        add_facet(cc, tri);
        continue;
      }
      std::array<double, 9> xs;
      std::array<double, 3> ps;
      for (int i = 0; i < 3; ++i)
      {
        for (int d = 0; d < 3; ++d)
          xs[3 * i + d] = tri[i].r[d];
        ps[i] = tri[i].psi;
      }
      if (ps[0] == 0.0 and ps[1] == 0.0 and ps[2] == 0.0)
        continue; // a triangle within the front line: zero area
      TriangleCut c2;
      cut_triangle(xs, ps, c2);
      std::array<Vertex, 5> v;
      for (int p = 0; p < c2.num_points; ++p)
        v[p] = p < 3 ? tri[p] : Vertex{c2.x[p], 0.0, 0.0};
      for (int j = 0; j < c2.num_tris; ++j)
        if (c2.side[j] < 0)
          add_facet(cc, {v[c2.tris[j][0]], v[c2.tris[j][1]], v[c2.tris[j][2]]});
    }
  }

  /// The front segment in the cell (front cells): the points of phi = 0
  /// where psi = 0, extreme along grad psi x grad phi. Returns false when the
  /// front meets the cell in a point only.
  bool front_segment(CrackCell3D& cc, FrontSegment& seg, double h_cell) const
  {
    std::vector<Point3> cand;
    if (cut_.kind == ZeroSet::cut or cut_.kind == ZeroSet::face)
    {
      for (const auto& tri : zero_triangles())
      {
        std::array<double, 9> xs;
        std::array<double, 3> ps;
        for (int i = 0; i < 3; ++i)
        {
          for (int d = 0; d < 3; ++d)
            xs[3 * i + d] = tri[i].r[d];
          ps[i] = tri[i].psi;
          if (ps[i] == 0.0)
            cand.push_back(tri[i].r);
        }
        if (ps[0] == 0.0 and ps[1] == 0.0 and ps[2] == 0.0)
          continue;
        TriangleCut c2;
        cut_triangle(xs, ps, c2);
        if (c2.zero_segment[0] >= 0)
          for (int e : c2.zero_segment)
            cand.push_back(c2.x[e]);
      }
    }
    else
    {
      const std::vector<Vertex> z = zero_points();
      for (const Vertex& p : z)
        if (p.psi == 0.0)
          cand.push_back(p.r);
      if (z.size() == 2 and z[0].psi * z[1].psi < 0.0)
      {
        const double t = z[0].psi / (z[0].psi - z[1].psi);
        cand.push_back(axpy(z[0].r, t, sub(z[1].r, z[0].r)));
      }
    }
    if (cand.size() < 2)
      return false;
    // Extremes along the front direction (physical), grad psi x grad phi;
    // if psi vanishes on the whole cell, the front is the zero edge of phi
    // (oriented later by its neighbours in the polyline).
    // With parallel gradients psi vanishes on the whole zero set of phi in
    // the cell (a front cell has psi = 0 on it somewhere): no crack there,
    // and a front line only if that zero set is an edge.
    Point3 dir = cross(grad_psi_, grad_phi_);
    if (!(norm(dir) > 1e-12 * norm(grad_psi_) * norm(grad_phi_)) or norm(grad_psi_) == 0.0)
    {
      if (cut_.kind != ZeroSet::edge)
        return false;
      dir = sub(T_.physical(cand.back()), T_.physical(cand.front()));
    }
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    Point3 P = cand[0], Q = cand[0];
    for (const Point3& r : cand)
    {
      const double s = dot(T_.physical(r), dir);
      if (s < lo)
        lo = s, P = r;
      if (s > hi)
        hi = s, Q = r;
    }
    cc.front_segment = {P[0], P[1], P[2], Q[0], Q[1], Q[2]};
    const Point3 Pp = T_.physical(P), Qp = T_.physical(Q);
    cc.front_length = dist(Pp, Qp);
    if (!(cc.front_length > 1e-10 * h_cell))
    {
      cc.front_length = 0.0;
      return false;
    }
    seg = {Pp, Qp, c_, grad_phi_, grad_psi_};
    return true;
  }

  const Point3& grad_phi() const { return grad_phi_; }

private:
  double zero_psi(double v) const { return std::abs(v) <= zero_tol * gmax_ ? 0.0 : v; }
  double zero_phi(double v) const { return std::abs(v) <= zero_tol * fmax_ ? 0.0 : v; }

  void add_tet(CrackCell3D& cc, std::array<Vertex, 4> v, int side, int psi_side) const
  {
    const double vol = signed_volume(v[0].r, v[1].r, v[2].r, v[3].r);
    if (std::abs(vol) < sliver_tol / 6.0)
    {
      cc.dropped_volume += std::abs(vol);
      return;
    }
    std::array<bool, 4> front;
    for (int i = 0; i < 4; ++i)
      front[i] = v[i].on_front();
    const int nf = front_first(v, front);
    if (signed_volume(v[0].r, v[1].r, v[2].r, v[3].r) < 0.0)
      std::swap(v[2], v[3]);
    for (const Vertex& p : v)
      cc.sub.insert(cc.sub.end(), p.r.begin(), p.r.end());
    cc.side.push_back(static_cast<std::int8_t>(side));
    cc.psi_side.push_back(static_cast<std::int8_t>(psi_side));
    cc.num_front.push_back(static_cast<std::int8_t>(nf));
  }

  void add_facet(CrackCell3D& cc, std::array<Vertex, 3> v) const
  {
    Point3 n = cross(sub(T_.physical(v[1].r), T_.physical(v[0].r)), sub(T_.physical(v[2].r), T_.physical(v[0].r)));
    const double area = 0.5 * norm(n);
    // Against the cell's face scale: |det J|^(2/3).
    if (!(area > sliver_tol * std::pow(std::abs(T_.detJ), 2.0 / 3.0)))
      return;
    std::array<bool, 3> front;
    for (int i = 0; i < 3; ++i)
      front[i] = v[i].psi == 0.0; // all facet points have phi = 0
    const int nf = front_first(v, front);
    n = cross(sub(T_.physical(v[1].r), T_.physical(v[0].r)), sub(T_.physical(v[2].r), T_.physical(v[0].r)));
    if (dot(n, grad_phi_) < 0.0)
    {
      if (nf == 2)
        std::swap(v[0], v[1]);
      else
        std::swap(v[1], v[2]);
      n = scale(-1.0, n);
    }
    for (const Vertex& p : v)
      cc.facets.insert(cc.facets.end(), p.r.begin(), p.r.end());
    cc.facet_area.push_back(area);
    const Point3 u = unit(n);
    cc.facet_normal.insert(cc.facet_normal.end(), u.begin(), u.end());
    cc.facet_num_front.push_back(static_cast<std::int8_t>(nf));
  }

  const P1Tetrahedron& T_;
  std::int32_t c_;
  double fmax_ = 0.0, gmax_ = 0.0;
  Point3 grad_phi_, grad_psi_;
  std::array<double, 12> xin_;
  std::array<double, 4> fin_, gin_;
  TetrahedronCut cut_;
  std::array<Vertex, 8> pts_;
};
} // namespace

CrackGeometry3D compute_crack_geometry_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                          std::span<const double> phi, std::span<const double> psi, double snap_tol,
                                          std::span<const std::int64_t> node_keys, bool require_crack)
{
  if (x.size() % 3 != 0 or cells.size() % 4 != 0)
    throw std::invalid_argument("compute_crack_geometry_3d: x must be (n, 3) and cells (m, 4)");
  const std::size_t num_nodes = x.size() / 3, num_cells = cells.size() / 4;
  if (phi.size() != num_nodes or psi.size() != num_nodes)
    throw std::invalid_argument("compute_crack_geometry_3d: phi and psi must have one value per node ("
                                + std::to_string(num_nodes) + "), got " + std::to_string(phi.size()) + " and "
                                + std::to_string(psi.size()));
  if (!(snap_tol >= 0.0 and snap_tol < 0.5))
    throw std::invalid_argument("compute_crack_geometry_3d: snap_tol must be in [0, 0.5), got "
                                + std::to_string(snap_tol));
  check_mesh_arrays(x, 3, cells, 4, "compute_crack_geometry_3d");
  if (!node_keys.empty() and node_keys.size() != num_nodes)
    throw std::invalid_argument("compute_crack_geometry_3d: node_keys must have one value per node");
  for (std::size_t i = 0; i < num_nodes; ++i)
    if (!std::isfinite(phi[i]) or !std::isfinite(psi[i]))
      throw std::invalid_argument("compute_crack_geometry_3d: a level set is not finite at node "
                                  + std::to_string(i));

  CrackGeometry3D g;
  const std::vector<double> h_node = compute_shortest_edges(x, 3, cells, 4);
  g.phi.assign(phi.begin(), phi.end());
  g.psi.assign(psi.begin(), psi.end());
  std::vector<char> snapped(num_nodes, 0);
  snap_to_zero(g.phi, h_node, snap_tol, snapped);
  snap_to_zero(g.psi, h_node, snap_tol, snapped);
  for (char s : snapped)
    g.num_snapped += s;

  g.cell_class.assign(num_cells, static_cast<std::int8_t>(CellClass3D::plain));
  g.cell_side.assign(num_cells, 0);
  g.crack_cell_index.assign(num_cells, -1);
  std::vector<FrontSegment> segments;
  // Faces of front cells (sorted global nodes) and how many front cells hold them.
  std::map<std::array<std::int32_t, 3>, std::pair<int, std::array<double, 9>>> front_faces;
  double h_front = std::numeric_limits<double>::infinity();
  std::int32_t num_extension = 0;

  for (std::size_t c = 0; c < num_cells; ++c)
  {
    const std::int32_t* v = &cells[4 * c];
    const std::array<double, 4> f = {g.phi[v[0]], g.phi[v[1]], g.phi[v[2]], g.phi[v[3]]};
    int npos = 0, nneg = 0;
    for (double fi : f)
      npos += fi > 0.0, nneg += fi < 0.0;
    const int nzero = 4 - npos - nneg;
    if (nzero == 0 and (npos == 0 or nneg == 0))
    {
      g.cell_side[c] = static_cast<std::int8_t>(npos > 0 ? 1 : -1);
      continue; // plain: phi = 0 does not meet the cell
    }
    if (nzero == 4)
      throw std::runtime_error("compute_crack_geometry_3d: all four nodes of cell " + std::to_string(c)
                               + " lie on the crack surface (phi = 0): a degenerate cell, or snap_tol too large");
    const std::array<double, 4> gv = {g.psi[v[0]], g.psi[v[1]], g.psi[v[2]], g.psi[v[3]]};
    if (gv[0] > 0.0 and gv[1] > 0.0 and gv[2] > 0.0 and gv[3] > 0.0)
    {
      // psi > 0 on the whole cell: phi = 0 crosses it where the crack is
      // absent (no cutting needed: the work stays with the crack's cells).
      const bool straddled = npos > 0 and nneg > 0;
      g.cell_class[c] = static_cast<std::int8_t>(straddled ? CellClass3D::extension : CellClass3D::plain);
      g.cell_side[c] = static_cast<std::int8_t>(straddled ? 0 : (npos > 0 ? 1 : -1));
      num_extension += straddled;
      continue;
    }
    const P1Tetrahedron T(x, cells, static_cast<std::int32_t>(c));
    const CellCutter cutter(T, static_cast<std::int32_t>(c), f, gv, node_keys);
    const ZeroSet kind = cutter.kind();
    const int side = kind == ZeroSet::cut ? 0 : (npos > 0 ? 1 : -1);
    // psi over the zero set of phi in the closed cell.
    double pmin = std::numeric_limits<double>::infinity(), pmax = -pmin;
    for (const Vertex& p : cutter.zero_points())
      pmin = std::min(pmin, p.psi), pmax = std::max(pmax, p.psi);
    // The crack is {phi = 0, psi < 0}; the front meets the closed cell where
    // psi changes sign or vanishes on the zero set of phi.
    CellClass3D cls;
    if (pmin <= 0.0 and pmax >= 0.0)
      cls = CellClass3D::front;
    else if (pmax < 0.0)
      cls = kind == ZeroSet::cut ? CellClass3D::cut : (kind == ZeroSet::face ? CellClass3D::face : CellClass3D::plain);
    else
      cls = kind == ZeroSet::cut ? CellClass3D::extension : CellClass3D::plain;
    g.num_degenerate_front_cells += pmin == 0.0 and pmax == 0.0 and (kind == ZeroSet::cut or kind == ZeroSet::face);
    g.cell_class[c] = static_cast<std::int8_t>(cls);
    g.cell_side[c] = static_cast<std::int8_t>(cls == CellClass3D::plain or cls == CellClass3D::face ? side : 0);
    num_extension += cls == CellClass3D::extension;
    if (cls == CellClass3D::plain or cls == CellClass3D::extension)
      continue;

    CrackCell3D cc;
    cc.cell = static_cast<std::int32_t>(c);
    cc.cls = cls;
    const bool at_front = cls == CellClass3D::front;
    cutter.add_sub_tetrahedra(cc, at_front);
    cutter.add_facets(cc, side, at_front);
    if (at_front)
    {
      double h_cell = 0.0;
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b)
          h_cell = std::max(h_cell, dist(T.xv[a], T.xv[b]));
      h_front = std::min(h_front, h_cell);
      // The polyline takes the segments of the cells where the crack is
      // present (psi < 0 somewhere on the zero set of phi): a front is the
      // border of the crack. (Around a polygon crack's corner at a node, P1
      // psi may vanish on a whole triangle; its edges border no crack.)
      FrontSegment seg;
      if (cutter.front_segment(cc, seg, h_cell) and pmin < 0.0)
        segments.push_back(seg);
      static constexpr int face_of[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
      for (const auto& fa : face_of)
      {
        std::array<std::int32_t, 3> key = {v[fa[0]], v[fa[1]], v[fa[2]]};
        std::sort(key.begin(), key.end());
        auto& entry = front_faces[key];
        ++entry.first;
        for (int i = 0; i < 3; ++i)
          for (int d = 0; d < 3; ++d)
            entry.second[3 * i + d] = T.xv[fa[i]][d];
      }
    }
    g.crack_cell_index[c] = static_cast<std::int32_t>(g.crack_cells.size());
    g.crack_cells.push_back(std::move(cc));
  }

  if (g.crack_cells.empty() and require_crack)
  {
    std::array<double, 6> box = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                                 std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                                 -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (std::size_t i = 0; i < num_nodes; ++i)
      for (int d = 0; d < 3; ++d)
        box[d] = std::min(box[d], x[3 * i + d]), box[3 + d] = std::max(box[3 + d], x[3 * i + d]);
    throw CrackOutsideMesh("no cell of the mesh (bounding box " + fmt_box(box)
                           + ") is cut by the crack: the crack surface lies outside the part"
                           + (num_extension > 0 ? " (its plane crosses " + std::to_string(num_extension)
                                                      + " cells, where psi > 0: the crack is absent there)"
                                                : std::string(""))
                           + "; move the crack into the part or check its units");
  }

  // Faces held by one front cell only: candidates for the part's boundary.
  std::vector<double> boundary_faces;
  for (const auto& [key, entry] : front_faces)
    if (entry.first == 1)
      boundary_faces.insert(boundary_faces.end(), entry.second.begin(), entry.second.end());
  if (!segments.empty())
    g.front = create_crack_front_3d(segments, boundary_faces, JOIN_TOLERANCE * h_front);
  g.front_segments = std::move(segments);
  g.front_cell_size = h_front;
  return g;
}

namespace
{
/// Frames from the surface: its analytic directions at each front point
/// (O(h^2) accurate, as the point) instead of the P1 polyline's (O(h)).
void surface_frames(CrackFront3D& f, const CrackSurface3D& surface)
{
  for (std::int32_t i = 0; i < f.num_points(); ++i)
  {
    const auto [d1, d2] = surface.front_directions({f.x[3 * i], f.x[3 * i + 1], f.x[3 * i + 2]});
    const Point3 e2 = unit(d2);
    const Point3 e1 = unit(axpy(d1, -dot(d1, e2), e2));
    const Point3 e3 = cross(e1, e2);
    std::copy(e1.begin(), e1.end(), f.frame.begin() + 9 * i);
    std::copy(e2.begin(), e2.end(), f.frame.begin() + 9 * i + 3);
    std::copy(e3.begin(), e3.end(), f.frame.begin() + 9 * i + 6);
  }
}
} // namespace

CrackGeometry3D compute_crack_geometry_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                          const CrackSurface3D& surface, double snap_tol,
                                          std::span<const std::int64_t> node_keys, bool require_crack)
{
  const LevelSets3D ls = compute_level_sets_3d(x, surface);
  CrackGeometry3D g;
  try
  {
    g = compute_crack_geometry_3d(x, cells, ls.phi, ls.psi, snap_tol, node_keys, require_crack);
  }
  catch (const CrackOutsideMesh& e)
  {
    throw CrackOutsideMesh(surface.describe() + ", bounding box " + fmt_box(surface.bounding_box()) + ": "
                           + e.what());
  }
  surface_frames(g.front, surface);
  return g;
}

void set_crack_front_3d(CrackGeometry3D& g, std::span<const FrontSegment> segments,
                        std::span<const double> boundary_faces, double h_front, const CrackSurface3D* surface)
{
  if (boundary_faces.size() % 9 != 0)
    throw std::invalid_argument("set_crack_front_3d: boundary_faces must be (n, 3, 3)");
  if (segments.empty())
  {
    g.front = CrackFront3D();
    return;
  }
  if (!(h_front > 0.0) or !std::isfinite(h_front))
    throw std::invalid_argument("set_crack_front_3d: h_front must be finite and > 0");
  g.front = create_crack_front_3d(segments, boundary_faces, JOIN_TOLERANCE * h_front);
  if (surface)
    surface_frames(g.front, *surface);
}

} // namespace cracklip
