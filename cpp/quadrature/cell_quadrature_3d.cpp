#include "quadrature/cell_quadrature_3d.h"

#include "geometry/p1_simplex.h"
#include "geometry/vec3.h"
#include "quadrature/front_rules_3d.h"
#include "quadrature/rules.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace cracklip
{
using namespace vec3;

bool front_line(std::span<const double> x, std::span<const std::int32_t> cells, const CrackGeometry3D& g,
                std::int32_t c, Point3& point, Point3& direction)
{
  const P1Tetrahedron T(x, cells, c);
  std::array<double, 4> f, p;
  for (int a = 0; a < 4; ++a)
    f[a] = g.phi[T.nodes[a]], p[a] = g.psi[T.nodes[a]];
  const Point3 gf = T.gradient(f), gp = T.gradient(p);
  const Point3 d = cross(gp, gf);
  if (!(norm(d) > 1e-12 * norm(gp) * norm(gf)))
    return false;
  direction = unit(d);
  // Least-norm correction from the centroid xc: p = xc - G^T (G G^T)^{-1} v,
  // G = [grad phi; grad psi], v = (phi(xc), psi(xc)).
  const Point3 xc = T.physical({0.25, 0.25, 0.25});
  const double v0 = 0.25 * (f[0] + f[1] + f[2] + f[3]), v1 = 0.25 * (p[0] + p[1] + p[2] + p[3]);
  const double a = dot(gf, gf), b = dot(gf, gp), cc = dot(gp, gp), det = a * cc - b * b;
  const double l0 = (cc * v0 - b * v1) / det, l1 = (a * v1 - b * v0) / det;
  point = axpy(axpy(xc, -l0, gf), -l1, gp);
  return true;
}

Point3 front_direction(std::span<const double> x, std::span<const std::int32_t> cells, const CrackGeometry3D& g,
                       std::int32_t c)
{
  Point3 point, direction;
  return front_line(x, cells, g, c, point, direction) ? direction : Point3{0.0, 0.0, 0.0};
}

double diameter(std::span<const Point3> points)
{
  double d = 0.0;
  for (std::size_t a = 0; a < points.size(); ++a)
    for (std::size_t b = a + 1; b < points.size(); ++b)
      d = std::max(d, dist(points[a], points[b]));
  return d;
}

bool near_line(std::span<const Point3> vertices, const Point3& on_line, const Point3& direction, double factor)
{
  if (!(factor > 0.0))
    return false;
  double dmin = std::numeric_limits<double>::infinity();
  for (const Point3& v : vertices)
  {
    const Point3 w = sub(v, on_line);
    dmin = std::min(dmin, norm(axpy(w, -dot(w, direction), direction)));
  }
  return dmin < factor * diameter(vertices);
}

int front_function_degree(const QuadratureOptions3D& options, double rho)
{
  const int drop = rho < 1.0 ? 0 : rho < 2.0 ? 2 : rho < 4.0 ? 4 : 5;
  return std::max(options.degree, options.far_degree - drop);
}

void compute_cell_quadrature_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                const CrackGeometry3D& g, std::int32_t c, const QuadratureOptions3D& options,
                                CellQuadrature3D& out)
{
  out.clear();
  if (c < 0 or static_cast<std::size_t>(c) >= g.crack_cell_index.size())
    throw std::invalid_argument("compute_cell_quadrature_3d: cell " + std::to_string(c) + " out of range");
  const P1Tetrahedron T(x, cells, c);
  const double det = std::abs(T.detJ);
  // A rule on the simplex's own coordinates mapped into the cell's reference
  // coordinates through the sub-tetrahedron's reference vertices R (4, 3).
  auto append = [&](const quadrature::Rule& rule, const double* R, int side, int nf)
  {
    const Point3 R0 = {R[0], R[1], R[2]}, R1 = {R[3], R[4], R[5]}, R2 = {R[6], R[7], R[8]},
                 R3 = {R[9], R[10], R[11]};
    const double scale6 = 6.0 * det * signed_volume(R0, R1, R2, R3);
    const Point3 e1 = sub(R1, R0), e2 = sub(R2, R0), e3 = sub(R3, R0);
    for (int q = 0; q < rule.size(); ++q)
    {
      const double* p = &rule.points[3 * q];
      const Point3 r = axpy(axpy(axpy(R0, p[0], e1), p[1], e2), p[2], e3);
      out.ref.insert(out.ref.end(), r.begin(), r.end());
      out.weight.push_back(rule.weights[q] * scale6);
      out.side.push_back(static_cast<std::int8_t>(side));
      out.front_vertices.push_back(static_cast<std::int8_t>(nf));
    }
  };
  const std::int32_t i = g.crack_cell_index[c];
  if (i < 0)
  {
    static constexpr double whole[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    append(quadrature::tetrahedron_cached(options.degree), whole, 0, 0);
    return;
  }
  const CrackCell3D& cc = g.crack_cells[i];
  auto gauss_rule = [](int degree) -> const quadrature::Rule& { return quadrature::tetrahedron_cached(degree); };
  const bool collapsed = options.front_rule == FrontQuadrature::collapsed;
  const quadrature::Rule& front_gauss = quadrature::tetrahedron_cached(options.front_degree);
  Point3 dir = {0, 0, 0}, on_line = {0, 0, 0};
  const bool has_line = collapsed and front_line(x, cells, g, c, on_line, dir);
  for (int k = 0; k < cc.num_sub(); ++k)
  {
    const double* R = &cc.sub[12 * k];
    const int nf = cc.num_front[k];
    std::array<double, 12> xv;
    std::array<Point3, 4> X;
    for (int a = 0; a < 4; ++a)
    {
      X[a] = T.physical({R[3 * a], R[3 * a + 1], R[3 * a + 2]});
      for (int d = 0; d < 3; ++d)
        xv[3 * a + d] = X[a][d];
    }
    if (nf == 0)
    {
      // Near the front line: the near-front rule (signed cones from it).
      if (has_line and near_line(X, on_line, dir, options.near_factor))
        append(quadrature::tetrahedron_near_front(xv, on_line, dir, options.front_radial, options.front_angular,
                                                  options.front_axial),
               R, cc.side[k], 0);
      else if (options.front_functions)
      {
        // Distance to the front from the P1 level sets at the vertices.
        double rmin = std::numeric_limits<double>::infinity();
        for (int a = 0; a < 4; ++a)
        {
          const auto N = P1Tetrahedron::shape({R[3 * a], R[3 * a + 1], R[3 * a + 2]});
          double f = 0.0, p = 0.0;
          for (int b = 0; b < 4; ++b)
            f += N[b] * g.phi[T.nodes[b]], p += N[b] * g.psi[T.nodes[b]];
          rmin = std::min(rmin, std::hypot(f, p));
        }
        append(gauss_rule(front_function_degree(options, rmin / diameter(X))), R, cc.side[k], 0);
      }
      else
        append(gauss_rule(options.degree), R, cc.side[k], 0);
      continue;
    }
    if (!collapsed)
    {
      append(front_gauss, R, cc.side[k], nf);
      continue;
    }
    if (nf == 2)
    {
      append(quadrature::tetrahedron_edge_collapsed(xv, options.front_radial, options.front_angular,
                                                    options.front_axial),
             R, cc.side[k], nf);
      continue;
    }
    if (!options.signed_point_rule or !has_line)
    {
      // The plain collapse onto the vertex (also without a front line: P1
      // psi vanishing on the crossing).
      append(quadrature::tetrahedron_vertex_collapsed(options.front_radial,
                                                      std::max(options.front_angular, options.front_axial)),
             R, cc.side[k], nf);
      continue;
    }
    const Point3 d = dir;
    append(quadrature::tetrahedron_point_collapsed(xv, d, options.front_radial, options.front_angular,
                                                   options.front_axial),
           R, cc.side[k], nf);
  }
}

void compute_enriched_cell_quadrature(std::span<const double> x, std::span<const std::int32_t> cells,
                                      const EnrichmentLayout& layout, std::span<const CrackGeometry3D* const> cracks,
                                      std::int32_t c, const QuadratureOptions3D& options, CellQuadrature3D& out)
{
  out.clear();
  // The crack whose front functions the cell carries, if any.
  int front_crack = -1;
  if (const std::int32_t ie = layout.cell_index.empty() ? -1 : layout.cell_index[c]; ie >= 0)
    for (std::int32_t j = layout.cell_offsets[ie]; j < layout.cell_offsets[ie + 1] and front_crack < 0; ++j)
      if (const std::int32_t k = layout.cell_enr[j];
          layout.kind[k] != static_cast<std::int8_t>(EnrichmentKind::heaviside))
        front_crack = layout.crack[k];
  const int ic = crossing_crack(cracks, c);
  if (ic >= 0)
  {
    // Front functions are smooth but not polynomial away from the front:
    // the sub-tetrahedra away from it get a degree graded by the distance.
    QuadratureOptions3D o = options;
    o.front_functions = front_crack >= 0;
    compute_cell_quadrature_3d(x, cells, *cracks[ic], c, o, out);
    return;
  }
  const P1Tetrahedron T(x, cells, c);
  const double scale6 = std::abs(T.detJ);
  auto append = [&](const quadrature::Rule& rule)
  {
    for (int q = 0; q < rule.size(); ++q)
    {
      out.ref.insert(out.ref.end(), rule.points.begin() + 3 * q, rule.points.begin() + 3 * q + 3);
      out.weight.push_back(rule.weights[q] * scale6);
      out.side.push_back(0);
      out.front_vertices.push_back(0);
    }
  };
  if (front_crack < 0)
  {
    append(quadrature::tetrahedron_cached(options.degree));
    return;
  }
  Point3 on_line, dir;
  const bool near = options.front_rule == FrontQuadrature::collapsed and options.near_factor > 0.0
                    and front_line(x, cells, *cracks[front_crack], c, on_line, dir)
                    and near_line(T.xv, on_line, dir, options.near_factor);
  if (near)
  {
    std::array<double, 12> xv;
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i)
        xv[3 * a + i] = T.xv[a][i];
    append(quadrature::tetrahedron_near_front(xv, on_line, dir, options.front_radial, options.front_angular,
                                              options.front_axial));
  }
  else
  {
    // Gauss graded by the distance of the nearest vertex to the front (its
    // level sets' distance at the vertices).
    const CrackGeometry3D& g = *cracks[front_crack];
    double rmin = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 4; ++a)
      rmin = std::min(rmin, std::hypot(g.phi[T.nodes[a]], g.psi[T.nodes[a]]));
    append(quadrature::tetrahedron_cached(front_function_degree(options, rmin / diameter(T.xv))));
  }
}

} // namespace cracklip
