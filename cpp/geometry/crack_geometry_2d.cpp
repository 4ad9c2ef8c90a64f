#include "geometry/crack_geometry_2d.h"

#include "geometry/mesh_arrays.h"
#include "geometry/snapping.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>

namespace cracklip
{
namespace
{
using P2 = std::array<double, 2>;

constexpr std::array<P2, 3> ref_vertex = {P2{0.0, 0.0}, P2{1.0, 0.0}, P2{0.0, 1.0}};

P2 lerp(P2 a, P2 b, double t) { return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])}; }

int sgn(double v) { return (v > 0.0) - (v < 0.0); }

/// Closest point on the polyline; `rays` extends the first and last segment
/// beyond the end points. Returns distance and a unit normal used for the
/// sign (segment normal, or the mean normal at an interior vertex).
struct Closest
{
  double dist;
  double sign;
};

Closest closest(const CrackPath& crack, P2 p, bool rays)
{
  const auto& q = crack.points;
  const int nseg = static_cast<int>(q.size() / 2) - 1;
  double best = std::numeric_limits<double>::max();
  double best_sign = 0.0;
  for (int k = 0; k < nseg; ++k)
  {
    const P2 a = {q[2 * k], q[2 * k + 1]}, b = {q[2 * k + 2], q[2 * k + 3]};
    const P2 d = {b[0] - a[0], b[1] - a[1]};
    const double len2 = d[0] * d[0] + d[1] * d[1];
    double t = ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2;
    const double lo = (rays and k == 0) ? -std::numeric_limits<double>::infinity() : 0.0;
    const double hi = (rays and k == nseg - 1) ? std::numeric_limits<double>::infinity() : 1.0;
    t = std::clamp(t, lo, hi);
    const P2 c = {a[0] + t * d[0], a[1] + t * d[1]};
    const double dist = std::hypot(p[0] - c[0], p[1] - c[1]);
    if (dist < best)
    {
      best = dist;
      const double len = std::sqrt(len2);
      P2 n = {-d[1] / len, d[0] / len};
      // At an interior polyline vertex use the mean of both normals.
      int kv = -1;
      if (t == 0.0 and k > 0)
        kv = k - 1;
      else if (t == 1.0 and k < nseg - 1)
        kv = k + 1;
      if (kv >= 0)
      {
        const P2 a2 = {q[2 * kv], q[2 * kv + 1]}, b2 = {q[2 * kv + 2], q[2 * kv + 3]};
        const double l2 = std::hypot(b2[0] - a2[0], b2[1] - a2[1]);
        n = {n[0] - (b2[1] - a2[1]) / l2, n[1] + (b2[0] - a2[0]) / l2};
      }
      best_sign = sgn((p[0] - c[0]) * n[0] + (p[1] - c[1]) * n[1]);
    }
  }
  return {best, best_sign};
}

/// Parameter interval [lo, hi] of the segment P + s (Q - P), s in [0, 1],
/// where every tip level set is <= 0 (the crack is present).
std::array<double, 2> present_interval(const std::vector<double>& psiP,
                                       const std::vector<double>& psiQ)
{
  double lo = 0.0, hi = 1.0;
  for (std::size_t j = 0; j < psiP.size(); ++j)
  {
    const double a = psiP[j], b = psiQ[j];
    if (a <= 0.0 and b <= 0.0)
      continue;
    if (a > 0.0 and b > 0.0)
      return {1.0, 0.0};
    const double s = a / (a - b);
    if (a <= 0.0)
      hi = std::min(hi, s);
    else
      lo = std::max(lo, s);
  }
  return {lo, hi};
}

} // namespace

double signed_distance(const CrackPath& crack, std::array<double, 2> p)
{
  const Closest c = closest(crack, p, true);
  return c.sign * c.dist;
}

CrackGeometry compute_crack_geometry(std::span<const double> x,
                                     std::span<const std::int32_t> cells,
                                     const CrackPath& crack, double snap_tol)
{
  if (x.size() % 2 != 0 or cells.size() % 3 != 0)
    throw std::invalid_argument("compute_crack_geometry: x must be (n, 2) and cells (m, 3)");
  const std::size_t npts = crack.points.size() / 2;
  if (npts < 2 or crack.points.size() % 2 != 0)
    throw std::invalid_argument("compute_crack_geometry: a crack needs at least two points (x, y), got "
                                + std::to_string(crack.points.size()) + " coordinates");
  for (std::size_t k = 0; k < npts; ++k)
    if (!std::isfinite(crack.points[2 * k]) or !std::isfinite(crack.points[2 * k + 1]))
      throw std::invalid_argument("compute_crack_geometry: crack point " + std::to_string(k)
                                  + " is not finite; crack points must be finite numbers");
  for (std::size_t k = 0; k + 1 < npts; ++k)
  {
    const double len = std::hypot(crack.points[2 * k + 2] - crack.points[2 * k],
                                  crack.points[2 * k + 3] - crack.points[2 * k + 1]);
    if (!(len > 0.0))
      throw std::invalid_argument("compute_crack_geometry: crack segment " + std::to_string(k)
                                  + " has zero length; remove the repeated point");
  }
  if (!(snap_tol >= 0.0 and snap_tol < 0.5))
    throw std::invalid_argument("compute_crack_geometry: snap_tol must be in [0, 0.5), got "
                                + std::to_string(snap_tol));

  const std::size_t num_nodes = x.size() / 2;
  const std::size_t num_cells = cells.size() / 3;
  check_mesh_arrays(x, 2, cells, 3, "compute_crack_geometry");

  CrackGeometry g;

  // Shortest edge at each node (snapping scale) and longest edge per cell.
  const std::vector<double> h_node = compute_shortest_edges(x, 2, cells, 3);
  std::vector<double> h_cell(num_cells, 0.0);
  for (std::size_t c = 0; c < num_cells; ++c)
    for (int i = 0; i < 3; ++i)
    {
      const int a = cells[3 * c + i], b = cells[3 * c + (i + 1) % 3];
      h_cell[c] = std::max(h_cell[c], std::hypot(x[2 * a] - x[2 * b], x[2 * a + 1] - x[2 * b + 1]));
    }

  // Level sets with snapping.
  g.phi.resize(num_nodes);
  std::vector<char> snapped(num_nodes, 0);
  for (std::size_t i = 0; i < num_nodes; ++i)
    g.phi[i] = signed_distance(crack, {x[2 * i], x[2 * i + 1]});
  snap_to_zero(g.phi, h_node, snap_tol, snapped);
  for (int e = 0; e < 2; ++e)
  {
    if (!crack.tip[e])
      continue;
    const std::size_t i0 = (e == 0) ? 0 : npts - 1;
    const std::size_t i1 = (e == 0) ? 1 : npts - 2;
    const P2 T = {crack.points[2 * i0], crack.points[2 * i0 + 1]};
    P2 t = {T[0] - crack.points[2 * i1], T[1] - crack.points[2 * i1 + 1]};
    const double len = std::hypot(t[0], t[1]);
    t = {t[0] / len, t[1] / len};
    g.tips.insert(g.tips.end(), T.begin(), T.end());
    g.tip_tangents.insert(g.tip_tangents.end(), t.begin(), t.end());
    g.tip_orientation.push_back(e == 0 ? -1 : 1);
    const std::size_t offset = g.psi.size();
    for (std::size_t i = 0; i < num_nodes; ++i)
      g.psi.push_back((x[2 * i] - T[0]) * t[0] + (x[2 * i + 1] - T[1]) * t[1]);
    snap_to_zero(std::span(g.psi).subspan(offset, num_nodes), h_node, snap_tol, snapped);
  }
  const int num_tips = static_cast<int>(g.tips.size() / 2);
  for (char s : snapped)
    g.num_snapped += s;

  g.cell_class.assign(num_cells, static_cast<std::int8_t>(CellClass::plain));
  g.cell_side.assign(num_cells, 0);
  g.crack_cell_index.assign(num_cells, -1);
  g.tip_cell_index.assign(num_cells, -1);

  std::vector<double> psiP(num_tips), psiQ(num_tips);
  for (std::size_t c = 0; c < num_cells; ++c)
  {
    const std::int32_t* v = &cells[3 * c];
    const std::array<double, 3> f = {g.phi[v[0]], g.phi[v[1]], g.phi[v[2]]};
    const std::array<int, 3> s = {sgn(f[0]), sgn(f[1]), sgn(f[2])};
    const int npos = (s[0] > 0) + (s[1] > 0) + (s[2] > 0);
    const int nneg = (s[0] < 0) + (s[1] < 0) + (s[2] < 0);
    const int nzero = 3 - npos - nneg;
    if (nzero == 3)
      throw std::runtime_error("compute_crack_geometry: all three nodes of cell "
                               + std::to_string(c)
                               + " lie on the crack (degenerate cell or snap_tol too large)");

    // Physical position of a reference point.
    auto phys = [&](P2 r)
    {
      P2 out;
      for (int d = 0; d < 2; ++d)
        out[d] = x[2 * v[0] + d] + r[0] * (x[2 * v[1] + d] - x[2 * v[0] + d])
                 + r[1] * (x[2 * v[2] + d] - x[2 * v[0] + d]);
      return out;
    };
    auto psi_at = [&](P2 r, std::vector<double>& out)
    {
      for (int j = 0; j < num_tips; ++j)
      {
        const double* p = &g.psi[j * num_nodes];
        out[j] = p[v[0]] + r[0] * (p[v[1]] - p[v[0]]) + r[1] * (p[v[2]] - p[v[0]]);
      }
    };
    // Orient P -> Q so that phi grows to the left.
    auto orient = [&](P2& P, P2& Q)
    {
      const P2 Pp = phys(P), Qp = phys(Q);
      const P2 n = {-(Qp[1] - Pp[1]), Qp[0] - Pp[0]};
      // Gradient of phi_h along n via the reference map.
      const double J00 = x[2 * v[1]] - x[2 * v[0]], J01 = x[2 * v[2]] - x[2 * v[0]];
      const double J10 = x[2 * v[1] + 1] - x[2 * v[0] + 1], J11 = x[2 * v[2] + 1] - x[2 * v[0] + 1];
      const double det = J00 * J11 - J01 * J10;
      const double gr0 = f[1] - f[0], gr1 = f[2] - f[0];
      const double gx = (J11 * gr0 - J10 * gr1) / det, gy = (-J01 * gr0 + J00 * gr1) / det;
      if (gx * n[0] + gy * n[1] < 0.0)
        std::swap(P, Q);
    };

    // Orient the zero-line segment PQ of phi_h (+ side on its left) and find
    // where on it the crack is present: [lo, hi] in its parameter, and
    // whether a crack piece longer than round-off is there. The distance
    // check guards against far-field sign flips of phi.
    auto presence = [&](P2& P, P2& Q)
    {
      orient(P, Q);
      psi_at(P, psiP);
      psi_at(Q, psiQ);
      const auto [lo, hi] = present_interval(psiP, psiQ);
      const double len = hi - lo;
      const P2 M = phys(lerp(P, Q, 0.5 * (lo + hi)));
      const bool present = len > 1e-12 and closest(crack, M, false).dist <= 0.5 * h_cell[c];
      return std::tuple<double, double, bool>{lo, hi, present};
    };
    // Record a tip cell: the crack is present on [lo, hi] of segment PQ and
    // ends inside the cell at one end of that interval.
    auto add_tip_cell = [&](P2 P, P2 Q, double lo, double hi)
    {
      TipCell tc;
      tc.cell = static_cast<std::int32_t>(c);
      const bool tip_at_hi = hi < 1.0 - 1e-12;
      if (tip_at_hi and lo > 1e-12)
        throw std::runtime_error("compute_crack_geometry: both tips of the crack lie in cell "
                                 + std::to_string(c) + "; refine the mesh (crack shorter than h)");
      const P2 T = lerp(P, Q, tip_at_hi ? hi : lo);
      const P2 E = tip_at_hi ? P : Q;
      tc.segment = {E[0], E[1], T[0], T[1]};
      // Which tip: the nearest to T.
      const P2 Tp = phys(T);
      double dmin = std::numeric_limits<double>::max();
      for (int j = 0; j < num_tips; ++j)
      {
        const double d = std::hypot(Tp[0] - g.tips[2 * j], Tp[1] - g.tips[2 * j + 1]);
        if (d < dmin)
          dmin = d, tc.tip = j;
      }
      g.tip_cell_index[c] = static_cast<std::int32_t>(g.tip_cells.size());
      g.tip_cells.push_back(tc);
    };

    if (npos > 0 and nneg > 0)
    {
      // Straddled: the zero line of phi_h crosses the interior.
      CrackCell cc;
      cc.cell = static_cast<std::int32_t>(c);
      P2 P, Q;
      if (nzero == 1)
      {
        const int k = (s[0] == 0) ? 0 : ((s[1] == 0) ? 1 : 2);
        const int a = (k + 1) % 3, b = (k + 2) % 3;
        const P2 R = lerp(ref_vertex[a], ref_vertex[b], f[a] / (f[a] - f[b]));
        P = ref_vertex[k];
        Q = R;
        cc.num_sub = 2;
        const std::array<P2, 6> tri = {ref_vertex[k], ref_vertex[a], R, ref_vertex[k], R, ref_vertex[b]};
        for (int i = 0; i < 6; ++i)
          cc.sub[2 * i] = tri[i][0], cc.sub[2 * i + 1] = tri[i][1];
        cc.side = {static_cast<std::int8_t>(s[a]), static_cast<std::int8_t>(s[b]), 0};
      }
      else
      {
        const int k = (s[0] != s[1] and s[0] != s[2]) ? 0 : ((s[1] != s[0] and s[1] != s[2]) ? 1 : 2);
        const int a = (k + 1) % 3, b = (k + 2) % 3;
        P = lerp(ref_vertex[k], ref_vertex[a], f[k] / (f[k] - f[a]));
        Q = lerp(ref_vertex[k], ref_vertex[b], f[k] / (f[k] - f[b]));
        cc.num_sub = 3;
        const std::array<P2, 9> tri = {ref_vertex[k], P, Q, P, ref_vertex[a], ref_vertex[b],
                                       P, ref_vertex[b], Q};
        for (int i = 0; i < 9; ++i)
          cc.sub[2 * i] = tri[i][0], cc.sub[2 * i + 1] = tri[i][1];
        cc.side = {static_cast<std::int8_t>(s[k]), static_cast<std::int8_t>(s[a]),
                   static_cast<std::int8_t>(s[a])};
      }
      const auto [lo, hi, present] = presence(P, Q);
      const double len = hi - lo;
      if (!present)
        g.cell_class[c] = static_cast<std::int8_t>(CellClass::extension);
      else if (len >= 1.0 - 1e-12)
      {
        g.cell_class[c] = static_cast<std::int8_t>(CellClass::cut);
        cc.cls = CellClass::cut;
        cc.segment = {P[0], P[1], Q[0], Q[1]};
        cc.owns_segment = true;
        g.crack_cell_index[c] = static_cast<std::int32_t>(g.crack_cells.size());
        g.crack_cells.push_back(cc);
      }
      else
      {
        g.cell_class[c] = static_cast<std::int8_t>(CellClass::tip);
        add_tip_cell(P, Q, lo, hi);
      }
      continue;
    }

    // Not straddled: the cell has a single side.
    const int side = (npos > 0) ? 1 : -1;
    g.cell_side[c] = static_cast<std::int8_t>(side);
    if (nzero == 2)
    {
      // The zero line runs along the edge between the two zero vertices.
      const int k = (s[0] != 0) ? 0 : ((s[1] != 0) ? 1 : 2);
      P2 P = ref_vertex[(k + 1) % 3], Q = ref_vertex[(k + 2) % 3];
      const auto [lo, hi, present] = presence(P, Q);
      const double len = hi - lo;
      if (!present)
        continue; // crack absent along this edge: a plain cell
      if (len >= 1.0 - 1e-12)
      {
        g.cell_class[c] = static_cast<std::int8_t>(CellClass::edge);
        CrackCell cc;
        cc.cell = static_cast<std::int32_t>(c);
        cc.cls = CellClass::edge;
        cc.num_sub = 1;
        for (int i = 0; i < 3; ++i)
          cc.sub[2 * i] = ref_vertex[i][0], cc.sub[2 * i + 1] = ref_vertex[i][1];
        cc.side = {static_cast<std::int8_t>(side), 0, 0};
        cc.segment = {P[0], P[1], Q[0], Q[1]};
        cc.owns_segment = side > 0;
        g.crack_cell_index[c] = static_cast<std::int32_t>(g.crack_cells.size());
        g.crack_cells.push_back(cc);
      }
      else
      {
        g.cell_class[c] = static_cast<std::int8_t>(CellClass::tip);
        g.cell_side[c] = 0;
        add_tip_cell(P, Q, lo, hi);
      }
    }
  }
  return g;
}

} // namespace cracklip
