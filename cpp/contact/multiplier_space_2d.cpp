#include "contact/multiplier_space_2d.h"
#include "contact/vital_edges.h"
#include "enrichment/enriched_basis_2d.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>

namespace cracklip
{
MultiplierSpace create_multiplier_space(std::span<const double> x, std::span<const std::int32_t> cells,
                                        std::span<const CrackGeometry* const> cracks,
                                        const EnrichmentLayout& layout, MultiplierKind kind,
                                        bool with_tip_segments)
{
  MultiplierSpace space;
  space.kind = kind;
  NodalMultipliers nodal; // (crack, node) -> full

  // Cut edges of each crack, for the stable space: (crack, a, b) with a < b.
  std::vector<std::array<std::int32_t, 3>> cut_edges;
  std::vector<std::array<double, 2>> cut_points;

  for (std::size_t icr = 0; icr < cracks.size(); ++icr)
  {
    const auto ic = static_cast<std::int32_t>(icr);
    const CrackGeometry& g = *cracks[icr];
    for (const CrackCell& cc : g.crack_cells)
    {
      if (!cc.owns_segment)
        continue;
      CrackSegment seg;
      seg.crack = ic;
      seg.cell = cc.cell;
      seg.ref = cc.segment;
      const std::int32_t* v = &cells[3 * cc.cell];
      for (int a = 0; a < 3; ++a)
      {
        // On an edge cell only the nodes on the crack edge have a trace.
        if (cc.cls == CellClass::edge and g.phi[v[a]] != 0.0)
          continue;
        seg.mult.push_back(add_nodal_multiplier(space, nodal, ic, v[a]));
        seg.local.push_back(a);
      }
      space.segments.push_back(seg);
      if (cc.cls == CellClass::cut)
        for (int a = 0; a < 3; ++a)
        {
          std::int32_t p = v[a], q = v[(a + 1) % 3];
          const double fp = g.phi[p], fq = g.phi[q];
          if (fp * fq < 0.0)
          {
            if (p > q)
              std::swap(p, q);
            cut_edges.push_back({ic, p, q});
            cut_points.push_back(cut_point<2>(&x[2 * p], &x[2 * q], g.phi[p], g.phi[q]));
          }
        }
    }
    if (!with_tip_segments)
      continue;
    for (const TipCell& tc : g.tip_cells)
    {
      CrackSegment seg;
      seg.crack = ic;
      seg.cell = tc.cell;
      seg.ref = tc.segment; // entry point E, then the tip T
      seg.tip = true;
      seg.tip_end = 1;
      seg.tip_index = tc.tip;
      const std::int32_t* v = &cells[3 * tc.cell];
      if (kind == MultiplierKind::naive)
        for (int a = 0; a < 3; ++a)
        {
          seg.mult.push_back(add_nodal_multiplier(space, nodal, ic, v[a]));
          seg.local.push_back(a);
        }
      else
      {
        seg.mult.push_back(add_cell_multiplier(space, ic, tc.cell));
        seg.local.push_back(-1);
      }
      space.segments.push_back(seg);
    }
  }

  const std::int32_t nfull = space.num_full();
  if (kind == MultiplierKind::naive)
  {
    number_naive(space);
    return space;
  }

  // Stable (P1-): drop cut edges by score until every score is <= 1, tie
  // the stars, then the stars without enriched nodes to a neighbouring star.
  MultiplierGroups uf(nfull);
  const std::vector<MultiplierKey> keys = multiplier_keys(space, x, cells, 2);
  const auto heaviside = tie_stars<2>(space.segments, cut_edges, cut_points, nodal, layout,
                                      static_cast<std::int8_t>(EnrichmentKind::heaviside), space, keys, uf);
  // The multiplier at a crack end sees a jump that fades (like sqrt(r) in a
  // tip cell, linearly over the last cut cell of a Heaviside-only crack)
  // and is barely controlled: left alone it makes the inf-sup constant drop.
  // Such an end is tied to the multiplier of the segment next to it.
  for (std::size_t icr = 0; icr < cracks.size(); ++icr)
  {
    const CrackGeometry& g = *cracks[icr];
    const auto ic = static_cast<std::int32_t>(icr);
    // Physical end points of this crack's segments.
    std::vector<std::size_t> own;
    std::vector<std::array<std::array<double, 2>, 2>> ends;
    for (std::size_t s = 0; s < space.segments.size(); ++s)
      if (const CrackSegment& seg = space.segments[s]; seg.crack == ic)
      {
        const P1Cell cell(x, cells, seg.cell);
        own.push_back(s);
        ends.push_back({cell.physical({seg.ref[0], seg.ref[1]}), cell.physical({seg.ref[2], seg.ref[3]})});
      }
    if (own.empty())
      continue;
    auto length = [&](std::size_t i) { return std::hypot(ends[i][1][0] - ends[i][0][0], ends[i][1][1] - ends[i][0][1]); };
    // Calls fn(segment, shape values, weight) at two Gauss points of every
    // segment of this crack: exact for a product of two functions linear on
    // each segment.
    auto for_each_point = [&](auto&& fn)
    {
      for (std::size_t i = 0; i < own.size(); ++i)
      {
        const CrackSegment& seg = space.segments[own[i]];
        for (const double t : {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)})
          fn(seg, P1Cell::shape({(1 - t) * seg.ref[0] + t * seg.ref[2], (1 - t) * seg.ref[1] + t * seg.ref[3]}),
             0.5 * length(i));
      }
    };
    // Shape value of a segment's k-th multiplier (P0: 1).
    auto value = [](const CrackSegment& seg, const std::array<double, 3>& N, std::size_t k)
    { return seg.local[k] < 0 ? 1.0 : N[seg.local[k]]; };
    // Sum of the multiplier functions of the groups G at a point.
    auto mu = [&](const CrackSegment& seg, const std::array<double, 3>& N, const std::set<std::int32_t>& G)
    {
      double m = 0.0;
      for (std::size_t k = 0; k < seg.mult.size(); ++k)
        if (G.count(uf.find(seg.mult[k])))
          m += value(seg, N, k);
      return m;
    };
    // Share of the weight of the groups G that sees the full Heaviside jump:
    // int(mu w) / int(mu), w the sum of the shape functions of the crack's
    // Heaviside-enriched nodes (1 where the crack opens fully, fading to 0
    // over the last cut cell of a Heaviside-only crack).
    auto full_jump_share = [&](const std::set<std::int32_t>& G)
    {
      double mu_w = 0.0, mu_1 = 0.0;
      for_each_point(
          [&](const CrackSegment& seg, const std::array<double, 3>& N, double wq)
          {
            const std::int32_t* v = &cells[3 * seg.cell];
            double w = 0.0;
            for (int a = 0; a < 3; ++a)
              if (heaviside.count({ic, v[a]}))
                w += N[a];
            const double m = mu(seg, N, G);
            mu_w += wq * m * w;
            mu_1 += wq * m;
          });
      return mu_1 > 0.0 ? mu_w / mu_1 : 0.0;
    };
    for (std::size_t j = 0; j < g.tips.size() / 2; ++j)
    {
      const std::array<double, 2> T = {g.tips[2 * j], g.tips[2 * j + 1]};
      // The segment with the end point nearest T; distances within 1e-9 of
      // the longest segment count as equal (two segments ending at a tip on
      // a mesh edge or node) and the cell's key decides.
      double tol = 0.0;
      for (std::size_t i = 0; i < own.size(); ++i)
        tol = std::max(tol, 1e-9 * length(i));
      std::vector<std::tuple<double, std::array<double, 12>, std::size_t>> nearest; // (distance, key, index)
      for (std::size_t i = 0; i < own.size(); ++i)
        for (const auto& P : ends[i])
          nearest.emplace_back(std::hypot(P[0] - T[0], P[1] - T[1]), cell_key(x, cells, 2, space.segments[own[i]].cell),
                               i);
      double dmin = std::numeric_limits<double>::max();
      for (const auto& n : nearest)
        dmin = std::min(dmin, std::get<0>(n));
      std::size_t end = 0; // index into own / ends
      const std::array<double, 12>* end_key = nullptr;
      for (const auto& [d, key, i] : nearest)
        if (d <= dmin + tol and (end_key == nullptr or key < *end_key))
          end = i, end_key = &key;
      const CrackSegment& end_seg = space.segments[own[end]];
      if (!end_seg.tip and with_tip_segments)
      {
        // A tip-enriched crack whose tip sits on an edge or a vertex (no tip
        // cell): tip dofs, not Heaviside ones, open its last segments. Tie
        // that segment like a tip cell when it is shorter than the crack's
        // mean segment.
        std::vector<double> lengths; // summed in ascending order: the same sum in any order
        for (std::size_t i = 0; i < own.size(); ++i)
          lengths.push_back(length(i) / static_cast<double>(own.size()));
        std::sort(lengths.begin(), lengths.end());
        const double mean_len = std::accumulate(lengths.begin(), lengths.end(), 0.0);
        if (length(end) >= mean_len)
          continue;
      }
      else if (!end_seg.tip)
      {
        // The end of a Heaviside-only crack (its last cut cell): its group G
        // is controlled when it sees the full jump over as large a share of
        // its weight as the hat of the last fully enriched node, which fades
        // with the jump (2/3; a constant over the fade has 1/2 and gave
        // sqrt(beta) = 0.44 on inclined cracks). Otherwise G absorbs the
        // group it overlaps most (int mu_G mu_c) until it is.
        std::set<std::int32_t> G;
        for (std::int32_t f : end_seg.mult)
          G.insert(uf.find(f));
        while (full_jump_share(G) < 2.0 / 3.0 - 1e-9) // 2/3 itself is common: keep it
        {
          std::map<std::int32_t, double> overlap;
          for_each_point(
              [&](const CrackSegment& seg, const std::array<double, 3>& N, double wq)
              {
                if (const double m = mu(seg, N, G); m > 0.0)
                  for (std::size_t k = 0; k < seg.mult.size(); ++k)
                    if (const std::int32_t r = uf.find(seg.mult[k]); !G.count(r))
                      overlap[r] += wq * m * value(seg, N, k);
              });
          const auto gkey = group_keys(uf, keys);
          std::vector<std::tuple<double, MultiplierKey, std::int32_t>> candidates;
          for (const auto& [r, o] : overlap)
            if (o > 0.0)
              candidates.emplace_back(o, gkey.at(r), r);
          if (candidates.empty())
            break;
          const std::int32_t pick = std::get<2>(*pick_largest(candidates));
          for (std::int32_t r : G)
            uf.unite(r, pick);
          G = {uf.find(pick)};
        }
        continue;
      }
      // The tip cell's P0 multiplier sees a jump fading like sqrt(r) over
      // its whole segment and is always tied (so is a short end segment of
      // a tip-enriched crack without a tip cell, above).
      const auto& E = ends[end];
      const double len = length(end);
      const std::int32_t r_end = uf.find(end_seg.mult.front());
      for (std::int32_t f : end_seg.mult)
        uf.unite(f, r_end);
      std::vector<std::int32_t> picks;
      for (std::size_t i = 0; i < own.size(); ++i)
      {
        if (i == end)
          continue;
        // The end point shared with the end segment (0 or 1 of this one).
        int shared = -1;
        for (int a = 0; a < 2; ++a)
          for (const auto& P : E)
            if (std::hypot(ends[i][a][0] - P[0], ends[i][a][1] - P[1]) <= 1e-9 * len)
              shared = a;
        if (shared < 0)
          continue;
        // Tie the end multiplier to the neighbour's multiplier that is
        // largest at the shared point (the one continuous across it) among
        // those not already on the end segment (equals: the smallest key;
        // so also when all of these vanish there).
        const CrackSegment& nb = space.segments[own[i]];
        const auto N = P1Cell::shape({nb.ref[2 * shared], nb.ref[2 * shared + 1]});
        std::vector<std::tuple<double, MultiplierKey, std::int32_t>> candidates;
        for (std::size_t k = 0; k < nb.mult.size(); ++k)
        {
          const std::int32_t f = nb.mult[k];
          bool on_end = false;
          for (std::int32_t fe : end_seg.mult)
            on_end = on_end or uf.find(fe) == uf.find(f);
          if (!on_end)
            candidates.emplace_back(value(nb, N, k), keys[f], f);
        }
        if (!candidates.empty())
          picks.push_back(std::get<2>(*pick_largest(candidates)));
      }
      // Every neighbour chose against the end group as it was (the order of
      // the segments does not enter).
      for (const std::int32_t pick : picks)
        uf.unite(r_end, pick);
    }
  }
  uf.number(space);
  return space;
}

} // namespace cracklip
