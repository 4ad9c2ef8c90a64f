// The 2D geometry's part of the enrichment layout: tips of a curve
// (crack_enrichment.h).
#include "enrichment/crack_enrichment.h"

#include <cmath>

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

CrackEnrichment<2>::CrackEnrichment(std::span<const double> x, std::span<const std::int32_t> cells,
                                    const CrackGeometry& g, std::int32_t ic, const EnrichmentOptions& options,
                                    EnrichmentLayout& layout)
    : x_(x), layout_(layout)
{
  const std::size_t num_cells = cells.size() / 3;
  const auto num_nodes = static_cast<std::int32_t>(x.size() / 2);
  // Core tip nodes: within the radius of a tip, and the nodes of the cells
  // whose closure holds it (a later tip wins a node).
  core_tip_.assign(num_nodes, -1);
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
      layout.tip_crack.push_back(ic);
      layout.tip_local.push_back(j);
      tips_.push_back(tid);
      for (std::int32_t i = 0; i < num_nodes; ++i)
        if (std::hypot(x[2 * i] - frame.tip[0], x[2 * i + 1] - frame.tip[1]) <= options.radius)
          core_tip_[i] = tid;
      for (std::size_t c = 0; c < num_cells; ++c)
        if (in_closure(x, &cells[3 * c], frame.tip))
          for (int a = 0; a < 3; ++a)
            core_tip_[cells[3 * c + a]] = tid;
    }
  }
  // The distance of a node to the crack line at a tip.
  auto line_distance = [this](std::int32_t i, std::int32_t t)
  {
    const TipFrame& f = layout_.tip_frames[t];
    return std::abs(-f.e1[1] * (x_[2 * i] - f.tip[0]) + f.e1[0] * (x_[2 * i + 1] - f.tip[1]));
  };
  input_ = SelectionInput{cells, 3, g.cell_class, g.phi, core_tip_, tips_, line_distance};
}

void CrackEnrichment<2>::shift(const PseudoNode& pn, int side, std::span<double> out) const
{
  const TipFrame& frame = layout_.tip_frames[pn.tip];
  const std::array<double, 2> xi = {x_[2 * pn.node], x_[2 * pn.node + 1]};
  if (pn.kind == EnrichmentKind::tip_scalar)
  {
    std::array<double, 4> F;
    std::array<std::array<double, 2>, 4> dF;
    branch_functions(frame, xi, side, F, dF);
    out[0] = F[pn.function];
    return;
  }
  std::array<std::array<double, 2>, 2> U;
  std::array<std::array<std::array<double, 2>, 2>, 2> dU;
  williams_displacement(frame, xi, side, layout_.kappa, U, dU);
  for (int m = 0; m < 2; ++m)
    for (int d = 0; d < 2; ++d)
      out[2 * m + d] = U[m][d];
}

} // namespace cracklip
