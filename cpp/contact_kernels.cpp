#include "contact_kernels.h"

#include "enriched_basis.h"
#include "quadrature.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace cracklip
{
namespace
{
/// Unit normal of the crack in cell c pointing to phi > 0.
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
} // namespace

SegmentPoints compute_segment_points(std::span<const double> x, std::span<const std::int32_t> cells,
                                     std::span<const CrackGeometry* const> cracks,
                                     const MultiplierSpace& space, int n)
{
  const quadrature::Rule g = quadrature::gauss_legendre(n);
  SegmentPoints out;
  for (std::size_t s = 0; s < space.segments.size(); ++s)
  {
    const CrackSegment& seg = space.segments[s];
    const CrackGeometry& geo = *cracks[seg.crack];
    const P1Cell cell(x, cells, seg.cell);
    const std::array<double, 2> P = {seg.ref[0], seg.ref[1]}, Q = {seg.ref[2], seg.ref[3]};
    const auto Pp = cell.physical(P), Qp = cell.physical(Q);
    const double L = std::hypot(Qp[0] - Pp[0], Qp[1] - Pp[1]);
    // Which end (if any) is a crack tip of this crack.
    int tip_end = seg.tip ? seg.tip_end : -1;
    for (std::size_t j = 0; tip_end < 0 and j < geo.tips.size() / 2; ++j)
    {
      if (std::hypot(Pp[0] - geo.tips[2 * j], Pp[1] - geo.tips[2 * j + 1]) <= 1e-12 * L)
        tip_end = 0;
      else if (std::hypot(Qp[0] - geo.tips[2 * j], Qp[1] - geo.tips[2 * j + 1]) <= 1e-12 * L)
        tip_end = 1;
    }
    const auto normal = crack_normal(cell, geo);
    for (int q = 0; q < g.size(); ++q)
    {
      double t = g.points[q], w = g.weights[q];
      if (tip_end >= 0)
      {
        // tau^2 from the tip end: t_tip = tau^2, dt = 2 tau dtau.
        const double tau = g.points[q];
        const double from_tip = tau * tau;
        w = g.weights[q] * 2.0 * tau;
        t = tip_end == 0 ? from_tip : 1.0 - from_tip;
      }
      const std::array<double, 2> r = {P[0] + t * (Q[0] - P[0]), P[1] + t * (Q[1] - P[1])};
      const auto xp = cell.physical(r);
      const auto ip = static_cast<std::int32_t>(out.weight.size());
      out.segment.push_back(static_cast<std::int32_t>(s));
      out.cell.push_back(seg.cell);
      out.ref.insert(out.ref.end(), r.begin(), r.end());
      out.x.insert(out.x.end(), xp.begin(), xp.end());
      out.weight.push_back(w * L);
      out.normal.insert(out.normal.end(), normal.begin(), normal.end());
      const auto N = P1Cell::shape(r);
      for (std::size_t k = 0; k < seg.mult.size(); ++k)
      {
        const double v = seg.local[k] >= 0 ? N[seg.local[k]] : 1.0;
        if (v == 0.0)
          continue;
        out.entry_point.push_back(ip);
        out.entry_mult.push_back(seg.mult[k]);
        out.entry_value.push_back(v);
      }
    }
  }
  return out;
}

void assemble_coupling(std::span<const double> x, std::span<const std::int32_t> cells,
                       const EnrichmentLayout& layout, std::span<const CrackGeometry* const> cracks,
                       const MultiplierSpace& space, int n, Triplets& B, Triplets& M)
{
  const SegmentPoints sp = compute_segment_points(x, cells, cracks, space, n);
  std::vector<double> vp, vm, grad;
  std::vector<int> side;
  std::size_t e = 0;
  const std::size_t npts = sp.weight.size();
  for (std::size_t p = 0; p < npts; ++p)
  {
    const std::size_t e0 = e;
    while (e < sp.entry_point.size() and sp.entry_point[e] == static_cast<std::int32_t>(p))
      ++e;
    const std::int32_t c = sp.cell[p];
    const CrackSegment& seg = space.segments[sp.segment[p]];
    const P1Cell cell(x, cells, c);
    const CellBasis basis(cell, layout, c);
    const std::array<double, 2> r = {sp.ref[2 * p], sp.ref[2 * p + 1]};
    region_sides(cracks, c, 1, side);
    side[seg.crack] = 1;
    evaluate_basis(cell, basis, layout, side, r, vp, grad);
    side[seg.crack] = -1;
    evaluate_basis(cell, basis, layout, side, r, vm, grad);
    const double nx = sp.normal[2 * p], ny = sp.normal[2 * p + 1];
    const double w = sp.weight[p];
    for (std::size_t k = e0; k < e; ++k)
    {
      const double psi = sp.entry_value[k] * w;
      for (int j = 0; j < basis.num_dofs(); ++j)
      {
        const double jump = (vp[2 * j] - vm[2 * j]) * nx + (vp[2 * j + 1] - vm[2 * j + 1]) * ny;
        if (std::abs(jump) < 1e-300)
          continue;
        B.row.push_back(sp.entry_mult[k]);
        B.col.push_back(basis.dofs[j]);
        B.value.push_back(psi * jump);
      }
      for (std::size_t l = e0; l < e; ++l)
      {
        M.row.push_back(sp.entry_mult[k]);
        M.col.push_back(sp.entry_mult[l]);
        M.value.push_back(psi * sp.entry_value[l]);
      }
    }
  }
}

std::array<double, 2> lip_interaction_integral(std::span<const double> x,
                                               std::span<const std::int32_t> cells,
                                               std::span<const CrackGeometry* const> cracks,
                                               const MultiplierSpace& space,
                                               std::span<const double> lambda_full,
                                               const TipFrame& tip, std::int32_t crack, double radius,
                                               double E, double nu, int n)
{
  if (lambda_full.size() != static_cast<std::size_t>(space.num_full()))
    throw std::invalid_argument("lip_interaction_integral: lambda_full has the wrong size");
  const SegmentPoints sp = compute_segment_points(x, cells, cracks, space, n);
  const double mu = E / (2.0 * (1.0 + nu));
  const double kappa = 3.0 - 4.0 * nu;
  const double scale = 1.0 / (2.0 * mu * std::sqrt(2.0 * std::numbers::pi));
  std::array<double, 2> I = {0.0, 0.0};
  std::array<std::array<double, 2>, 2> U;
  std::array<std::array<std::array<double, 2>, 2>, 2> dUp, dUm;
  std::vector<double> p_at(sp.weight.size(), 0.0);
  for (std::size_t k = 0; k < sp.entry_point.size(); ++k)
    p_at[sp.entry_point[k]] -= sp.entry_value[k] * lambda_full[sp.entry_mult[k]];
  for (std::size_t p = 0; p < sp.weight.size(); ++p)
  {
    const CrackSegment& seg = space.segments[sp.segment[p]];
    if (seg.crack != crack or p_at[p] == 0.0)
      continue;
    const P1Cell cell(x, cells, sp.cell[p]);
    const auto N = P1Cell::shape({sp.ref[2 * p], sp.ref[2 * p + 1]});
    double q = 0.0;
    for (int a = 0; a < 3; ++a)
      q += N[a] * (std::hypot(cell.xv[a][0] - tip.tip[0], cell.xv[a][1] - tip.tip[1]) < radius ? 1.0 : 0.0);
    if (q == 0.0)
      continue;
    const std::array<double, 2> xp = {sp.x[2 * p], sp.x[2 * p + 1]};
    williams_displacement(tip, xp, 1, kappa, U, dUp);
    williams_displacement(tip, xp, -1, kappa, U, dUm);
    const double nx = sp.normal[2 * p], ny = sp.normal[2 * p + 1];
    for (int m = 0; m < 2; ++m)
    {
      // [[ d u_aux / d x_1 ]] . n, x_1 along e1.
      double jump = 0.0;
      for (int i = 0; i < 2; ++i)
      {
        const double dp = dUp[m][i][0] * tip.e1[0] + dUp[m][i][1] * tip.e1[1];
        const double dm = dUm[m][i][0] * tip.e1[0] + dUm[m][i][1] * tip.e1[1];
        jump += (dp - dm) * (i == 0 ? nx : ny);
      }
      I[m] -= sp.weight[p] * p_at[p] * q * scale * jump;
    }
  }
  return I;
}

} // namespace cracklip
