// Crack geometry on Kuhn-cube tetrahedral meshes of [0, 1]^3 against closed
// forms: volumes split by a plane, cross-section areas, straight and
// circular fronts, snapping and degenerate positions.
#include "geometry/crack_geometry_3d.h"
#include "geometry/p1_simplex.h"
#include "geometry/vec3.h"
#include "meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <random>

using namespace cracklip;
using namespace cracklip::vec3;

namespace
{
struct Mesh : test::KuhnMesh
{
  using KuhnMesh::KuhnMesh;
  P1Tetrahedron tet(std::int32_t c) const { return P1Tetrahedron(x, cells, c); }
};

/// Points on the plane z = z0 + ax x + ay y.
Point3 on_plane(double x, double y, double z0, double ax, double ay) { return {x, y, z0 + ax * x + ay * y}; }

/// A polygon in the plane z = z0 + ax x + ay y over the xy-polygon q (CCW),
/// as (n, 3) vertices: counter-clockwise seen from +z, so its normal has a
/// positive z component.
std::vector<double> plane_polygon(const std::vector<std::array<double, 2>>& q, double z0, double ax, double ay)
{
  std::vector<double> v;
  for (const auto& p : q)
  {
    const Point3 r = on_plane(p[0], p[1], z0, ax, ay);
    v.insert(v.end(), r.begin(), r.end());
  }
  return v;
}

double lip_area(const CrackGeometry3D& g)
{
  double a = 0.0;
  for (const CrackCell3D& cc : g.crack_cells)
    for (double f : cc.facet_area)
      a += f;
  return a;
}

/// Every crack cell: sub-tetrahedra positive, their reference volumes plus
/// the dropped slivers sum to 1/6 (to 1e-13 relative).
void check_sub_volumes(const CrackGeometry3D& g)
{
  for (const CrackCell3D& cc : g.crack_cells)
  {
    double v = cc.dropped_volume;
    ASSERT_GE(cc.dropped_volume, 0.0);
    for (int k = 0; k < cc.num_sub(); ++k)
    {
      const double* s = &cc.sub[12 * k];
      const double vk = signed_volume({s[0], s[1], s[2]}, {s[3], s[4], s[5]}, {s[6], s[7], s[8]}, {s[9], s[10], s[11]});
      ASSERT_TRUE(std::isfinite(vk));
      ASSERT_GT(vk, 0.0) << "cell " << cc.cell;
      v += vk;
    }
    ASSERT_NEAR(v, 1.0 / 6.0, 1e-13 / 6.0) << "cell " << cc.cell;
    for (double a : cc.facet_area)
      ASSERT_TRUE(std::isfinite(a) and a > 0.0);
  }
}

/// Physical volume where phi < 0: plain and face cells by their side, cut and
/// front cells by their sub-tetrahedra (no extension cells allowed).
double volume_below(const Mesh& m, const CrackGeometry3D& g)
{
  double vol = 0.0;
  for (std::int32_t c = 0; c < m.num_cells(); ++c)
  {
    const P1Tetrahedron T = m.tet(c);
    EXPECT_NE(static_cast<CellClass3D>(g.cell_class[c]), CellClass3D::extension);
    if (const std::int32_t i = g.crack_cell_index[c]; i >= 0)
    {
      const CrackCell3D& cc = g.crack_cells[i];
      for (int k = 0; k < cc.num_sub(); ++k)
        if (cc.side[k] < 0)
        {
          const double* s = &cc.sub[12 * k];
          vol += std::abs(T.detJ)
                 * signed_volume({s[0], s[1], s[2]}, {s[3], s[4], s[5]}, {s[6], s[7], s[8]}, {s[9], s[10], s[11]});
        }
    }
    else if (g.cell_side[c] < 0)
      vol += T.volume();
  }
  return vol;
}

/// In every front cell: each sub-tetrahedron meets the front (phi = psi = 0
/// of the cell's P1 level sets) exactly at its num_front first vertices (an
/// edge, a vertex, or not at all). Shown with the level sets at its
/// vertices: the sub-tetrahedron lies on one side of phi = 0 and one side of
/// psi = 0, so a point of it with phi = psi = 0 is a convex combination of
/// the vertices where both vanish; those are the first num_front, and they
/// lie on the cell's front segment line. Cells where P1 psi vanishes on
/// the whole zero set of phi (the P1 front is a surface there, counted in
/// num_degenerate_front_cells) are skipped and counted.
int check_front_structure(const Mesh& m, const CrackGeometry3D& g)
{
  int degenerate = 0;
  for (const CrackCell3D& cc : g.crack_cells)
  {
    if (cc.cls != CellClass3D::front)
      continue;
    const P1Tetrahedron T = m.tet(cc.cell);
    std::array<double, 4> f, p;
    double scale_f = 0.0, scale_p = 0.0;
    for (int a = 0; a < 4; ++a)
    {
      f[a] = g.phi[T.nodes[a]], p[a] = g.psi[T.nodes[a]];
      scale_f = std::max(scale_f, std::abs(f[a])), scale_p = std::max(scale_p, std::abs(p[a]));
    }
    // psi on the zero set of phi: at its zero nodes and edge zeros. If psi
    // vanishes at three or more of them, the P1 front is a surface here.
    int zeros = 0, psi_zeros = 0;
    for (int a = 0; a < 4; ++a)
    {
      if (f[a] == 0.0)
        ++zeros, psi_zeros += std::abs(p[a]) <= 2e-12 * scale_p;
      for (int b = a + 1; b < 4; ++b)
        if (f[a] * f[b] < 0.0)
        {
          const double t = f[a] / (f[a] - f[b]);
          ++zeros, psi_zeros += std::abs(p[a] + t * (p[b] - p[a])) <= 2e-12 * scale_p;
        }
    }
    if (zeros >= 3 and psi_zeros == zeros)
    {
      ++degenerate;
      continue;
    }
    // The cuts count a point within 1e-12 of the cell's level-set scale as
    // on the zero set (their documented resolution); the test's own
    // evaluation adds round-off, so flagged front vertices must lie within
    // 2e-12 and the others beyond 0.5e-12 (a gap, not a single threshold).
    const double ef = 2e-12 * scale_f, ep = 2e-12 * scale_p;
    const double gf = 0.5e-12 * scale_f, gp = 0.5e-12 * scale_p;
    const Point3 P = T.physical({cc.front_segment[0], cc.front_segment[1], cc.front_segment[2]});
    const Point3 Q = T.physical({cc.front_segment[3], cc.front_segment[4], cc.front_segment[5]});
    double h = 0.0;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        h = std::max(h, dist(T.xv[a], T.xv[b]));
    for (int k = 0; k < cc.num_sub(); ++k)
    {
      const int nf = cc.num_front[k];
      EXPECT_TRUE(nf >= 0 and nf <= 2);
      EXPECT_NE(cc.psi_side[k], 0);
      for (int i = 0; i < 4; ++i)
      {
        const Point3 r = {cc.sub[12 * k + 3 * i], cc.sub[12 * k + 3 * i + 1], cc.sub[12 * k + 3 * i + 2]};
        const auto N = P1Tetrahedron::shape(r);
        double fi = 0.0, pi = 0.0;
        for (int a = 0; a < 4; ++a)
          fi += N[a] * f[a], pi += N[a] * p[a];
        EXPECT_GE(fi * cc.side[k], -ef) << "sub-tetrahedron on both sides of phi = 0, cell " << cc.cell;
        EXPECT_GE(pi * cc.psi_side[k], -ep) << "sub-tetrahedron on both sides of psi = 0, cell " << cc.cell;
        if (i < nf)
          EXPECT_TRUE(std::abs(fi) <= ef and std::abs(pi) <= ep)
              << "flagged front vertex off the front, cell " << cc.cell << " sub " << k << " vertex " << i;
        else
          EXPECT_TRUE(std::abs(fi) > gf or std::abs(pi) > gp)
              << "front vertex not flagged, cell " << cc.cell << " sub " << k << " vertex " << i;
        if (i < nf and cc.front_length > 0.0)
        {
          const Point3 x = T.physical(r);
          EXPECT_LT(norm(cross(sub(x, P), unit(sub(Q, P)))), 1e-12 * h) << "front vertex off the front line";
        }
      }
    }
  }
  EXPECT_EQ(degenerate, g.num_degenerate_front_cells);
  return degenerate;
}

double fit_rate(const std::vector<double>& h, const std::vector<double>& e)
{
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(h.size());
  for (std::size_t i = 0; i < h.size(); ++i)
  {
    const double lx = std::log(h[i]), ly = std::log(e[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}
} // namespace

// A plane crossing the whole cube, the crack a large polygon around it: the
// lip area is the cross-section area sqrt(1 + ax^2 + ay^2) (the graph of
// z0 + ax x + ay y over the unit square) and the volume below it is
// z0 + ax/2 + ay/2, both to round-off; no front cell.
TEST(CrackGeometry3D, PlaneThroughTheCubeGivesTheExactSection)
{
  const double z0 = 0.37, ax = 0.1, ay = 0.05;
  const Mesh m(6);
  const CrackSurface3D s = create_polygon_crack(plane_polygon({{-10, -10}, {11, -10}, {11, 11}, {-10, 11}}, z0, ax, ay));
  const CrackGeometry3D g = compute_crack_geometry_3d(m.x, m.cells, s, 1e-6);
  check_sub_volumes(g);
  EXPECT_NEAR(lip_area(g), std::sqrt(1.0 + ax * ax + ay * ay), 1e-12);
  EXPECT_NEAR(volume_below(m, g), z0 + ax / 2 + ay / 2, 1e-13);
  const Point3 n = unit(Point3{-ax, -ay, 1.0});
  int cut = 0;
  for (const CrackCell3D& cc : g.crack_cells)
  {
    EXPECT_EQ(cc.cls, CellClass3D::cut);
    cut += cc.cls == CellClass3D::cut;
    for (int k = 0; k < cc.num_facets(); ++k)
      for (int d = 0; d < 3; ++d)
        EXPECT_NEAR(cc.facet_normal[3 * k + d], n[d], 1e-13);
  }
  EXPECT_GT(cut, 0);
  EXPECT_EQ(g.front.num_points(), 0);
  EXPECT_EQ(g.num_snapped, 0);
}

// The plane z = 1/2 through a layer of nodes: no cell is cut; the cells with
// a face on it are face cells; only the upper (+) one of each pair holds the
// facet, so the lip area is exactly 1; the volume below is 1/2.
TEST(CrackGeometry3D, CrackOnMeshFacesGivesFaceCellsWithOneOwner)
{
  const Mesh m(4);
  const CrackSurface3D s = create_polygon_crack(plane_polygon({{-10, -10}, {11, -10}, {11, 11}, {-10, 11}}, 0.5, 0, 0));
  const CrackGeometry3D g = compute_crack_geometry_3d(m.x, m.cells, s, 1e-6);
  check_sub_volumes(g);
  EXPECT_NEAR(lip_area(g), 1.0, 1e-13);
  EXPECT_NEAR(volume_below(m, g), 0.5, 1e-14);
  int face_plus = 0, face_minus = 0;
  for (const CrackCell3D& cc : g.crack_cells)
  {
    ASSERT_EQ(cc.cls, CellClass3D::face);
    ASSERT_EQ(cc.num_sub(), 1);
    (g.cell_side[cc.cell] > 0 ? face_plus : face_minus) += 1;
    EXPECT_EQ(cc.num_facets(), g.cell_side[cc.cell] > 0 ? 1 : 0);
  }
  // Each of the 4 x 4 squares of the plane is two triangles, each a face
  // of one cell above and one below.
  EXPECT_EQ(face_plus, 32);
  EXPECT_EQ(face_minus, 32);
}

// A straight front across the cube: the crack is the part of the plane
// z = z0 + ax x + ay y where x < x0 + k y (a large polygon with one edge in
// the cube). psi is then linear (the in-plane distance to a line), so the P1
// level sets are exact: the lip area is the section over that half of the
// square, (x0 + k / 2) sqrt(1 + ax^2 + ay^2), to 1e-12; the front is one
// open piece on the exact line, its ends on the faces y = 0 and y = 1, its
// length the line's, and its frames the exact ones.
TEST(CrackGeometry3D, StraightFrontIsExact)
{
  const double z0 = 0.43, ax = 0.07, ay = 0.11, x0 = 0.61, k = 0.13;
  for (const int n : {5, 8})
  {
    const Mesh m(n);
    const CrackSurface3D s = create_polygon_crack(
        plane_polygon({{-5, -3}, {x0 - 3 * k, -3}, {x0 + 4 * k, 4}, {-5, 4}}, z0, ax, ay));
    const CrackGeometry3D g = compute_crack_geometry_3d(m.x, m.cells, s, 1e-6);
    check_sub_volumes(g);
    check_front_structure(m, g);
    const double J = std::sqrt(1.0 + ax * ax + ay * ay);
    EXPECT_NEAR(lip_area(g), (x0 + k / 2) * J, 1e-12);
    const CrackFront3D& f = g.front;
    ASSERT_EQ(f.num_pieces(), 1);
    EXPECT_EQ(f.closed[0], 0);
    const int np = f.num_points();
    ASSERT_GE(np, n);
    // The exact front line and frame.
    const Point3 A = on_plane(x0, 0.0, z0, ax, ay), B = on_plane(x0 + k, 1.0, z0, ax, ay);
    const Point3 e2 = unit(Point3{-ax, -ay, 1.0});
    const Point3 t = unit(sub(B, A));
    const Point3 e1 = cross(t, e2); // points to x > x0 + k y, away from the crack
    EXPECT_GT(e1[0], 0.0);
    const Point3 e3 = cross(e1, e2); // = -t: the front runs from y = 1 to y = 0
    EXPECT_NEAR(f.s[np - 1], dist(A, B), 1e-13);
    for (int i = 0; i < np; ++i)
    {
      const Point3 p = {f.x[3 * i], f.x[3 * i + 1], f.x[3 * i + 2]};
      EXPECT_LT(norm(cross(sub(p, A), t)), 1e-14) << "front point off the exact front";
      if (i > 0)
        EXPECT_GT(f.s[i], f.s[i - 1]);
      for (int d = 0; d < 3; ++d)
      {
        EXPECT_NEAR(f.frame[9 * i + d], e1[d], 1e-13);
        EXPECT_NEAR(f.frame[9 * i + 3 + d], e2[d], 1e-13);
        EXPECT_NEAR(f.frame[9 * i + 6 + d], e3[d], 1e-13);
      }
      EXPECT_EQ(f.on_boundary[i], i == 0 or i == np - 1) << i;
    }
    // Ordered along e3: starts at y = 1.
    EXPECT_NEAR(f.x[1], 1.0, 1e-15);
    EXPECT_NEAR(f.x[3 * (np - 1) + 1], 0.0, 1e-15);
    EXPECT_EQ(f.num_segments(), np - 1);
  }
}

// Front along mesh edges: plane z = 1/2 (through nodes) and front x = 1/2
// (through nodes): face cells, front cells whose front is a cell edge
// shared by several cells, counted once; the lip area is exactly 1/2 and
// the front one open piece of length 1 from y = 0 to y = 1.
TEST(CrackGeometry3D, FrontAlongMeshEdges)
{
  const Mesh m(4);
  const CrackSurface3D s = create_polygon_crack(plane_polygon({{-5, -3}, {0.5, -3}, {0.5, 4}, {-5, 4}}, 0.5, 0, 0));
  const CrackGeometry3D g = compute_crack_geometry_3d(m.x, m.cells, s, 1e-6);
  check_sub_volumes(g);
  check_front_structure(m, g);
  EXPECT_NEAR(lip_area(g), 0.5, 1e-14);
  ASSERT_EQ(g.front.num_pieces(), 1);
  EXPECT_EQ(g.front.closed[0], 0);
  EXPECT_EQ(g.front.num_points(), 5);
  EXPECT_NEAR(g.front.s.back(), 1.0, 1e-15);
  EXPECT_EQ(g.front.on_boundary.front(), 1);
  EXPECT_EQ(g.front.on_boundary.back(), 1);
  for (int i = 1; i + 1 < g.front.num_points(); ++i)
    EXPECT_EQ(g.front.on_boundary[i], 0);
}

// Penny crack of radius a (tilted normal): one closed front piece whose
// points lie on the circle to O(h^2), with orthonormal right-handed frames,
// e2 the normal and e1 radial outward: exact from the surface (the circle's
// directions at the point), O(h) from the P1 level sets alone (the
// polyline's tangent); the lip area tends to pi a^2 and the front length to
// 2 pi a at O(h^2).
TEST(CrackGeometry3D, PennyFrontConvergesToTheCircle)
{
  const Point3 c = {0.51, 0.49, 0.503};
  const Point3 nrm = unit(Point3{0.1, 0.2, 1.0});
  const double a = 0.3;
  const CrackSurface3D s = create_ellipse_crack(c, nrm, {1, 0, 0}, a, a);
  std::vector<double> hs, e_pos, e_rms, e_area, e_len, e_frame;
  for (const int n : {8, 16, 32, 64})
  {
    const Mesh m(n);
    const CrackGeometry3D g = compute_crack_geometry_3d(m.x, m.cells, s, 1e-6);
    const LevelSets3D ls0 = compute_level_sets_3d(m.x, s);
    const CrackGeometry3D g1 = compute_crack_geometry_3d(m.x, m.cells, ls0.phi, ls0.psi, 1e-6);
    if (n <= 16)
    {
      check_sub_volumes(g);
      check_front_structure(m, g);
    }
    const CrackFront3D& f = g.front;
    ASSERT_EQ(g1.front.x, f.x);
    double frame1 = 0.0;
    for (int i = 0; i < g1.front.num_points(); ++i)
    {
      const Point3 p = {f.x[3 * i], f.x[3 * i + 1], f.x[3 * i + 2]};
      const Point3 rp = sub(p, c);
      const Point3 radial = unit(axpy(rp, -dot(rp, nrm), nrm));
      frame1 = std::max(frame1, dist({g1.front.frame[9 * i], g1.front.frame[9 * i + 1], g1.front.frame[9 * i + 2]}, radial));
    }
    ASSERT_EQ(f.num_pieces(), 1);
    EXPECT_EQ(f.closed[0], 1);
    double pos = 0.0, pos2 = 0.0, frame = 0.0, len = 0.0;
    for (int i = 0; i < f.num_points(); ++i)
    {
      const Point3 p = {f.x[3 * i], f.x[3 * i + 1], f.x[3 * i + 2]};
      const auto ls = s.level_sets(p);
      pos = std::max(pos, std::hypot(ls[0], ls[1])); // distance to the circle
      pos2 += ls[0] * ls[0] + ls[1] * ls[1];
      EXPECT_EQ(f.on_boundary[i], 0);
      std::array<Point3, 3> e;
      for (int r = 0; r < 3; ++r)
        e[r] = {f.frame[9 * i + 3 * r], f.frame[9 * i + 3 * r + 1], f.frame[9 * i + 3 * r + 2]};
      for (int r = 0; r < 3; ++r)
        for (int q = 0; q < 3; ++q)
          EXPECT_NEAR(dot(e[r], e[q]), r == q ? 1.0 : 0.0, 1e-14);
      const Point3 e3 = cross(e[0], e[1]);
      EXPECT_LT(dist(e3, e[2]), 1e-14);
      for (int d = 0; d < 3; ++d)
        EXPECT_NEAR(e[1][d], nrm[d], 1e-13);
      const Point3 rp = sub(p, c);
      const Point3 radial = unit(axpy(rp, -dot(rp, nrm), nrm));
      EXPECT_LT(dist(e[0], radial), 1e-14);
    }
    frame = frame1;
    for (int k = 0; k < f.num_segments(); ++k)
    {
      const int i = f.segments[2 * k], j = f.segments[2 * k + 1];
      len += std::hypot(f.x[3 * i] - f.x[3 * j], f.x[3 * i + 1] - f.x[3 * j + 1], f.x[3 * i + 2] - f.x[3 * j + 2]);
    }
    hs.push_back(1.0 / n);
    e_pos.push_back(pos);
    e_rms.push_back(std::sqrt(pos2 / f.num_points()));
    e_area.push_back(std::abs(lip_area(g) - std::numbers::pi * a * a) / (std::numbers::pi * a * a));
    e_len.push_back(std::abs(len - 2 * std::numbers::pi * a) / (2 * std::numbers::pi * a));
    e_frame.push_back(frame);
    std::printf("penny n=%d: front points %d, distance to circle max %.3e rms %.3e, P1 frame e1 error %.3e, "
                "area rel error %.3e, length rel error %.3e\n",
                n, f.num_points(), pos, e_rms.back(), frame, e_area.back(), e_len.back());
  }
  const double r_pos = fit_rate(hs, e_pos), r_rms = fit_rate(hs, e_rms), r_area = fit_rate(hs, e_area), r_len = fit_rate(hs, e_len),
               r_frame = fit_rate(hs, e_frame);
  std::printf("penny rates: position max %.2f rms %.2f, area %.2f, length %.2f, frame %.2f\n", r_pos, r_rms, r_area,
              r_len, r_frame);
  // O(h^2): the least-squares slopes over h = 1/8 .. 1/64; the maximum over
  // the points is noisier (pre-asymptotic on the coarsest mesh) than the rms.
  EXPECT_GT(r_pos, 1.7);
  EXPECT_GT(r_rms, 1.9);
  EXPECT_GT(r_area, 1.8);
  EXPECT_GT(r_len, 1.8);
  EXPECT_GT(r_frame, 0.9);
  EXPECT_LT(e_pos.back(), 2e-4);
  EXPECT_LT(e_area.back(), 1e-3);
}

// Elliptical crack (a != b, tilted axes): the lip area tends to pi a b at
// O(h^2).
TEST(CrackGeometry3D, EllipseLipAreaConvergesToPiAB)
{
  const Point3 c = {0.497, 0.512, 0.488};
  const Point3 nrm = unit(Point3{-0.15, 0.1, 1.0});
  const double a = 0.36, b = 0.18;
  const CrackSurface3D s = create_ellipse_crack(c, nrm, {1.0, 0.6, 0.0}, a, b);
  std::vector<double> hs, err;
  for (const int n : {8, 16, 32, 64})
  {
    const Mesh m(n);
    const CrackGeometry3D g = compute_crack_geometry_3d(m.x, m.cells, s, 1e-6);
    hs.push_back(1.0 / n);
    err.push_back(std::abs(lip_area(g) - std::numbers::pi * a * b) / (std::numbers::pi * a * b));
    std::printf("ellipse n=%d: area rel error %.3e\n", n, err.back());
  }
  const double rate = fit_rate(hs, err);
  std::printf("ellipse area rate %.2f\n", rate);
  EXPECT_GT(rate, 1.8);
  EXPECT_LT(err.back(), 1e-3);
}

// A surface crack: a half-disc (circle centred on the face y = 0) leaves the
// part through that face: one open piece, both ends on the boundary.
TEST(CrackGeometry3D, SurfaceCrackGivesAnOpenPieceEndingOnTheBoundary)
{
  const Mesh m(10);
  const CrackSurface3D s = create_ellipse_crack({0.5, 0.0, 0.513}, {0, 0, 1}, {1, 0, 0}, 0.3, 0.22);
  const CrackGeometry3D g = compute_crack_geometry_3d(m.x, m.cells, s, 1e-6);
  check_sub_volumes(g);
  check_front_structure(m, g);
  const CrackFront3D& f = g.front;
  ASSERT_EQ(f.num_pieces(), 1);
  EXPECT_EQ(f.closed[0], 0);
  const int np = f.num_points();
  EXPECT_EQ(f.on_boundary[0], 1);
  EXPECT_EQ(f.on_boundary[np - 1], 1);
  EXPECT_NEAR(f.x[1], 0.0, 1e-15);
  EXPECT_NEAR(f.x[3 * (np - 1) + 1], 0.0, 1e-15);
  for (int i = 1; i + 1 < np; ++i)
    EXPECT_EQ(f.on_boundary[i], 0);
  // e1 points away from the crack: from the centre outward.
  for (int i = 0; i < np; ++i)
  {
    const Point3 r = {f.x[3 * i] - 0.5, f.x[3 * i + 1], 0.0};
    EXPECT_GT(dot(r, Point3{f.frame[9 * i], f.frame[9 * i + 1], f.frame[9 * i + 2]}), 0.0);
  }
}

// Two separate penny cracks given as one level-set pair would be two
// cracks; one crack with two front pieces: an annulus-free case is a
// polygon crack crossing the whole cube in x with two straight fronts (a
// strip y0 < y < y1): two open pieces, four boundary ends.
TEST(CrackGeometry3D, StripCrackHasTwoOpenPieces)
{
  const Mesh m(7);
  const CrackSurface3D s = create_polygon_crack(plane_polygon({{-3, 0.23}, {4, 0.23}, {4, 0.71}, {-3, 0.71}}, 0.52, 0, 0.02));
  const CrackGeometry3D g = compute_crack_geometry_3d(m.x, m.cells, s, 1e-6);
  check_front_structure(m, g);
  ASSERT_EQ(g.front.num_pieces(), 2);
  for (int p = 0; p < 2; ++p)
  {
    EXPECT_EQ(g.front.closed[p], 0);
    EXPECT_EQ(g.front.on_boundary[g.front.piece_offsets[p]], 1);
    EXPECT_EQ(g.front.on_boundary[g.front.piece_offsets[p + 1] - 1], 1);
    EXPECT_NEAR(g.front.s[g.front.piece_offsets[p + 1] - 1], std::sqrt(1.0 + 0.0), 1e-13);
  }
  EXPECT_NEAR(lip_area(g), 0.48 * std::sqrt(1.0 + 0.02 * 0.02), 1e-12);
}

// Nearest front point and frame interpolation: for points around a straight
// front the projection is the foot of the perpendicular on the exact line.
TEST(CrackGeometry3D, FrontLocatorProjectsOntoTheFront)
{
  const Mesh m(6);
  const double z0 = 0.43, ax = 0.07, ay = 0.11, x0 = 0.61, k = 0.13;
  const CrackSurface3D s = create_polygon_crack(plane_polygon({{-5, -3}, {x0 - 3 * k, -3}, {x0 + 4 * k, 4}, {-5, 4}}, z0, ax, ay));
  const CrackGeometry3D g = compute_crack_geometry_3d(m.x, m.cells, s, 1e-6);
  const FrontLocator loc(g.front);
  const Point3 A = on_plane(x0, 0.0, z0, ax, ay), B = on_plane(x0 + k, 1.0, z0, ax, ay);
  const Point3 t = unit(sub(B, A));
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  for (int q = 0; q < 200; ++q)
  {
    const Point3 p = {u(rng), u(rng), u(rng)};
    const FrontProjection pr = loc.project(p);
    // The front runs from B (s = 0) to A.
    const double s_exact = std::clamp(dot(sub(p, B), scale(-1.0, t)), 0.0, dist(A, B));
    const Point3 foot = axpy(B, -s_exact, t);
    EXPECT_LT(dist(pr.x, foot), 1e-13);
    EXPECT_NEAR(pr.s, s_exact, 1e-13);
    EXPECT_NEAR(pr.distance, dist(p, foot), 1e-13);
    EXPECT_LT(dist(pr.frame[2], scale(-1.0, t)), 1e-13);
    EXPECT_LT(dist(pr.frame[1], unit(Point3{-ax, -ay, 1.0})), 1e-13);
  }
}

// Snapping and degenerate positions, fuzzed: planes and ellipses through
// nodes, fronts through nodes and along edges, tiny offsets below and above
// the snapping threshold. Nothing throws, every sub-tetrahedron has positive
// volume, sub-volumes and slivers sum to the cell's, lip areas are finite.
TEST(CrackGeometry3D, FuzzDegeneratePositions)
{
  const int n = 5;
  const Mesh m(n);
  std::mt19937_64 rng(17);
  std::uniform_int_distribution<int> node(1, n - 1), pick(0, 5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double offsets[] = {0.0, 1e-14, 1e-9, 2e-7, 1e-3};
  int cases = 0, snapped = 0, with_front = 0, degenerate = 0;
  for (int trial = 0; trial < 3000; ++trial)
  {
    const double off = offsets[pick(rng) % 5] * (u(rng) > 0 ? 1 : -1);
    const Point3 c = {double(node(rng)) / n + (pick(rng) == 0 ? off : 0.0), double(node(rng)) / n,
                      double(node(rng)) / n + off};
    std::optional<CrackSurface3D> s;
    const int kind = pick(rng);
    if (kind <= 1)
    {
      // Circle or ellipse through nodes: radius = distance to a node.
      const Point3 nrm = kind == 0 ? Point3{0, 0, 1} : unit(Point3{u(rng), u(rng), 1.0});
      const double r = double(node(rng)) / n * (kind == 0 ? 1.0 : 0.9);
      s = create_ellipse_crack(c, nrm, {1, 0, 0}, r, kind == 0 ? r : 0.6 * r);
    }
    else if (kind <= 3)
    {
      // Polygon in z = const through nodes, front on x = const through nodes
      // (or slanted), possibly offset.
      const double xf = double(node(rng)) / n + (kind == 3 ? off : 0.0);
      const double sl = kind == 3 ? 0.0 : u(rng);
      s = create_polygon_crack(plane_polygon({{-5, -3}, {xf - 3 * sl, -3}, {xf + 4 * sl, 4}, {-5, 4}}, c[2], 0, 0));
    }
    else
    {
      // A square crack with corners at nodes.
      const double x1 = c[0] + 2.0 / n, y1 = c[1] + 2.0 / n;
      s = create_polygon_crack(plane_polygon({{c[0] - 1.0 / n, c[1] - 1.0 / n}, {x1, c[1] - 1.0 / n}, {x1, y1}, {c[0] - 1.0 / n, y1}},
                                             c[2], kind == 5 ? 0.1 : 0.0, 0.0));
    }
    CrackGeometry3D g;
    try
    {
      g = compute_crack_geometry_3d(m.x, m.cells, *s, 1e-6);
    }
    catch (const CrackOutsideMesh&)
    {
      continue;
    }
    ++cases;
    snapped += g.num_snapped > 0;
    with_front += g.front.num_points() > 0;
    check_sub_volumes(g);
    if (::testing::Test::HasFailure())
    {
      std::printf("trial %d kind %d off %g c (%g %g %g)\n", trial, kind, off, c[0], c[1], c[2]);
      return;
    }
    degenerate += check_front_structure(m, g) > 0;
    if (::testing::Test::HasFailure())
    {
      std::printf("trial %d kind %d off %g c (%g %g %g)\n", trial, kind, off, c[0], c[1], c[2]);
      return;
    }
    EXPECT_TRUE(std::isfinite(lip_area(g)));
    for (double v : g.front.frame)
      ASSERT_TRUE(std::isfinite(v));
  }
  std::printf("fuzz: %d configurations, %d with snapped nodes, %d with a front, %d with degenerate front cells\n",
              cases, snapped, with_front, degenerate);
  EXPECT_GT(cases, 2500);
  EXPECT_GT(snapped, 500);
  EXPECT_GT(with_front, 1500);
}

TEST(CrackGeometry3D, CrackOutsideThePartNamesBothBoxes)
{
  const Mesh m(3);
  const CrackSurface3D s = create_ellipse_crack({5.0, 5.0, 0.5}, {0, 0, 1}, {1, 0, 0}, 0.3, 0.2);
  try
  {
    compute_crack_geometry_3d(m.x, m.cells, s, 1e-6);
    FAIL() << "no error";
  }
  catch (const CrackOutsideMesh& e)
  {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("ellipse crack (centre (5, 5, 0.5)"), std::string::npos) << msg;
    EXPECT_NE(msg.find("bounding box [4.7, 5.3] x [4.8, 5.2] x [0.5, 0.5]"), std::string::npos) << msg;
    EXPECT_NE(msg.find("mesh (bounding box [0, 1] x [0, 1] x [0, 1])"), std::string::npos) << msg;
    EXPECT_NE(msg.find("its plane crosses"), std::string::npos) << msg;
  }
}

TEST(CrackGeometry3D, BadArraysAndDegenerateLevelSets)
{
  const Mesh m(2);
  const std::size_t nn = m.x.size() / 3;
  std::vector<double> phi(nn, 1.0), psi(nn, -1.0);
  EXPECT_THROW(compute_crack_geometry_3d(m.x, m.cells, std::span(phi).first(nn - 1), psi, 1e-6), std::invalid_argument);
  EXPECT_THROW(compute_crack_geometry_3d(m.x, m.cells, phi, psi, 0.7), std::invalid_argument);
  // phi = 0 at all nodes of a cell.
  std::vector<double> z(nn, 0.0);
  EXPECT_THROW(compute_crack_geometry_3d(m.x, m.cells, z, psi, 1e-6), std::runtime_error);
  // psi = phi: psi vanishes on the whole zero set of phi, so there is no
  // crack ({phi = 0, psi < 0} is empty): no lip facet, no front segment.
  for (std::size_t i = 0; i < nn; ++i)
    phi[i] = m.x[3 * i + 2] - 0.3, psi[i] = phi[i];
  const CrackGeometry3D g = compute_crack_geometry_3d(m.x, m.cells, phi, psi, 1e-6);
  EXPECT_EQ(lip_area(g), 0.0);
  EXPECT_EQ(g.front.num_points(), 0);
  // psi proportional to phi on a front cell's zero polygon is impossible
  // (it would vanish there); psi = 2 (z - 0.3) + (x - 0.5) crosses it.
  for (std::size_t i = 0; i < nn; ++i)
    psi[i] = 2 * phi[i] + m.x[3 * i] - 0.5;
  EXPECT_NO_THROW(compute_crack_geometry_3d(m.x, m.cells, phi, psi, 1e-6));
}
