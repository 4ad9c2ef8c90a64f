#include "quadrature/cell_quadrature_2d.h"

#include "quadrature/rules.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace cracklip
{
namespace
{
double area2(const Triangle2& t)
{
  return std::abs((t[1][0] - t[0][0]) * (t[2][1] - t[0][1]) - (t[2][0] - t[0][0]) * (t[1][1] - t[0][1]));
}

/// Append a reference-triangle rule mapped onto physical triangle t.
void append(const quadrature::Rule& rule, const Triangle2& t, const P1Cell& cell, int side,
            CellQuadrature& out)
{
  const double scale = area2(t);
  for (int q = 0; q < rule.size(); ++q)
  {
    const double u = rule.points[2 * q], v = rule.points[2 * q + 1];
    const Point2 p = {t[0][0] + u * (t[1][0] - t[0][0]) + v * (t[2][0] - t[0][0]),
                      t[0][1] + u * (t[1][1] - t[0][1]) + v * (t[2][1] - t[0][1])};
    const Point2 r = cell.reference(p);
    out.ref.insert(out.ref.end(), r.begin(), r.end());
    out.weight.push_back(rule.weights[q] * scale);
    out.side.push_back(static_cast<std::int8_t>(side));
  }
}
} // namespace

namespace
{
/// Fan triangle (apex, A, B) split into pieces whose angle at the apex is at
/// most max_angle (rays at equal angle steps).
void split_fan(Point2 apex, Point2 A, Point2 B, double max_angle, std::vector<Triangle2>& out)
{
  const double a0 = std::atan2(A[1] - apex[1], A[0] - apex[0]);
  double da = std::atan2(B[1] - apex[1], B[0] - apex[0]) - a0;
  if (da > std::numbers::pi)
    da -= 2 * std::numbers::pi;
  if (da < -std::numbers::pi)
    da += 2 * std::numbers::pi;
  const int pieces = std::max(1, static_cast<int>(std::ceil(std::abs(da) / max_angle)));
  const double ex = B[0] - A[0], ey = B[1] - A[1];
  const double rx = A[0] - apex[0], ry = A[1] - apex[1];
  Point2 prev = A;
  for (int j = 1; j <= pieces; ++j)
  {
    Point2 next = B;
    if (j < pieces)
    {
      // apex + s (dx, dy) = A + u (ex, ey)
      const double ang = a0 + da * j / pieces;
      const double dx = std::cos(ang), dy = std::sin(ang);
      const double u = (dx * ry - dy * rx) / (dy * ex - dx * ey);
      next = {A[0] + u * ex, A[1] + u * ey};
    }
    out.push_back({apex, prev, next});
    prev = next;
  }
}

double signed_area2(Point2 a, Point2 b, Point2 c)
{
  return (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
}
} // namespace

std::vector<Triangle2> fan_triangles(Point2 apex, std::span<const Point2> polygon, double max_angle)
{
  std::vector<Triangle2> out;
  double total = 0.0;
  const std::size_t n = polygon.size();
  for (std::size_t k = 0; k < n; ++k)
    total += area2({apex, polygon[k], polygon[(k + 1) % n]});
  for (std::size_t k = 0; k < n; ++k)
  {
    const Point2 A = polygon[k], B = polygon[(k + 1) % n];
    if (area2({apex, A, B}) > 1e-12 * total)
      split_fan(apex, A, B, max_angle, out);
  }
  return out;
}

std::vector<std::pair<Triangle2, double>> signed_fans(Point2 apex, const Triangle2& tri, double max_angle)
{
  // int_tri f = sum_k sign(apex, v_k, v_k+1) / sign(tri) int_fan(apex, v_k, v_k+1) f,
  // for the apex inside or outside the triangle.
  std::vector<std::pair<Triangle2, double>> out;
  const double o = signed_area2(tri[0], tri[1], tri[2]);
  std::vector<Triangle2> pieces;
  for (int k = 0; k < 3; ++k)
  {
    const Point2 A = tri[k], B = tri[(k + 1) % 3];
    const double ok = signed_area2(apex, A, B);
    if (std::abs(ok) <= 1e-12 * std::abs(o))
      continue;
    pieces.clear();
    split_fan(apex, A, B, max_angle, pieces);
    for (const Triangle2& f : pieces)
      out.emplace_back(f, (ok > 0) == (o > 0) ? 1.0 : -1.0);
  }
  return out;
}

void fan_rule(std::span<const Triangle2> fans, const QuadratureOptions& options,
              std::vector<double>& points, std::vector<double>& weights)
{
  // Fan triangle (T, A, B): x = T + t^2 P(eta), P(eta) = (A - T) + eta (B - A),
  // dA = 2 |TAB| 2 t^3 dt deta: the Jacobian cancels 1/r and sqrt(r) is
  // polynomial in t. Across the fan, the ray length 1 / |P(eta)| is nearly
  // singular at the foot of the perpendicular from T (complex poles at
  // distance d / L): the sinh substitution s0 + eta L = d sinh(u) makes it
  // constant, leaving only the smooth angular variation of the integrand.
  const quadrature::Rule gt = quadrature::gauss_legendre(options.tip_radial);
  const quadrature::Rule gu = quadrature::gauss_legendre(options.tip_angular);
  for (const Triangle2& f : fans)
  {
    const Point2 T = f[0], A = f[1], B = f[2];
    const double ax = A[0] - T[0], ay = A[1] - T[1];
    const double ex = B[0] - A[0], ey = B[1] - A[1];
    const double L = std::hypot(ex, ey);
    const double area2 = std::abs(ax * ey - ay * ex);
    const double d = area2 / L;            // distance from T to the line AB
    const double s0 = (ax * ex + ay * ey) / L; // foot of the perpendicular: s = -s0
    const double u0 = std::asinh(s0 / d), u1 = std::asinh((s0 + L) / d);
    for (int j = 0; j < gu.size(); ++j)
    {
      const double u = u0 + (u1 - u0) * gu.points[j];
      const double eta = (d * std::sinh(u) - s0) / L;
      const double deta = (u1 - u0) * d * std::cosh(u) / L;
      const double px = ax + eta * ex, py = ay + eta * ey;
      for (int i = 0; i < gt.size(); ++i)
      {
        const double t = gt.points[i];
        points.push_back(T[0] + t * t * px);
        points.push_back(T[1] + t * t * py);
        weights.push_back(gu.weights[j] * gt.weights[i] * deta * area2 * 2.0 * t * t * t);
      }
    }
  }
}

void tip_polygon_rule(Point2 apex, std::span<const Point2> polygon, const QuadratureOptions& options,
                      std::vector<double>& points, std::vector<double>& weights)
{
  if (options.tip_rule == TipQuadrature::collapsed)
  {
    fan_rule(fan_triangles(apex, polygon, options.tip_max_angle), options, points, weights);
    return;
  }
  const quadrature::Rule rule = quadrature::triangle_product((options.tip_degree + 3) / 2);
  for (const Triangle2& t : fan_triangles(apex, polygon, 2 * std::numbers::pi))
  {
    const double scale = area2(t);
    for (int q = 0; q < rule.size(); ++q)
    {
      const double u = rule.points[2 * q], v = rule.points[2 * q + 1];
      points.push_back(t[0][0] + u * (t[1][0] - t[0][0]) + v * (t[2][0] - t[0][0]));
      points.push_back(t[0][1] + u * (t[1][1] - t[0][1]) + v * (t[2][1] - t[0][1]));
      weights.push_back(rule.weights[q] * scale);
    }
  }
}

const TipFrame* cell_tip(const P1Cell& cell, const CellBasis& basis, const EnrichmentLayout& layout)
{
  if (!basis.has_tip)
    return nullptr;
  const Point2 xc = cell.physical({1.0 / 3.0, 1.0 / 3.0});
  const TipFrame* best = nullptr;
  double dbest = std::numeric_limits<double>::max();
  for (const std::int32_t k : basis.enr)
    if (layout.tip[k] >= 0)
    {
      const TipFrame& f = layout.tip_frames[layout.tip[k]];
      const double d = std::hypot(f.tip[0] - xc[0], f.tip[1] - xc[1]);
      if (d < dbest)
        dbest = d, best = &f;
    }
  return best;
}

void compute_cell_quadrature(const P1Cell& cell, std::int32_t c,
                             std::span<const CrackGeometry* const> cracks, const TipFrame* tip,
                             const QuadratureOptions& options, CellQuadrature& out)
{
  out.clear();
  // Regions in physical coordinates with their side.
  std::vector<Triangle2> regions;
  std::vector<int> sides;
  bool fanned_from_tip = false;
  const Triangle2 whole = {cell.xv[0], cell.xv[1], cell.xv[2]};
  for (const CrackGeometry* g : cracks)
  {
    if (const std::int32_t it = g->tip_cell_index[c]; it >= 0)
    {
      const TipCell& tc = g->tip_cells[it];
      const Point2 E = cell.physical({tc.segment[0], tc.segment[1]});
      const Point2 T = cell.physical({tc.segment[2], tc.segment[3]});
      // Cell boundary with the entry point E inserted on its edge.
      std::vector<Point2> poly;
      for (int k = 0; k < 3; ++k)
      {
        poly.push_back(whole[k]);
        const Point2 A = whole[k], B = whole[(k + 1) % 3];
        const double ex = B[0] - A[0], ey = B[1] - A[1];
        const double len2 = ex * ex + ey * ey;
        const double cross = ex * (E[1] - A[1]) - ey * (E[0] - A[0]);
        const double dotp = (E[0] - A[0]) * ex + (E[1] - A[1]) * ey;
        if (std::abs(cross) < 1e-12 * len2 and dotp > 1e-12 * len2 and dotp < (1 - 1e-12) * len2)
          poly.push_back(E);
      }
      const double max_angle = options.tip_rule == TipQuadrature::collapsed ? options.tip_max_angle
                                                                             : 2 * std::numbers::pi;
      for (const Triangle2& f : fan_triangles(T, poly, max_angle))
      {
        const Point2 m = cell.reference({(f[0][0] + f[1][0] + f[2][0]) / 3.0, (f[0][1] + f[1][1] + f[2][1]) / 3.0});
        const auto N = P1Cell::shape(m);
        double phi = 0.0;
        for (int a = 0; a < 3; ++a)
          phi += N[a] * g->phi[cell.nodes[a]];
        regions.push_back(f);
        sides.push_back(phi >= 0.0 ? 1 : -1);
      }
      fanned_from_tip = true;
      break;
    }
  }
  if (!fanned_from_tip)
  {
    // The sub-triangles of a crossed cell, else the cell itself (side 0).
    const CellRegions crossed(cracks, c);
    for (int s = 0; s < crossed.size(); ++s)
    {
      const auto t = crossed.triangle(s);
      regions.push_back({cell.physical(t[0]), cell.physical(t[1]), cell.physical(t[2])});
      sides.push_back(crossed.side(s));
    }
  }

  if (!tip or options.tip_rule == TipQuadrature::gauss)
  {
    const quadrature::Rule rule = !tip ? quadrature::triangle(options.degree)
                                       : quadrature::triangle_product((options.tip_degree + 3) / 2);
    for (std::size_t r = 0; r < regions.size(); ++r)
      append(rule, regions[r], cell, sides[r], out);
    return;
  }
  // Far from the tip the tip functions are smooth on the cell: Gauss rule.
  if (!fanned_from_tip)
  {
    const double diam = std::max({std::hypot(whole[1][0] - whole[0][0], whole[1][1] - whole[0][1]),
                                  std::hypot(whole[2][0] - whole[1][0], whole[2][1] - whole[1][1]),
                                  std::hypot(whole[0][0] - whole[2][0], whole[0][1] - whole[2][1])});
    double dist = std::numeric_limits<double>::max();
    for (int i = 0; i < 3; ++i)
      dist = std::min(dist, std::hypot(whole[i][0] - tip->tip[0], whole[i][1] - tip->tip[1]));
    if (dist - diam > options.far_factor * diam)
    {
      const quadrature::Rule rule = quadrature::triangle(options.far_degree);
      for (std::size_t r = 0; r < regions.size(); ++r)
        append(rule, regions[r], cell, sides[r], out);
      return;
    }
  }
  // Collapsed rule, fanned from the tip: the tip cell's regions are fan
  // triangles already; any other region is a signed sum of fans from the
  // tip (outside it), so the near-singular integrand next to the tip is
  // integrated as exactly as in the tip cell.
  std::vector<double> pts, w;
  for (std::size_t r = 0; r < regions.size(); ++r)
  {
    std::vector<std::pair<Triangle2, double>> fans;
    if (fanned_from_tip)
      fans.emplace_back(regions[r], 1.0);
    else
      fans = signed_fans(tip->tip, regions[r], options.tip_max_angle);
    for (const auto& [f, sign] : fans)
    {
      pts.clear();
      w.clear();
      fan_rule(std::span(&f, 1), options, pts, w);
      for (std::size_t q = 0; q < w.size(); ++q)
      {
        const Point2 ref = cell.reference({pts[2 * q], pts[2 * q + 1]});
        out.ref.insert(out.ref.end(), ref.begin(), ref.end());
        out.weight.push_back(sign * w[q]);
        out.side.push_back(static_cast<std::int8_t>(sides[r]));
      }
    }
  }
}

void compute_enriched_cell_quadrature(std::span<const double> x, std::span<const std::int32_t> cells,
                                      const EnrichmentLayout& layout, std::span<const CrackGeometry* const> cracks,
                                      std::int32_t c, const QuadratureOptions& options, CellQuadrature& out)
{
  const P1Cell cell(x, cells, c);
  compute_cell_quadrature(cell, c, cracks, cell_tip(cell, CellBasis(cell, layout, c), layout), options, out);
}

} // namespace cracklip
