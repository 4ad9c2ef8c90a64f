#include "quadrature/front_rules_3d.h"

#include "geometry/vec3.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cracklip::quadrature
{
using namespace cracklip::vec3;

namespace
{
V vertex(std::span<const double> xv, int i) { return {xv[3 * i], xv[3 * i + 1], xv[3 * i + 2]}; }

void check_points(int a, int b, int c, const char* what)
{
  if (a < 1 or b < 1 or c < 1)
    throw std::invalid_argument(std::string(what) + ": numbers of points must be >= 1");
}

/// Largest |b| a decomposition point F may have (barycentric in the far
/// face or edge): beyond, the front is parallel to that face within 1e-3
/// and the plain collapse converges fast; round-off grows like max |b|.
constexpr double max_decomposition = 1000.0;
} // namespace

Rule tetrahedron_edge_collapsed(std::span<const double, 12> xv, int n_tau, int n_eta, int n_t)
{
  check_points(n_tau, n_eta, n_t, "tetrahedron_edge_collapsed");
  const V A = vertex(xv, 0), B = vertex(xv, 1), C = vertex(xv, 2), D = vertex(xv, 3);
  const V AB = sub(B, A);
  const double lab2 = dot(AB, AB);
  if (!(lab2 > 0.0))
    throw std::invalid_argument("tetrahedron_edge_collapsed: the front edge AB has zero length");
  // Parts of C - A and D - A normal to AB; the angular substitution.
  const V Cn = axpy(sub(C, A), -dot(sub(C, A), AB) / lab2, AB);
  const V Dn = axpy(sub(D, A), -dot(sub(D, A), AB) / lab2, AB);
  const V E = sub(Dn, Cn);
  const double L = norm(E);
  const double h0 = L > 0.0 ? norm(cross(Cn, Dn)) / L : 0.0;
  const double s0 = L > 0.0 ? dot(Cn, E) / L : 0.0;
  // sinh substitution unless degenerate (a flat tetrahedron: h0 ~ 0).
  const bool sinh_map = L > 0.0 and h0 > 1e-14 * L;
  const double u0 = sinh_map ? std::asinh(s0 / h0) : 0.0, u1 = sinh_map ? std::asinh((s0 + L) / h0) : 1.0;
  const Rule &gt = gauss_legendre_cached(n_tau), &gu = gauss_legendre_cached(n_eta), &ga = gauss_legendre_cached(n_t);
  Rule rule;
  rule.dim = 3;
  rule.points.reserve(3 * n_tau * n_eta * n_t);
  rule.weights.reserve(n_tau * n_eta * n_t);
  for (int j = 0; j < n_eta; ++j)
  {
    const double u = u0 + (u1 - u0) * gu.points[j];
    const double eta = sinh_map ? (h0 * std::sinh(u) - s0) / L : u;
    const double deta = sinh_map ? (u1 - u0) * h0 * std::cosh(u) / L : 1.0;
    for (int i = 0; i < n_tau; ++i)
    {
      const double tau = gt.points[i], rho = tau * tau;
      for (int k = 0; k < n_t; ++k)
      {
        const double t = ga.points[k];
        rule.points.insert(rule.points.end(), {(1.0 - rho) * t, rho * (1.0 - eta), rho * eta});
        rule.weights.push_back(gt.weights[i] * gu.weights[j] * ga.weights[k] * deta * 2.0 * tau * rho
                               * (1.0 - rho));
      }
    }
  }
  return rule;
}

Rule tetrahedron_point_collapsed(std::span<const double, 12> xv, std::span<const double, 3> front, int n_tau,
                                 int n_eta, int n_t)
{
  check_points(n_tau, n_eta, n_t, "tetrahedron_point_collapsed");
  const V A = vertex(xv, 0), B = vertex(xv, 1), C = vertex(xv, 2), D = vertex(xv, 3);
  const V d = {front[0], front[1], front[2]};
  if (!(norm(d) > 0.0))
    throw std::invalid_argument("tetrahedron_point_collapsed: the front direction is zero");
  // Where the front line meets the plane of BCD: F = A + lam d, with
  // barycentric coordinates (bB, bC, bD) in BCD.
  const V nu = cross(sub(C, B), sub(D, B));
  const double dn = dot(d, nu);
  Rule rule;
  rule.dim = 3;
  if (std::abs(dn) > 1e-12 * norm(d) * norm(nu))
  {
    const V F = axpy(A, dot(sub(B, A), nu) / dn, d);
    const double area2 = dot(nu, nu);
    const double bB = dot(cross(sub(C, F), sub(D, F)), nu) / area2;
    const double bC = dot(cross(sub(D, F), sub(B, F)), nu) / area2;
    const double bD = 1.0 - bB - bC;
    if (std::max({std::abs(bB), std::abs(bC), std::abs(bD)}) <= max_decomposition)
    {
      // Pieces (A, F, X, Y) with weight b: AFCD (bB), AFDB (bC), AFBC (bD).
      // In ABCD's coordinates F - A = (bB, bC, bD), X - A a unit vector.
      const std::array<double, 3> f = {bB, bC, bD};
      const std::array<std::array<int, 2>, 3> xy = {{{1, 2}, {2, 0}, {0, 1}}}; // C,D / D,B / B,C as axes
      const std::array<V, 3> vert = {B, C, D};
      for (int k = 0; k < 3; ++k)
      {
        if (std::abs(f[k]) <= 1e-14)
          continue;
        const V X = vert[xy[k][0]], Y = vert[xy[k][1]];
        const std::array<double, 12> piece = {A[0], A[1], A[2], F[0], F[1], F[2],
                                              X[0], X[1], X[2], Y[0], Y[1], Y[2]};
        const Rule r = tetrahedron_edge_collapsed(piece, n_tau, n_eta, n_t);
        for (int q = 0; q < r.size(); ++q)
        {
          const double a = r.points[3 * q], b = r.points[3 * q + 1], c = r.points[3 * q + 2];
          std::array<double, 3> p = {a * f[0], a * f[1], a * f[2]};
          p[xy[k][0]] += b;
          p[xy[k][1]] += c;
          rule.points.insert(rule.points.end(), p.begin(), p.end());
          rule.weights.push_back(f[k] * r.weights[q]);
        }
      }
      return rule;
    }
  }
  // Far: the plain collapse onto A.
  return tetrahedron_vertex_collapsed(n_tau, std::max(n_eta, n_t));
}

Rule tetrahedron_vertex_collapsed(int n_tau, int n)
{
  check_points(n_tau, n, 1, "tetrahedron_vertex_collapsed");
  // x = A + rho ((1 - s1 - s2) (B - A) + s1 (C - A) + s2 (D - A)),
  // dV = rho^2 drho dsigma (in the reference measure), rho = tau^2.
  const Rule& gt = gauss_legendre_cached(n_tau);
  const Rule tri = triangle_product(n);
  Rule rule;
  rule.dim = 3;
  for (int i = 0; i < n_tau; ++i)
  {
    const double tau = gt.points[i], rho = tau * tau;
    for (int q = 0; q < tri.size(); ++q)
    {
      const double s1 = tri.points[2 * q], s2 = tri.points[2 * q + 1];
      rule.points.insert(rule.points.end(), {rho * (1.0 - s1 - s2), rho * s1, rho * s2});
      rule.weights.push_back(gt.weights[i] * tri.weights[q] * 2.0 * tau * rho * rho);
    }
  }
  return rule;
}

Rule triangle_edge_collapsed(int n_tau, int n_t)
{
  check_points(n_tau, n_t, 1, "triangle_edge_collapsed");
  const Rule &gt = gauss_legendre_cached(n_tau), &ga = gauss_legendre_cached(n_t);
  Rule rule;
  rule.dim = 2;
  for (int i = 0; i < n_tau; ++i)
  {
    const double tau = gt.points[i], beta = tau * tau;
    for (int k = 0; k < n_t; ++k)
    {
      rule.points.insert(rule.points.end(), {(1.0 - beta) * ga.points[k], beta});
      rule.weights.push_back(gt.weights[i] * ga.weights[k] * 2.0 * tau * (1.0 - beta));
    }
  }
  return rule;
}

Rule triangle_point_collapsed(std::span<const double, 9> xv, std::span<const double, 3> front, int n_tau, int n_t)
{
  check_points(n_tau, n_t, 1, "triangle_point_collapsed");
  const V A = vertex(xv, 0), B = vertex(xv, 1), C = vertex(xv, 2);
  const V d = {front[0], front[1], front[2]};
  // The front line A + lam d meets the line B + s (C - B) where
  // (B - A + s (C - B)) x d = 0: s = -((B - A) x d).n / ((C - B) x d).n,
  // n the triangle's normal.
  const V n = cross(sub(B, A), sub(C, A));
  const double den = dot(cross(sub(C, B), d), n);
  if (std::abs(den) > 1e-12 * norm(sub(C, B)) * norm(d) * norm(n))
  {
    const double s = -dot(cross(sub(B, A), d), n) / den;
    if (std::max(std::abs(s), std::abs(1.0 - s)) <= max_decomposition)
    {
      // F - A = (1 - s, s) in ABC's coordinates; pieces AFC (1 - s), AFB (s).
      const Rule r = triangle_edge_collapsed(n_tau, n_t);
      Rule rule;
      rule.dim = 2;
      for (const auto& [X, w] : {std::pair{1, 1.0 - s}, std::pair{0, s}})
      {
        if (std::abs(w) <= 1e-14)
          continue;
        for (int q = 0; q < r.size(); ++q)
        {
          const double a = r.points[2 * q], b = r.points[2 * q + 1];
          std::array<double, 2> p = {a * (1.0 - s), a * s};
          p[X] += b;
          rule.points.insert(rule.points.end(), p.begin(), p.end());
          rule.weights.push_back(w * r.weights[q]);
        }
      }
      return rule;
    }
  }
  return tip_fan(n_tau, n_t);
}

namespace
{
/// The point of the line (origin, direction d) nearest to p.
V nearest_on_line(const V& p, const V& origin, const V& d)
{
  const V e = unit(d);
  return axpy(origin, dot(sub(p, origin), e), e);
}
} // namespace

Rule tetrahedron_near_front(std::span<const double, 12> xv, std::span<const double, 3> origin,
                            std::span<const double, 3> front, int n_tau, int n_eta, int n_t)
{
  const std::array<V, 4> X = {vertex(xv, 0), vertex(xv, 1), vertex(xv, 2), vertex(xv, 3)};
  const V d = {front[0], front[1], front[2]};
  if (!(norm(d) > 0.0))
    throw std::invalid_argument("tetrahedron_near_front: the front direction is zero");
  const V centroid = scale(0.25, add(add(X[0], X[1]), add(X[2], X[3])));
  const V O = nearest_on_line(centroid, {origin[0], origin[1], origin[2]}, d);
  const double vol = dot(sub(X[1], X[0]), cross(sub(X[2], X[0]), sub(X[3], X[0])));
  // Faces oriented so that vol(O, face) sums to vol(ABCD): (B, C, D),
  // (A, D, C), (A, B, D), (A, C, B).
  static constexpr int faces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  // O in ABCD's coordinates (x = A + o . (B - A, C - A, D - A)).
  const V e1 = sub(X[1], X[0]), e2 = sub(X[2], X[0]), e3 = sub(X[3], X[0]), w = sub(O, X[0]);
  const V o = {dot(w, cross(e2, e3)) / vol, dot(e1, cross(w, e3)) / vol, dot(e1, cross(e2, w)) / vol};
  const std::array<V, 4> ref = {V{0, 0, 0}, V{1, 0, 0}, V{0, 1, 0}, V{0, 0, 1}};
  Rule rule;
  rule.dim = 3;
  for (const auto& f : faces)
  {
    const V &P = X[f[0]], &Q = X[f[1]], &R = X[f[2]];
    const double cone = dot(sub(P, O), cross(sub(Q, O), sub(R, O)));
    if (std::abs(cone) <= 1e-14 * std::abs(vol))
      continue;
    const std::array<double, 12> cv = {O[0], O[1], O[2], P[0], P[1], P[2], Q[0], Q[1], Q[2], R[0], R[1], R[2]};
    const Rule r = tetrahedron_point_collapsed(cv, front, n_tau, n_eta, n_t);
    const V a = sub(ref[f[0]], o), b = sub(ref[f[1]], o), c = sub(ref[f[2]], o);
    for (int q = 0; q < r.size(); ++q)
    {
      const double* p = &r.points[3 * q];
      const V pt = axpy(axpy(axpy(o, p[0], a), p[1], b), p[2], c);
      rule.points.insert(rule.points.end(), pt.begin(), pt.end());
      rule.weights.push_back(r.weights[q] * cone / vol);
    }
  }
  return rule;
}

Rule triangle_near_front(std::span<const double, 9> xv, std::span<const double, 3> origin,
                         std::span<const double, 3> front, int n_tau, int n_t)
{
  const std::array<V, 3> X = {vertex(xv, 0), vertex(xv, 1), vertex(xv, 2)};
  const V d = {front[0], front[1], front[2]};
  if (!(norm(d) > 0.0))
    throw std::invalid_argument("triangle_near_front: the front direction is zero");
  const V centroid = scale(1.0 / 3.0, add(add(X[0], X[1]), X[2]));
  const V O = nearest_on_line(centroid, {origin[0], origin[1], origin[2]}, d);
  const V n = cross(sub(X[1], X[0]), sub(X[2], X[0]));
  const double n2 = dot(n, n); // (2 area)^2: signed area ratios are (u x v) . n / n2
  // O in ABC's coordinates (least squares in the plane: O lies in it).
  const V e1 = sub(X[1], X[0]), e2 = sub(X[2], X[0]), w = sub(O, X[0]);
  const std::array<double, 2> o = {dot(cross(w, e2), n) / n2, dot(cross(e1, w), n) / n2};
  const std::array<std::array<double, 2>, 3> ref = {{{0, 0}, {1, 0}, {0, 1}}};
  Rule rule;
  rule.dim = 2;
  for (int k = 0; k < 3; ++k)
  {
    const int i = k, j = (k + 1) % 3;
    const double fan = dot(cross(sub(X[i], O), sub(X[j], O)), n);
    if (std::abs(fan) <= 1e-14 * n2)
      continue;
    const std::array<double, 9> fv = {O[0], O[1], O[2], X[i][0], X[i][1], X[i][2], X[j][0], X[j][1], X[j][2]};
    const Rule r = triangle_point_collapsed(fv, front, n_tau, n_t);
    for (int q = 0; q < r.size(); ++q)
    {
      const double a = r.points[2 * q], b = r.points[2 * q + 1];
      rule.points.push_back(o[0] + a * (ref[i][0] - o[0]) + b * (ref[j][0] - o[0]));
      rule.points.push_back(o[1] + a * (ref[i][1] - o[1]) + b * (ref[j][1] - o[1]));
      rule.weights.push_back(r.weights[q] * fan / n2);
    }
  }
  return rule;
}

} // namespace cracklip::quadrature
