// The 3D geometry's part of the enrichment layout: fronts of a surface
// (crack_enrichment.h).
//
// The front functions are those of front_functions_3d.h in the level sets'
// local coordinates (x1 = psi, x2 = phi) with the directions interpolated
// from nodal frames (the frame of each node's nearest point on the front),
// times the ramp R of corrected blending. Core front nodes are the nodes
// within the enrichment radius of the front, the nodes of the cells holding
// it and those of the extension cells next to the crack's cells.
#include "enrichment/crack_enrichment.h"

#include "enrichment/front_functions_3d.h"
#include "geometry/cut_tetrahedron.h"
#include "geometry/p1_simplex.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace cracklip
{
namespace
{
/// A cut cell opens a node's Heaviside function when the side opposite the
/// node holds at least this fraction of the cell's volume.
constexpr double OPENING_VOLUME = 1e-9;

/// A node keeps its Heaviside function when the ramp leaves at least this
/// share of it (int N_i^2 (1 - R)^2 on the other side against int N_i^2
/// over its crossed cells; keep_heaviside) ...
constexpr double RAMPED_SHARE = 1e-8;

/// ... or at least this share of the jump on its cells' lip facets
/// (max N_i (1 - R) there).
constexpr double JUMP_SHARE = 1e-3;

/// The frame (rows e1, e2, e3) of a node's nearest front point.
std::array<double, 9> node_frame(const FrontLocator& front, std::span<const double> x, std::int32_t i)
{
  const FrontProjection p = front.project({x[3 * i], x[3 * i + 1], x[3 * i + 2]});
  std::array<double, 9> f;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      f[3 * k + j] = p.frame[k][j];
  return f;
}

/// |volume| of a sub-tetrahedron given by its reference vertices R (4, 3).
double sub_volume(const double* R)
{
  return std::abs(signed_volume({R[0], R[1], R[2]}, {R[3], R[4], R[5]}, {R[6], R[7], R[8]}, {R[9], R[10], R[11]}));
}
} // namespace

CrackEnrichment<3>::CrackEnrichment(std::span<const double> x, std::span<const std::int32_t> cells,
                                    const CrackGeometry3D& g, std::int32_t ic, const EnrichmentOptions& options,
                                    EnrichmentLayout& layout)
    : x_(x), cells_(cells), g_(g), options_(options)
{
  const std::size_t num_cells = cells.size() / 4;
  const auto num_nodes = static_cast<std::int32_t>(x.size() / 3);
  if (g.psi.size() != static_cast<std::size_t>(num_nodes))
    throw std::invalid_argument("create_enrichment_layout: crack " + std::to_string(ic) + " has psi on "
                                + std::to_string(g.psi.size()) + " nodes, the mesh "
                                + std::to_string(num_nodes));
  const auto first_piece = static_cast<std::int32_t>(layout.tip_crack.size());
  const auto pieces = g.front.num_pieces();
  if (g.front.num_segments() > 0)
    locator_ = std::make_unique<FrontLocator>(g.front);
  for (std::int32_t k = 0; k < pieces; ++k)
  {
    layout.tip_crack.push_back(ic);
    layout.tip_local.push_back(k);
    tips_.push_back(first_piece + k);
  }
  core_tip_.assign(num_nodes, -1);
  if (options.tip != TipEnrichment::none and locator_)
  {
    // Within the radius of the front: |phi| and |psi| bound the distance
    // from below, so only nodes with both below the radius are projected.
    for (std::int32_t i = 0; i < num_nodes; ++i)
      if (std::abs(g.phi[i]) <= options.radius and std::abs(g.psi[i]) <= options.radius)
      {
        const FrontProjection p = locator_->project({x[3 * i], x[3 * i + 1], x[3 * i + 2]});
        if (p.distance <= options.radius)
          core_tip_[i] = first_piece + p.piece;
      }
    // The nodes of the cells holding the front, and of the extension
    // cells that share a node with the crack's cells: a Heaviside
    // function may not live on an extension cell unless the ramp is 1
    // there (every node core), and a node of such a cell that also
    // belongs to a cut cell needs its Heaviside function there (the 1 - R
    // share of the jump). In 2D the tip cell's closure plays this part;
    // in 3D the extension cells along the front are many, and a coarse
    // mesh (element size near the radius) put core nodes of cut blending
    // cells on extension cells with non-core nodes: the jump lost up to
    // 35 % there.
    std::vector<std::int8_t> on_crack_cell(num_nodes, 0);
    for (std::size_t c = 0; c < num_cells; ++c)
      if (g.cell_class[c] == 1 or g.cell_class[c] == 2)
        for (int a = 0; a < 4; ++a)
          on_crack_cell[cells[4 * c + a]] = 1;
    for (std::size_t c = 0; c < num_cells; ++c)
    {
      const std::int32_t* v = &cells[4 * c];
      bool core_cell = g.cell_class[c] == 3;
      if (g.cell_class[c] == 4)
        for (int a = 0; a < 4; ++a)
          core_cell = core_cell or on_crack_cell[v[a]];
      if (core_cell)
        for (int a = 0; a < 4; ++a)
          if (core_tip_[v[a]] < 0)
            core_tip_[v[a]] = first_piece + locator_->project({x[3 * v[a]], x[3 * v[a] + 1], x[3 * v[a] + 2]}).piece;
    }
  }
  auto plane_distance = [this](std::int32_t i, std::int32_t) { return std::abs(g_.phi[i]); };
  input_ = SelectionInput{cells, 4, g.cell_class, g.phi, core_tip_, tips_, plane_distance};
  // A cut cell opens a node's Heaviside function if it has volume on the
  // side opposite the node (slivers are dropped by the cutting).
  input_.opens = [this](std::int32_t c, std::int32_t node)
  {
    const std::int32_t i = g_.crack_cell_index[c];
    if (i < 0)
      return false;
    const CrackCell3D& cc = g_.crack_cells[i];
    const int other = g_.phi[node] >= 0.0 ? -1 : 1;
    double vol = 0.0;
    for (int k = 0; k < cc.num_sub(); ++k)
      if (cc.side[k] == other)
        vol += sub_volume(&cc.sub[12 * k]);
    return vol > OPENING_VOLUME / 6.0;
  };
  // With corrected blending a node's Heaviside function N_i (H - H_i)
  // (1 - R) opens where its crossed cells (cut cells, and the face cells
  // whose crack face holds the node: the cells the selection opens it on)
  // lie on the other side of the crack and the ramp R is not 1. Where the core nodes around it make (1 - R)
  // vanish, the ramped front functions carry the jump and nothing is left
  // of it (kept, it made the system singular: pivots of 1e-16 on a penny
  // crack). It is dropped when both its share of the jump on the lips,
  // max N_i (1 - R) over its cells' lip facets, is below JUMP_SHARE and
  // int N_i^2 (1 - R)^2 over the other side (sub-tetrahedron midpoints)
  // is below RAMPED_SHARE of int N_i^2 over its crossed cells. The first
  // keeps the functions of nodes whose cells the crack only grazes (other
  // side 1e-6 of the cell; volume alone dropped them, and the jump lost
  // their N_i there: 1.4 % dips of a penny's opening in the middle of the
  // crack); the second those that still carry the field beside the lips.
  // Without front functions R = 0 and nothing is dropped: the Heaviside
  // functions keep their partition of unity. Face cells count as cut cells
  // do (the node on the face: the cell beyond it is its other side, the
  // face its lip facet): measured on cut cells only, a crack on a node
  // layer kept no Heaviside function at all (hard case 3D-3: 0 enriched
  // dofs, energy error 1.10 -> 1.02 from n = 4 to 8, not converging).
  input_.keep_heaviside = [this](std::int32_t node, std::span<const std::int8_t> is_core)
  {
    if (!options_.corrected or options_.tip == TipEnrichment::none)
      return true;
    if (bare_.empty())
      measure_shares(is_core);
    return jump_share_[node] > JUMP_SHARE or ramped_[node] > RAMPED_SHARE * bare_[node];
  };
}

void CrackEnrichment<3>::measure_shares(std::span<const std::int8_t> is_core)
{
  const std::size_t num_nodes = g_.phi.size();
  bare_.assign(num_nodes, 0.0), ramped_.assign(num_nodes, 0.0), jump_share_.assign(num_nodes, 0.0);
  for (const CrackCell3D& cc : g_.crack_cells)
  {
    // Cut and face cells: those a Heaviside function opens on (front cells'
    // nodes are all core, extension cells forbid it).
    if (cc.cls != CellClass3D::cut and cc.cls != CellClass3D::face)
      continue;
    const std::int32_t* v = &cells_[4 * cc.cell];
    auto ramp_at = [&](const std::array<double, 4>& N)
    {
      double ramp = 0.0;
      for (int b = 0; b < 4; ++b)
        ramp += is_core[v[b]] ? N[b] : 0.0;
      return ramp;
    };
    for (int k = 0; k < cc.num_sub(); ++k)
    {
      const double* R = &cc.sub[12 * k];
      const double vol = sub_volume(R);
      const Point3 mid = {0.25 * (R[0] + R[3] + R[6] + R[9]), 0.25 * (R[1] + R[4] + R[7] + R[10]),
                          0.25 * (R[2] + R[5] + R[8] + R[11])};
      const auto N = P1Tetrahedron::shape(mid);
      const double ramp = ramp_at(N);
      for (int a = 0; a < 4; ++a)
      {
        bare_[v[a]] += vol * N[a] * N[a];
        if (cc.side[k] == (g_.phi[v[a]] >= 0.0 ? -1 : 1))
          ramped_[v[a]] += vol * N[a] * N[a] * (1.0 - ramp) * (1.0 - ramp);
      }
    }
    // N_i (1 - R) is quadratic on a facet: sampled at its vertices, edge
    // midpoints and centroid.
    static constexpr double samples[7][3]
        = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}, {1. / 3, 1. / 3, 1. / 3}};
    for (int f = 0; f < cc.num_facets(); ++f)
    {
      const double* T = &cc.facets[9 * f];
      for (const auto& b : samples)
      {
        const Point3 r = {b[0] * T[0] + b[1] * T[3] + b[2] * T[6], b[0] * T[1] + b[1] * T[4] + b[2] * T[7],
                          b[0] * T[2] + b[1] * T[5] + b[2] * T[8]};
        const auto N = P1Tetrahedron::shape(r);
        const double open = 1.0 - ramp_at(N);
        for (int a = 0; a < 4; ++a)
          jump_share_[v[a]] = std::max(jump_share_[v[a]], N[a] * open);
      }
    }
  }
}

void CrackEnrichment<3>::shift(const PseudoNode& pn, int side, std::span<double> out) const
{
  // The functions at the node: local coordinates from its level sets,
  // directions from its own frame (what interpolation gives there).
  const std::int32_t i = pn.node;
  const std::array<double, 9> f = node_frame(*locator_, x_, i);
  LocalCoordinates lc{};
  lc.x1 = g_.psi[i];
  lc.x2 = g_.phi[i];
  for (int k = 0; k < 3; ++k)
    lc.e[k] = {f[3 * k], f[3 * k + 1], f[3 * k + 2]};
  if (pn.kind == EnrichmentKind::tip_scalar)
  {
    std::array<double, 4> F;
    std::array<Point3, 4> dF;
    front_branch_functions(lc, side, F, dF);
    out[0] = F[pn.function];
    return;
  }
  std::array<Point3, 3> U;
  std::array<std::array<Point3, 3>, 3> dU;
  front_vector_functions(lc, side, options_.kappa, U, dU);
  for (int m = 0; m < 3; ++m)
    for (int d = 0; d < 3; ++d)
      out[3 * m + d] = U[m][d];
}

void CrackEnrichment<3>::complete(EnrichmentLayout& layout, std::span<const double> x,
                                  std::span<const std::int32_t> cells, std::span<const CrackGeometry3D* const> cracks)
{
  // Frames at every node of every cell carrying front functions, per crack.
  std::vector<std::pair<std::int32_t, std::int32_t>> need; // (node, crack)
  for (std::size_t ie = 0; ie < layout.cells.size(); ++ie)
  {
    const std::int32_t c = layout.cells[ie];
    for (std::int32_t j = layout.cell_offsets[ie]; j < layout.cell_offsets[ie + 1]; ++j)
    {
      const std::int32_t k = layout.cell_enr[j];
      if (layout.kind[k] != static_cast<std::int8_t>(EnrichmentKind::heaviside))
        for (int a = 0; a < 4; ++a)
          need.push_back({cells[4 * c + a], layout.crack[k]});
    }
  }
  std::sort(need.begin(), need.end());
  need.erase(std::unique(need.begin(), need.end()), need.end());
  std::vector<std::unique_ptr<FrontLocator>> locators(cracks.size());
  for (const auto& [v, ic] : need)
  {
    if (!locators[ic])
      locators[ic] = std::make_unique<FrontLocator>(cracks[ic]->front);
    const std::array<double, 9> f = node_frame(*locators[ic], x, v);
    layout.frame_node.push_back(v);
    layout.frame_crack.push_back(ic);
    layout.node_frames.insert(layout.node_frames.end(), f.begin(), f.end());
  }
}

} // namespace cracklip
