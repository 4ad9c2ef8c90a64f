#include "assembly/enriched_kernels_3d.h"

#include "quadrature/front_rules_3d.h"
#include "quadrature/rules.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace cracklip
{
namespace
{
/// The crack (index) crossing cell c (class cut, face or front), or -1.
int crossing_crack_3d(std::span<const CrackGeometry3D* const> cracks, std::int32_t c)
{
  for (std::size_t ic = 0; ic < cracks.size(); ++ic)
  {
    const std::int8_t cls = cracks[ic]->cell_class[c];
    if (cls == 1 or cls == 2 or cls == 3)
      return static_cast<int>(ic);
  }
  return -1;
}
} // namespace

void region_sides_3d(std::span<const CrackGeometry3D* const> cracks, std::int32_t c, int crossing_side,
                     std::vector<int>& side)
{
  side.resize(cracks.size());
  for (std::size_t ic = 0; ic < cracks.size(); ++ic)
  {
    const std::int8_t cls = cracks[ic]->cell_class[c];
    side[ic] = (cls == 1 or cls == 2 or cls == 3) ? crossing_side : cracks[ic]->cell_side[c];
  }
}

void compute_enriched_cell_quadrature_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                         const EnrichmentLayout3D& layout,
                                         std::span<const CrackGeometry3D* const> cracks, std::int32_t c,
                                         const QuadratureOptions3D& options, CellQuadrature3D& out)
{
  out.clear();
  // The crack whose front functions the cell carries, if any.
  int front_crack = -1;
  if (const std::int32_t ie = layout.cell_index.empty() ? -1 : layout.cell_index[c]; ie >= 0)
    for (std::int32_t j = layout.cell_offsets[ie]; j < layout.cell_offsets[ie + 1] and front_crack < 0; ++j)
      if (const std::int32_t k = layout.cell_enr[j];
          layout.kind[k] != static_cast<std::int8_t>(EnrichmentKind::heaviside))
        front_crack = layout.crack[k];
  const int ic = crossing_crack_3d(cracks, c);
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
  bool near = false;
  if (options.front_rule == FrontQuadrature::collapsed and options.near_factor > 0.0
      and front_line(x, cells, *cracks[front_crack], c, on_line, dir))
  {
    double dmin = 1e300, diam = 0.0;
    for (int a = 0; a < 4; ++a)
    {
      double w[3], along = 0.0;
      for (int i = 0; i < 3; ++i)
        w[i] = T.xv[a][i] - on_line[i], along += w[i] * dir[i];
      double d2 = 0.0;
      for (int i = 0; i < 3; ++i)
        d2 += (w[i] - along * dir[i]) * (w[i] - along * dir[i]);
      dmin = std::min(dmin, std::sqrt(d2));
      for (int b = a + 1; b < 4; ++b)
      {
        double e2 = 0.0;
        for (int i = 0; i < 3; ++i)
          e2 += (T.xv[a][i] - T.xv[b][i]) * (T.xv[a][i] - T.xv[b][i]);
        diam = std::max(diam, std::sqrt(e2));
      }
    }
    near = dmin < options.near_factor * diam;
  }
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
    double rmin = std::numeric_limits<double>::infinity(), diam = 0.0;
    for (int a = 0; a < 4; ++a)
    {
      rmin = std::min(rmin, std::hypot(g.phi[T.nodes[a]], g.psi[T.nodes[a]]));
      for (int b = a + 1; b < 4; ++b)
      {
        double e2 = 0.0;
        for (int i = 0; i < 3; ++i)
          e2 += (T.xv[a][i] - T.xv[b][i]) * (T.xv[a][i] - T.xv[b][i]);
        diam = std::max(diam, std::sqrt(e2));
      }
    }
    append(quadrature::tetrahedron_cached(front_function_degree(options, rmin / diam)));
  }
}

std::int32_t assemble_enriched_stiffness_3d(const MatrixSink& sink, std::span<const double> x,
                                            std::span<const std::int32_t> cells, const EnrichmentLayout3D& layout,
                                            std::span<const CrackGeometry3D* const> cracks, double E, double nu,
                                            const QuadratureOptions3D& options)
{
  const std::array<double, 36> D = elasticity_matrix_3d(E, nu);
  CellQuadrature3D q;
  std::vector<double> val, grad, B, DB, Ke;
  std::vector<int> side;
  for (const std::int32_t c : layout.cells)
  {
    const P1Tetrahedron cell(x, cells, c);
    const CellBasis3D basis(cell, layout, c);
    const int nd = basis.num_dofs();
    Ke.assign(static_cast<std::size_t>(nd) * nd, 0.0);
    compute_enriched_cell_quadrature_3d(x, cells, layout, cracks, c, options, q);
    for (int p = 0; p < q.size(); ++p)
    {
      region_sides_3d(cracks, c, q.side[p], side);
      evaluate_basis_3d(cell, basis, layout, cracks, side, {q.ref[3 * p], q.ref[3 * p + 1], q.ref[3 * p + 2]}, val,
                        grad);
      // B (6, nd): Voigt strains xx, yy, zz, yz, xz, xy (engineering shears).
      B.assign(6 * static_cast<std::size_t>(nd), 0.0);
      for (int i = 0; i < nd; ++i)
      {
        const double* g = &grad[9 * i]; // g[3 a + b] = d val_a / d x_b
        B[0 * nd + i] = g[0];
        B[1 * nd + i] = g[4];
        B[2 * nd + i] = g[8];
        B[3 * nd + i] = g[5] + g[7];
        B[4 * nd + i] = g[2] + g[6];
        B[5 * nd + i] = g[1] + g[3];
      }
      DB.assign(6 * static_cast<std::size_t>(nd), 0.0);
      for (int r = 0; r < 6; ++r)
        for (int s = 0; s < 6; ++s)
          if (const double d = D[6 * r + s]; d != 0.0)
            for (int i = 0; i < nd; ++i)
              DB[r * nd + i] += d * B[s * nd + i];
      // Ke += w B^T D B on the upper triangle, row by row over contiguous
      // columns (vectorisable), skipping the zeros of B (half of it: a
      // standard or Heaviside dof strains three of the six components).
      const double w = q.weight[p];
      for (int r = 0; r < 6; ++r)
      {
        const double* Br = &B[r * nd];
        const double* DBr = &DB[r * nd];
        for (int i = 0; i < nd; ++i)
        {
          const double b = w * Br[i];
          if (b == 0.0)
            continue;
          double* row = &Ke[i * nd];
          for (int j = i; j < nd; ++j)
            row[j] += b * DBr[j];
        }
      }
    }
    for (int i = 0; i < nd; ++i)
      for (int j = 0; j < i; ++j)
        Ke[i * nd + j] = Ke[j * nd + i];
    for (int i = 0; i < 12; ++i) // the standard-standard block is DOLFINx's
      for (int j = 0; j < 12; ++j)
        Ke[i * nd + j] = 0.0;
    sink(basis.dofs, basis.dofs, Ke);
  }
  return static_cast<std::int32_t>(layout.cells.size());
}

std::vector<double> evaluate_displacement_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                             const EnrichmentLayout3D& layout,
                                             std::span<const CrackGeometry3D* const> cracks, std::span<const double> u,
                                             std::span<const std::int32_t> point_cells,
                                             std::span<const double> ref_points, std::span<const std::int8_t> sides,
                                             std::vector<double>* grad_out)
{
  const std::size_t n = point_cells.size();
  if (ref_points.size() != 3 * n or sides.size() != n)
    throw std::invalid_argument("evaluate_displacement_3d: " + std::to_string(n) + " cells but "
                                + std::to_string(ref_points.size()) + " reference values and "
                                + std::to_string(sides.size()) + " sides");
  if (u.size() != 3 * static_cast<std::size_t>(layout.num_nodes_total()))
    throw std::invalid_argument("evaluate_displacement_3d: u has " + std::to_string(u.size()) + " dofs, the layout "
                                + std::to_string(3 * layout.num_nodes_total()));
  std::vector<double> out(3 * n, 0.0), val, grad;
  if (grad_out)
    grad_out->assign(9 * n, 0.0);
  std::vector<int> side;
  for (std::size_t p = 0; p < n; ++p)
  {
    const std::int32_t c = point_cells[p];
    const P1Tetrahedron cell(x, cells, c);
    const CellBasis3D basis(cell, layout, c);
    const Point3 r = {ref_points[3 * p], ref_points[3 * p + 1], ref_points[3 * p + 2]};
    int s = sides[p];
    const int ic = crossing_crack_3d(cracks, c);
    if (s == 0 and ic >= 0)
    {
      const auto N = P1Tetrahedron::shape(r);
      double phi = 0.0;
      for (int a = 0; a < 4; ++a)
        phi += N[a] * cracks[ic]->phi[cell.nodes[a]];
      s = phi >= 0.0 ? 1 : -1;
    }
    region_sides_3d(cracks, c, s, side);
    evaluate_basis_3d(cell, basis, layout, cracks, side, r, val, grad);
    for (int i = 0; i < basis.num_dofs(); ++i)
    {
      const double ui = u[basis.dofs[i]];
      if (ui == 0.0)
        continue;
      for (int a = 0; a < 3; ++a)
      {
        out[3 * p + a] += ui * val[3 * i + a];
        if (grad_out)
          for (int b = 0; b < 3; ++b)
            (*grad_out)[9 * p + 3 * a + b] += ui * grad[(3 * i + a) * 3 + b];
      }
    }
  }
  return out;
}

} // namespace cracklip
