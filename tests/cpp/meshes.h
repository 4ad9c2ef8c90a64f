// Small structured meshes for the C++ unit tests (no DOLFINx).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

namespace cracklip::test
{
/// Structured n x n grid of [0,1]^2 split into 2 n^2 triangles: x (nodes, 2), cells (cells, 3).
inline void triangle_grid(int n, std::vector<double>& x, std::vector<std::int32_t>& cells)
{
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      x.insert(x.end(), {double(i) / n, double(j) / n});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
    {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      cells.insert(cells.end(), {a, b, c, a, c, d});
    }
}

/// Kuhn mesh of [0,1]^3: n^3 cubes, each split into 6 tetrahedra around its
/// main diagonal: x (nodes, 3), cells (cells, 4).
inline void kuhn_cube(int n, std::vector<double>& x, std::vector<std::int32_t>& cells)
{
  auto id = [n](int i, int j, int k) { return (k * (n + 1) + j) * (n + 1) + i; };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        x.insert(x.end(), {double(i) / n, double(j) / n, double(k) / n});
  // The six paths from corner 000 to 111, one axis at a time.
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& p : perms)
        {
          std::array<int, 3> c = {i, j, k};
          std::array<std::int32_t, 4> tet;
          tet[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s)
          {
            ++c[p[s]];
            tet[s + 1] = id(c[0], c[1], c[2]);
          }
          cells.insert(cells.end(), tet.begin(), tet.end());
        }
}

/// The Kuhn mesh of [0,1]^3 with n cubes per edge, as arrays.
struct KuhnMesh
{
  std::vector<double> x;
  std::vector<std::int32_t> cells;
  explicit KuhnMesh(int n) { kuhn_cube(n, x, cells); }
  std::int32_t num_cells() const { return static_cast<std::int32_t>(cells.size() / 4); }
};

/// The same mesh in another order (seed): nodes renumbered, cells shuffled,
/// every cell's vertices rotated by a random amount. x (nodes, dim), cells
/// (cells, npc) are replaced.
inline void shuffle_mesh(int dim, int npc, unsigned seed, std::vector<double>& x, std::vector<std::int32_t>& cells)
{
  std::mt19937 rng(seed);
  const std::size_t nn = x.size() / dim, nc = cells.size() / npc;
  std::vector<std::int32_t> label(nn), order(nc);
  std::iota(label.begin(), label.end(), 0);
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(label.begin(), label.end(), rng);
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<double> y(x.size());
  for (std::size_t i = 0; i < nn; ++i)
    std::copy_n(&x[dim * i], dim, &y[dim * label[i]]);
  std::vector<std::int32_t> c(cells.size());
  for (std::size_t k = 0; k < nc; ++k)
  {
    const int shift = static_cast<int>(rng() % npc);
    for (int a = 0; a < npc; ++a)
      c[npc * k + a] = label[cells[npc * order[k] + (a + shift) % npc]];
  }
  x.swap(y);
  cells.swap(c);
}
} // namespace cracklip::test
