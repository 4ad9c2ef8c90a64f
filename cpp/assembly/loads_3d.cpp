#include "assembly/loads_3d.h"

#include "assembly/enriched_kernels_3d.h"
#include "enrichment/enriched_basis_3d.h"
#include "geometry/cut_tetrahedron.h"
#include "quadrature/rules.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace cracklip
{
namespace
{
void check(std::size_t n, std::span<const double> ref, std::span<const double> weights, std::span<const double> b,
           const EnrichmentLayout3D& layout, const char* what)
{
  if (ref.size() != 3 * n or weights.size() != n)
    throw std::invalid_argument(std::string(what) + ": expected ref (n, 3) and weights (n)");
  if (b.size() != 3 * static_cast<std::size_t>(layout.num_nodes_total()))
    throw std::invalid_argument(std::string(what) + ": the load vector has the wrong size");
}

int crossing(std::span<const CrackGeometry3D* const> cracks, std::int32_t c)
{
  for (std::size_t k = 0; k < cracks.size(); ++k)
  {
    const std::int8_t cls = cracks[k]->cell_class[c];
    if (cls == 1 or cls == 2 or cls == 3)
      return static_cast<int>(k);
  }
  return -1;
}

Point3 cross(const Point3& a, const Point3& b)
{
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
} // namespace

FacetBasis3D compute_facet_basis_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                    const EnrichmentLayout3D& layout, std::span<const CrackGeometry3D* const> cracks,
                                    std::span<const std::int32_t> facet_cells,
                                    std::span<const std::int32_t> facet_local, int degree)
{
  if (facet_cells.size() != facet_local.size())
    throw std::invalid_argument("compute_facet_basis_3d: facet arrays differ in length");
  const quadrature::Rule rule = quadrature::triangle(std::max(1, degree));
  constexpr std::array<Point3, 4> R = {{{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}};
  FacetBasis3D out;
  std::vector<double> val, grad;
  std::vector<int> side;
  TriangleCut cut;
  for (std::size_t f = 0; f < facet_cells.size(); ++f)
  {
    const std::int32_t c = facet_cells[f];
    const int lf = facet_local[f];
    if (lf < 0 or lf > 3)
      throw std::invalid_argument("compute_facet_basis_3d: local facet index must be 0 .. 3");
    const P1Tetrahedron cell(x, cells, c);
    const CellBasis3D basis(cell, layout, c);
    int v[3], k = 0;
    for (int a = 0; a < 4; ++a)
      if (a != lf)
        v[k++] = a;
    // Physical area and outward normal (away from the opposite vertex).
    Point3 e1, e2, w;
    for (int i = 0; i < 3; ++i)
      e1[i] = cell.xv[v[1]][i] - cell.xv[v[0]][i], e2[i] = cell.xv[v[2]][i] - cell.xv[v[0]][i],
      w[i] = cell.xv[lf][i] - cell.xv[v[0]][i];
    Point3 n = cross(e1, e2);
    const double n2 = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(n2 > 0.0))
      throw std::runtime_error("compute_facet_basis_3d: facet " + std::to_string(lf) + " of cell "
                               + std::to_string(c) + " has zero area");
    const double area = 0.5 * n2;
    const double orient = (n[0] * w[0] + n[1] * w[1] + n[2] * w[2]) > 0.0 ? -1.0 : 1.0;
    for (auto& ni : n)
      ni *= orient / n2;
    // The facet in reference coordinates, cut by the crack crossing the cell.
    std::array<double, 9> tri;
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i)
        tri[3 * a + i] = R[v[a]][i];
    const int ic = crossing(cracks, c);
    int num = 1;
    std::array<std::array<Point3, 3>, 3> pieces;
    std::array<int, 3> piece_side = {0, 0, 0};
    pieces[0] = {R[v[0]], R[v[1]], R[v[2]]};
    if (ic >= 0)
    {
      const std::array<double, 3> phi = {cracks[ic]->phi[cell.nodes[v[0]]], cracks[ic]->phi[cell.nodes[v[1]]],
                                         cracks[ic]->phi[cell.nodes[v[2]]]};
      if (phi[0] == 0.0 and phi[1] == 0.0 and phi[2] == 0.0)
        piece_side[0] = cracks[ic]->cell_side[c] != 0 ? cracks[ic]->cell_side[c] : 1; // the facet is on the crack
      else
      {
        cut_triangle(std::span<const double, 9>(tri), phi, cut);
        num = cut.num_tris;
        for (int t = 0; t < num; ++t)
        {
          for (int a = 0; a < 3; ++a)
            pieces[t][a] = cut.x[cut.tris[t][a]];
          piece_side[t] = cut.side[t];
        }
      }
    }
    // Reference area of the whole facet, to scale the pieces' weights.
    auto tri_area = [](const std::array<Point3, 3>& p)
    {
      Point3 a, b;
      for (int i = 0; i < 3; ++i)
        a[i] = p[1][i] - p[0][i], b[i] = p[2][i] - p[0][i];
      const Point3 cr = cross(a, b);
      return 0.5 * std::sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
    };
    const double whole = tri_area({R[v[0]], R[v[1]], R[v[2]]});
    for (int t = 0; t < num; ++t)
    {
      region_sides_3d(cracks, c, piece_side[t], side);
      const double piece_area = area * tri_area(pieces[t]) / whole;
      for (int q = 0; q < rule.size(); ++q)
      {
        const double s = rule.points[2 * q], u = rule.points[2 * q + 1];
        Point3 r;
        for (int i = 0; i < 3; ++i)
          r[i] = pieces[t][0][i] + s * (pieces[t][1][i] - pieces[t][0][i]) + u * (pieces[t][2][i] - pieces[t][0][i]);
        evaluate_basis_3d(cell, basis, layout, cracks, side, r, val, grad);
        const Point3 xp = cell.physical(r);
        const auto ip = static_cast<std::int32_t>(out.weights.size());
        out.points.insert(out.points.end(), xp.begin(), xp.end());
        out.normals.insert(out.normals.end(), n.begin(), n.end());
        out.weights.push_back(2.0 * rule.weights[q] * piece_area);
        for (int i = 0; i < basis.num_dofs(); ++i)
        {
          if (val[3 * i] == 0.0 and val[3 * i + 1] == 0.0 and val[3 * i + 2] == 0.0)
            continue;
          out.entry_point.push_back(ip);
          out.entry_dof.push_back(basis.dofs[i]);
          out.entry_value.insert(out.entry_value.end(), {val[3 * i], val[3 * i + 1], val[3 * i + 2]});
        }
      }
    }
  }
  return out;
}

void assemble_lip_load_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                          const EnrichmentLayout3D& layout, std::span<const CrackGeometry3D* const> cracks,
                          std::int32_t crack, std::span<const std::int32_t> point_cells, std::span<const double> ref,
                          std::span<const double> weights, std::span<const double> traction, std::span<double> b)
{
  const std::size_t n = point_cells.size();
  check(n, ref, weights, b, layout, "assemble_lip_load_3d");
  if (traction.size() != 3 * n)
    throw std::invalid_argument("assemble_lip_load_3d: expected traction (n, 3)");
  if (crack < 0 or static_cast<std::size_t>(crack) >= cracks.size())
    throw std::invalid_argument("assemble_lip_load_3d: crack index out of range");
  std::vector<double> vp, vm, grad;
  std::vector<int> side;
  for (std::size_t p = 0; p < n; ++p)
  {
    const double t[3] = {traction[3 * p], traction[3 * p + 1], traction[3 * p + 2]};
    if (t[0] == 0.0 and t[1] == 0.0 and t[2] == 0.0)
      continue;
    const std::int32_t c = point_cells[p];
    const P1Tetrahedron cell(x, cells, c);
    const CellBasis3D basis(cell, layout, c);
    const Point3 r = {ref[3 * p], ref[3 * p + 1], ref[3 * p + 2]};
    region_sides_3d(cracks, c, 1, side);
    side[crack] = 1;
    evaluate_basis_3d(cell, basis, layout, cracks, side, r, vp, grad);
    side[crack] = -1;
    evaluate_basis_3d(cell, basis, layout, cracks, side, r, vm, grad);
    for (int j = 12; j < basis.num_dofs(); ++j) // standard functions (first 12) do not jump
      b[basis.dofs[j]] += weights[p] * ((vp[3 * j] - vm[3 * j]) * t[0] + (vp[3 * j + 1] - vm[3 * j + 1]) * t[1]
                                        + (vp[3 * j + 2] - vm[3 * j + 2]) * t[2]);
  }
}

void assemble_cell_load_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                           const EnrichmentLayout3D& layout, std::span<const CrackGeometry3D* const> cracks,
                           std::span<const std::int32_t> point_cells, std::span<const double> ref,
                           std::span<const std::int8_t> sides, std::span<const double> weights,
                           std::span<const double> force, std::span<double> b)
{
  const std::size_t n = point_cells.size();
  check(n, ref, weights, b, layout, "assemble_cell_load_3d");
  if (sides.size() != n or force.size() != 3 * n)
    throw std::invalid_argument("assemble_cell_load_3d: expected sides (n), force (n, 3)");
  std::vector<double> val, grad;
  std::vector<int> side;
  for (std::size_t p = 0; p < n; ++p)
  {
    const std::int32_t c = point_cells[p];
    const P1Tetrahedron cell(x, cells, c);
    const CellBasis3D basis(cell, layout, c);
    if (basis.enr.empty())
      continue;
    region_sides_3d(cracks, c, sides[p], side);
    evaluate_basis_3d(cell, basis, layout, cracks, side, {ref[3 * p], ref[3 * p + 1], ref[3 * p + 2]}, val, grad);
    for (int j = 12; j < basis.num_dofs(); ++j)
      b[basis.dofs[j]] += weights[p] * (force[3 * p] * val[3 * j] + force[3 * p + 1] * val[3 * j + 1]
                                        + force[3 * p + 2] * val[3 * j + 2]);
  }
}

} // namespace cracklip
