#include "geometry/cut_tetrahedron.h"

#include "geometry/vec3.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace cracklip
{
namespace
{
using vec3::cross, vec3::dot, vec3::sub;

int sgn(double v) { return (v > 0.0) - (v < 0.0); }

/// Points of a cut: the input vertices first, then cut points on edges.
template <std::size_t N>
struct PointList
{
  int& n;
  std::array<Point3, N>& x;
  std::array<CutPoint, N>& from;

  int add_vertex(const Point3& p, int a)
  {
    x[n] = p;
    from[n] = {a, a, 0.0};
    return n++;
  }
  /// The zero of f on edge (a, b), where f_a and f_b have opposite signs.
  int add_cut(int a, int b, double fa, double fb)
  {
    const double t = fa / (fa - fb);
    for (int d = 0; d < 3; ++d)
      x[n][d] = x[a][d] + t * (x[b][d] - x[a][d]);
    from[n] = {a, b, t};
    return n++;
  }
};

void check_values(std::span<const double> f, const char* what)
{
  bool all_zero = true;
  for (double v : f)
  {
    if (!std::isfinite(v))
      throw std::invalid_argument(std::string(what) + ": a level-set value is not finite");
    all_zero = all_zero and v == 0.0;
  }
  if (all_zero)
    throw std::invalid_argument(std::string(what)
                                + ": all level-set values are zero (the simplex lies on the zero set)");
}
} // namespace

double signed_volume(const Point3& a, const Point3& b, const Point3& c, const Point3& d)
{
  return dot(sub(b, a), cross(sub(c, a), sub(d, a))) / 6.0;
}

void cut_tetrahedron(std::span<const double, 12> xin, std::array<double, 4> f, TetrahedronCut& out)
{
  check_values(f, "cut_tetrahedron");
  out = TetrahedronCut{};
  PointList<8> pts{out.num_points, out.x, out.from};
  for (int i = 0; i < 4; ++i)
    pts.add_vertex({xin[3 * i], xin[3 * i + 1], xin[3 * i + 2]}, i);

  std::array<int, 4> s;
  int npos = 0, nneg = 0;
  for (int i = 0; i < 4; ++i)
  {
    s[i] = sgn(f[i]);
    npos += s[i] > 0;
    nneg += s[i] < 0;
  }
  const int nzero = 4 - npos - nneg;

  auto add_tet = [&](int a, int b, int c, int d, int side)
  {
    std::array<int, 4> t = {a, b, c, d};
    if (signed_volume(out.x[a], out.x[b], out.x[c], out.x[d]) < 0.0)
      std::swap(t[2], t[3]);
    out.tets[out.num_tets] = t;
    out.side[out.num_tets++] = static_cast<std::int8_t>(side);
  };
  // Orient an interface triangle so that its normal points to f > 0: test
  // it against the input vertex of largest |f| (the most robust sign).
  int far = 0;
  for (int i = 1; i < 4; ++i)
    if (std::abs(f[i]) > std::abs(f[far]))
      far = i;
  auto add_interface = [&](int a, int b, int c)
  {
    const Point3 n = cross(sub(out.x[b], out.x[a]), sub(out.x[c], out.x[a]));
    if (dot(n, sub(out.x[far], out.x[a])) * f[far] < 0.0)
      std::swap(b, c);
    out.interface[out.num_interface++] = {a, b, c};
  };
  // Vertex indices by sign.
  std::array<int, 4> pos{}, neg{}, zero{};
  {
    int ip = 0, in = 0, iz = 0;
    for (int i = 0; i < 4; ++i)
      (s[i] > 0 ? pos[ip++] : (s[i] < 0 ? neg[in++] : zero[iz++])) = i;
  }

  if (npos == 0 or nneg == 0)
  {
    // One side: the tetrahedron itself, touching the zero set at nzero vertices.
    const int side = npos > 0 ? 1 : -1;
    add_tet(0, 1, 2, 3, side);
    out.kind = nzero == 0 ? ZeroSet::none
                          : (nzero == 1 ? ZeroSet::vertex : (nzero == 2 ? ZeroSet::edge : ZeroSet::face));
    if (nzero == 3)
      add_interface(zero[0], zero[1], zero[2]);
    return;
  }
  out.kind = ZeroSet::cut;

  if (nzero == 2)
  {
    // One + and one - vertex: the zero plane holds the two zero vertices.
    const int p = pos[0], n = neg[0], z0 = zero[0], z1 = zero[1];
    const int C = pts.add_cut(p, n, f[p], f[n]);
    add_tet(z0, z1, C, p, +1);
    add_tet(z0, z1, C, n, -1);
    add_interface(z0, z1, C);
    return;
  }

  // The lone vertex: the only one of its sign (absent in the 2-2 case).
  const bool lone_pos = npos == 1;
  const int a = lone_pos ? pos[0] : neg[0];
  const int a_side = lone_pos ? 1 : -1;
  if (nzero == 1)
  {
    // Lone vertex a, zero vertex z, b and c on the other side.
    const int z = zero[0];
    const std::array<int, 4>& others = lone_pos ? neg : pos;
    const int b = others[0], c = others[1];
    const int P = pts.add_cut(a, b, f[a], f[b]), Q = pts.add_cut(a, c, f[a], f[c]);
    add_tet(a, z, P, Q, a_side);
    // Pyramid: apex z over the quad (b, c, Q, P) in the face (a, b, c).
    add_tet(z, b, c, Q, -a_side);
    add_tet(z, b, Q, P, -a_side);
    add_interface(z, P, Q);
    return;
  }

  auto add_prism = [&](std::array<int, 3> u, std::array<int, 3> v, int side)
  {
    // Prism u0 u1 u2 / v0 v1 v2 (ui - vi lateral edges, planar lateral quads):
    // diagonals u1-v0, u2-v1, u2-v0, an acyclic choice, so three tetrahedra.
    add_tet(u[0], u[1], u[2], v[0], side);
    add_tet(u[1], u[2], v[0], v[1], side);
    add_tet(u[2], v[0], v[1], v[2], side);
  };
  if (npos == 1 or nneg == 1)
  {
    // Lone vertex a against b, c, d: a triangle, a tetrahedron and a prism.
    const std::array<int, 4>& others = lone_pos ? neg : pos;
    const int b = others[0], c = others[1], d = others[2];
    const int Pb = pts.add_cut(a, b, f[a], f[b]), Pc = pts.add_cut(a, c, f[a], f[c]),
              Pd = pts.add_cut(a, d, f[a], f[d]);
    add_tet(a, Pb, Pc, Pd, a_side);
    add_prism({Pb, Pc, Pd}, {b, c, d}, -a_side);
    add_interface(Pb, Pc, Pd);
    return;
  }
  // Two against two: a quad interface between two prisms.
  const int a0 = neg[0], a1 = neg[1], b0 = pos[0], b1 = pos[1];
  const int P00 = pts.add_cut(a0, b0, f[a0], f[b0]), P01 = pts.add_cut(a0, b1, f[a0], f[b1]);
  const int P10 = pts.add_cut(a1, b0, f[a1], f[b0]), P11 = pts.add_cut(a1, b1, f[a1], f[b1]);
  add_prism({a0, P00, P01}, {a1, P10, P11}, -1);
  add_prism({b0, P00, P10}, {b1, P01, P11}, +1);
  add_interface(P00, P01, P11);
  add_interface(P00, P11, P10);
}

void cut_triangle(std::span<const double, 9> xin, std::array<double, 3> f, TriangleCut& out)
{
  check_values(f, "cut_triangle");
  out = TriangleCut{};
  PointList<5> pts{out.num_points, out.x, out.from};
  for (int i = 0; i < 3; ++i)
    pts.add_vertex({xin[3 * i], xin[3 * i + 1], xin[3 * i + 2]}, i);
  std::array<int, 3> s;
  int npos = 0, nneg = 0;
  for (int i = 0; i < 3; ++i)
  {
    s[i] = sgn(f[i]);
    npos += s[i] > 0;
    nneg += s[i] < 0;
  }
  const int nzero = 3 - npos - nneg;
  auto add_tri = [&](int a, int b, int c, int side)
  {
    out.tris[out.num_tris] = {a, b, c};
    out.side[out.num_tris++] = static_cast<std::int8_t>(side);
  };
  if (npos == 0 or nneg == 0)
  {
    add_tri(0, 1, 2, npos > 0 ? 1 : -1);
    out.kind = nzero == 0 ? ZeroSet::none : (nzero == 1 ? ZeroSet::vertex : ZeroSet::edge);
    if (nzero == 2)
    {
      const int k = s[0] != 0 ? 0 : (s[1] != 0 ? 1 : 2);
      out.zero_segment = {(k + 1) % 3, (k + 2) % 3};
    }
    return;
  }
  out.kind = ZeroSet::cut;
  if (nzero == 1)
  {
    // Zero vertex k; the cut point C on the opposite edge (b, c) keeps the
    // cyclic order k, b, c.
    const int k = s[0] == 0 ? 0 : (s[1] == 0 ? 1 : 2);
    const int b = (k + 1) % 3, c = (k + 2) % 3;
    const int C = pts.add_cut(b, c, f[b], f[c]);
    add_tri(k, b, C, s[b]);
    add_tri(k, C, c, s[c]);
    out.zero_segment = {k, C};
    return;
  }
  // Lone vertex a (cyclic order a, b, c); cut points P on (a, b), Q on (a, c).
  const int a = (s[0] != s[1] and s[0] != s[2]) ? 0 : ((s[1] != s[0] and s[1] != s[2]) ? 1 : 2);
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  const int P = pts.add_cut(a, b, f[a], f[b]), Q = pts.add_cut(a, c, f[a], f[c]);
  add_tri(a, P, Q, s[a]);
  add_tri(P, b, c, s[b]);
  add_tri(P, c, Q, s[b]);
  out.zero_segment = {P, Q};
}

} // namespace cracklip
