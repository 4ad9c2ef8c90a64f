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
    // Tip enrichment.
    std::vector<std::int32_t> tip_of(num_nodes, -1);
    std::vector<std::int8_t> is_core(num_nodes, 0);
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
        for (std::int32_t i = 0; i < num_nodes; ++i)
          if (std::hypot(x[2 * i] - frame.tip[0], x[2 * i + 1] - frame.tip[1]) <= options.radius)
            tip_of[i] = tid;
        for (std::size_t c = 0; c < num_cells; ++c)
          if (in_closure(x, &cells[3 * c], frame.tip))
            for (int a = 0; a < 3; ++a)
              tip_of[cells[3 * c + a]] = tid;
      }
      for (std::int32_t i = 0; i < num_nodes; ++i)
        is_core[i] = tip_of[i] >= 0;
      if (options.corrected)
        // Blending nodes: the other nodes of cells that hold a core node.
        for (std::size_t c = 0; c < num_cells; ++c)
        {
          const std::int32_t* v = &cells[3 * c];
          const int a = is_core[v[0]] ? 0 : (is_core[v[1]] ? 1 : (is_core[v[2]] ? 2 : -1));
          if (a >= 0)
            for (int b = 0; b < 3; ++b)
              if (tip_of[v[b]] < 0)
                tip_of[v[b]] = tip_of[v[a]];
        }
    }
    // Heaviside candidates.
    std::vector<std::int8_t> split(num_nodes, 0), forbidden(num_nodes, 0);
    for (std::size_t c = 0; c < num_cells; ++c)
    {
      const auto cls = static_cast<CellClass>(g.cell_class[c]);
      const std::int32_t* v = &cells[3 * c];
      // With the corrected scheme the Heaviside functions carry 1 - R, which
      // vanishes on a cell whose nodes are all core tip nodes (always the
      // tip cell): there they cannot open a crack that is not present, so
      // such a tip or extension cell forbids nothing. (Forbidding its nodes
      // would strip the Heaviside from a core node of a neighbouring cut
      // blending cell, where the jump is then missing: a tip close to the
      // tip cell's far edge.)
      const bool ramp_one = options.tip != TipEnrichment::none and options.corrected
                            and is_core[v[0]] and is_core[v[1]] and is_core[v[2]];
      // A node's Heaviside function N_i (H - H_i) is non-zero on a cut cell,
      // and on an edge cell only if the node lies on the crack edge (a node
      // off the edge is on the cell's own side, where the function is 0).
      for (int a = 0; a < 3; ++a)
      {
        if (cls == CellClass::cut or (cls == CellClass::edge and g.phi[v[a]] == 0.0))
          split[v[a]] = 1;
        else if ((cls == CellClass::tip or cls == CellClass::extension) and !ramp_one)
          forbidden[v[a]] = 1;
      }
    }
    // Core nodes of crossed cells that also hold a non-core node: there
    // (1 - R) N_i (H - H_i) is not zero (elsewhere it vanishes identically).
    std::vector<std::int8_t> blending_core(num_nodes, 0);
    for (std::size_t c = 0; c < num_cells; ++c)
    {
      const std::int32_t* v = &cells[3 * c];
      const auto cls = static_cast<CellClass>(g.cell_class[c]);
      if (is_core[v[0]] and is_core[v[1]] and is_core[v[2]])
        continue;
      for (int a = 0; a < 3; ++a)
        if (is_core[v[a]] and (cls == CellClass::cut or (cls == CellClass::edge and g.phi[v[a]] == 0.0)))
          blending_core[v[a]] = 1;
    }
    // Scalar branch functions under the corrected scheme: in the tip frame
    // (x1, x2) the identities  x2 F1 + x1 F3 - x2 F4 = 0  and
    // x2 F2 - x2 F3 - x1 F4 = 0  hold everywhere, and where every node of the
    // cell carries the functions sum_i N_i R x_i = R x. So for each component
    // sum_i N_i R (x2_i F1 + x1_i F3 - x2_i F4) = 0 (and likewise for the
    // second identity, also with the shifted functions): two exact
    // dependencies per component and tip. Dropping F1 and F2 at the node
    // farthest from the crack line (x2_p != 0) removes them without changing
    // the span. Only when the tip's functions cover the whole support of its
    // ramp (no overlap with another tip's nodes), else nothing is dropped.
    std::vector<std::int32_t> dropped_node; // per tip of this crack's tips: node or -1
    if (options.tip == TipEnrichment::scalar and options.corrected)
    {
      const auto first_tip = static_cast<std::int32_t>(layout.tip_frames.size() - g.tips.size() / 2);
      for (auto t = first_tip; t < static_cast<std::int32_t>(layout.tip_frames.size()); ++t)
      {
        const TipFrame& f = layout.tip_frames[t];
        bool complete = true;
        for (std::size_t c = 0; c < num_cells and complete; ++c)
        {
          const std::int32_t* v = &cells[3 * c];
          bool has_core = false;
          for (int a = 0; a < 3; ++a)
            has_core = has_core or (is_core[v[a]] and tip_of[v[a]] == t);
          for (int a = 0; a < 3 and has_core; ++a)
            complete = complete and tip_of[v[a]] == t;
        }
        std::int32_t best = -1;
        double best_d = 0.0;
        for (std::int32_t i = 0; i < num_nodes and complete; ++i)
          if (tip_of[i] == t)
          {
            const double d = std::abs(-f.e1[1] * (x[2 * i] - f.tip[0]) + f.e1[0] * (x[2 * i + 1] - f.tip[1]));
            if (d > best_d)
              best_d = d, best = i;
          }
        dropped_node.push_back(best);
      }
    }
    auto dropped = [&](std::int32_t i, int l)
    { return l < 2 and std::find(dropped_node.begin(), dropped_node.end(), i) != dropped_node.end(); };
    for (std::int32_t i = 0; i < num_nodes; ++i)
    {
      const auto icr = static_cast<std::int32_t>(ic);
      if (tip_of[i] >= 0)
      {
        if (options.tip == TipEnrichment::scalar)
          for (int l = 0; l < 4; ++l)
          {
            if (dropped(i, l))
              continue;
            node_enr[i].push_back(layout.num_enriched());
            add(i, icr, EnrichmentKind::tip_scalar, l, tip_of[i], is_core[i]);
          }
        else
        {
          node_enr[i].push_back(layout.num_enriched());
          add(i, icr, EnrichmentKind::tip_vector, 0, tip_of[i], is_core[i]);
        }
      }
      // Heaviside on split nodes outside the core. With the corrected scheme
      // the Heaviside functions carry the factor 1 - R: blending nodes keep
      // them, and so do core nodes of blending cells, since the ramped tip
      // functions carry only the fraction R of the jump there.
      const bool heaviside_ok = !is_core[i] or (options.corrected and blending_core[i]);
      if (heaviside_ok and split[i] and !forbidden[i])
      {
        node_enr[i].push_back(layout.num_enriched());
        add(i, icr, EnrichmentKind::heaviside, 0, -1, false);
      }
    }
  }

  // Enriched cells and their pseudo-nodes.
  static_cast<EnrichedCells&>(layout) = create_enriched_cells(cells, 3, node_enr);
  return layout;
}

} // namespace cracklip
