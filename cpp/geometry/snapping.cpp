#include "geometry/snapping.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace cracklip
{

std::vector<double> compute_shortest_edges(std::span<const double> x, int gdim,
                                           std::span<const std::int32_t> cells, int nodes_per_cell)
{
  if (gdim != 2 and gdim != 3)
    throw std::invalid_argument("compute_shortest_edges: gdim must be 2 or 3");
  const std::size_t num_nodes = x.size() / gdim;
  const std::size_t num_cells = cells.size() / nodes_per_cell;
  std::vector<double> h(num_nodes, std::numeric_limits<double>::max());
  for (std::size_t c = 0; c < num_cells; ++c)
  {
    const std::int32_t* v = &cells[nodes_per_cell * c];
    for (int i = 0; i < nodes_per_cell; ++i)
      for (int j = i + 1; j < nodes_per_cell; ++j)
      {
        const std::int32_t a = v[i], b = v[j];
        const double len = gdim == 2 ? std::hypot(x[2 * a] - x[2 * b], x[2 * a + 1] - x[2 * b + 1])
                                     : std::hypot(x[3 * a] - x[3 * b], x[3 * a + 1] - x[3 * b + 1],
                                                  x[3 * a + 2] - x[3 * b + 2]);
        h[a] = std::min(h[a], len);
        h[b] = std::min(h[b], len);
      }
  }
  return h;
}

std::int32_t snap_to_zero(std::span<double> values, std::span<const double> h_node, double snap_tol,
                          std::span<char> snapped)
{
  std::int32_t count = 0;
  for (std::size_t i = 0; i < values.size(); ++i)
    if (values[i] != 0.0 and std::abs(values[i]) < snap_tol * h_node[i])
    {
      values[i] = 0.0;
      snapped[i] = 1;
      ++count;
    }
  return count;
}

} // namespace cracklip
