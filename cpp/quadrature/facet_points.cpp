#include "quadrature/facet_points.h"

#include "geometry/cut_tetrahedron.h"
#include "geometry/vec3.h"
#include "quadrature/rules.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace cracklip
{
namespace
{
/// The crack (index) crossing cell c (cut, along an edge / a face, or
/// holding a tip / the front), or -1.
template <typename Crack>
int crossing(std::span<const Crack* const> cracks, std::int32_t c)
{
  int ic = -1;
  for (std::size_t k = 0; k < cracks.size(); ++k)
    if (crosses(*cracks[k], c))
      ic = static_cast<int>(k);
  return ic;
}
} // namespace

void compute_facet_points(const P1Cell& cell, std::span<const CrackGeometry* const> cracks, std::int32_t c, int lf,
                          int degree, FacetPoints& out)
{
  out.clear();
  const quadrature::Rule& g = quadrature::gauss_legendre_cached(std::max(1, (degree + 2) / 2));
  constexpr std::array<std::array<double, 2>, 3> ref = {{{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}};
  const int a = (lf + 1) % 3, b = (lf + 2) % 3;
  const double tx = cell.xv[b][0] - cell.xv[a][0], ty = cell.xv[b][1] - cell.xv[a][1];
  const double len = std::hypot(tx, ty);
  // Outward: away from the opposite vertex.
  const double orient
      = ty * (cell.xv[lf][0] - cell.xv[a][0]) - tx * (cell.xv[lf][1] - cell.xv[a][1]) > 0.0 ? -1.0 : 1.0;
  out.normal = {orient * ty / len, -orient * tx / len};
  // Pieces of the facet in parameter t in [0, 1], split where a crack
  // crossing (or ending in) the cell crosses the facet.
  std::vector<double> cuts = {0.0, 1.0};
  const int ic = crossing(cracks, c);
  if (ic >= 0)
  {
    const double fa = cracks[ic]->phi[cell.nodes[a]], fb = cracks[ic]->phi[cell.nodes[b]];
    if (fa * fb < 0.0)
      cuts = {0.0, fa / (fa - fb), 1.0};
  }
  for (std::size_t p = 0; p + 1 < cuts.size(); ++p)
  {
    const double t0 = cuts[p], t1 = cuts[p + 1];
    // Side of the crossing crack on this piece: sign of phi at its middle.
    int s = 0;
    if (ic >= 0)
    {
      const double tm = 0.5 * (t0 + t1);
      const double fm = (1 - tm) * cracks[ic]->phi[cell.nodes[a]] + tm * cracks[ic]->phi[cell.nodes[b]];
      s = fm >= 0.0 ? 1 : -1;
    }
    for (int q = 0; q < g.size(); ++q)
    {
      const double t = t0 + (t1 - t0) * g.points[q];
      out.ref.push_back(ref[a][0] + t * (ref[b][0] - ref[a][0]));
      out.ref.push_back(ref[a][1] + t * (ref[b][1] - ref[a][1]));
      out.weight.push_back(g.weights[q] * (t1 - t0) * len);
      out.side.push_back(static_cast<std::int8_t>(s));
    }
  }
}

void compute_facet_points(const P1Tetrahedron& cell, std::span<const CrackGeometry3D* const> cracks, std::int32_t c,
                          int lf, int degree, FacetPoints& out)
{
  using namespace vec3;
  out.clear();
  const quadrature::Rule& rule = quadrature::simplex(2, std::max(1, degree));
  constexpr std::array<Point3, 4> R = {{{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}};
  int v[3], k = 0;
  for (int a = 0; a < 4; ++a)
    if (a != lf)
      v[k++] = a;
  // Physical area and outward normal (away from the opposite vertex).
  Point3 n = cross(sub(cell.xv[v[1]], cell.xv[v[0]]), sub(cell.xv[v[2]], cell.xv[v[0]]));
  const Point3 w = sub(cell.xv[lf], cell.xv[v[0]]);
  const double n2 = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(n2 > 0.0))
    throw std::runtime_error("compute_facet_basis: facet " + std::to_string(lf) + " of cell " + std::to_string(c)
                             + " has zero area");
  const double area = 0.5 * n2;
  const double orient = (n[0] * w[0] + n[1] * w[1] + n[2] * w[2]) > 0.0 ? -1.0 : 1.0;
  for (auto& ni : n)
    ni *= orient / n2;
  out.normal.assign(n.begin(), n.end());
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
      TriangleCut cut;
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
    const Point3 cr = cross(sub(p[1], p[0]), sub(p[2], p[0]));
    return 0.5 * std::sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
  };
  const double whole = tri_area({R[v[0]], R[v[1]], R[v[2]]});
  for (int t = 0; t < num; ++t)
  {
    const double piece_area = area * tri_area(pieces[t]) / whole;
    for (int q = 0; q < rule.size(); ++q)
    {
      const double s = rule.points[2 * q], u = rule.points[2 * q + 1];
      for (int i = 0; i < 3; ++i)
        out.ref.push_back(pieces[t][0][i] + s * (pieces[t][1][i] - pieces[t][0][i])
                          + u * (pieces[t][2][i] - pieces[t][0][i]));
      out.weight.push_back(2.0 * rule.weights[q] * piece_area);
      out.side.push_back(static_cast<std::int8_t>(piece_side[t]));
    }
  }
}

} // namespace cracklip
