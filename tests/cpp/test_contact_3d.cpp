// Crack-lip contact on tetrahedra against closed forms: the lip pieces'
// areas, the stable multiplier space (stars, front cells tied, the group
// functions summing to one), the coupling B on Heaviside jumps (polynomial:
// exact) and on the sqrt(r) jump of the front functions (exact with the
// collapsed rules), the tangent bases.
#include "contact/contact_kernels_3d.h"
#include "contact/multiplier_space_3d.h"
#include "enrichment/dof_numbering.h"
#include "geometry/p1_simplex.h"
#include "geometry/vec3.h"
#include "meshes.h"
#include "quadrature/rules.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

using namespace cracklip;
using namespace cracklip::vec3;

namespace
{
using Mesh = test::KuhnMesh;

/// The group of full multiplier f has a nodal member (a front cell's P0
/// multiplier tied to an interior star).
bool tied_to_nodal(const MultiplierSpace3D& space, std::int32_t f)
{
  const std::int32_t r = space.full_to_reduced[f];
  for (std::int32_t q = space.reduced_offsets[r]; q < space.reduced_offsets[r + 1]; ++q)
    if (space.full_node[space.reduced_full[q]] >= 0)
      return true;
  return false;
}

/// The polygon over the xy-polygon q on the plane z = z0 + ax x + ay y (CCW
/// seen from +z: the + side is above).
CrackSurface3D plane_crack(const std::vector<std::array<double, 2>>& q, double z0, double ax, double ay)
{
  std::vector<double> v;
  for (const auto& p : q)
    v.insert(v.end(), {p[0], p[1], z0 + ax * p[0] + ay * p[1]});
  return create_polygon_crack(v);
}

/// A plane through the whole cube (no front).
CrackSurface3D through(double z0, double ax, double ay)
{
  return plane_crack({{-10, -10}, {11, -10}, {11, 11}, {-10, 11}}, z0, ax, ay);
}

/// The crack x < x0 + k y of that plane: a straight front across the cube.
CrackSurface3D straight_front(double z0, double ax, double ay, double x0, double k)
{
  return plane_crack({{-5, -3}, {x0 - 3 * k, -3}, {x0 + 4 * k, 4}, {-5, 4}}, z0, ax, ay);
}

EnrichmentLayout layout_of(const Mesh& m, const CrackGeometry3D& g, TipEnrichment front, double radius)
{
  EnrichmentOptions o;
  o.tip = front;
  o.radius = radius;
  o.kappa = 1.8;
  const CrackGeometry3D* c[] = {&g};
  return create_enrichment_layout(m.x, m.cells, c, o);
}

struct Assembled
{
  Triplets B, M, T1, T2;
};

Assembled assemble(const Mesh& m, const EnrichmentLayout& layout, const CrackGeometry3D& g,
                   const MultiplierSpace3D& space, const LipRule3D& rule = {})
{
  Assembled a;
  const CrackGeometry3D* c[] = {&g};
  assemble_coupling_3d(m.x, m.cells, layout, c, space, rule,
                       {coo_sink(a.B), coo_sink(a.M), coo_sink(a.T1), coo_sink(a.T2)});
  return a;
}

/// The multiplier functions active at every contact point sum to one.
void expect_partition_of_unity(const ContactPoints3D& cp)
{
  std::vector<double> sum(cp.weight.size(), 0.0);
  for (std::size_t e = 0; e < cp.entry_value.size(); ++e)
    sum[cp.entry_point[e]] += cp.entry_value[e];
  for (std::size_t p = 0; p < sum.size(); ++p)
    ASSERT_NEAR(sum[p], 1.0, 1e-14) << "point " << p;
}

/// sum_rows c_row (T v)_row.
double weighted(const Triplets& T, const std::vector<double>& c, const std::map<std::int32_t, double>& v)
{
  double s = 0.0;
  for (std::size_t i = 0; i < T.value.size(); ++i)
    if (const auto it = v.find(T.col[i]); it != v.end())
      s += c[T.row[i]] * T.value[i] * it->second;
  return s;
}

/// int over the triangle of area A of sqrt(l), l >= 0 linear with vertex
/// values l: 2 A [l0, l1, l2] G, G = (4/15) s^(5/2), G'' = sqrt(s)
/// (Hermite-Genocchi), confluent where values coincide.
double integral_sqrt_linear(double A, std::array<double, 3> l)
{
  std::sort(l.begin(), l.end());
  auto G = [](double s) { return 4.0 / 15.0 * std::pow(std::max(s, 0.0), 2.5); };
  auto G1 = [](double s) { return 2.0 / 3.0 * std::pow(std::max(s, 0.0), 1.5); };
  auto dd = [&](double a, double b) { return a == b ? G1(a) : (G(b) - G(a)) / (b - a); };
  const double a = l[0], b = l[1], c = l[2];
  double d2;
  if (a == c)
    d2 = 0.5 * std::sqrt(std::max(a, 0.0));
  else if (a == b)
    d2 = (dd(a, c) - G1(a)) / (c - a);
  else
    d2 = (dd(b, c) - dd(a, b)) / (c - a);
  return 2.0 * A * d2;
}
} // namespace

// Pieces and their points: the weights of a cell's points sum to its facets'
// area; on a horizontal plane every cube's six tetrahedra give the square
// h^2, an inclined plane gives its section sqrt(1 + ax^2 + ay^2); the mass
// matrix sums to the area in both spaces (the functions sum to one).
TEST(Contact3D, PieceAreasAndMass)
{
  const int n = 5;
  const Mesh m(n);
  {
    const CrackGeometry3D g = compute_crack_geometry_3d(m.x, m.cells, through(0.47, 0.0, 0.0), 1e-6);
    const EnrichmentLayout layout = layout_of(m, g, TipEnrichment::none, 0.0);
    const CrackGeometry3D* c[] = {&g};
    const MultiplierSpace3D space = create_multiplier_space_3d(m.x, m.cells, c, layout, MultiplierKind::stable, true);
    const ContactPoints3D cp = compute_contact_points_3d(m.x, m.cells, c, space, {});
    std::map<std::int32_t, double> cube_area, cell_area;
    for (std::size_t p = 0; p < cp.weight.size(); ++p)
    {
      cube_area[cp.cell[p] / 6] += cp.weight[p]; // kuhn_cube: six cells per cube
      cell_area[cp.cell[p]] += cp.weight[p];
    }
    EXPECT_EQ(static_cast<int>(cube_area.size()), n * n);
    for (const auto& [cube, a] : cube_area)
      EXPECT_NEAR(a, 1.0 / (n * n), 1e-15) << "cube " << cube;
    for (const auto& [cell, a] : cell_area)
    {
      const CrackCell3D& cc = g.crack_cells[g.crack_cell_index[cell]];
      double facets = 0.0;
      for (double f : cc.facet_area)
        facets += f;
      EXPECT_NEAR(a, facets, 1e-15);
    }
  }
  const double ax = 0.1, ay = -0.05;
  const CrackGeometry3D g = compute_crack_geometry_3d(m.x, m.cells, through(0.43, ax, ay), 1e-6);
  const EnrichmentLayout layout = layout_of(m, g, TipEnrichment::none, 0.0);
  const CrackGeometry3D* c[] = {&g};
  for (const MultiplierKind kind : {MultiplierKind::naive, MultiplierKind::stable})
  {
    const MultiplierSpace3D space = create_multiplier_space_3d(m.x, m.cells, c, layout, kind, true);
    const Assembled a = assemble(m, layout, g, space);
    double total = 0.0;
    for (double v : a.M.value)
      total += v;
    EXPECT_NEAR(total, std::sqrt(1 + ax * ax + ay * ay), 1e-13);
  }
}

// The stable space on a plane through the cube: the vital edges form stars
// (an end of vital degree 1), every graph node keeps one, each group is one
// star (no group merges: every node is Heaviside-enriched), far fewer
// unknowns than nodal multipliers; the group functions sum to one at every
// point; the two maps of the restriction agree.
TEST(Contact3D, StableSpaceIsOneUnknownPerStar)
{
  const Mesh m(6);
  const CrackGeometry3D g = compute_crack_geometry_3d(m.x, m.cells, through(0.43, 0.1, -0.05), 1e-6);
  const EnrichmentLayout layout = layout_of(m, g, TipEnrichment::none, 0.0);
  const CrackGeometry3D* c[] = {&g};
  const MultiplierSpace3D naive = create_multiplier_space_3d(m.x, m.cells, c, layout, MultiplierKind::naive, true);
  const MultiplierSpace3D space = create_multiplier_space_3d(m.x, m.cells, c, layout, MultiplierKind::stable, true);
  EXPECT_EQ(naive.num_reduced, naive.num_full());
  EXPECT_EQ(space.num_full(), naive.num_full());
  ASSERT_GT(space.num_full(), 60);
  // Stars from the vital edges alone: connected components of the vital graph.
  std::map<std::int32_t, int> vital_degree;
  const std::size_t nv = space.vital_edges.size() / 2;
  for (std::size_t i = 0; i < 2 * nv; ++i)
    ++vital_degree[space.vital_edges[i]];
  std::set<std::int32_t> centres;
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < nv; ++i)
  {
    const std::int32_t a = space.vital_edges[2 * i], b = space.vital_edges[2 * i + 1];
    ASSERT_EQ(std::min(vital_degree[a], vital_degree[b]), 1) << "vital edge " << a << "-" << b << " is not a star's";
    if (vital_degree[a] > 1)
      centres.insert(a);
    else if (vital_degree[b] > 1)
      centres.insert(b);
    else
      ++pairs;
  }
  // Every nodal multiplier is on a vital edge (no node of the crack lies on it).
  for (std::int32_t f = 0; f < space.num_full(); ++f)
    EXPECT_GE(vital_degree[space.full_node[f]], 1) << "node " << space.full_node[f];
  EXPECT_EQ(static_cast<std::size_t>(space.num_reduced), centres.size() + pairs);
  EXPECT_LT(2 * space.num_reduced, space.num_full());
  // Both maps.
  ASSERT_EQ(space.reduced_offsets.size(), static_cast<std::size_t>(space.num_reduced + 1));
  for (std::int32_t r = 0; r < space.num_reduced; ++r)
  {
    ASSERT_LT(space.reduced_offsets[r], space.reduced_offsets[r + 1]);
    for (std::int32_t k = space.reduced_offsets[r]; k < space.reduced_offsets[r + 1]; ++k)
      EXPECT_EQ(space.full_to_reduced[space.reduced_full[k]], r);
  }
  // A constant reduced field is one at every point.
  const ContactPoints3D cp = compute_contact_points_3d(m.x, m.cells, c, space, {});
  expect_partition_of_unity(cp);
  const std::vector<double> ones(space.num_full(), 1.0);
  for (double v : evaluate_multipliers_3d(space, 0, cp.cell, cp.ref, ones))
    ASSERT_NEAR(v, 1.0, 1e-14);
}

// B on Heaviside jumps: [[N_i (H - H_i)]] = 2 N_i, polynomial on the pieces,
// so B is exact: with v = sum_i x_i (z dof of i's Heaviside function),
// [[v]] = 2 x e_z and int_crack [[v]] . n = 2 int_square x = 1 (n_z dA =
// dx dy on the graph of a plane), and weighted by the naive multipliers
// lambda = y: 2 int_square x y = 1/2. The tangential couplings give
// 2 int x e_z . t_c dA. The stable space's B and M are R^T B and R^T M R of
// the naive ones (same points).
TEST(Contact3D, HeavisideJumpIsIntegratedExactly)
{
  const double ax = 0.1, ay = -0.05, J = std::sqrt(1 + ax * ax + ay * ay);
  const Mesh m(5);
  const CrackGeometry3D g = compute_crack_geometry_3d(m.x, m.cells, through(0.43, ax, ay), 1e-6);
  const EnrichmentLayout layout = layout_of(m, g, TipEnrichment::none, 0.0);
  const CrackGeometry3D* c[] = {&g};
  const MultiplierSpace3D space = create_multiplier_space_3d(m.x, m.cells, c, layout, MultiplierKind::naive, true);
  const Assembled a = assemble(m, layout, g, space);
  std::map<std::int32_t, double> v;
  for (std::int32_t k = 0; k < layout.num_enriched(); ++k)
    v[node_dof(layout.num_std_nodes + k, 2, 3)] = m.x[3 * layout.node[k]];
  std::vector<double> one(space.num_full(), 1.0), y(space.num_full());
  for (std::int32_t f = 0; f < space.num_full(); ++f)
    y[f] = m.x[3 * space.full_node[f] + 1];
  EXPECT_NEAR(weighted(a.B, one, v), 1.0, 1e-13);
  EXPECT_NEAR(weighted(a.B, y, v), 0.5, 1e-13);
  // t1, t2 are constant on a plane: the default reference is e_y (the axis
  // least aligned with n = (-ax, -ay, 1) / J).
  const Point3 n = {-ax / J, -ay / J, 1.0 / J};
  Point3 t1, t2;
  tangent_basis(n, default_tangent_reference(g), t1, t2);
  EXPECT_EQ(default_tangent_reference(g), (Point3{0.0, 1.0, 0.0}));
  EXPECT_NEAR(weighted(a.T1, one, v), 2.0 * t1[2] * J * 0.5, 1e-13); // int x dA = J / 2
  EXPECT_NEAR(weighted(a.T2, one, v), 2.0 * t2[2] * J * 0.5, 1e-13);
  // Stable: the rows of the naive B summed over each group.
  const MultiplierSpace3D stable = create_multiplier_space_3d(m.x, m.cells, c, layout, MultiplierKind::stable, true);
  const Assembled s = assemble(m, layout, g, stable);
  std::vector<double> group(stable.num_reduced, 0.0), naive_rows(stable.num_reduced, 0.0);
  for (std::size_t i = 0; i < s.B.value.size(); ++i)
    if (const auto it = v.find(s.B.col[i]); it != v.end())
      group[stable.full_to_reduced[s.B.row[i]]] += s.B.value[i] * it->second;
  for (std::size_t i = 0; i < a.B.value.size(); ++i)
    if (const auto it = v.find(a.B.col[i]); it != v.end())
      naive_rows[stable.full_to_reduced[a.B.row[i]]] += a.B.value[i] * it->second;
  for (std::int32_t r = 0; r < stable.num_reduced; ++r)
    EXPECT_NEAR(group[r], naive_rows[r], 1e-15);
}

// The tangent basis: orthonormal, (t1, t2, n) right-handed, t1 along the
// reference's tangential part; a reference along the normal falls back on
// the axis least aligned with it.
TEST(Contact3D, TangentBasis)
{
  const Point3 n = unit(Point3{0.3, -0.2, 0.9});
  Point3 t1, t2;
  tangent_basis(n, {1.0, 0.0, 0.0}, t1, t2);
  EXPECT_NEAR(dot(t1, n), 0.0, 1e-15);
  EXPECT_NEAR(dot(t2, n), 0.0, 1e-15);
  EXPECT_NEAR(dot(t1, t2), 0.0, 1e-15);
  EXPECT_NEAR(norm(t1), 1.0, 1e-15);
  EXPECT_NEAR(norm(t2), 1.0, 1e-15);
  EXPECT_NEAR(dist(cross(t1, t2), n), 0.0, 1e-15);
  const Point3 a = unit(axpy({1.0, 0.0, 0.0}, -n[0], n));
  EXPECT_NEAR(dist(t1, a), 0.0, 1e-15);
  tangent_basis(n, scale(2.0, n), t1, t2); // degenerate reference
  EXPECT_NEAR(dist(t1, unit(axpy({0.0, 1.0, 0.0}, -n[1], n))), 0.0, 1e-15);
}

// The front: with front enrichment everywhere (radius beyond the cube: every
// node core, ramp 1, no Heaviside function left) the mode I function's
// jump on the lips is [[U_I]] = 2 (kappa + 1) sqrt(r) e2, r = -psi. Each
// front cell's P0 multiplier row of B then integrates 2 (kappa + 1) sqrt(-psi)
// over its facets: against the closed form per facet (Hermite-Genocchi),
// exact to round-off with the collapsed rules (the facets touching the front
// at an edge: tau^2 across it; at a vertex: the signed decomposition), and
// visibly not with plain Gauss on every facet. In the stable space every
// front cell's P0 multiplier is tied to an interior group.
// (exact here: 0.0845489104204; the collapsed rules give it to 4e-16.)
TEST(Contact3D, FrontJumpIsIntegratedExactly)
{
  const double z0 = 0.43, ax = 0.07, ay = 0.11, x0 = 0.61, k = 0.13, kappa = 1.8;
  const Mesh m(5);
  const CrackGeometry3D g = compute_crack_geometry_3d(m.x, m.cells, straight_front(z0, ax, ay, x0, k), 1e-6);
  const EnrichmentLayout layout = layout_of(m, g, TipEnrichment::vector, 10.0);
  const CrackGeometry3D* c[] = {&g};
  const MultiplierSpace3D space = create_multiplier_space_3d(m.x, m.cells, c, layout, MultiplierKind::stable, true);
  std::map<std::int32_t, double> v; // mode I dof of every front-enriched node
  for (std::int32_t e = 0; e < layout.num_enriched(); ++e)
    if (layout.kind[e] == static_cast<std::int8_t>(EnrichmentKind::tip_vector))
      v[node_dof(layout.num_std_nodes + e, 0, 3)] = 1.0;
  ASSERT_EQ(static_cast<std::int32_t>(v.size()), static_cast<std::int32_t>(m.x.size() / 3));
  std::vector<double> p0(space.num_full(), 0.0);
  double exact = 0.0;
  int front_pieces = 0, touching = 0;
  double plain_gauss = 0.0; // Gauss of degree 11 on every facet
  const quadrature::Rule gauss = quadrature::triangle(11);
  for (const LipPiece3D& piece : space.pieces)
  {
    if (!piece.front)
      continue;
    ++front_pieces;
    ASSERT_EQ(piece.mult.size(), 1u);
    p0[piece.mult[0]] = 1.0;
    EXPECT_TRUE(tied_to_nodal(space, piece.mult[0])) << "front cell " << piece.cell << " has a multiplier of its own";
    const CrackCell3D& cc = g.crack_cells[g.crack_cell_index[piece.cell]];
    const std::int32_t* nodes = &m.cells[4 * piece.cell];
    for (int f = 0; f < cc.num_facets(); ++f)
    {
      std::array<double, 3> l;
      for (int a = 0; a < 3; ++a)
      {
        const auto N = P1Tetrahedron::shape({cc.facets[9 * f + 3 * a], cc.facets[9 * f + 3 * a + 1], cc.facets[9 * f + 3 * a + 2]});
        l[a] = 0.0;
        for (int b = 0; b < 4; ++b)
          l[a] -= N[b] * g.psi[nodes[b]];
        l[a] = std::max(l[a], 0.0); // -0 and round-off at the front
      }
      touching += cc.facet_num_front[f] > 0;
      exact += 2.0 * (kappa + 1.0) * integral_sqrt_linear(cc.facet_area[f], l);
      for (int q = 0; q < gauss.size(); ++q)
      {
        const double s = gauss.points[2 * q], t = gauss.points[2 * q + 1];
        plain_gauss += 2.0 * (kappa + 1.0) * 2.0 * cc.facet_area[f] * gauss.weights[q]
                       * std::sqrt((1.0 - s - t) * l[0] + s * l[1] + t * l[2]);
      }
    }
  }
  ASSERT_GT(front_pieces, 10);
  ASSERT_GT(touching, 10);
  const Assembled a = assemble(m, layout, g, space);
  EXPECT_NEAR(weighted(a.B, p0, v), exact, 1e-12 * exact);
  // The plain fan on the facets touching the front at a vertex (the
  // lip rule without the signed decomposition): sqrt(r) = tau sqrt(d(eta))
  // there, d linear and positive across the fan, nearly as exact. Gauss
  // of degree 11 on every facet misses the sqrt(r) by 2e-4: the collapsed
  // rules are what makes B exact.
  const Assembled fan = assemble(m, layout, g, space, {6, 0.0, false});
  EXPECT_NEAR(weighted(fan.B, p0, v), exact, 1e-11 * exact);
  EXPECT_GT(std::abs(plain_gauss - exact), 1e-5 * exact) << plain_gauss / exact - 1;
}

// A penny crack (a curved front through the cells at every angle): every
// front cell's P0 multiplier joins a group with nodal members, the group
// functions sum to one at every contact point (front cells included), and
// every reduced multiplier sees a jump (a non-zero row of B).
TEST(Contact3D, PennyFrontCellsAreTied)
{
  const Mesh m(8);
  const CrackSurface3D s = create_ellipse_crack({0.5, 0.49, 0.47}, {0.1, 0.2, 1.0}, {1.0, 0.0, 0.0}, 0.3, 0.3);
  const CrackGeometry3D g = compute_crack_geometry_3d(m.x, m.cells, s, 1e-6);
  const EnrichmentLayout layout = layout_of(m, g, TipEnrichment::vector, 0.1);
  const CrackGeometry3D* c[] = {&g};
  const MultiplierSpace3D naive = create_multiplier_space_3d(m.x, m.cells, c, layout, MultiplierKind::naive, true);
  const MultiplierSpace3D space = create_multiplier_space_3d(m.x, m.cells, c, layout, MultiplierKind::stable, true);
  int front = 0;
  for (const LipPiece3D& piece : space.pieces)
  {
    if (!piece.front)
      continue;
    ++front;
    EXPECT_TRUE(tied_to_nodal(space, piece.mult.at(0))) << "front cell " << piece.cell;
  }
  EXPECT_GT(front, 30);
  EXPECT_LT(2 * space.num_reduced, naive.num_reduced);
  expect_partition_of_unity(compute_contact_points_3d(m.x, m.cells, c, space, {}));
  const Assembled a = assemble(m, layout, g, space);
  std::vector<double> row_norm(space.num_reduced, 0.0);
  // Reduced rows: sum of the members' rows; their squared norms.
  std::map<std::pair<std::int32_t, std::int32_t>, double> reduced;
  for (std::size_t i = 0; i < a.B.value.size(); ++i)
    reduced[{space.full_to_reduced[a.B.row[i]], a.B.col[i]}] += a.B.value[i];
  for (const auto& [rc, v] : reduced)
    row_norm[rc.first] += v * v;
  for (std::int32_t r = 0; r < space.num_reduced; ++r)
    EXPECT_GT(row_norm[r], 0.0) << "reduced multiplier " << r << " sees no jump";
}

namespace
{
/// The groups of a stable space as sets of their members' order-free keys.
std::set<std::set<MultiplierKey>> groups_by_key(const Mesh& m, const MultiplierSpace3D& space)
{
  const std::vector<MultiplierKey> keys = multiplier_keys(space, m.x, m.cells, 3);
  std::set<std::set<MultiplierKey>> out;
  for (std::int32_t r = 0; r < space.num_reduced; ++r)
  {
    std::set<MultiplierKey> g;
    for (std::int32_t q = space.reduced_offsets[r]; q < space.reduced_offsets[r + 1]; ++q)
      g.insert(keys[space.reduced_full[q]]);
    out.insert(g);
  }
  return out;
}
} // namespace

// The groups do not depend on the order of the input (multiplier_groups.h):
// the penny on the structured mesh (equal scores and spacings everywhere,
// front cells with equal weights from two groups) in five random orders
// (nodes renumbered, cells shuffled, vertices rotated in each cell) gives
// the same groups, named by their members' coordinates, as the mesh in its
// own order; so does the inclined through crack (Heaviside only).
TEST(Contact3D, GroupsDoNotDependOnTheOrder)
{
  const CrackSurface3D penny = create_ellipse_crack({0.5, 0.49, 0.47}, {0.1, 0.2, 1.0}, {1.0, 0.0, 0.0}, 0.3, 0.3);
  const CrackSurface3D plane = through(0.5, 0.0, 0.0);
  for (const auto& [s, front] : {std::pair{&penny, TipEnrichment::vector}, std::pair{&plane, TipEnrichment::none}})
  {
    auto groups_of = [&, s = s, front = front](const Mesh& m)
    {
      const CrackGeometry3D g = compute_crack_geometry_3d(m.x, m.cells, *s, 1e-6);
      const EnrichmentLayout layout = layout_of(m, g, front, 0.1);
      const CrackGeometry3D* c[] = {&g};
      return groups_by_key(m, create_multiplier_space_3d(m.x, m.cells, c, layout, MultiplierKind::stable, true));
    };
    const Mesh m(8);
    const auto reference = groups_of(m);
    ASSERT_GT(reference.size(), 8u);
    for (unsigned seed = 1; seed <= 5; ++seed)
    {
      Mesh p(8);
      test::shuffle_mesh(3, 4, seed, p.x, p.cells);
      EXPECT_EQ(groups_of(p), reference) << "order " << seed << (front == TipEnrichment::none ? " (plane)" : " (penny)");
    }
  }
}
