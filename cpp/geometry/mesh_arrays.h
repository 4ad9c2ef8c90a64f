// Checks of a mesh given as plain arrays (layer a), in any dimension.
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>

namespace cracklip
{

/// Throws std::invalid_argument (the message starts with `who`) unless
/// every coordinate of x (num_nodes, gdim) is finite and every entry of
/// cells (num_cells, nodes_per_cell) names a node.
inline void check_mesh_arrays(std::span<const double> x, int gdim, std::span<const std::int32_t> cells,
                              int nodes_per_cell, const std::string& who)
{
  const std::size_t num_nodes = x.size() / gdim;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!std::isfinite(x[i]))
      throw std::invalid_argument(who + ": mesh node " + std::to_string(i / gdim)
                                  + " has a non-finite coordinate; node coordinates must be finite");
  for (std::size_t i = 0; i < cells.size(); ++i)
    if (cells[i] < 0 or static_cast<std::size_t>(cells[i]) >= num_nodes)
      throw std::invalid_argument(who + ": cell " + std::to_string(i / nodes_per_cell) + " refers to node "
                                  + std::to_string(cells[i]) + "; node indices must lie in [0, "
                                  + std::to_string(num_nodes) + ")");
}

} // namespace cracklip
