// The stable multiplier reduction on cut edges (P1-): the same template for
// the cut triangles of the 2D solver and for cut tetrahedra.
#include "contact/vital_edges.h"
#include "meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <type_traits>

using namespace cracklip;

namespace
{
// Cut edges of the level set phi = n . x - c on a mesh (cells of npc nodes), sorted.
template <int Dim>
void cut_edges(const std::vector<double>& x, const std::vector<std::int32_t>& cells, int npc,
               std::array<double, Dim> normal, double c, std::vector<CutEdge>& edges,
               std::vector<std::array<double, Dim>>& points)
{
  const std::size_t n = x.size() / Dim;
  std::vector<double> phi(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    phi[i] = -c;
    for (int k = 0; k < Dim; ++k)
      phi[i] += normal[k] * x[Dim * i + k];
  }
  std::map<CutEdge, std::array<double, Dim>> found;
  for (std::size_t e = 0; e < cells.size() / npc; ++e)
    for (int a = 0; a < npc; ++a)
      for (int b = a + 1; b < npc; ++b)
      {
        std::int32_t p = cells[npc * e + a], q = cells[npc * e + b];
        if (phi[p] * phi[q] >= 0.0)
          continue;
        if (p > q)
          std::swap(p, q);
        found[{0, p, q}] = cut_point<Dim>(&x[Dim * p], &x[Dim * q], phi[p], phi[q]);
      }
  for (const auto& [e, pt] : found)
    edges.push_back(e), points.push_back(pt);
}

// The P1- properties: every node of the cut-edge graph keeps a vital edge,
// every vital edge has an end of vital degree 1 (the vital edges form
// stars), and no vital edge scores above 1 in the original sense.
void check_stars(const std::vector<CutEdge>& edges, const std::vector<std::int8_t>& alive, std::size_t& stars)
{
  std::map<std::int32_t, int> deg, vital;
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (int s = 1; s <= 2; ++s)
    {
      ++deg[edges[i][s]];
      if (alive[i])
        ++vital[edges[i][s]];
    }
  for (const auto& [v, d] : deg)
    EXPECT_GE(vital[v], 1) << "node " << v << " lost every cut edge";
  std::set<std::int32_t> centres;
  std::size_t leaves = 0;
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (alive[i])
    {
      const int da = vital[edges[i][1]], db = vital[edges[i][2]];
      EXPECT_EQ(std::min(da, db), 1) << "vital edge " << i << " joins two nodes of vital degree " << da << ", " << db;
      if (da > 1)
        centres.insert(edges[i][1]);
      else if (db > 1)
        centres.insert(edges[i][2]);
      else
        ++leaves; // a lone vital edge: a star of two nodes
    }
  stars = centres.size() + leaves;
}
} // namespace

TEST(VitalEdges, PathKeepsBothEnds)
{
  // 0 - 1 - 2 - 3 on one crack: the middle edge scores min(2, 2) = 2 and goes;
  // two stars {0, 1}, {2, 3} remain.
  const std::vector<CutEdge> edges = {{0, 0, 1}, {0, 1, 2}, {0, 2, 3}};
  const std::vector<std::array<double, 2>> pts = {{{0.5, 0.0}}, {{1.5, 0.0}}, {{2.5, 0.0}}};
  EXPECT_EQ(select_vital_edges<2>(edges, pts), (std::vector<std::int8_t>{1, 0, 1}));
  // Degrees per crack: the same path on two cracks is two separate paths.
  const std::vector<CutEdge> two = {{0, 0, 1}, {1, 1, 2}};
  const std::vector<std::array<double, 3>> p3 = {{{0, 0, 0}}, {{1, 0, 0}}};
  EXPECT_EQ(select_vital_edges<3>(two, p3), (std::vector<std::int8_t>{1, 1}));
}

TEST(VitalEdges, TieGoesToTheWidestSpacing)
{
  // A square 0-1-2-3-0: every edge scores 2. The first dropped is the one
  // whose cut point is farthest from its neighbours' (edge (0, 1), its point
  // moved away); then (2, 3) scores 2 still and goes: two stars remain.
  const std::vector<CutEdge> edges = {{0, 0, 1}, {0, 0, 3}, {0, 1, 2}, {0, 2, 3}};
  const std::vector<std::array<double, 2>> pts = {{{0.5, -1.0}}, {{0.0, 0.5}}, {{1.0, 0.5}}, {{0.5, 1.0}}};
  EXPECT_EQ(select_vital_edges<2>(edges, pts), (std::vector<std::int8_t>{0, 1, 1, 0}));
}

TEST(VitalEdges, CutTrianglesFormStars)
{
  std::vector<double> x;
  std::vector<std::int32_t> cells;
  test::triangle_grid(12, x, cells);
  std::vector<CutEdge> edges;
  std::vector<std::array<double, 2>> pts;
  cut_edges<2>(x, cells, 3, {0.3, 1.0}, 0.47, edges, pts);
  const auto alive = select_vital_edges<2>(edges, pts);
  std::size_t stars = 0;
  check_stars(edges, alive, stars);
  EXPECT_GT(stars, 4u);
  EXPECT_LT(stars, edges.size());
}

TEST(VitalEdges, CutTetrahedraFormStars)
{
  std::vector<double> x;
  std::vector<std::int32_t> cells;
  test::kuhn_cube(6, x, cells);
  std::vector<CutEdge> edges;
  std::vector<std::array<double, 3>> pts;
  cut_edges<3>(x, cells, 4, {0.2, -0.3, 1.0}, 0.41, edges, pts);
  ASSERT_GT(edges.size(), 100u);
  const auto alive = select_vital_edges<3>(edges, pts);
  std::size_t stars = 0;
  check_stars(edges, alive, stars);
  // A surface multiplier space: fewer unknowns than graph nodes, more than a handful.
  EXPECT_GT(stars, 10u);
  EXPECT_LT(stars, edges.size() / 2);
  // Deterministic: the same input gives the same stars.
  EXPECT_EQ(select_vital_edges<3>(edges, pts), alive);
}

// The vital edges as pairs of end points (sorted): a name free of numbering.
template <int Dim>
std::set<std::array<std::array<double, Dim>, 2>> vital_by_position(const std::vector<double>& x,
                                                                  const std::vector<CutEdge>& edges,
                                                                  const std::vector<std::int8_t>& alive)
{
  std::set<std::array<std::array<double, Dim>, 2>> out;
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (alive[i])
    {
      std::array<std::array<double, Dim>, 2> e;
      for (int s = 0; s < 2; ++s)
        std::copy_n(&x[Dim * edges[i][1 + s]], Dim, e[s].begin());
      std::sort(e.begin(), e.end());
      out.insert(e);
    }
  return out;
}

// A cut point is the same bits whichever end comes first.
TEST(VitalEdges, CutPointIsSymmetric)
{
  const double p[3] = {0.1, 0.7, 0.3}, q[3] = {0.4, 0.2, 0.9};
  EXPECT_EQ((cut_point<3>(p, q, -0.37, 0.11)), (cut_point<3>(q, p, 0.11, -0.37)));
  const auto c = cut_point<3>(p, q, -0.37, 0.11);
  const double t = 0.37 / 0.48;
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(c[k], p[k] + t * (q[k] - p[k]), 1e-15);
}

// The structured grids tie everywhere (equal scores and, up to round-off,
// equal spacings): the stars must still not depend on how the nodes, cells
// and edges are numbered. Five random orders of each grid (and the edges
// in reverse) give the same vital edges, named by their end points.
TEST(VitalEdges, StarsDoNotDependOnTheOrder)
{
  auto check = [](auto dim_tag, auto make, int npc, auto normal, double c)
  {
    constexpr int Dim = decltype(dim_tag)::value;
    std::vector<double> x;
    std::vector<std::int32_t> cells;
    make(x, cells);
    std::vector<CutEdge> edges;
    std::vector<std::array<double, Dim>> pts;
    cut_edges<Dim>(x, cells, npc, normal, c, edges, pts);
    const auto reference = vital_by_position<Dim>(x, edges, select_vital_edges<Dim>(edges, pts));
    ASSERT_GT(reference.size(), 10u);
    std::vector<CutEdge> rev(edges.rbegin(), edges.rend());
    std::vector<std::array<double, Dim>> rpts(pts.rbegin(), pts.rend());
    EXPECT_EQ(vital_by_position<Dim>(x, rev, select_vital_edges<Dim>(rev, rpts)), reference);
    for (unsigned seed = 1; seed <= 5; ++seed)
    {
      std::vector<double> y = x;
      std::vector<std::int32_t> k = cells;
      test::shuffle_mesh(Dim, npc, seed, y, k);
      std::vector<CutEdge> e;
      std::vector<std::array<double, Dim>> p;
      cut_edges<Dim>(y, k, npc, normal, c, e, p);
      EXPECT_EQ(vital_by_position<Dim>(y, e, select_vital_edges<Dim>(e, p)), reference) << "order " << seed;
    }
  };
  check(std::integral_constant<int, 2>(), [](auto& x, auto& c) { test::triangle_grid(12, x, c); }, 3,
        std::array<double, 2>{0.0, 1.0}, 0.513);
  check(std::integral_constant<int, 2>(), [](auto& x, auto& c) { test::triangle_grid(12, x, c); }, 3,
        std::array<double, 2>{0.3, 1.0}, 0.47);
  check(std::integral_constant<int, 3>(), [](auto& x, auto& c) { test::kuhn_cube(6, x, c); }, 4,
        std::array<double, 3>{0.0, 0.0, 1.0}, 0.513);
  check(std::integral_constant<int, 3>(), [](auto& x, auto& c) { test::kuhn_cube(6, x, c); }, 4,
        std::array<double, 3>{0.2, -0.3, 1.0}, 0.41);
}

TEST(VitalEdges, RejectsBadInput)
{
  const std::vector<CutEdge> edges = {{0, 2, 1}};
  const std::vector<std::array<double, 2>> pts = {{{0.0, 0.0}}};
  EXPECT_THROW(select_vital_edges<2>(edges, pts), std::invalid_argument);
  const std::vector<CutEdge> ok = {{0, 1, 2}};
  EXPECT_THROW(select_vital_edges<2>(ok, std::span<const std::array<double, 2>>()), std::invalid_argument);
}
