#include "contact/multiplier_space_3d.h"

#include "geometry/p1_simplex.h"

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

namespace cracklip
{
namespace
{
/// A node's shape function counts as having a trace on a piece when it
/// exceeds this at one of the piece's facet vertices (N_a is linear and >= 0
/// on the cell; cut points off an edge of the node give round-off there).
constexpr double TRACE_TOL = 1e-12;

/// For every node a of the cell: int over the piece's facets of N_a (exact:
/// area times N_a at the centroid).
std::array<double, 4> shape_integrals(const CrackCell3D& cc)
{
  std::array<double, 4> w = {0.0, 0.0, 0.0, 0.0};
  for (int k = 0; k < cc.num_facets(); ++k)
  {
    const double* R = &cc.facets[9 * k];
    const Point3 mid = {(R[0] + R[3] + R[6]) / 3.0, (R[1] + R[4] + R[7]) / 3.0, (R[2] + R[5] + R[8]) / 3.0};
    const auto N = P1Tetrahedron::shape(mid);
    for (int a = 0; a < 4; ++a)
      w[a] += cc.facet_area[k] * N[a];
  }
  return w;
}

/// Tie the P0 multiplier of every front piece of crack ic to an interior
/// group (multiplier_space_3d.h).
void tie_front_pieces(const MultiplierSpace3D& space, std::int32_t ic, std::span<const std::int32_t> cells,
                      const CrackGeometry3D& g, const NodalMultipliers& nodal,
                      const std::vector<std::int8_t>& interior, const std::vector<MultiplierKey>& keys,
                      MultiplierGroups& groups)
{
  std::vector<std::size_t> front;
  for (std::size_t p = 0; p < space.pieces.size(); ++p)
    if (space.pieces[p].crack == ic and space.pieces[p].front)
      front.push_back(p);
  std::vector<std::int8_t> tied(front.size(), 0);
  // The interior groups are final here: their keys serve every piece.
  const auto gkey = group_keys(groups, keys);
  for (std::size_t i = 0; i < front.size(); ++i)
  {
    const LipPiece3D& piece = space.pieces[front[i]];
    const CrackCell3D& cc = g.crack_cells[g.crack_cell_index[piece.cell]];
    const auto w = shape_integrals(cc);
    // Weight of every interior group on the piece; the heaviest wins
    // (equals: by key, multiplier_groups.h).
    std::map<std::int32_t, double> weight; // root -> weight
    for (int a = 0; a < 4; ++a)
    {
      const auto it = nodal.find({ic, cells[4 * piece.cell + a]});
      if (it != nodal.end() and interior[it->second])
        weight[groups.find(it->second)] += w[a];
    }
    if (weight.empty())
      continue;
    std::vector<std::tuple<double, MultiplierKey, std::int32_t>> candidates;
    for (const auto& [r, wr] : weight)
      candidates.emplace_back(wr, gkey.at(r), r);
    groups.unite(piece.mult.front(), std::get<2>(*pick_largest(candidates)));
    tied[i] = 1;
  }
  // Front cells without an interior group at their nodes: the group of the
  // tied front cells sharing most nodes with them (equals: by key), all
  // such cells next to a tied one at once, repeated along the front.
  std::map<std::int32_t, std::vector<std::size_t>> by_node; // mesh node -> front pieces (indices into front)
  for (std::size_t i = 0; i < front.size(); ++i)
    for (int a = 0; a < 4; ++a)
      by_node[cells[4 * space.pieces[front[i]].cell + a]].push_back(i);
  for (;;)
  {
    const auto fkey = group_keys(groups, keys);
    std::vector<std::pair<std::size_t, std::int32_t>> joins; // (front piece, root)
    for (std::size_t i = 0; i < front.size(); ++i)
    {
      if (tied[i])
        continue;
      const std::int32_t* vi = &cells[4 * space.pieces[front[i]].cell];
      std::set<std::size_t> near; // tied front pieces sharing a node with piece i
      for (int a = 0; a < 4; ++a)
        for (const std::size_t k : by_node[vi[a]])
          if (tied[k])
            near.insert(k);
      std::map<std::int32_t, int> shared; // root -> most nodes shared with one of its tied front cells
      for (const std::size_t j : near)
      {
        const std::int32_t* vj = &cells[4 * space.pieces[front[j]].cell];
        int n = 0;
        for (int a = 0; a < 4; ++a)
          n += static_cast<int>(std::count(vj, vj + 4, vi[a]));
        const std::int32_t r = groups.find(space.pieces[front[j]].mult.front());
        shared[r] = std::max(shared[r], n);
      }
      if (shared.empty())
        continue;
      std::vector<std::tuple<double, MultiplierKey, std::int32_t>> candidates;
      for (const auto& [r, n] : shared)
        candidates.emplace_back(n, fkey.at(r), r);
      joins.emplace_back(i, std::get<2>(*pick_largest(candidates)));
    }
    if (joins.empty())
      break;
    for (const auto& [i, r] : joins)
    {
      groups.unite(space.pieces[front[i]].mult.front(), r);
      tied[i] = 1;
    }
  }
  // A crack with no interior group (all its pieces in front cells): one
  // group for all of them.
  std::int32_t first = -1;
  for (std::size_t i = 0; i < front.size(); ++i)
    if (!tied[i])
    {
      const std::int32_t f = space.pieces[front[i]].mult.front();
      if (first < 0)
        first = f;
      else
        groups.unite(f, first);
    }
}
/// A group holding front cells' P0 multipliers whose weight (int of its
/// function) lies for more than FRONT_SHARE on the front cells' pieces
/// absorbs the group it overlaps most on the interior pieces (int psi_g
/// psi_h), until no such group is left (or it overlaps none).
constexpr double FRONT_SHARE = 1.0 / 3.0;

void absorb_front_heavy_groups(const MultiplierSpace3D& space, std::int32_t ic, const CrackGeometry3D& g,
                               const std::vector<MultiplierKey>& keys, MultiplierGroups& groups)
{
  const std::int32_t nfull = space.num_full();
  std::vector<double> mass(nfull, 0.0), front_mass(nfull, 0.0);
  std::map<std::pair<std::int32_t, std::int32_t>, double> overlap; // (f, l), f != l: int psi_f psi_l, interior
  for (const LipPiece3D& piece : space.pieces)
  {
    if (piece.crack != ic)
      continue;
    const CrackCell3D& cc = g.crack_cells[g.crack_cell_index[piece.cell]];
    for (int k = 0; k < cc.num_facets(); ++k)
    {
      const double A = cc.facet_area[k];
      // Values of the piece's multipliers at the facet's vertices.
      std::vector<std::array<double, 3>> v(piece.mult.size());
      for (std::size_t m = 0; m < piece.mult.size(); ++m)
        for (int i = 0; i < 3; ++i)
        {
          const double* r = &cc.facets[9 * k + 3 * i];
          v[m][i] = piece.local[m] < 0 ? 1.0 : P1Tetrahedron::shape({r[0], r[1], r[2]})[piece.local[m]];
        }
      for (std::size_t m = 0; m < piece.mult.size(); ++m)
      {
        const double integral = A * (v[m][0] + v[m][1] + v[m][2]) / 3.0;
        mass[piece.mult[m]] += integral;
        if (piece.front)
          front_mass[piece.mult[m]] += integral;
        else // int f g over a triangle: A / 12 (sum f_i g_i + sum f_i sum g_j)
          for (std::size_t l = 0; l < piece.mult.size(); ++l)
            if (l != m)
              overlap[{piece.mult[m], piece.mult[l]}]
                  += A / 12.0
                     * (v[m][0] * v[l][0] + v[m][1] * v[l][1] + v[m][2] * v[l][2]
                        + (v[m][0] + v[m][1] + v[m][2]) * (v[l][0] + v[l][1] + v[l][2]));
      }
    }
  }
  std::set<std::int32_t> given_up; // roots that overlap no interior group
  for (;;)
  {
    std::map<std::int32_t, std::array<double, 2>> total; // root -> (front mass, mass)
    for (std::int32_t f = 0; f < nfull; ++f)
      if (space.full_crack[f] == ic)
      {
        auto& t = total[groups.find(f)];
        t[0] += front_mass[f], t[1] += mass[f];
      }
    // The group of the largest front share above FRONT_SHARE (equals: by key).
    const auto gkey = group_keys(groups, keys);
    std::vector<std::tuple<double, MultiplierKey, std::int32_t>> heavy;
    for (const auto& [r, t] : total)
      if (t[1] > 0.0 and t[0] / t[1] > FRONT_SHARE + 1e-12 and !given_up.count(r))
        heavy.emplace_back(t[0] / t[1], gkey.at(r), r);
    if (heavy.empty())
      return;
    const std::int32_t worst = std::get<2>(*pick_largest(heavy));
    std::map<std::int32_t, double> with; // other root -> overlap
    for (const auto& [fl, o] : overlap)
      if (groups.find(fl.first) == worst)
        if (const std::int32_t r = groups.find(fl.second); r != worst)
          with[r] += o;
    std::vector<std::tuple<double, MultiplierKey, std::int32_t>> candidates;
    for (const auto& [r, o] : with)
      if (o > 0.0)
        candidates.emplace_back(o, gkey.at(r), r);
    if (candidates.empty())
      given_up.insert(worst);
    else
      groups.unite(worst, std::get<2>(*pick_largest(candidates)));
  }
}
} // namespace

MultiplierSpace3D create_multiplier_space_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                             std::span<const CrackGeometry3D* const> cracks,
                                             const EnrichmentLayout& layout, MultiplierKind kind,
                                             bool with_front_pieces)
{
  if (x.size() % 3 != 0 or cells.size() % 4 != 0)
    throw std::invalid_argument("create_multiplier_space_3d: expected x (n, 3) and cells (m, 4)");
  MultiplierSpace3D space;
  space.kind = kind;
  NodalMultipliers nodal; // (crack, node) -> full
  static constexpr int EDGES[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  std::vector<CutEdge> cut_edges;
  std::vector<std::array<double, 3>> cut_points;
  for (std::size_t icr = 0; icr < cracks.size(); ++icr)
  {
    const auto ic = static_cast<std::int32_t>(icr);
    const CrackGeometry3D& g = *cracks[icr];
    if (g.phi.size() * 3 != x.size())
      throw std::invalid_argument("create_multiplier_space_3d: crack " + std::to_string(ic)
                                  + " has level sets of another mesh");
    for (const CrackCell3D& cc : g.crack_cells)
    {
      if (cc.num_facets() == 0)
        continue;
      const bool front = cc.cls == CellClass3D::front;
      if (front and !with_front_pieces)
        continue;
      LipPiece3D piece;
      piece.crack = ic;
      piece.cell = cc.cell;
      piece.front = front;
      const std::int32_t* v = &cells[4 * cc.cell];
      if (front and kind == MultiplierKind::stable)
      {
        piece.mult.push_back(add_cell_multiplier(space, ic, cc.cell));
        piece.local.push_back(-1);
      }
      else
        for (int a = 0; a < 4; ++a)
        {
          double trace = 0.0;
          for (int k = 0; k < 3 * cc.num_facets(); ++k)
          {
            const double* r = &cc.facets[3 * k];
            trace = std::max(trace, P1Tetrahedron::shape({r[0], r[1], r[2]})[a]);
          }
          if (trace <= TRACE_TOL)
            continue;
          piece.mult.push_back(add_nodal_multiplier(space, nodal, ic, v[a]));
          piece.local.push_back(a);
        }
      if (!piece.mult.empty()) // else a sliver piece no shape function sees
        space.pieces.push_back(std::move(piece));
      if (cc.cls != CellClass3D::cut)
        continue;
      for (const auto& e : EDGES)
      {
        std::int32_t p = v[e[0]], q = v[e[1]];
        if (!(g.phi[p] * g.phi[q] < 0.0))
          continue;
        if (p > q)
          std::swap(p, q);
        cut_edges.push_back({ic, p, q});
        cut_points.push_back(cut_point<3>(&x[3 * p], &x[3 * q], g.phi[p], g.phi[q]));
      }
    }
  }

  const std::int32_t nfull = space.num_full();
  if (kind == MultiplierKind::naive)
  {
    number_naive(space);
    return space;
  }
  MultiplierGroups groups(nfull);
  const std::vector<MultiplierKey> keys = multiplier_keys(space, x, cells, 3);
  tie_stars<3>(space.pieces, cut_edges, cut_points, nodal, layout, static_cast<std::int8_t>(EnrichmentKind::heaviside),
               space, keys, groups);
  // Nodal multipliers active on an interior (non-front) piece.
  std::vector<std::int8_t> interior(nfull, 0);
  for (const LipPiece3D& piece : space.pieces)
    if (!piece.front)
      for (const std::int32_t f : piece.mult)
        interior[f] = 1;
  for (std::size_t icr = 0; icr < cracks.size(); ++icr)
  {
    tie_front_pieces(space, static_cast<std::int32_t>(icr), cells, *cracks[icr], nodal, interior, keys, groups);
    absorb_front_heavy_groups(space, static_cast<std::int32_t>(icr), *cracks[icr], keys, groups);
  }
  groups.number(space);
  return space;
}

} // namespace cracklip
