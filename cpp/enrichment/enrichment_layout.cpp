#include "enrichment/enrichment_layout.h"

#include "enrichment/crack_enrichment.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace cracklip
{
namespace
{
/// Throws unless every crack's geometry lives on this mesh and no cell is
/// crossed by two cracks (classes other than plain and extension).
template <typename Crack>
void check_cracks(std::span<const Crack* const> cracks, std::size_t num_cells, std::size_t num_nodes)
{
  std::vector<std::int32_t> crossed_by(num_cells, -1);
  for (std::size_t ic = 0; ic < cracks.size(); ++ic)
  {
    const Crack& g = *cracks[ic];
    if (g.cell_class.size() != num_cells or g.phi.size() != num_nodes)
      throw std::invalid_argument("create_enrichment_layout: crack geometry of crack " + std::to_string(ic)
                                  + " has " + std::to_string(g.phi.size()) + " nodes and "
                                  + std::to_string(g.cell_class.size()) + " cells, the mesh "
                                  + std::to_string(num_nodes) + " and " + std::to_string(num_cells)
                                  + "; compute the geometry on this mesh");
    for (std::size_t c = 0; c < num_cells; ++c)
    {
      const std::int8_t cls = g.cell_class[c];
      if (cls == 0 or cls == 4) // plain, extension
        continue;
      if (crossed_by[c] >= 0)
        throw std::runtime_error("cell " + std::to_string(c) + " is crossed by cracks "
                                 + std::to_string(crossed_by[c]) + " and " + std::to_string(ic)
                                 + ": cracks closer than the mesh size are not supported; "
                                   "refine the mesh near them");
      crossed_by[c] = static_cast<std::int32_t>(ic);
    }
  }
}

template <int dim>
EnrichmentLayout create_layout(std::span<const double> x, std::span<const std::int32_t> cells,
                               std::span<const CrackGeometryOf<dim>* const> cracks, const EnrichmentOptions& options)
{
  const std::size_t num_cells = cells.size() / (dim + 1);
  const auto num_nodes = static_cast<std::int32_t>(x.size() / dim);
  if (options.tip != TipEnrichment::none and !(options.radius >= 0.0))
    throw std::invalid_argument(std::string(dim == 2 ? "tip enrichment radius must be >= 0 (0: the tip cell's nodes "
                                                       "only), got "
                                                     : "front enrichment radius must be >= 0 (0: the front cells' "
                                                       "nodes only), got ")
                                + std::to_string(options.radius));
  EnrichmentLayout layout;
  layout.dim = dim;
  layout.num_std_nodes = num_nodes;
  layout.kappa = options.kappa;
  layout.corrected = options.corrected;
  check_cracks(cracks, num_cells, static_cast<std::size_t>(num_nodes));

  std::vector<std::vector<std::int32_t>> node_pseudo(num_nodes);
  for (std::size_t icr = 0; icr < cracks.size(); ++icr)
  {
    const auto ic = static_cast<std::int32_t>(icr);
    CrackEnrichment<dim> geometry(x, cells, *cracks[ic], ic, options, layout);
    for (const PseudoNode& pn : select_enrichment(geometry.selection(), options.tip, options.corrected,
                                                  layout.num_enriched(), node_pseudo))
    {
      const int side = cracks[ic]->phi[pn.node] >= 0.0 ? 1 : -1;
      layout.node.push_back(pn.node);
      layout.crack.push_back(ic);
      layout.kind.push_back(static_cast<std::int8_t>(pn.kind));
      layout.function.push_back(pn.function);
      layout.tip.push_back(pn.tip);
      layout.node_side.push_back(static_cast<std::int8_t>(side));
      layout.core.push_back(pn.core ? 1 : 0);
      std::array<double, dim * dim> sh{};
      if (pn.kind == EnrichmentKind::heaviside)
        sh[0] = side;
      else
        geometry.shift(pn, side, sh);
      layout.shift.insert(layout.shift.end(), sh.begin(), sh.end());
    }
  }
  static_cast<EnrichedCells&>(layout) = create_enriched_cells(cells, dim + 1, node_pseudo);
  CrackEnrichment<dim>::complete(layout, x, cells, cracks);
  return layout;
}
} // namespace

const double* EnrichmentLayout::frame(std::int32_t n, std::int32_t ic) const
{
  // frame_node sorted by (node, crack).
  std::size_t lo = 0, hi = frame_node.size();
  while (lo < hi)
  {
    const std::size_t mid = (lo + hi) / 2;
    if (frame_node[mid] < n or (frame_node[mid] == n and frame_crack[mid] < ic))
      lo = mid + 1;
    else
      hi = mid;
  }
  if (lo < frame_node.size() and frame_node[lo] == n and frame_crack[lo] == ic)
    return &node_frames[9 * lo];
  return nullptr;
}

void EnrichmentLayout::require_dimension(int d, const char* who) const
{
  if (dim != d)
    throw std::invalid_argument(std::string(who) + ": the enrichment layout belongs to a " + std::to_string(dim)
                                + "D mesh, the arrays to a " + std::to_string(d) + "D one");
}

EnrichmentLayout with_cells_below(const EnrichmentLayout& layout, std::int32_t num_cells)
{
  EnrichmentLayout out = layout;
  out.cells.clear();
  out.cell_offsets.assign(1, 0);
  out.cell_enr.clear();
  std::fill(out.cell_index.begin(), out.cell_index.end(), -1);
  for (std::size_t i = 0; i < layout.cells.size(); ++i)
  {
    const std::int32_t c = layout.cells[i];
    if (c >= num_cells)
      continue;
    out.cell_index[c] = static_cast<std::int32_t>(out.cells.size());
    out.cells.push_back(c);
    out.cell_enr.insert(out.cell_enr.end(), layout.cell_enr.begin() + layout.cell_offsets[i],
                        layout.cell_enr.begin() + layout.cell_offsets[i + 1]);
    out.cell_offsets.push_back(static_cast<std::int32_t>(out.cell_enr.size()));
  }
  return out;
}

EnrichmentLayout create_enrichment_layout(std::span<const double> x, std::span<const std::int32_t> cells,
                                          std::span<const CrackGeometry* const> cracks,
                                          const EnrichmentOptions& options)
{
  return create_layout<2>(x, cells, cracks, options);
}

EnrichmentLayout create_enrichment_layout(std::span<const double> x, std::span<const std::int32_t> cells,
                                          std::span<const CrackGeometry3D* const> cracks,
                                          const EnrichmentOptions& options)
{
  return create_layout<3>(x, cells, cracks, options);
}

} // namespace cracklip
