// Geometry of one P1 tetrahedron (layer a): the 3D counterpart of P1Cell.
#pragma once

#include "geometry/cut_tetrahedron.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>

namespace cracklip
{

/// Node indices, vertex coordinates, the affine map from the reference
/// tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1) (x = x0 + J xi), the
/// constant shape-function gradients grad[a] = dN_a/dx and det J (signed:
/// mesh cells may have either orientation; volumes use |det J| / 6).
struct P1Tetrahedron
{
  std::array<std::int32_t, 4> nodes;
  std::array<Point3, 4> xv;
  std::array<std::array<double, 3>, 3> J;    ///< J[i][j] = dx_i / dxi_j
  std::array<std::array<double, 3>, 3> Jinv; ///< Jinv[j][i] = dxi_j / dx_i
  std::array<Point3, 4> grad;
  double detJ;

  P1Tetrahedron(std::span<const double> x, std::span<const std::int32_t> cells, std::int32_t c)
  {
    for (int a = 0; a < 4; ++a)
    {
      nodes[a] = cells[4 * c + a];
      xv[a] = {x[3 * nodes[a]], x[3 * nodes[a] + 1], x[3 * nodes[a] + 2]};
    }
    init(c);
  }

  /// From vertex coordinates (4, 3) only (nodes set to -1).
  explicit P1Tetrahedron(std::span<const double, 12> xc)
  {
    for (int a = 0; a < 4; ++a)
    {
      nodes[a] = -1;
      xv[a] = {xc[3 * a], xc[3 * a + 1], xc[3 * a + 2]};
    }
    init(-1);
  }

  Point3 physical(const Point3& r) const
  {
    Point3 p;
    for (int i = 0; i < 3; ++i)
      p[i] = xv[0][i] + J[i][0] * r[0] + J[i][1] * r[1] + J[i][2] * r[2];
    return p;
  }
  /// Reference coordinates of a physical point (affine inverse).
  Point3 reference(const Point3& p) const
  {
    const Point3 d = {p[0] - xv[0][0], p[1] - xv[0][1], p[2] - xv[0][2]};
    Point3 r;
    for (int j = 0; j < 3; ++j)
      r[j] = Jinv[j][0] * d[0] + Jinv[j][1] * d[1] + Jinv[j][2] * d[2];
    return r;
  }
  /// Physical gradient of the linear function with nodal values f.
  Point3 gradient(const std::array<double, 4>& f) const
  {
    Point3 g = {0, 0, 0};
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i)
        g[i] += f[a] * grad[a][i];
    return g;
  }
  double volume() const { return std::abs(detJ) / 6.0; }
  static std::array<double, 4> shape(const Point3& r) { return {1.0 - r[0] - r[1] - r[2], r[0], r[1], r[2]}; }

private:
  void init(std::int32_t c)
  {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        J[i][j] = xv[j + 1][i] - xv[0][i];
    detJ = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0])
           + J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
    if (!(std::abs(detJ) > 0.0) or !std::isfinite(detJ))
      throw std::runtime_error("cell " + std::to_string(c) + " has zero volume");
    // Inverse by cofactors.
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
      {
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
        Jinv[j][i] = (J[i1][j1] * J[i2][j2] - J[i1][j2] * J[i2][j1]) / detJ;
      }
    // grad N_a = rows of J^{-1} (a = 1..3), grad N_0 = -sum.
    for (int a = 1; a < 4; ++a)
      grad[a] = {Jinv[a - 1][0], Jinv[a - 1][1], Jinv[a - 1][2]};
    for (int i = 0; i < 3; ++i)
      grad[0][i] = -grad[1][i] - grad[2][i] - grad[3][i];
  }
};

} // namespace cracklip
