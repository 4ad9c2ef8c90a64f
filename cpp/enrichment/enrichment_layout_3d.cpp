#include "enrichment/enrichment_layout_3d.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace cracklip
{
namespace
{
double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

void normalize(double* v)
{
  const double n = std::sqrt(dot3(v, v));
  if (n > 0.0)
    v[0] /= n, v[1] /= n, v[2] /= n;
}

/// Orthonormal frame from an interpolated one: e2 normalised, e1 made
/// orthogonal to it, e3 = e1 x e2.
std::array<double, 9> orthonormal(const std::array<double, 9>& f)
{
  std::array<double, 9> o = f;
  double* e1 = &o[0];
  double* e2 = &o[3];
  double* e3 = &o[6];
  normalize(e2);
  const double d = dot3(e1, e2);
  for (int i = 0; i < 3; ++i)
    e1[i] -= d * e2[i];
  normalize(e1);
  e3[0] = e1[1] * e2[2] - e1[2] * e2[1];
  e3[1] = e1[2] * e2[0] - e1[0] * e2[2];
  e3[2] = e1[0] * e2[1] - e1[1] * e2[0];
  return o;
}
} // namespace

const double* EnrichmentLayout3D::frame(std::int32_t n, std::int32_t ic) const
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

FrontProjection project_on_front(const CrackFields3D& crack, const Point3& x)
{
  FrontProjection best;
  best.distance = std::numeric_limits<double>::max();
  const std::size_t pieces = crack.front_closed.size();
  for (std::size_t k = 0; k < pieces; ++k)
  {
    const std::int32_t a = crack.front_offsets[k], b = crack.front_offsets[k + 1];
    const std::int32_t n = b - a;
    if (n <= 0)
      continue;
    const std::int32_t segments = crack.front_closed[k] ? n : n - 1;
    auto consider = [&](std::int32_t i, std::int32_t j)
    {
      const double* p = &crack.front_points[3 * i];
      const double* q = &crack.front_points[3 * j];
      const double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
      const double w[3] = {x[0] - p[0], x[1] - p[1], x[2] - p[2]};
      const double dd = dot3(d, d);
      const double t = dd > 0.0 ? std::clamp(dot3(w, d) / dd, 0.0, 1.0) : 0.0;
      const double c[3] = {p[0] + t * d[0], p[1] + t * d[1], p[2] + t * d[2]};
      const double dist = std::sqrt((x[0] - c[0]) * (x[0] - c[0]) + (x[1] - c[1]) * (x[1] - c[1])
                                    + (x[2] - c[2]) * (x[2] - c[2]));
      if (dist < best.distance)
      {
        best.distance = dist;
        best.point = {c[0], c[1], c[2]};
        best.piece = static_cast<std::int32_t>(k);
        std::array<double, 9> f;
        for (int m = 0; m < 9; ++m)
          f[m] = (1.0 - t) * crack.front_frames[9 * i + m] + t * crack.front_frames[9 * j + m];
        best.frame = f;
      }
    };
    if (n == 1)
      consider(a, a);
    for (std::int32_t s = 0; s < segments; ++s)
      consider(a + s, a + (s + 1) % n);
  }
  if (best.piece < 0)
    throw std::invalid_argument("project_on_front: the crack has no front point");
  best.frame = orthonormal(best.frame);
  return best;
}

EnrichmentLayout3D create_enrichment_layout_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                               std::span<const CrackFields3D> cracks,
                                               const EnrichmentOptions3D& options)
{
  const std::size_t num_cells = cells.size() / 4;
  const auto num_nodes = static_cast<std::int32_t>(x.size() / 3);
  if (options.front != TipEnrichment::none and !(options.radius >= 0.0))
    throw std::invalid_argument("front enrichment radius must be >= 0 (0: the front cells' nodes only), got "
                                + std::to_string(options.radius));
  EnrichmentLayout3D layout;
  layout.num_std_nodes = num_nodes;
  layout.kappa = options.kappa;
  layout.corrected = options.corrected;

  std::vector<std::int32_t> crossed_by(num_cells, -1);
  for (std::size_t ic = 0; ic < cracks.size(); ++ic)
  {
    const CrackFields3D& g = cracks[ic];
    if (g.cell_class.size() != num_cells or g.phi.size() != static_cast<std::size_t>(num_nodes)
        or g.psi.size() != static_cast<std::size_t>(num_nodes))
      throw std::invalid_argument("create_enrichment_layout_3d: crack " + std::to_string(ic) + " has level sets on "
                                  + std::to_string(g.phi.size()) + " nodes and classes of "
                                  + std::to_string(g.cell_class.size()) + " cells, the mesh "
                                  + std::to_string(num_nodes) + " and " + std::to_string(num_cells));
    for (std::size_t c = 0; c < num_cells; ++c)
    {
      const std::int8_t cls = g.cell_class[c];
      if (cls == 0 or cls == 4)
        continue;
      if (crossed_by[c] >= 0)
        throw std::runtime_error("cell " + std::to_string(c) + " is crossed by cracks " + std::to_string(crossed_by[c])
                                 + " and " + std::to_string(ic) + ": cracks closer than the mesh size are not "
                                   "supported; refine the mesh near them");
      crossed_by[c] = static_cast<std::int32_t>(ic);
    }
  }

  std::vector<std::vector<std::int32_t>> node_pseudo(num_nodes);
  for (std::size_t icr = 0; icr < cracks.size(); ++icr)
  {
    const CrackFields3D& g = cracks[icr];
    const auto ic = static_cast<std::int32_t>(icr);
    const auto first_piece = static_cast<std::int32_t>(layout.piece_crack.size());
    const auto pieces = static_cast<std::int32_t>(g.front_closed.size());
    std::vector<std::int32_t> tips;
    for (std::int32_t k = 0; k < pieces; ++k)
    {
      layout.piece_crack.push_back(ic);
      layout.piece_local.push_back(k);
      tips.push_back(first_piece + k);
    }
    std::vector<std::int32_t> core_tip(num_nodes, -1);
    if (options.front != TipEnrichment::none and pieces > 0)
    {
      // Within the radius of the front: |phi| and |psi| bound the distance
      // from below, so only nodes with both below the radius are projected.
      for (std::int32_t i = 0; i < num_nodes; ++i)
        if (std::abs(g.phi[i]) <= options.radius and std::abs(g.psi[i]) <= options.radius)
        {
          const FrontProjection p = project_on_front(g, {x[3 * i], x[3 * i + 1], x[3 * i + 2]});
          if (p.distance <= options.radius)
            core_tip[i] = first_piece + p.piece;
        }
      // The nodes of the cells holding the front.
      for (std::size_t c = 0; c < num_cells; ++c)
        if (g.cell_class[c] == 3)
          for (int a = 0; a < 4; ++a)
          {
            const std::int32_t v = cells[4 * c + a];
            if (core_tip[v] < 0)
              core_tip[v] = first_piece
                            + project_on_front(g, {x[3 * v], x[3 * v + 1], x[3 * v + 2]}).piece;
          }
    }
    auto plane_distance = [&](std::int32_t i, std::int32_t) { return std::abs(g.phi[i]); };
    const SelectionInput input{cells, 4, g.cell_class, g.phi, core_tip, tips, plane_distance};
    for (const PseudoNode& pn : select_enrichment(input, options.front, options.corrected, layout.num_enriched(),
                                                  node_pseudo))
    {
      const std::int32_t i = pn.node;
      const int side = g.phi[i] >= 0.0 ? 1 : -1;
      layout.node.push_back(i);
      layout.crack.push_back(ic);
      layout.kind.push_back(static_cast<std::int8_t>(pn.kind));
      layout.function.push_back(pn.function);
      layout.piece.push_back(pn.tip);
      layout.node_side.push_back(static_cast<std::int8_t>(side));
      layout.core.push_back(pn.core ? 1 : 0);
      std::array<double, 9> sh{};
      if (pn.kind == EnrichmentKind::heaviside)
        sh[0] = side;
      else
      {
        // The functions at the node: local coordinates from its level sets,
        // directions from its own frame (what interpolation gives there).
        const FrontProjection p = project_on_front(g, {x[3 * i], x[3 * i + 1], x[3 * i + 2]});
        LocalCoordinates lc{};
        lc.x1 = g.psi[i];
        lc.x2 = g.phi[i];
        for (int k = 0; k < 3; ++k)
          lc.e[k] = {p.frame[3 * k], p.frame[3 * k + 1], p.frame[3 * k + 2]};
        if (pn.kind == EnrichmentKind::tip_scalar)
        {
          std::array<double, 4> F;
          std::array<Point3, 4> dF;
          front_branch_functions(lc, side, F, dF);
          sh[0] = F[pn.function];
        }
        else
        {
          std::array<Point3, 3> U;
          std::array<std::array<Point3, 3>, 3> dU;
          front_vector_functions(lc, side, options.kappa, U, dU);
          for (int m = 0; m < 3; ++m)
            for (int d = 0; d < 3; ++d)
              sh[3 * m + d] = U[m][d];
        }
      }
      layout.shift.insert(layout.shift.end(), sh.begin(), sh.end());
    }
  }
  static_cast<EnrichedCells&>(layout) = create_enriched_cells(cells, 4, node_pseudo);

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
  for (const auto& [v, ic] : need)
  {
    const FrontProjection p = project_on_front(cracks[ic], {x[3 * v], x[3 * v + 1], x[3 * v + 2]});
    layout.frame_node.push_back(v);
    layout.frame_crack.push_back(ic);
    layout.node_frames.insert(layout.node_frames.end(), p.frame.begin(), p.frame.end());
  }
  return layout;
}

} // namespace cracklip
