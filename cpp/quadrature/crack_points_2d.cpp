#include "quadrature/crack_points_2d.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cracklip
{

std::array<double, 2> crack_normal(const P1Cell& cell, const CrackGeometry& g)
{
  double gx = 0.0, gy = 0.0;
  for (int a = 0; a < 3; ++a)
    gx += g.phi[cell.nodes[a]] * cell.grad[a][0], gy += g.phi[cell.nodes[a]] * cell.grad[a][1];
  const double n = std::hypot(gx, gy);
  if (!(n > 0.0))
    throw std::runtime_error("crack normal undefined in cell (phi constant)");
  return {gx / n, gy / n};
}

quadrature::Rule segment_rule(const CrackGeometry& g, std::array<double, 2> P, std::array<double, 2> Q, int n)
{
  const double L = std::hypot(Q[0] - P[0], Q[1] - P[1]);
  double rp = 0.0, rq = 0.0, best = -1.0;
  for (std::size_t j = 0; j < g.tips.size() / 2; ++j)
  {
    const double dp = std::hypot(P[0] - g.tips[2 * j], P[1] - g.tips[2 * j + 1]);
    const double dq = std::hypot(Q[0] - g.tips[2 * j], Q[1] - g.tips[2 * j + 1]);
    if (best < 0.0 or std::min(dp, dq) < best)
      best = std::min(dp, dq), rp = dp, rq = dq;
  }
  if (best < 0.0 or best >= L)
    return quadrature::gauss_legendre(n);
  // A tip on an end: exactly 0 there (rounding would leave a near-zero r).
  if (rp <= 1e-12 * L)
    rp = 0.0;
  if (rq <= 1e-12 * L)
    rq = 0.0;
  return quadrature::line_toward_tip(n, rp, rq);
}

CrackPoints compute_crack_points(std::span<const double> x, std::span<const std::int32_t> cells,
                                 const CrackGeometry& g, int n)
{
  if (n < 1)
    throw std::invalid_argument("compute_crack_points: need at least one point per segment");
  CrackPoints out;
  auto add = [&](std::int32_t c, const std::array<double, 4>& seg)
  {
    const P1Cell cell(x, cells, c);
    const std::array<double, 2> P = {seg[0], seg[1]}, Q = {seg[2], seg[3]};
    const auto Pp = cell.physical(P), Qp = cell.physical(Q);
    const double L = std::hypot(Qp[0] - Pp[0], Qp[1] - Pp[1]);
    if (!(L > 0.0))
      return;
    const quadrature::Rule rule = segment_rule(g, Pp, Qp, n);
    const auto normal = crack_normal(cell, g);
    for (int q = 0; q < rule.size(); ++q)
    {
      const double t = rule.points[q];
      const std::array<double, 2> r = {P[0] + t * (Q[0] - P[0]), P[1] + t * (Q[1] - P[1])};
      const auto xp = cell.physical(r);
      out.cell.push_back(c);
      out.ref.insert(out.ref.end(), r.begin(), r.end());
      out.x.insert(out.x.end(), xp.begin(), xp.end());
      out.weight.push_back(rule.weights[q] * L);
      out.normal.insert(out.normal.end(), normal.begin(), normal.end());
    }
  };
  for (const CrackCell& cc : g.crack_cells)
    if (cc.owns_segment)
      add(cc.cell, cc.segment);
  for (const TipCell& tc : g.tip_cells)
    add(tc.cell, tc.segment); // (P, T): the tip is the second end
  return out;
}

} // namespace cracklip
