// Snapping nodal level-set values onto zero (layer a; the same in 2D and 3D).
//
// Rule: a node whose |value| is below snap_tol times the shortest edge at
// that node is moved onto the level set (its value becomes exactly 0). No
// sub-cell is then thinner than snap_tol * h, which bounds the conditioning
// of the enriched system; the surface moves by at most snap_tol * h.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip
{

/// Shortest edge at each node, (num_nodes): x (num_nodes, gdim), cells
/// (num_cells, nodes_per_cell) of simplices (every pair of a cell's nodes
/// is an edge). Nodes in no cell get the largest double.
std::vector<double> compute_shortest_edges(std::span<const double> x, int gdim,
                                           std::span<const std::int32_t> cells, int nodes_per_cell);

/// Set values[i] = 0 where 0 < |values[i]| < snap_tol * h_node[i] and mark
/// snapped[i] = 1 there (other marks are kept, so several level sets can
/// share one mark array). Returns the number of values changed.
std::int32_t snap_to_zero(std::span<double> values, std::span<const double> h_node, double snap_tol,
                          std::span<char> snapped);

} // namespace cracklip
