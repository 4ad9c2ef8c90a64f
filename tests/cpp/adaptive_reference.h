// Adaptive reference integration for the quadrature tests (no DOLFINx).
//
// Global adaptive Gauss-Kronrod (7-15 points, the QUADPACK pair): the
// interval of largest error estimate is bisected until the sum of the
// estimates is below the tolerance. Nested for 2D and 3D integrals; the
// singular integrands of the tests are integrable, and their endpoint or
// near-endpoint singularities are resolved by the bisection.
#pragma once

#include "geometry/vec3.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <queue>
#include <string>
#include <stdexcept>
#include <vector>

namespace cracklip::test
{

/// int_a^b f to the absolute tolerance tol or the relative one rel, the
/// larger (pieces at round-off accepted; at most max_intervals pieces, else
/// throws).
inline double adaptive_integral(const std::function<double(double)>& f, double a, double b, double tol,
                                int max_intervals = 20000, double rel = 1e-13)
{
  // Kronrod nodes (the even-indexed ones 1, 3, 5, 7 are the Gauss nodes)
  // and weights on [-1, 1].
  static constexpr double xk[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                                   0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                                   0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                                   0.207784955007898467600689403773245, 0.0};
  static constexpr double wk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                                   0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                                   0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                                   0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
  static constexpr double wg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                                   0.381830050505118944950369775488975, 0.417959183673469387755102040816327};
  struct Piece
  {
    double a, b, value, error, absval;
    bool operator<(const Piece& o) const { return error < o.error; }
  };
  auto gk = [&](double lo, double hi)
  {
    const double c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
    const double fc = f(c);
    double k = wk[7] * fc, g = wg[3] * fc, ka = wk[7] * std::abs(fc);
    for (int i = 0; i < 7; ++i)
    {
      const double f1 = f(c - h * xk[i]), f2 = f(c + h * xk[i]);
      k += wk[i] * (f1 + f2);
      ka += wk[i] * (std::abs(f1) + std::abs(f2));
      if (i % 2 == 1)
        g += wg[i / 2] * (f1 + f2);
    }
    return Piece{lo, hi, k * h, std::abs((k - g) * h), ka * std::abs(h)};
  };
  // Pieces whose error estimate is at round-off (below 1e-14 of the
  // integral of |f| over them) are accepted and set aside; the others are
  // bisected, largest error first, until their errors sum to at most tol.
  std::priority_queue<Piece> heap;
  double done = 0.0, value = 0.0, error = 0.0;
  auto push = [&](const Piece& p)
  {
    if (p.error <= 1e-14 * p.absval)
      done += p.value;
    else
    {
      heap.push(p);
      value += p.value;
      error += p.error;
    }
  };
  push(gk(a, b));
  int n = 1;
  while (!heap.empty() and error > std::max(tol, rel * std::abs(value + done)))
  {
    if (++n > max_intervals)
    {
      char msg[200];
      std::snprintf(msg, sizeof msg, "adaptive_integral: tolerance %.3e not reached on [%g, %g]: error %.3e, value %.6e",
                    tol, a, b, error, value + done);
      throw std::runtime_error(msg);
    }
    const Piece p = heap.top();
    heap.pop();
    value -= p.value;
    error -= p.error;
    const double m = 0.5 * (p.a + p.b);
    push(gk(p.a, m));
    push(gk(m, p.b));
  }
  // Re-sum to avoid the drift of the running updates.
  value = done;
  while (!heap.empty())
  {
    value += heap.top().value;
    heap.pop();
  }
  return value;
}

/// int_0^1 du int_0^1 dv int_0^1 dw f(u, v, w), nested (outer u), each
/// level to a tenth of the tolerance of the level around it.
inline double adaptive_cube(const std::function<double(double, double, double)>& f, double tol)
{
  return adaptive_integral(
      [&](double u)
      {
        return adaptive_integral(
            [&](double v) { return adaptive_integral([&](double w) { return f(u, v, w); }, 0.0, 1.0, 0.01 * tol); },
            0.0, 1.0, 0.1 * tol);
      },
      0.0, 1.0, tol);
}

/// int over the unit square of f(u, v), nested.
inline double adaptive_square(const std::function<double(double, double)>& f, double tol)
{
  return adaptive_integral(
      [&](double u) { return adaptive_integral([&](double v) { return f(u, v); }, 0.0, 1.0, 0.1 * tol); }, 0.0, 1.0,
      tol);
}

using Fr = std::function<double(const std::array<double, 3>&, double)>;

/// int_T f(x, r) over the tetrahedron X (4 points) with its edge X0 X1 on a
/// front line, r the distance to that line, in plain collapsed coordinates:
/// x = X0 + (1 - rho) t (X1 - X0) + rho (1 - eta) (X2 - X0) + rho eta (X3 - X0),
/// dV = 6 |T| rho (1 - rho) drho deta dt; r = rho |(1 - eta) C' + eta D'|
/// (C', D' the parts of X2 - X0, X3 - X0 normal to the edge), evaluated so,
/// without the cancellation of |x - X0| minus its part along the edge.
inline double edge_reference(const std::array<std::array<double, 3>, 4>& X, const Fr& f, double tol)
{
  using namespace vec3;
  const V e = unit(sub(X[1], X[0]));
  const V Cn = axpy(sub(X[2], X[0]), -dot(sub(X[2], X[0]), e), e), Dn = axpy(sub(X[3], X[0]), -dot(sub(X[3], X[0]), e), e);
  const double V6 = std::abs(dot(sub(X[1], X[0]), cross(sub(X[2], X[0]), sub(X[3], X[0]))));
  return V6 * adaptive_cube(
                  [&](double eta, double rho, double t)
                  {
                    const V x = axpy(axpy(axpy(X[0], (1 - rho) * t, sub(X[1], X[0])), rho * (1 - eta), sub(X[2], X[0])),
                                     rho * eta, sub(X[3], X[0]));
                    return rho * (1 - rho) * f(x, rho * norm(axpy(scale(1 - eta, Cn), eta, Dn)));
                  },
                  tol / V6);
}

/// int_T f(x, r) with X0 on a front line along the unit vector e, r the
/// distance to that line: x = X0 + rho Q, Q = (1 - s1 - s2) (X1 - X0) +
/// s1 (X2 - X0) + s2 (X3 - X0), s2 = (1 - s1) v, dV = 6 |T| rho^2 (1 - s1)
/// drho ds1 dv; r = rho |Q'| (Q' the part of Q normal to e).
inline double point_reference(const std::array<std::array<double, 3>, 4>& X, const std::array<double, 3>& e,
                              const Fr& f, double tol)
{
  using namespace vec3;
  const double V6 = std::abs(dot(sub(X[1], X[0]), cross(sub(X[2], X[0]), sub(X[3], X[0]))));
  return V6 * adaptive_cube(
                  [&](double s1, double v, double rho)
                  {
                    const double s2 = (1 - s1) * v;
                    const V Q = axpy(axpy(scale(1 - s1 - s2, sub(X[1], X[0])), s1, sub(X[2], X[0])), s2, sub(X[3], X[0]));
                    return (1 - s1) * rho * rho * f(axpy(X[0], rho, Q), rho * norm(axpy(Q, -dot(Q, e), e)));
                  },
                  tol / V6);
}

} // namespace cracklip::test
