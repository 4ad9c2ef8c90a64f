// Enriched dof numbering, sparsity and the matrix sink: the same code for
// triangles (the 2D solver's instantiation) and tetrahedra.
#include "assembly/matrix_sink.h"
#include "assembly/sparsity.h"
#include "enrichment/dof_numbering.h"
#include "meshes.h"

#include <gtest/gtest.h>

#include <set>

using namespace cracklip;

namespace
{
// Pseudo-nodes on the nodes with x < 0.3 (two per node for every third of them).
std::vector<std::vector<std::int32_t>> some_pseudo_nodes(const std::vector<double>& x, int gdim, std::int32_t& count)
{
  const std::size_t n = x.size() / gdim;
  std::vector<std::vector<std::int32_t>> out(n);
  count = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (x[gdim * i] < 0.3)
      for (int r = 0; r < (i % 3 == 0 ? 2 : 1); ++r)
        out[i].push_back(count++);
  return out;
}

// Brute-force node pattern: every pair of nodes (standard or pseudo) active on a common cell.
std::set<std::pair<std::int32_t, std::int32_t>> brute_pattern(const std::vector<std::int32_t>& cells, int npc,
                                                               const std::vector<std::vector<std::int32_t>>& pseudo,
                                                               std::int32_t num_std)
{
  std::set<std::pair<std::int32_t, std::int32_t>> out;
  for (std::size_t c = 0; c < cells.size() / npc; ++c)
  {
    std::vector<std::int32_t> nodes(cells.begin() + npc * c, cells.begin() + npc * (c + 1));
    for (int a = 0; a < npc; ++a)
      for (auto k : pseudo[cells[npc * c + a]])
        nodes.push_back(num_std + k);
    for (auto i : nodes)
      for (auto j : nodes)
        out.insert({i, j});
  }
  return out;
}

void check_numbering_and_sparsity(const std::vector<double>& x, const std::vector<std::int32_t>& cells, int gdim)
{
  const int npc = gdim + 1;
  std::int32_t num_pseudo = 0;
  const auto pseudo = some_pseudo_nodes(x, gdim, num_pseudo);
  ASSERT_GT(num_pseudo, 0);
  const EnrichedCells e = create_enriched_cells(cells, npc, pseudo);
  const std::size_t num_cells = cells.size() / npc;
  ASSERT_EQ(e.cell_index.size(), num_cells);
  // Exactly the cells with an enriched node, in order, each with its nodes' pseudo-nodes.
  std::size_t expected = 0;
  for (std::size_t c = 0; c < num_cells; ++c)
  {
    std::vector<std::int32_t> want;
    for (int a = 0; a < npc; ++a)
      want.insert(want.end(), pseudo[cells[npc * c + a]].begin(), pseudo[cells[npc * c + a]].end());
    if (want.empty())
    {
      EXPECT_EQ(e.cell_index[c], -1);
      continue;
    }
    const std::int32_t ie = e.cell_index[c];
    ASSERT_EQ(ie, static_cast<std::int32_t>(expected++));
    EXPECT_EQ(e.cells[ie], static_cast<std::int32_t>(c));
    EXPECT_EQ(std::vector<std::int32_t>(e.cell_enr.begin() + e.cell_offsets[ie],
                                        e.cell_enr.begin() + e.cell_offsets[ie + 1]),
              want);
  }
  EXPECT_EQ(e.cells.size(), expected);
  // Sparsity against brute force; scalar expansion with block size gdim.
  const auto num_std = static_cast<std::int32_t>(x.size() / gdim);
  const CSR blocks = create_block_sparsity(cells, npc, num_std, num_pseudo, e);
  ASSERT_EQ(blocks.offsets.size(), static_cast<std::size_t>(num_std + num_pseudo + 1));
  std::set<std::pair<std::int32_t, std::int32_t>> got;
  for (std::int32_t i = 0; i + 1 < static_cast<std::int32_t>(blocks.offsets.size()); ++i)
  {
    for (auto k = blocks.offsets[i]; k < blocks.offsets[i + 1]; ++k)
    {
      got.insert({i, blocks.indices[k]});
      if (k > blocks.offsets[i])
        EXPECT_LT(blocks.indices[k - 1], blocks.indices[k]); // sorted, unique
    }
  }
  EXPECT_EQ(got, brute_pattern(cells, npc, pseudo, num_std));
  const CSR scalar = expand_blocks(blocks, gdim);
  EXPECT_EQ(scalar.indices.size(), blocks.indices.size() * gdim * gdim);
  // Row of component d of pseudo-node 0: the columns of its block row, expanded.
  const std::int32_t node = num_std;
  for (int d = 0; d < gdim; ++d)
  {
    const std::int32_t row = node_dof(node, d, gdim);
    std::vector<std::int32_t> want;
    for (auto k = blocks.offsets[node]; k < blocks.offsets[node + 1]; ++k)
      for (int b = 0; b < gdim; ++b)
        want.push_back(node_dof(blocks.indices[k], b, gdim));
    EXPECT_EQ(std::vector<std::int32_t>(scalar.indices.begin() + scalar.offsets[row],
                                        scalar.indices.begin() + scalar.offsets[row + 1]),
              want);
  }
}
} // namespace

TEST(DofNumbering, TrianglesTheSolversInstantiation)
{
  std::vector<double> x;
  std::vector<std::int32_t> cells;
  test::triangle_grid(6, x, cells);
  check_numbering_and_sparsity(x, cells, 2);
}

TEST(DofNumbering, Tetrahedra)
{
  std::vector<double> x;
  std::vector<std::int32_t> cells;
  test::kuhn_cube(4, x, cells);
  check_numbering_and_sparsity(x, cells, 3);
}

TEST(DofNumbering, RejectsBadInput)
{
  std::vector<std::vector<std::int32_t>> pseudo(3);
  const std::vector<std::int32_t> cells = {0, 1, 2, 0};
  EXPECT_THROW(create_enriched_cells(cells, 3, pseudo), std::invalid_argument); // not whole cells
  const std::vector<std::int32_t> bad = {0, 1, 5};
  EXPECT_THROW(create_enriched_cells(bad, 3, pseudo), std::invalid_argument); // node out of range
}

TEST(MatrixSink, CooCollectsBlocksOfAnySize)
{
  Triplets t;
  const MatrixSink sink = coo_sink(t);
  const std::int32_t rows[] = {0, -1, 7};
  const std::int32_t cols[] = {3, 4};
  const double vals[] = {1.0, 0.0, 2.0, 3.0, 4.0, 5.0};
  sink(rows, cols, vals);
  EXPECT_EQ(t.row, (std::vector<std::int32_t>{0, 7, 7}));
  EXPECT_EQ(t.col, (std::vector<std::int32_t>{3, 3, 4}));
  EXPECT_EQ(t.value, (std::vector<double>{1.0, 4.0, 5.0}));
  const double wrong[] = {1.0};
  EXPECT_THROW(sink(rows, cols, wrong), std::invalid_argument);
}
