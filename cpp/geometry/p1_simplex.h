// Geometry of one P1 simplex (layer a), in any dimension: a triangle (dim
// 2) or a tetrahedron (dim 3) of a mesh given as plain arrays.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>

namespace cracklip
{

/// Node indices, vertex coordinates, the affine map from the reference
/// simplex (vertex 0 at the origin, vertex a at the unit point of axis a -
/// 1: x = x0 + J xi), the constant shape-function gradients grad[a] =
/// dN_a/dx and det J (signed: mesh cells may have either orientation;
/// measure() is |det J| / dim!).
template <int dim>
struct P1Simplex
{
  static_assert(dim == 2 or dim == 3, "P1Simplex: triangles (2) or tetrahedra (3)");
  using Point = std::array<double, dim>;
  static constexpr int num_vertices = dim + 1;

  std::array<std::int32_t, dim + 1> nodes;
  std::array<Point, dim + 1> xv;
  std::array<Point, dim> J;    ///< J[i][j] = dx_i / dxi_j
  std::array<Point, dim> Jinv; ///< Jinv[j][i] = dxi_j / dx_i
  std::array<Point, dim + 1> grad;
  double detJ;

  /// Cell c of a mesh with coordinates x (num_nodes, dim) and cells
  /// (num_cells, dim + 1).
  P1Simplex(std::span<const double> x, std::span<const std::int32_t> cells, std::int32_t c)
  {
    for (int a = 0; a <= dim; ++a)
    {
      nodes[a] = cells[(dim + 1) * c + a];
      for (int i = 0; i < dim; ++i)
        xv[a][i] = x[dim * nodes[a] + i];
    }
    init(c);
  }

  /// From vertex coordinates (dim + 1, dim) only (nodes set to -1).
  explicit P1Simplex(std::span<const double, dim*(dim + 1)> xc)
  {
    for (int a = 0; a <= dim; ++a)
    {
      nodes[a] = -1;
      for (int i = 0; i < dim; ++i)
        xv[a][i] = xc[dim * a + i];
    }
    init(-1);
  }

  Point physical(const Point& r) const
  {
    Point p;
    for (int i = 0; i < dim; ++i)
    {
      p[i] = xv[0][i];
      for (int j = 0; j < dim; ++j)
        p[i] += J[i][j] * r[j];
    }
    return p;
  }
  /// Reference coordinates of a physical point (affine inverse).
  Point reference(const Point& p) const
  {
    Point d, r;
    for (int i = 0; i < dim; ++i)
      d[i] = p[i] - xv[0][i];
    for (int j = 0; j < dim; ++j)
    {
      r[j] = Jinv[j][0] * d[0];
      for (int i = 1; i < dim; ++i)
        r[j] += Jinv[j][i] * d[i];
    }
    return r;
  }
  /// Physical gradient of the linear function with nodal values f.
  Point gradient(const std::array<double, dim + 1>& f) const
  {
    Point g{};
    for (int a = 0; a <= dim; ++a)
      for (int i = 0; i < dim; ++i)
        g[i] += f[a] * grad[a][i];
    return g;
  }
  /// Area (dim 2) or volume (dim 3).
  double volume() const { return std::abs(detJ) / (dim == 2 ? 2.0 : 6.0); }
  /// P1 shape functions at reference coordinates r.
  static std::array<double, dim + 1> shape(const Point& r)
  {
    std::array<double, dim + 1> N;
    N[0] = 1.0;
    for (int i = 0; i < dim; ++i)
      N[0] -= r[i], N[i + 1] = r[i];
    return N;
  }
  /// Local index (0..dim) of a mesh node in this cell, -1 if absent.
  int local(std::int32_t node) const
  {
    for (int a = 0; a <= dim; ++a)
      if (nodes[a] == node)
        return a;
    return -1;
  }

private:
  void init(std::int32_t c)
  {
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j)
        J[i][j] = xv[j + 1][i] - xv[0][i];
    if constexpr (dim == 2)
      detJ = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    else
      detJ = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0])
             + J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
    if (!(std::abs(detJ) > 0.0) or !std::isfinite(detJ))
      throw std::runtime_error("cell " + std::to_string(c) + (dim == 2 ? " has zero area" : " has zero volume"));
    // Inverse by cofactors (the adjugate over det J).
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j)
      {
        if constexpr (dim == 2)
          Jinv[j][i] = (i == j ? J[1 - i][1 - j] : -J[1 - i][1 - j]) / detJ;
        else
        {
          const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
          Jinv[j][i] = (J[i1][j1] * J[i2][j2] - J[i1][j2] * J[i2][j1]) / detJ;
        }
      }
    // grad N_a = rows of J^{-1} (a = 1..dim), grad N_0 = -their sum.
    for (int a = 1; a <= dim; ++a)
      grad[a] = Jinv[a - 1];
    for (int i = 0; i < dim; ++i)
    {
      grad[0][i] = -grad[1][i];
      for (int a = 2; a <= dim; ++a)
        grad[0][i] -= grad[a][i];
    }
  }
};

/// The simplices by their usual names.
using P1Cell = P1Simplex<2>;
using P1Tetrahedron = P1Simplex<3>;

} // namespace cracklip
