#include "contact/contact_kernels_3d.h"

#include "enrichment/enriched_basis.h"
#include "geometry/vec3.h"
#include "quadrature/crack_points_3d.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace cracklip
{
using namespace vec3;

namespace
{
/// The coordinate axis least aligned with v (ties within 1e-12 |v|, e.g.
/// round-off in a summed normal: the first).
Point3 least_aligned_axis(const Point3& v)
{
  int k = 0;
  const double tol = 1e-12 * norm(v);
  for (int d = 1; d < 3; ++d)
    if (std::abs(v[d]) < std::abs(v[k]) - tol)
      k = d;
  Point3 e = {0.0, 0.0, 0.0};
  e[k] = 1.0;
  return e;
}

/// Pieces of crack ic by cell.
std::unordered_map<std::int32_t, std::size_t> pieces_by_cell(const MultiplierSpace3D& space, std::int32_t ic)
{
  std::unordered_map<std::int32_t, std::size_t> out;
  for (std::size_t p = 0; p < space.pieces.size(); ++p)
    if (space.pieces[p].crack == ic)
      out[space.pieces[p].cell] = p;
  return out;
}
} // namespace

Point3 default_tangent_reference(const CrackGeometry3D& g)
{
  Point3 m = {0.0, 0.0, 0.0};
  for (const CrackCell3D& cc : g.crack_cells)
    for (int k = 0; k < cc.num_facets(); ++k)
      for (int d = 0; d < 3; ++d)
        m[d] += cc.facet_area[k] * cc.facet_normal[3 * k + d];
  return least_aligned_axis(m);
}

void tangent_basis(const Point3& n, const Point3& a, Point3& t1, Point3& t2)
{
  Point3 t = axpy(a, -dot(a, n), n);
  if (!(norm(t) > 1e-3 * norm(a)))
  {
    const Point3 e = least_aligned_axis(n);
    t = axpy(e, -dot(e, n), n);
  }
  t1 = unit(t);
  t2 = cross(n, t1);
}

ContactPoints3D compute_contact_points_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                                          std::span<const CrackGeometry3D* const> cracks,
                                          const MultiplierSpace3D& space, const LipRule3D& rule,
                                          std::span<const double> tangent_reference)
{
  if (!tangent_reference.empty() and tangent_reference.size() != 3 * cracks.size())
    throw std::invalid_argument("compute_contact_points_3d: expected one tangent reference (3 values) per crack, got "
                                + std::to_string(tangent_reference.size()) + " values for "
                                + std::to_string(cracks.size()) + " cracks");
  ContactPoints3D out;
  for (std::size_t icr = 0; icr < cracks.size(); ++icr)
  {
    const auto ic = static_cast<std::int32_t>(icr);
    const auto piece_of = pieces_by_cell(space, ic);
    if (piece_of.empty())
      continue;
    Point3 a;
    if (tangent_reference.empty())
      a = default_tangent_reference(*cracks[icr]);
    else
    {
      a = {tangent_reference[3 * icr], tangent_reference[3 * icr + 1], tangent_reference[3 * icr + 2]};
      if (!(norm(a) > 0.0) or !std::isfinite(norm(a)))
        throw std::invalid_argument("compute_contact_points_3d: the tangent reference of crack " + std::to_string(ic)
                                    + " must be a finite non-zero vector");
    }
    const LipPoints3D lp = compute_lip_points_3d(x, cells, *cracks[icr], rule.n, rule.near_factor, rule.signed_point_rule);
    for (std::size_t q = 0; q < lp.weight.size(); ++q)
    {
      const auto it = piece_of.find(lp.cell[q]);
      if (it == piece_of.end())
        continue;
      const LipPiece3D& piece = space.pieces[it->second];
      const auto ip = static_cast<std::int32_t>(out.weight.size());
      const Point3 r = {lp.ref[3 * q], lp.ref[3 * q + 1], lp.ref[3 * q + 2]};
      const Point3 n = {lp.normal[3 * q], lp.normal[3 * q + 1], lp.normal[3 * q + 2]};
      Point3 t1, t2;
      tangent_basis(n, a, t1, t2);
      out.piece.push_back(static_cast<std::int32_t>(it->second));
      out.cell.push_back(lp.cell[q]);
      out.ref.insert(out.ref.end(), r.begin(), r.end());
      out.x.insert(out.x.end(), lp.x.begin() + 3 * q, lp.x.begin() + 3 * q + 3);
      out.weight.push_back(lp.weight[q]);
      out.normal.insert(out.normal.end(), n.begin(), n.end());
      out.t1.insert(out.t1.end(), t1.begin(), t1.end());
      out.t2.insert(out.t2.end(), t2.begin(), t2.end());
      const auto N = P1Tetrahedron::shape(r);
      for (std::size_t k = 0; k < piece.mult.size(); ++k)
      {
        const double v = piece.local[k] >= 0 ? N[piece.local[k]] : 1.0;
        if (v == 0.0)
          continue;
        out.entry_point.push_back(ip);
        out.entry_mult.push_back(piece.mult[k]);
        out.entry_value.push_back(v);
      }
    }
  }
  return out;
}

void assemble_coupling_3d(std::span<const double> x, std::span<const std::int32_t> cells,
                          const EnrichmentLayout& layout, std::span<const CrackGeometry3D* const> cracks,
                          const MultiplierSpace3D& space, const LipRule3D& rule, const ContactSinks3D& sinks,
                          std::span<const double> tangent_reference)
{
  if (!sinks.normal or !sinks.mass)
    throw std::invalid_argument("assemble_coupling_3d: the normal and mass sinks are required");
  const bool tangential = static_cast<bool>(sinks.tangent1) and static_cast<bool>(sinks.tangent2);
  const ContactPoints3D cp = compute_contact_points_3d(x, cells, cracks, space, rule, tangent_reference);
  std::vector<double> vp, vm, grad, bn, bt1, bt2, mass, psi;
  std::vector<std::int32_t> rows, cols;
  std::vector<int> side;
  // The points of one cell and one set of multipliers (a lip piece's
  // quadrature points come one after the other) are summed into one block
  // before it goes to the sinks: a hundredth of the triplets (a / h = 8:
  // B's 5.2e6 -> 5.3e4), which the caller's sparse matrices would otherwise
  // sort and sum (2e5 dofs: 4.5e7 triplets for B, M, Bt1, Bt2, set-up 6-8 s
  // -> 1.3 s).
  std::int32_t block_cell = -1;
  auto flush = [&]()
  {
    if (block_cell < 0)
      return;
    sinks.normal(rows, cols, bn);
    if (tangential)
    {
      sinks.tangent1(rows, cols, bt1);
      sinks.tangent2(rows, cols, bt2);
    }
    sinks.mass(rows, rows, mass);
    block_cell = -1;
  };
  std::size_t e = 0;
  for (std::size_t p = 0; p < cp.weight.size(); ++p)
  {
    const std::size_t e0 = e;
    while (e < cp.entry_point.size() and cp.entry_point[e] == static_cast<std::int32_t>(p))
      ++e;
    if (e == e0)
      continue;
    const std::int32_t c = cp.cell[p];
    const LipPiece3D& piece = space.pieces[cp.piece[p]];
    const P1Tetrahedron cell(x, cells, c);
    const EnrichedCellBasis<3> basis(cell, layout, c);
    const int nd = basis.num_dofs();
    if (nd <= 12)
      continue; // no enriched dof: nothing jumps
    const Point3 r = {cp.ref[3 * p], cp.ref[3 * p + 1], cp.ref[3 * p + 2]};
    region_sides(cracks, c, 1, side);
    side[piece.crack] = 1;
    evaluate_basis<3>(cell, basis, layout, cracks, side, r, vp, grad);
    side[piece.crack] = -1;
    evaluate_basis<3>(cell, basis, layout, cracks, side, r, vm, grad);
    const double w = cp.weight[p];
    const double* n = &cp.normal[3 * p];
    const double* t1 = &cp.t1[3 * p];
    const double* t2 = &cp.t2[3 * p];
    psi.assign(cp.entry_value.begin() + e0, cp.entry_value.begin() + e);
    if (block_cell != c or !std::equal(rows.begin(), rows.end(), cp.entry_mult.begin() + e0, cp.entry_mult.begin() + e))
    {
      flush();
      block_cell = c;
      rows.assign(cp.entry_mult.begin() + e0, cp.entry_mult.begin() + e);
      cols.assign(basis.dofs.begin() + 12, basis.dofs.end());
      bn.assign(rows.size() * cols.size(), 0.0);
      if (tangential)
        bt1.assign(rows.size() * cols.size(), 0.0), bt2.assign(rows.size() * cols.size(), 0.0);
      mass.assign(rows.size() * rows.size(), 0.0);
    }
    const std::size_t nr = rows.size(), nc = cols.size();
    for (std::size_t j = 0; j < nc; ++j)
    {
      const std::size_t i = j + 12;
      const double jump[3] = {vp[3 * i] - vm[3 * i], vp[3 * i + 1] - vm[3 * i + 1], vp[3 * i + 2] - vm[3 * i + 2]};
      const double jn = jump[0] * n[0] + jump[1] * n[1] + jump[2] * n[2];
      const double j1 = jump[0] * t1[0] + jump[1] * t1[1] + jump[2] * t1[2];
      const double j2 = jump[0] * t2[0] + jump[1] * t2[1] + jump[2] * t2[2];
      for (std::size_t k = 0; k < nr; ++k)
      {
        bn[k * nc + j] += psi[k] * w * jn;
        if (tangential)
          bt1[k * nc + j] += psi[k] * w * j1, bt2[k * nc + j] += psi[k] * w * j2;
      }
    }
    for (std::size_t k = 0; k < nr; ++k)
      for (std::size_t l = 0; l < nr; ++l)
        mass[k * nr + l] += psi[k] * psi[l] * w;
  }
  flush();
}

std::vector<double> evaluate_multipliers_3d(const MultiplierSpace3D& space, std::int32_t crack,
                                            std::span<const std::int32_t> point_cells, std::span<const double> ref,
                                            std::span<const double> lambda_full)
{
  const std::size_t n = point_cells.size();
  if (ref.size() != 3 * n)
    throw std::invalid_argument("evaluate_multipliers_3d: expected ref (n, 3)");
  if (lambda_full.size() != static_cast<std::size_t>(space.num_full()))
    throw std::invalid_argument("evaluate_multipliers_3d: lambda_full has " + std::to_string(lambda_full.size())
                                + " values for " + std::to_string(space.num_full()) + " full multipliers");
  const auto piece_of = pieces_by_cell(space, crack);
  std::vector<double> out(n, 0.0);
  for (std::size_t p = 0; p < n; ++p)
  {
    const auto it = piece_of.find(point_cells[p]);
    if (it == piece_of.end())
      continue;
    const LipPiece3D& piece = space.pieces[it->second];
    const auto N = P1Tetrahedron::shape({ref[3 * p], ref[3 * p + 1], ref[3 * p + 2]});
    for (std::size_t k = 0; k < piece.mult.size(); ++k)
      out[p] += (piece.local[k] >= 0 ? N[piece.local[k]] : 1.0) * lambda_full[piece.mult[k]];
  }
  return out;
}

} // namespace cracklip
