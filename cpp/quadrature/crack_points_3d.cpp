#include "quadrature/crack_points_3d.h"

#include "geometry/p1_simplex.h"
#include "geometry/vec3.h"
#include "quadrature/cell_quadrature_3d.h"
#include "quadrature/front_rules_3d.h"

#include <limits>
#include <stdexcept>

namespace cracklip
{
using namespace vec3;

LipPoints3D compute_lip_points_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                  const CrackGeometry3D& g, int n, double near_factor, bool signed_point_rule)
{
  if (n < 1)
    throw std::invalid_argument("compute_lip_points_3d: need at least one point per direction");
  LipPoints3D out;
  const quadrature::Rule smooth = quadrature::triangle(2 * n - 1);
  const quadrature::Rule edge = quadrature::triangle_edge_collapsed(n, n);
  for (const CrackCell3D& cc : g.crack_cells)
  {
    if (cc.num_facets() == 0)
      continue;
    const P1Tetrahedron T(x, cells, cc.cell);
    Point3 dir = {0, 0, 0}, on_line = {0, 0, 0};
    const bool has_line = front_line(x, cells, g, cc.cell, on_line, dir);
    for (int k = 0; k < cc.num_facets(); ++k)
    {
      const double* R = &cc.facets[9 * k];
      const Point3 R0 = {R[0], R[1], R[2]}, R1 = {R[3], R[4], R[5]}, R2 = {R[6], R[7], R[8]};
      const int nf = cc.facet_num_front[k];
      std::array<double, 9> xv;
      std::array<Point3, 3> X;
      for (int a = 0; a < 3; ++a)
      {
        X[a] = T.physical({R[3 * a], R[3 * a + 1], R[3 * a + 2]});
        for (int d = 0; d < 3; ++d)
          xv[3 * a + d] = X[a][d];
      }
      quadrature::Rule rule;
      if (nf == 2)
        rule = edge;
      else if (nf == 1 and signed_point_rule and has_line)
        rule = quadrature::triangle_point_collapsed(xv, dir, n, n);
      else if (nf == 1)
        rule = quadrature::tip_fan(n, n); // the plain fan from the front vertex
      else
      {
        const bool near = has_line and near_line(X, on_line, dir, near_factor);
        rule = near ? quadrature::triangle_near_front(xv, on_line, dir, n, n) : smooth;
      }
      const double scale2 = 2.0 * cc.facet_area[k];
      for (int q = 0; q < rule.size(); ++q)
      {
        const Point3 r = axpy(axpy(R0, rule.points[2 * q], sub(R1, R0)), rule.points[2 * q + 1], sub(R2, R0));
        const Point3 p = T.physical(r);
        out.cell.push_back(cc.cell);
        out.ref.insert(out.ref.end(), r.begin(), r.end());
        out.x.insert(out.x.end(), p.begin(), p.end());
        out.weight.push_back(rule.weights[q] * scale2);
        out.normal.insert(out.normal.end(), cc.facet_normal.begin() + 3 * k, cc.facet_normal.begin() + 3 * k + 3);
        out.front_vertices.push_back(static_cast<std::int8_t>(nf));
      }
    }
  }
  return out;
}

} // namespace cracklip
