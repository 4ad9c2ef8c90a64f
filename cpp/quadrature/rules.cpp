#include "quadrature/rules.h"

#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>

namespace cracklip::quadrature
{

namespace
{
/// Conical product rule on the reference triangle: nu x nv Gauss points of
/// the unit square mapped by xi = u, eta = (1 - u) v (Jacobian 1 - u).
Rule conical_product(int nu, int nv);
} // namespace

Rule gauss_legendre(int n) { return gauss_legendre_cached(n); }

const Rule& gauss_legendre_cached(int n)
{
  // Rules by n, computed once (single-threaded, as the kernels that call it).
  static std::vector<std::unique_ptr<Rule>> cache;
  if (n >= 1 and n < static_cast<int>(cache.size()) and cache[n])
    return *cache[n];
  if (n < 1)
    throw std::invalid_argument("gauss_legendre: n must be >= 1, got "
                                + std::to_string(n));
  Rule rule;
  rule.dim = 1;
  rule.points.resize(n);
  rule.weights.resize(n);
  // Newton iteration on P_n from Chebyshev initial guesses, on [-1, 1].
  for (int i = 0; i < n; ++i)
  {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int it = 0; it < 100; ++it)
    {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k)
      {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      const double pn = (n == 1) ? x : p1;
      const double pnm1 = (n == 1) ? 1.0 : p0;
      dp = n * (x * pn - pnm1) / (x * x - 1.0);
      const double dx = pn / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16)
        break;
    }
    // Recompute derivative at the converged point.
    double p0 = 1.0, p1 = x;
    for (int k = 2; k <= n; ++k)
    {
      const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
      p0 = p1;
      p1 = p2;
    }
    const double pn = (n == 1) ? x : p1;
    const double pnm1 = (n == 1) ? 1.0 : p0;
    dp = n * (x * pn - pnm1) / (x * x - 1.0);
    rule.points[i] = 0.5 * (1.0 - x);
    rule.weights[i] = 1.0 / ((1.0 - x * x) * dp * dp);
  }
  if (static_cast<int>(cache.size()) <= n)
    cache.resize(n + 1);
  cache[n] = std::make_unique<Rule>(std::move(rule));
  return *cache[n];
}

namespace
{
Rule conical_product(int nu, int nv)
{
  const Rule gu = gauss_legendre(nu), gv = gauss_legendre(nv);
  Rule rule;
  rule.dim = 2;
  rule.points.reserve(2 * nu * nv);
  rule.weights.reserve(nu * nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
    {
      const double u = gu.points[i], v = gv.points[j];
      rule.points.push_back(u);
      rule.points.push_back((1.0 - u) * v);
      rule.weights.push_back(gu.weights[i] * gv.weights[j] * (1.0 - u));
    }
  return rule;
}
} // namespace

Rule line_toward_tip(int n, double r0, double r1)
{
  Rule g = gauss_legendre(n);
  if (!(r0 >= 0.0 and r1 >= 0.0))
    throw std::invalid_argument("line_toward_tip: distances must be >= 0");
  if (r0 == r1)
    return g;
  const bool near_p = r0 < r1;
  const double rn = near_p ? r0 : r1, rf = near_p ? r1 : r0;
  const double a = std::sqrt(rn), b = std::sqrt(rf);
  for (int q = 0; q < n; ++q)
  {
    // rho in [sqrt(r_near), sqrt(r_far)], r = rho^2, t_near = (r - r_near) / (r_far - r_near).
    const double rho = a + (b - a) * g.points[q];
    const double t = (rho * rho - rn) / (rf - rn);
    g.weights[q] *= (b - a) * 2.0 * rho / (rf - rn);
    g.points[q] = near_p ? t : 1.0 - t;
  }
  return g;
}

Rule triangle(int degree)
{
  if (degree < 0)
    throw std::invalid_argument("triangle quadrature: degree must be >= 0, got "
                                + std::to_string(degree));
  Rule rule;
  rule.dim = 2;
  if (degree <= 1)
  {
    rule.points = {1.0 / 3.0, 1.0 / 3.0};
    rule.weights = {0.5};
    return rule;
  }
  // Collapsed (Duffy) map of the unit square: xi = u, eta = (1 - u) v,
  // Jacobian (1 - u): degree + 1 in u, degree in v.
  return conical_product((degree + 3) / 2, (degree + 2) / 2);
}

namespace
{
Rule make_tetrahedron(int degree)
{
  if (degree < 0)
    throw std::invalid_argument("tetrahedron quadrature: degree must be >= 0, got "
                                + std::to_string(degree));
  Rule rule;
  rule.dim = 3;
  if (degree <= 1)
  {
    rule.points = {0.25, 0.25, 0.25};
    rule.weights = {1.0 / 6.0};
    return rule;
  }
  // A monomial of degree p becomes a polynomial of degree p + 2 in u (with
  // the Jacobian's (1 - u)^2), p + 1 in v and p in w.
  const Rule gu = gauss_legendre((degree + 4) / 2), gv = gauss_legendre((degree + 3) / 2),
             gw = gauss_legendre((degree + 2) / 2);
  for (int i = 0; i < gu.size(); ++i)
    for (int j = 0; j < gv.size(); ++j)
      for (int k = 0; k < gw.size(); ++k)
      {
        const double u = gu.points[i], v = gv.points[j], w = gw.points[k];
        rule.points.insert(rule.points.end(), {u, (1.0 - u) * v, (1.0 - u) * (1.0 - v) * w});
        rule.weights.push_back(gu.weights[i] * gv.weights[j] * gw.weights[k] * (1.0 - u) * (1.0 - u)
                               * (1.0 - v));
      }
  return rule;
}
} // namespace

Rule tetrahedron(int degree) { return tetrahedron_cached(degree); }

const Rule& tetrahedron_cached(int degree)
{
  static std::vector<std::unique_ptr<Rule>> cache;
  if (degree >= 0 and degree < static_cast<int>(cache.size()) and cache[degree])
    return *cache[degree];
  Rule rule = make_tetrahedron(degree);
  if (static_cast<int>(cache.size()) <= degree)
    cache.resize(degree + 1);
  cache[degree] = std::make_unique<Rule>(std::move(rule));
  return *cache[degree];
}

Rule triangle_product(int n)
{
  if (n < 1)
    throw std::invalid_argument("triangle_product: n must be >= 1");
  return conical_product(n, n);
}

Rule tip_fan(int n_t, int n_eta)
{
  if (n_t < 1 or n_eta < 1)
    throw std::invalid_argument("tip_fan: numbers of points must be >= 1");
  const Rule gt = gauss_legendre(n_t), ge = gauss_legendre(n_eta);
  Rule rule;
  rule.dim = 2;
  for (int i = 0; i < n_t; ++i)
    for (int j = 0; j < n_eta; ++j)
    {
      const double t = gt.points[i], eta = ge.points[j];
      const double rho = t * t;
      rule.points.push_back(rho * (1.0 - eta));
      rule.points.push_back(rho * eta);
      rule.weights.push_back(2.0 * t * t * t * gt.weights[i] * ge.weights[j]);
    }
  return rule;
}

} // namespace cracklip::quadrature
