// The enrichment layout, the enriched basis and the point values, written
// once for any dimension, on the same problem in 2D (a crack line on
// triangles) and 3D (a crack plane on tetrahedra): the basis reproduces
// the fields it is built from exactly.
//   - Heaviside: a through crack, u = a on the + side, 0 on the - side
//     (standard dofs a (1 + H_i) / 2, Heaviside dofs a / 2).
//   - Tip / front: a crack ending at x = 0.53, every node within the radius
//     (ramp R = 1): the Williams mode I field U_I (standard dofs U_I(x_i),
//     the mode I dof of every vector pseudo-node 1), values and gradients.
#include "enrichment/enriched_basis.h"
#include "enrichment/enrichment_layout.h"
#include "enrichment/front_functions_3d.h"
#include "enrichment/tip_functions_2d.h"
#include "meshes.h"
#include "post/displacement.h"

#include <cmath>
#include <gtest/gtest.h>
#include <vector>

using namespace cracklip;

namespace
{
constexpr double kappa = 1.8;
constexpr double crack_at = 0.51, front_at = 0.53; // crack plane / line, tip / front position

/// The crack (a line at y = 0.51 on a triangle grid, a plane at z = 0.51 on a
/// Kuhn cube, both through or ending at x = 0.53) and the exact mode I field.
template <int dim>
struct Problem
{
  std::vector<double> x;
  std::vector<std::int32_t> cells;
  CrackGeometryOf<dim> g;
  explicit Problem(bool through)
  {
    if constexpr (dim == 2)
    {
      test::triangle_grid(4, x, cells);
      g = compute_crack_geometry(x, cells, CrackPath{{-1.0, crack_at, through ? 2.0 : front_at, crack_at},
                                                     {false, !through}}, 1e-8);
    }
    else
    {
      test::kuhn_cube(4, x, cells);
      const std::size_t n = x.size() / 3;
      std::vector<double> phi(n), psi(n);
      for (std::size_t i = 0; i < n; ++i)
        phi[i] = x[3 * i + 2] - crack_at, psi[i] = through ? -1.0 : x[3 * i] - front_at;
      g = compute_crack_geometry_3d(x, cells, phi, psi, 1e-8);
    }
  }
  /// The crack's level set: the last coordinate's distance to the crack.
  static double phi(const double* p) { return p[dim - 1] - crack_at; }
  /// U_I (unscaled) and its gradient at p on lip branch `side`: the tip at
  /// (0.53, 0.51), e1 = x; the front through (0.53, ., 0.51) along -y.
  static void williams(const double* p, int side, std::array<double, dim>& U,
                       std::array<std::array<double, dim>, dim>& dU)
  {
    std::array<std::array<double, dim>, dim> u;
    std::array<std::array<std::array<double, dim>, dim>, dim> du;
    if constexpr (dim == 2)
      williams_displacement(TipFrame{{front_at, crack_at}, {1.0, 0.0}, 1}, {p[0], p[1]}, side, kappa, u, du);
    else
      front_vector_functions(FrontFrame{{front_at, 0.0, crack_at}, {1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, {0.0, -1.0, 0.0}},
                             {p[0], p[1], p[2]}, side, kappa, u, du);
    U = u[0], dU = du[0];
  }
};

/// The displacement u of the layout's dofs at four points of every cell
/// (side 0: the side each lies on): their physical coordinates, values
/// (n, dim) and gradients (n, dim, dim).
template <int dim>
struct Samples
{
  std::vector<std::array<double, dim>> x;
  std::vector<double> u, grad;
};

template <int dim>
Samples<dim> evaluate_at_samples(const Problem<dim>& pb, const EnrichmentLayout& layout, const std::vector<double>& u)
{
  const double bary[4][3] = {{0.25, 0.25, 0.25}, {0.6, 0.15, 0.1}, {0.1, 0.7, 0.05}, {0.15, 0.1, 0.6}};
  std::vector<std::int32_t> pc;
  std::vector<double> ref;
  Samples<dim> out;
  for (std::size_t c = 0; c < pb.cells.size() / (dim + 1); ++c)
    for (const auto& b : bary)
    {
      std::array<double, dim> r;
      for (int i = 0; i < dim; ++i)
        r[i] = dim == 2 ? b[i] * 0.9 : b[i];
      pc.push_back(static_cast<std::int32_t>(c));
      ref.insert(ref.end(), r.begin(), r.end());
      out.x.push_back(P1Simplex<dim>(pb.x, pb.cells, pc.back()).physical(r));
    }
  const CrackGeometryOf<dim>* gs[] = {&pb.g};
  const std::vector<std::int8_t> sides(pc.size(), 0);
  out.u = evaluate_displacement<dim>(pb.x, pb.cells, layout, gs, u, pc, ref, sides, &out.grad);
  return out;
}

template <int dim>
void check_heaviside_jump()
{
  const Problem<dim> pb(true);
  const CrackGeometryOf<dim>* gs[] = {&pb.g};
  const EnrichmentLayout layout = create_enrichment_layout(pb.x, pb.cells, gs, {});
  ASSERT_EQ(layout.dim, dim);
  ASSERT_GT(layout.num_enriched(), 0);
  const double a[3] = {0.7, -1.3, 0.4};
  std::vector<double> u(dim * layout.num_nodes_total(), 0.0);
  for (std::int32_t n = 0; n < layout.num_std_nodes; ++n)
    for (int d = 0; d < dim; ++d)
      u[dim * n + d] = 0.5 * a[d] * (1.0 + (Problem<dim>::phi(&pb.x[dim * n]) >= 0.0 ? 1.0 : -1.0));
  for (std::int32_t k = 0; k < layout.num_enriched(); ++k)
  {
    ASSERT_EQ(layout.kind[k], static_cast<std::int8_t>(EnrichmentKind::heaviside));
    for (int d = 0; d < dim; ++d)
      u[dim * (layout.num_std_nodes + k) + d] = 0.5 * a[d];
  }
  const Samples<dim> at = evaluate_at_samples(pb, layout, u);
  for (std::size_t p = 0; p < at.x.size(); ++p)
  {
    const auto& xp = at.x[p];
    const bool plus = Problem<dim>::phi(xp.data()) >= 0.0;
    for (int d = 0; d < dim; ++d)
    {
      EXPECT_NEAR(at.u[dim * p + d], plus ? a[d] : 0.0, 1e-14) << "dim " << dim << " point " << p;
      for (int j = 0; j < dim; ++j)
        EXPECT_NEAR(at.grad[dim * dim * p + dim * d + j], 0.0, 1e-12);
    }
  }
}

template <int dim>
void check_williams_field()
{
  const Problem<dim> pb(false);
  const CrackGeometryOf<dim>* gs[] = {&pb.g};
  EnrichmentOptions o;
  o.tip = TipEnrichment::vector;
  o.radius = 10.0; // every node: the ramp is 1 everywhere
  o.kappa = kappa;
  const EnrichmentLayout layout = create_enrichment_layout(pb.x, pb.cells, gs, o);
  std::vector<double> u(dim * layout.num_nodes_total(), 0.0);
  std::array<double, dim> U;
  std::array<std::array<double, dim>, dim> dU;
  for (std::int32_t n = 0; n < layout.num_std_nodes; ++n)
  {
    const double* xn = &pb.x[dim * n];
    Problem<dim>::williams(xn, Problem<dim>::phi(xn) >= 0.0 ? 1 : -1, U, dU);
    for (int d = 0; d < dim; ++d)
      u[dim * n + d] = U[d];
  }
  int vector_nodes = 0;
  for (std::int32_t k = 0; k < layout.num_enriched(); ++k)
  {
    ASSERT_EQ(layout.kind[k], static_cast<std::int8_t>(EnrichmentKind::tip_vector)) << "no Heaviside where R = 1";
    u[dim * (layout.num_std_nodes + k)] = 1.0; // mode I
    ++vector_nodes;
  }
  EXPECT_EQ(vector_nodes, layout.num_std_nodes);
  const Samples<dim> at = evaluate_at_samples(pb, layout, u);
  double umax = 0.0;
  for (std::size_t p = 0; p < at.x.size(); ++p)
  {
    const auto& xp = at.x[p];
    Problem<dim>::williams(xp.data(), Problem<dim>::phi(xp.data()) >= 0.0 ? 1 : -1, U, dU);
    for (int d = 0; d < dim; ++d)
    {
      umax = std::max(umax, std::abs(U[d]));
      EXPECT_NEAR(at.u[dim * p + d], U[d], 1e-12) << "dim " << dim << " point " << p;
      for (int j = 0; j < dim; ++j)
        EXPECT_NEAR(at.grad[dim * dim * p + dim * d + j], dU[d][j], 1e-10 * (1.0 + std::abs(dU[d][j])));
    }
  }
  EXPECT_GT(umax, 0.5); // a field worth reproducing
}

/// A through crack on a node layer (the line y = 1/2 along the triangles'
/// edges, the plane z = 1/2 along the tetrahedra's faces; n = 4), with the
/// scene's default enrichment (vector tip / front functions, corrected
/// blending; no tip / front here): no cell is cut, the cells beside it are
/// edge / face cells (class 2). Closed form: exactly the (n + 1)^(dim - 1)
/// nodes on the layer carry a Heaviside function, H_i = H(0) = +1 (phi >= 0
/// is the + side), so N_i (H - H_i) is 0 on the + side, -2 N_i on the - side,
/// and jumps by 2 N_i(x) across the edge / face; u = a on the + side and 0
/// on the - side (standard dofs a on and above the layer, Heaviside dofs
/// a / 2) is reproduced on both lips. In 3D the layout kept no Heaviside
/// function at all before face cells counted in its ramp shares (hard case
/// 3D-3).
template <int dim>
void check_crack_on_node_layer()
{
  constexpr int n = 4;
  std::vector<double> x;
  std::vector<std::int32_t> cells;
  CrackGeometryOf<dim> g;
  if constexpr (dim == 2)
  {
    test::triangle_grid(n, x, cells);
    g = compute_crack_geometry(x, cells, CrackPath{{-1.0, 0.5, 2.0, 0.5}, {false, false}}, 1e-8);
  }
  else
  {
    test::kuhn_cube(n, x, cells);
    const std::size_t nn = x.size() / 3;
    std::vector<double> phi(nn), psi(nn, -1.0);
    for (std::size_t i = 0; i < nn; ++i)
      phi[i] = x[3 * i + 2] - 0.5;
    g = compute_crack_geometry_3d(x, cells, phi, psi, 1e-8);
  }
  const auto num_cells = static_cast<std::int32_t>(cells.size() / (dim + 1));
  int cut = 0, along = 0;
  for (std::int32_t c = 0; c < num_cells; ++c)
    cut += g.cell_class[c] == 1, along += g.cell_class[c] == 2;
  ASSERT_EQ(cut, 0);
  ASSERT_EQ(along, dim == 2 ? 2 * n : 4 * n * n); // one cell on each side of every edge / face
  const CrackGeometryOf<dim>* gs[] = {&g};
  EnrichmentOptions o;
  o.tip = TipEnrichment::vector;
  o.radius = 0.1;
  const EnrichmentLayout layout = create_enrichment_layout(x, cells, gs, o);
  ASSERT_EQ(layout.num_enriched(), dim == 2 ? n + 1 : (n + 1) * (n + 1));
  for (std::int32_t k = 0; k < layout.num_enriched(); ++k)
  {
    EXPECT_EQ(layout.kind[k], static_cast<std::int8_t>(EnrichmentKind::heaviside));
    EXPECT_EQ(x[dim * layout.node[k] + dim - 1], 0.5);
    EXPECT_EQ(g.phi[layout.node[k]], 0.0);
    EXPECT_EQ(layout.shift[dim * dim * k], 1.0); // H(0) = +1
  }
  // The field u = a above, 0 below.
  const double a[3] = {0.7, -1.3, 0.4};
  std::vector<double> u(dim * layout.num_nodes_total(), 0.0);
  for (std::int32_t i = 0; i < layout.num_std_nodes; ++i)
    for (int d = 0; d < dim; ++d)
      u[dim * i + d] = g.phi[i] >= 0.0 ? a[d] : 0.0;
  for (std::int32_t k = 0; k < layout.num_enriched(); ++k)
    for (int d = 0; d < dim; ++d)
      u[dim * (layout.num_std_nodes + k) + d] = 0.5 * a[d];
  // On every edge / face cell, at points of its crack edge / face: each
  // pseudo-node's function on either lip, and the displacement of both lips.
  const double weights[3][3] = {{0.5, 0.5, 0.0}, {0.2, 0.3, 0.5}, {0.6, 0.1, 0.3}};
  int checked = 0;
  std::vector<double> val, grad;
  std::vector<std::int32_t> pc;
  std::vector<double> ref;
  std::vector<std::int8_t> sides;
  for (std::int32_t c = 0; c < num_cells; ++c)
  {
    if (g.cell_class[c] != 2)
      continue;
    const P1Simplex<dim> cell(x, cells, c);
    const EnrichedCellBasis<dim> basis(cell, layout, c);
    ASSERT_EQ(static_cast<int>(basis.enr.size()), dim); // the nodes of its crack edge / face
    std::vector<int> on; // local vertices on the crack
    for (int b = 0; b <= dim; ++b)
      if (g.phi[cell.nodes[b]] == 0.0)
        on.push_back(b);
    ASSERT_EQ(static_cast<int>(on.size()), dim);
    for (const auto& w : weights)
    {
      std::array<double, dim + 1> lam{};
      for (int j = 0; j < dim; ++j)
        lam[on[j]] = w[j] / (dim == 2 ? w[0] + w[1] : 1.0);
      std::array<double, dim> r;
      for (int i = 0; i < dim; ++i)
        r[i] = lam[i + 1];
      const auto N = P1Simplex<dim>::shape(r);
      std::array<std::vector<double>, 2> v; // side +1, -1
      for (int s = 0; s < 2; ++s)
      {
        const int side[1] = {s == 0 ? 1 : -1};
        evaluate_basis<dim>(cell, basis, layout, gs, side, r, val, grad);
        v[s] = val;
      }
      for (std::size_t j = 0; j < basis.enr.size(); ++j)
        for (int d = 0; d < dim; ++d)
        {
          const int i = dim * (dim + 1 + static_cast<int>(j)) + d; // scalar dof
          EXPECT_NEAR(v[0][dim * i + d], 0.0, 1e-15);
          EXPECT_NEAR(v[1][dim * i + d], -2.0 * N[basis.enr_local[j]], 1e-15);
          ++checked;
        }
      for (const int s : {1, -1})
      {
        pc.push_back(c);
        ref.insert(ref.end(), r.begin(), r.end());
        sides.push_back(static_cast<std::int8_t>(s));
      }
    }
  }
  EXPECT_EQ(checked, along * 3 * dim * dim);
  const std::vector<double> lips = evaluate_displacement<dim>(x, cells, layout, gs, u, pc, ref, sides);
  for (std::size_t p = 0; p < pc.size(); ++p)
    for (int d = 0; d < dim; ++d)
      EXPECT_NEAR(lips[dim * p + d], sides[p] > 0 ? a[d] : 0.0, 1e-14) << "dim " << dim << " point " << p;
}
} // namespace

TEST(EnrichedBasis, HeavisideReproducesAJumpIn2D) { check_heaviside_jump<2>(); }
TEST(EnrichedBasis, HeavisideReproducesAJumpIn3D) { check_heaviside_jump<3>(); }
TEST(EnrichedBasis, CrackAlongMeshEdgesOpensIn2D) { check_crack_on_node_layer<2>(); }
TEST(EnrichedBasis, CrackAlongMeshFacesOpensIn3D) { check_crack_on_node_layer<3>(); }
TEST(EnrichedBasis, TipFunctionsReproduceWilliamsModeIIn2D) { check_williams_field<2>(); }
TEST(EnrichedBasis, FrontFunctionsReproduceWilliamsModeIIn3D) { check_williams_field<3>(); }

// The layout reports its dimension, and the kernels refuse a layout of the
// other one.
TEST(EnrichedBasis, LayoutOfTheOtherDimensionIsRefused)
{
  const Problem<2> pb(true);
  const CrackGeometry* gs[] = {&pb.g};
  const EnrichmentLayout layout = create_enrichment_layout(pb.x, pb.cells, gs, {});
  EXPECT_EQ(layout.dim, 2);
  EXPECT_THROW(layout.require_dimension(3, "test"), std::invalid_argument);
  std::vector<double> u(2 * layout.num_nodes_total(), 0.0);
  const std::vector<std::int32_t> pc = {0};
  const std::vector<double> ref = {0.2, 0.2, 0.2};
  const std::vector<std::int8_t> sides = {0};
  const Problem<3> pb3(true);
  const CrackGeometry3D* gs3[] = {&pb3.g};
  EXPECT_THROW(evaluate_displacement<3>(pb3.x, pb3.cells, layout, gs3, u, pc, ref, sides), std::invalid_argument);
}
