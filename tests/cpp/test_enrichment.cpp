#include "enrichment/enrichment_layout.h"

#include <gtest/gtest.h>

using namespace cracklip;

namespace
{
// Structured n x n grid of [0,1]^2 split into 2 n^2 triangles.
void grid(int n, std::vector<double>& x, std::vector<std::int32_t>& cells)
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
} // namespace

TEST(HeavisideLayout, ThroughCrackEnrichesTwoRowsOfNodes)
{
  std::vector<double> x;
  std::vector<std::int32_t> cells;
  grid(10, x, cells);
  CrackPath c{{-1.0, 0.55, 2.0, 0.55}, {false, false}};
  const CrackGeometry g = compute_crack_geometry(x, cells, c, 1e-8);
  const CrackGeometry* gs[] = {&g};
  const EnrichmentLayout l = create_enrichment_layout(x, cells, gs, {});
  EXPECT_EQ(l.num_enriched(), 22); // rows y = 0.5 and y = 0.6
  for (int k = 0; k < l.num_enriched(); ++k)
    EXPECT_EQ(l.shift[4 * k], x[2 * l.node[k] + 1] > 0.55 ? 1.0 : -1.0);
  // Enriched cells: the 20 cut cells and their neighbours in rows 4 and 6.
  EXPECT_EQ(l.cells.size(), 60u);
}

TEST(HeavisideLayout, NodesAroundTheTipAreNotHeavisideEnriched)
{
  std::vector<double> x;
  std::vector<std::int32_t> cells;
  grid(10, x, cells);
  CrackPath c{{-1.0, 0.55, 0.43, 0.55}, {false, true}};
  const CrackGeometry g = compute_crack_geometry(x, cells, c, 1e-8);
  ASSERT_EQ(g.tip_cells.size(), 1u);
  const CrackGeometry* gs[] = {&g};
  const EnrichmentLayout l = create_enrichment_layout(x, cells, gs, {});
  const int tc = g.tip_cells[0].cell;
  for (int k = 0; k < l.num_enriched(); ++k)
    for (int a = 0; a < 3; ++a)
      EXPECT_NE(l.node[k], cells[3 * tc + a]);
  EXPECT_EQ(l.num_enriched(), 8); // x = 0, 0.1, 0.2, 0.3 on two rows
}

TEST(HeavisideLayout, TwoCracksInOneCellThrow)
{
  std::vector<double> x;
  std::vector<std::int32_t> cells;
  grid(4, x, cells);
  CrackPath a{{-1.0, 0.3, 2.0, 0.3}, {false, false}}, b{{-1.0, 0.32, 2.0, 0.32}, {false, false}};
  const CrackGeometry ga = compute_crack_geometry(x, cells, a, 1e-8);
  const CrackGeometry gb = compute_crack_geometry(x, cells, b, 1e-8);
  const CrackGeometry* gs[] = {&ga, &gb};
  EXPECT_THROW(create_enrichment_layout(x, cells, gs, {}), std::runtime_error);
}

TEST(HeavisideLayout, CellsBelowKeepThePseudoNodesAndTheCellsBelow)
{
  std::vector<double> x;
  std::vector<std::int32_t> cells;
  grid(10, x, cells);
  CrackPath c{{-1.0, 0.55, 2.0, 0.55}, {false, false}};
  const CrackGeometry g = compute_crack_geometry(x, cells, c, 1e-8);
  const CrackGeometry* gs[] = {&g};
  const EnrichmentLayout l = create_enrichment_layout(x, cells, gs, {});
  const std::int32_t below = 110; // rows 0-5 of cells (20 per row): the crack row 5 is cut in half
  const EnrichmentLayout o = with_cells_below(l, below);
  EXPECT_EQ(o.num_enriched(), l.num_enriched());
  EXPECT_EQ(o.node, l.node);
  ASSERT_EQ(o.cell_offsets.size(), o.cells.size() + 1);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < l.cells.size(); ++i)
  {
    const std::int32_t cell = l.cells[i];
    if (cell >= below)
    {
      EXPECT_EQ(o.cell_index[cell], -1);
      continue;
    }
    const std::int32_t j = o.cell_index[cell];
    ASSERT_EQ(j, static_cast<std::int32_t>(kept));
    EXPECT_EQ(o.cells[j], cell);
    const std::vector<std::int32_t> a(l.cell_enr.begin() + l.cell_offsets[i], l.cell_enr.begin() + l.cell_offsets[i + 1]);
    const std::vector<std::int32_t> b(o.cell_enr.begin() + o.cell_offsets[j], o.cell_enr.begin() + o.cell_offsets[j + 1]);
    EXPECT_EQ(a, b);
    ++kept;
  }
  EXPECT_EQ(o.cells.size(), kept);
  EXPECT_EQ(kept, 30u); // row 4 (20 cells) and the first half of the cut row 5 (10)
}
