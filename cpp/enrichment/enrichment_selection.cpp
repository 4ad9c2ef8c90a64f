#include "enrichment/enrichment_selection.h"

#include <algorithm>
#include <cmath>

namespace cracklip
{

std::vector<PseudoNode> select_enrichment(const SelectionInput& in, TipEnrichment tip, bool corrected,
                                          std::int32_t first_index,
                                          std::vector<std::vector<std::int32_t>>& node_pseudo)
{
  const int npc = in.nodes_per_cell;
  const std::size_t num_cells = in.cells.size() / npc;
  const auto num_nodes = static_cast<std::int32_t>(in.phi.size());
  const auto cls_of = [&](std::size_t c) { return in.cell_class[c]; };
  constexpr std::int8_t cut = 1, along = 2, front = 3, extension = 4;

  // Core tip nodes, then (corrected) blending nodes: the other nodes of
  // cells that hold a core node take that cell's first core node's tip.
  std::vector<std::int32_t> tip_of(in.core_tip.begin(), in.core_tip.end());
  std::vector<std::int8_t> is_core(num_nodes, 0);
  if (tip != TipEnrichment::none)
  {
    for (std::int32_t i = 0; i < num_nodes; ++i)
      is_core[i] = tip_of[i] >= 0;
    if (corrected)
      for (std::size_t c = 0; c < num_cells; ++c)
      {
        const std::int32_t* v = &in.cells[npc * c];
        int a = -1;
        for (int k = 0; k < npc and a < 0; ++k)
          if (is_core[v[k]])
            a = k;
        if (a >= 0)
          for (int b = 0; b < npc; ++b)
            if (tip_of[v[b]] < 0)
              tip_of[v[b]] = tip_of[v[a]];
      }
  }
  else
    std::fill(tip_of.begin(), tip_of.end(), -1);

  auto all_core = [&](const std::int32_t* v)
  {
    for (int k = 0; k < npc; ++k)
      if (!is_core[v[k]])
        return false;
    return true;
  };
  // Heaviside candidates.
  std::vector<std::int8_t> split(num_nodes, 0), forbidden(num_nodes, 0);
  for (std::size_t c = 0; c < num_cells; ++c)
  {
    const std::int8_t cls = cls_of(c);
    const std::int32_t* v = &in.cells[npc * c];
    // With the corrected scheme the Heaviside functions carry 1 - R, which
    // vanishes on a cell whose nodes are all core tip nodes (always the
    // tip cell): there they cannot open a crack that is not present, so
    // such a tip or extension cell forbids nothing.
    const bool ramp_one = tip != TipEnrichment::none and corrected and all_core(v);
    // A node's Heaviside function N_i (H - H_i) is non-zero on a cut cell,
    // and on a cell whose crack edge / face holds the node only if the node
    // lies on it (a node off it is on the cell's own side, where it is 0).
    for (int a = 0; a < npc; ++a)
    {
      if ((cls == cut and (!in.opens or in.opens(static_cast<std::int32_t>(c), v[a])))
          or (cls == along and in.phi[v[a]] == 0.0))
        split[v[a]] = 1;
      else if ((cls == front or cls == extension) and !ramp_one)
        forbidden[v[a]] = 1;
    }
  }
  // Core nodes of crossed cells that also hold a non-core node: there
  // (1 - R) N_i (H - H_i) is not zero (elsewhere it vanishes identically).
  std::vector<std::int8_t> blending_core(num_nodes, 0);
  for (std::size_t c = 0; c < num_cells; ++c)
  {
    const std::int32_t* v = &in.cells[npc * c];
    const std::int8_t cls = cls_of(c);
    if (all_core(v))
      continue;
    for (int a = 0; a < npc; ++a)
      if (is_core[v[a]]
          and ((cls == cut and (!in.opens or in.opens(static_cast<std::int32_t>(c), v[a])))
               or (cls == along and in.phi[v[a]] == 0.0)))
        blending_core[v[a]] = 1;
  }
  // Scalar branch functions under the corrected scheme: drop F_1, F_2 at
  // the node farthest from the crack's plane, per tip, when the tip's
  // functions cover the whole support of its ramp.
  std::vector<std::int32_t> dropped_node;
  if (tip == TipEnrichment::scalar and corrected)
    for (const std::int32_t t : in.tips)
    {
      bool complete = true;
      for (std::size_t c = 0; c < num_cells and complete; ++c)
      {
        const std::int32_t* v = &in.cells[npc * c];
        bool has_core = false;
        for (int a = 0; a < npc; ++a)
          has_core = has_core or (is_core[v[a]] and tip_of[v[a]] == t);
        for (int a = 0; a < npc and has_core; ++a)
          complete = complete and tip_of[v[a]] == t;
      }
      std::int32_t best = -1;
      double best_d = 0.0;
      for (std::int32_t i = 0; i < num_nodes and complete; ++i)
        if (tip_of[i] == t)
          if (const double d = in.plane_distance(i, t); d > best_d)
            best_d = d, best = i;
      dropped_node.push_back(best);
    }
  auto dropped = [&](std::int32_t i, int l)
  { return l < 2 and std::find(dropped_node.begin(), dropped_node.end(), i) != dropped_node.end(); };

  std::vector<PseudoNode> out;
  auto add = [&](std::int32_t i, EnrichmentKind kind, int function, std::int32_t t, bool core)
  {
    node_pseudo[i].push_back(first_index + static_cast<std::int32_t>(out.size()));
    out.push_back({i, kind, static_cast<std::int8_t>(function), t, core});
  };
  for (std::int32_t i = 0; i < num_nodes; ++i)
  {
    if (tip_of[i] >= 0)
    {
      if (tip == TipEnrichment::scalar)
      {
        for (int l = 0; l < 4; ++l)
          if (!dropped(i, l))
            add(i, EnrichmentKind::tip_scalar, l, tip_of[i], is_core[i]);
      }
      else
        add(i, EnrichmentKind::tip_vector, 0, tip_of[i], is_core[i]);
    }
    // Heaviside on split nodes outside the core; with the corrected scheme
    // also on core nodes of blending cells, since the ramped tip functions
    // carry only the fraction R of the jump there.
    const bool heaviside_ok = !is_core[i] or (corrected and blending_core[i]);
    if (heaviside_ok and split[i] and !forbidden[i] and (!in.keep_heaviside or in.keep_heaviside(i, is_core)))
      add(i, EnrichmentKind::heaviside, 0, -1, false);
  }
  return out;
}

} // namespace cracklip
