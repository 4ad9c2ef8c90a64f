#include "contact/contact_kernels_2d.h"

#include "quadrature/crack_points_2d.h"
#include "enrichment/enriched_basis_2d.h"
#include "quadrature/rules.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <unordered_map>

namespace cracklip
{
SegmentPoints compute_segment_points(std::span<const double> x, std::span<const std::int32_t> cells,
                                     std::span<const CrackGeometry* const> cracks,
                                     const MultiplierSpace& space, int n)
{
  SegmentPoints out;
  for (std::size_t s = 0; s < space.segments.size(); ++s)
  {
    const CrackSegment& seg = space.segments[s];
    const CrackGeometry& geo = *cracks[seg.crack];
    const P1Cell cell(x, cells, seg.cell);
    const std::array<double, 2> P = {seg.ref[0], seg.ref[1]}, Q = {seg.ref[2], seg.ref[3]};
    const auto Pp = cell.physical(P), Qp = cell.physical(Q);
    const double L = std::hypot(Qp[0] - Pp[0], Qp[1] - Pp[1]);
    const quadrature::Rule g = segment_rule(geo, Pp, Qp, n);
    const auto normal = crack_normal(cell, geo);
    for (int q = 0; q < g.size(); ++q)
    {
      const double t = g.points[q], w = g.weights[q];
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
                       const MultiplierSpace& space, int n, Triplets& B, Triplets& M,
                       Triplets* Bt)
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
        const double jx = vp[2 * j] - vm[2 * j], jy = vp[2 * j + 1] - vm[2 * j + 1];
        const double jump = jx * nx + jy * ny;
        if (std::abs(jump) >= 1e-300)
        {
          B.row.push_back(sp.entry_mult[k]);
          B.col.push_back(basis.dofs[j]);
          B.value.push_back(psi * jump);
        }
        const double slip = jx * ny - jy * nx; // t = (n_y, -n_x)
        if (Bt and std::abs(slip) >= 1e-300)
        {
          Bt->row.push_back(sp.entry_mult[k]);
          Bt->col.push_back(basis.dofs[j]);
          Bt->value.push_back(psi * slip);
        }
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

std::vector<double> evaluate_multipliers(const MultiplierSpace& space, std::int32_t crack,
                                         std::span<const std::int32_t> point_cells,
                                         std::span<const double> ref,
                                         std::span<const double> lambda_full)
{
  const std::size_t n = point_cells.size();
  if (ref.size() != 2 * n)
    throw std::invalid_argument("evaluate_multipliers: expected ref (n, 2)");
  if (lambda_full.size() != static_cast<std::size_t>(space.num_full()))
    throw std::invalid_argument("evaluate_multipliers: lambda_full has the wrong size");
  std::unordered_map<std::int32_t, std::size_t> segment_of;
  for (std::size_t s = 0; s < space.segments.size(); ++s)
    if (space.segments[s].crack == crack)
      segment_of[space.segments[s].cell] = s;
  std::vector<double> out(n, 0.0);
  for (std::size_t p = 0; p < n; ++p)
  {
    const auto it = segment_of.find(point_cells[p]);
    if (it == segment_of.end())
      continue;
    const CrackSegment& seg = space.segments[it->second];
    const auto N = P1Cell::shape({ref[2 * p], ref[2 * p + 1]});
    for (std::size_t k = 0; k < seg.mult.size(); ++k)
      out[p] += (seg.local[k] >= 0 ? N[seg.local[k]] : 1.0) * lambda_full[seg.mult[k]];
  }
  return out;
}

} // namespace cracklip
