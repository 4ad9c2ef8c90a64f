#include "enrichment/enrichment_layout.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace cracklip
{
namespace
{
bool in_closure(std::span<const double> x, const std::int32_t* v, std::array<double, 2> p)
{
  const double x0 = x[2 * v[0]], y0 = x[2 * v[0] + 1];
  const double a = x[2 * v[1]] - x0, b = x[2 * v[2]] - x0;
  const double c = x[2 * v[1] + 1] - y0, d = x[2 * v[2] + 1] - y0;
  const double det = a * d - b * c;
  const double px = p[0] - x0, py = p[1] - y0;
  const double l1 = (d * px - b * py) / det, l2 = (-c * px + a * py) / det;
  constexpr double tol = 1e-12;
  return l1 >= -tol and l2 >= -tol and l1 + l2 <= 1.0 + tol;
}
} // namespace

EnrichmentLayout create_enrichment_layout(std::span<const double> x,
                                          std::span<const std::int32_t> cells,
                                          std::span<const CrackGeometry* const> cracks,
                                          const EnrichmentOptions& options)
{
  const std::size_t num_cells = cells.size() / 3;
  const auto num_nodes = static_cast<std::int32_t>(x.size() / 2);
  if (options.tip != TipEnrichment::none and !(options.radius >= 0.0))
    throw std::invalid_argument("tip enrichment radius must be >= 0 (0: the tip cell's nodes only), got "
                                + std::to_string(options.radius));
  EnrichmentLayout layout;
  layout.num_std_nodes = num_nodes;
  layout.kappa = options.kappa;
  layout.corrected = options.corrected;

  // One cell may be crossed by one crack only.
  std::vector<std::int32_t> crossed_by(num_cells, -1);
  for (std::size_t ic = 0; ic < cracks.size(); ++ic)
  {
    const CrackGeometry& g = *cracks[ic];
    if (g.cell_class.size() != num_cells or g.phi.size() != static_cast<std::size_t>(num_nodes))
      throw std::invalid_argument("create_enrichment_layout: crack geometry of crack " + std::to_string(ic)
                                  + " has " + std::to_string(g.phi.size()) + " nodes and "
                                  + std::to_string(g.cell_class.size()) + " cells, the mesh "
                                  + std::to_string(num_nodes) + " and " + std::to_string(num_cells)
                                  + "; compute the geometry on this mesh");
    for (std::size_t c = 0; c < num_cells; ++c)
    {
      const auto cls = static_cast<CellClass>(g.cell_class[c]);
      if (cls == CellClass::plain or cls == CellClass::extension)
        continue;
      if (crossed_by[c] >= 0)
        throw std::runtime_error("cell " + std::to_string(c) + " is crossed by cracks "
                                 + std::to_string(crossed_by[c]) + " and " + std::to_string(ic)
                                 + ": cracks closer than the mesh size are not supported; "
                                   "refine the mesh near them");
      crossed_by[c] = static_cast<std::int32_t>(ic);
    }
  }

  auto add = [&](std::int32_t i, std::int32_t ic, EnrichmentKind kind, int function,
                 std::int32_t tip, bool core)
  {
    layout.core.push_back(core ? 1 : 0);
    const CrackGeometry& g = *cracks[ic];
    const int side = g.phi[i] >= 0.0 ? 1 : -1;
    layout.node.push_back(i);
    layout.crack.push_back(ic);
    layout.kind.push_back(static_cast<std::int8_t>(kind));
    layout.function.push_back(static_cast<std::int8_t>(function));
    layout.tip.push_back(tip);
    layout.node_side.push_back(static_cast<std::int8_t>(side));
    std::array<double, 4> sh = {0.0, 0.0, 0.0, 0.0};
    const std::array<double, 2> xi = {x[2 * i], x[2 * i + 1]};
    if (kind == EnrichmentKind::heaviside)
      sh[0] = side;
    else if (kind == EnrichmentKind::tip_scalar)
    {
      std::array<double, 4> F;
      std::array<std::array<double, 2>, 4> dF;
      branch_functions(layout.tip_frames[tip], xi, side, F, dF);
      sh[0] = F[function];
    }
    else
    {
      std::array<std::array<double, 2>, 2> U;
      std::array<std::array<std::array<double, 2>, 2>, 2> dU;
      williams_displacement(layout.tip_frames[tip], xi, side, options.kappa, U, dU);
      sh = {U[0][0], U[0][1], U[1][0], U[1][1]};
    }
    layout.shift.insert(layout.shift.end(), sh.begin(), sh.end());
  };

  std::vector<std::vector<std::int32_t>> node_enr(num_nodes);
  for (std::size_t ic = 0; ic < cracks.size(); ++ic)
  {
    const CrackGeometry& g = *cracks[ic];
    // Core tip nodes: within the radius of a tip, and the nodes of the
    // cells whose closure holds it (a later tip wins a node).
    std::vector<std::int32_t> core_tip(num_nodes, -1);
    std::vector<std::int32_t> tips;
    if (options.tip != TipEnrichment::none)
    {
      const int num_tips = static_cast<int>(g.tips.size() / 2);
      for (int j = 0; j < num_tips; ++j)
      {
        const auto tid = static_cast<std::int32_t>(layout.tip_frames.size());
        const TipFrame frame{{g.tips[2 * j], g.tips[2 * j + 1]},
                             {g.tip_tangents[2 * j], g.tip_tangents[2 * j + 1]},
                             g.tip_orientation[j]};
        layout.tip_frames.push_back(frame);
        layout.tip_crack.push_back(static_cast<std::int32_t>(ic));
        layout.tip_local.push_back(j);
        tips.push_back(tid);
        for (std::int32_t i = 0; i < num_nodes; ++i)
          if (std::hypot(x[2 * i] - frame.tip[0], x[2 * i + 1] - frame.tip[1]) <= options.radius)
            core_tip[i] = tid;
        for (std::size_t c = 0; c < num_cells; ++c)
          if (in_closure(x, &cells[3 * c], frame.tip))
            for (int a = 0; a < 3; ++a)
              core_tip[cells[3 * c + a]] = tid;
      }
    }
    // The distance of a node to the crack line at a tip.
    auto line_distance = [&](std::int32_t i, std::int32_t t)
    {
      const TipFrame& f = layout.tip_frames[t];
      return std::abs(-f.e1[1] * (x[2 * i] - f.tip[0]) + f.e1[0] * (x[2 * i + 1] - f.tip[1]));
    };
    const SelectionInput input{cells, 3, g.cell_class, g.phi, core_tip, tips, line_distance};
    const auto icr = static_cast<std::int32_t>(ic);
    for (const PseudoNode& pn : select_enrichment(input, options.tip, options.corrected, layout.num_enriched(), node_enr))
      add(pn.node, icr, pn.kind, pn.function, pn.tip, pn.core);
  }

  // Enriched cells and their pseudo-nodes.
  static_cast<EnrichedCells&>(layout) = create_enriched_cells(cells, 3, node_enr);
  return layout;
}

} // namespace cracklip
