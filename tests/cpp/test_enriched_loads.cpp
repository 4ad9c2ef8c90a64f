// The enriched stiffness and the enriched loads, written once for any
// dimension, against the divergence theorem in 2D and 3D. For a linear
// field u_lin (standard dofs only, stress sigma constant) and a Heaviside
// function phi_j = N_i (H - H_i) e_d of a through crack:
//   (K u_lin)_j = int eps(phi_j) : sigma
//               = - int_crack [[phi_j]] . sigma n        (node i inside the part)
// so K u_lin plus the lip load of the traction sigma n vanishes on the
// Heaviside dofs of interior nodes, and the cell load of the initial stress
// sigma is - K u_lin on every enriched dof (both integrands are polynomial:
// the rules are exact).
#include "assembly/enriched_loads.h"
#include "assembly/enriched_stiffness.h"
#include "fracture/interaction_density.h"
#include "meshes.h"
#include "quadrature/crack_points_2d.h"
#include "quadrature/crack_points_3d.h"

#include <cmath>
#include <gtest/gtest.h>
#include <vector>

using namespace cracklip;

namespace
{
constexpr double E = 3.0, nu = 0.27, crack_at = 0.51;

CrackGeometry through_crack_2d(const std::vector<double>& x, const std::vector<std::int32_t>& cells)
{
  return compute_crack_geometry(x, cells, CrackPath{{-1.0, crack_at, 2.0, 0.48}, {false, false}}, 1e-8);
}

CrackGeometry3D through_crack_3d(const std::vector<double>& x, const std::vector<std::int32_t>& cells)
{
  const std::size_t n = x.size() / 3;
  std::vector<double> phi(n), psi(n, -1.0);
  for (std::size_t i = 0; i < n; ++i)
    phi[i] = x[3 * i + 2] - crack_at - 0.03 * x[3 * i] + 0.02 * x[3 * i + 1]; // a tilted plane
  return compute_crack_geometry_3d(x, cells, phi, psi, 1e-8);
}

/// Lip points (cell, ref, weight, normal) of the crack.
void lip_points(const std::vector<double>& x, const std::vector<std::int32_t>& cells, const CrackGeometry& g,
                std::vector<std::int32_t>& pc, std::vector<double>& ref, std::vector<double>& w,
                std::vector<double>& normal)
{
  CrackPoints p = compute_crack_points(x, cells, g, 3);
  pc = p.cell, ref = p.ref, w = p.weight, normal = p.normal;
}

void lip_points(const std::vector<double>& x, const std::vector<std::int32_t>& cells, const CrackGeometry3D& g,
                std::vector<std::int32_t>& pc, std::vector<double>& ref, std::vector<double>& w,
                std::vector<double>& normal)
{
  LipPoints3D p = compute_lip_points_3d(x, cells, g, 3);
  pc = p.cell, ref = p.ref, w = p.weight, normal = p.normal;
}

template <int dim>
void check_divergence_theorem()
{
  std::vector<double> x;
  std::vector<std::int32_t> cells;
  if constexpr (dim == 2)
    test::triangle_grid(5, x, cells);
  else
    test::kuhn_cube(3, x, cells);
  const auto g = [&]
  {
    if constexpr (dim == 2)
      return through_crack_2d(x, cells);
    else
      return through_crack_3d(x, cells);
  }();
  const CrackGeometryOf<dim>* gs[] = {&g};
  const EnrichmentLayout layout = create_enrichment_layout(x, cells, gs, {});
  ASSERT_GT(layout.num_enriched(), 0);
  const std::int32_t ns = layout.num_std_nodes, ndof = dim * layout.num_nodes_total();

  // u_lin = G x on the standard dofs; sigma = D eps(G).
  double G[dim][dim], sigma[dim][dim];
  for (int i = 0; i < dim; ++i)
    for (int j = 0; j < dim; ++j)
      G[i][j] = 0.2 * (i + 1) * (j == i ? 1.0 : -0.5) + 0.1 * j;
  const IsotropicElasticity<dim> el(E, nu, "test");
  el.stress(G, sigma);
  std::vector<double> u(ndof, 0.0);
  for (std::int32_t n = 0; n < ns; ++n)
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j)
        u[dim * n + i] += G[i][j] * x[dim * n + j];

  // K u_lin on the enriched rows.
  Triplets K;
  const QuadratureOptionsOf<dim> opts;
  assemble_enriched_stiffness<dim>(coo_sink(K), x, cells, layout, gs, E, nu, opts);
  std::vector<double> Ku(ndof, 0.0);
  for (std::size_t k = 0; k < K.value.size(); ++k)
    Ku[K.row[k]] += K.value[k] * u[K.col[k]];

  // The lip load of t = sigma n.
  std::vector<std::int32_t> pc;
  std::vector<double> ref, w, normal, t;
  lip_points(x, cells, g, pc, ref, w, normal);
  ASSERT_GT(pc.size(), 0u);
  for (std::size_t p = 0; p < pc.size(); ++p)
    for (int i = 0; i < dim; ++i)
    {
      double ti = 0.0;
      for (int j = 0; j < dim; ++j)
        ti += sigma[i][j] * normal[dim * p + j];
      t.push_back(ti);
    }
  std::vector<double> lip(ndof, 0.0);
  assemble_lip_load<dim>(x, cells, layout, gs, 0, pc, ref, w, t, lip);

  // The cell load of the initial stress sigma at the stiffness's points.
  std::vector<std::int32_t> qc;
  std::vector<double> qref, qw, force, stress;
  std::vector<std::int8_t> qside;
  CellQuadratureOf<dim> q;
  constexpr auto pairs = voigt_pairs<dim>();
  for (const std::int32_t c : layout.cells)
  {
    compute_enriched_cell_quadrature(x, cells, layout, std::span<const CrackGeometryOf<dim>* const>(gs), c, opts, q);
    qc.insert(qc.end(), q.size(), c);
    qref.insert(qref.end(), q.ref.begin(), q.ref.end());
    qw.insert(qw.end(), q.weight.begin(), q.weight.end());
    qside.insert(qside.end(), q.side.begin(), q.side.end());
    for (int k = 0; k < q.size(); ++k)
      for (const auto& [i, j] : pairs)
        stress.push_back(sigma[i][j]);
  }
  force.assign(dim * qc.size(), 0.0);
  std::vector<double> body(ndof, 0.0);
  assemble_cell_load<dim>(x, cells, layout, gs, qc, qref, qside, qw, force, stress, body);

  double scale = 0.0;
  int interior = 0;
  for (std::int32_t k = 0; k < layout.num_enriched(); ++k)
    for (int d = 0; d < dim; ++d)
      scale = std::max(scale, std::abs(Ku[dim * (ns + k) + d]));
  ASSERT_GT(scale, 1e-3);
  for (std::int32_t k = 0; k < layout.num_enriched(); ++k)
  {
    const double* xn = &x[dim * layout.node[k]];
    bool inside = true;
    for (int i = 0; i < dim; ++i)
      inside = inside and xn[i] > 1e-12 and xn[i] < 1.0 - 1e-12;
    interior += inside;
    for (int d = 0; d < dim; ++d)
    {
      const std::int32_t j = dim * (ns + k) + d;
      EXPECT_NEAR(body[j], -Ku[j], 1e-13 * scale) << "dim " << dim << " pseudo-node " << k;
      if (inside)
        EXPECT_NEAR(Ku[j] + lip[j], 0.0, 1e-12 * scale) << "dim " << dim << " pseudo-node " << k;
    }
  }
  EXPECT_GE(interior, 8);
}
} // namespace

TEST(EnrichedLoads, StiffnessAndLoadsObeyTheDivergenceTheoremIn2D) { check_divergence_theorem<2>(); }
TEST(EnrichedLoads, StiffnessAndLoadsObeyTheDivergenceTheoremIn3D) { check_divergence_theorem<3>(); }
