#include "quadrature/rules.h"

#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <span>
#include <stdexcept>
#include <string>

namespace cracklip::quadrature
{

namespace
{
/// A rule kept per non-negative key, made once by make(key) (single-threaded
/// callers).
template <typename Make>
const Rule& cached(std::vector<std::unique_ptr<Rule>>& cache, int key, Make make)
{
  if (key >= 0 and key < static_cast<int>(cache.size()) and cache[key])
    return *cache[key];
  Rule rule = make(key);
  if (static_cast<int>(cache.size()) <= key)
    cache.resize(key + 1);
  cache[key] = std::make_unique<Rule>(std::move(rule));
  return *cache[key];
}

/// P_n(x) and its derivative P_n'(x) (n >= 1), by the three-term recurrence.
std::array<double, 2> legendre(int n, double x)
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
  return {pn, n * (x * pn - pnm1) / (x * x - 1.0)};
}

Rule make_gauss_legendre(int n)
{
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
    for (int it = 0; it < 100; ++it)
    {
      const auto [pn, dp] = legendre(n, x);
      const double dx = pn / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16)
        break;
    }
    // The derivative at the converged point.
    const double dp = legendre(n, x)[1];
    rule.points[i] = 0.5 * (1.0 - x);
    rule.weights[i] = 1.0 / ((1.0 - x * x) * dp * dp);
  }
  return rule;
}

/// Collapsed (Duffy) product rule on the reference simplex of dimension
/// counts.size(): counts[k] Gauss points in u_k, x_k = (1 - u_0) ... (1 -
/// u_{k-1}) u_k, weight prod_k w_k times the Jacobian prod_k (1 - u_k)^(dim
/// - 1 - k). Points in lexicographic order of (i_0, i_1, ...).
Rule collapsed_product(std::span<const int> counts)
{
  const int dim = static_cast<int>(counts.size());
  std::vector<const Rule*> g(dim);
  int total = 1;
  for (int k = 0; k < dim; ++k)
    g[k] = &gauss_legendre_cached(counts[k]), total *= counts[k];
  Rule rule;
  rule.dim = dim;
  rule.points.reserve(static_cast<std::size_t>(dim) * total);
  rule.weights.reserve(total);
  std::vector<int> i(dim, 0);
  for (int n = 0; n < total; ++n)
  {
    double scale = 1.0, w = g[0]->weights[i[0]];
    for (int k = 1; k < dim; ++k)
      w *= g[k]->weights[i[k]];
    for (int k = 0; k < dim; ++k)
    {
      const double u = g[k]->points[i[k]];
      rule.points.push_back(k == 0 ? u : scale * u);
      for (int r = 0; r < dim - 1 - k; ++r)
        w *= 1.0 - u;
      scale = k == 0 ? 1.0 - u : scale * (1.0 - u);
    }
    rule.weights.push_back(w);
    for (int k = dim - 1; k >= 0 and ++i[k] == counts[k]; --k) // next index, last fastest
      i[k] = 0;
  }
  return rule;
}

Rule make_simplex(int dim, int degree)
{
  if (degree < 0)
    throw std::invalid_argument("simplex quadrature: degree must be >= 0, got "
                                + std::to_string(degree));
  if (dim < 1 or dim > 3)
    throw std::invalid_argument("simplex quadrature: dimension must be 1, 2 or 3, got " + std::to_string(dim));
  if (degree <= 1)
  {
    Rule rule;
    rule.dim = dim;
    rule.points.assign(dim, 1.0 / (dim + 1));
    rule.weights = {dim == 1 ? 1.0 : dim == 2 ? 0.5 : 1.0 / 6.0};
    return rule;
  }
  std::array<int, 3> counts;
  for (int k = 0; k < dim; ++k)
    counts[k] = (degree + 1 + dim - k) / 2;
  return collapsed_product(std::span<const int>(counts.data(), dim));
}
} // namespace

Rule gauss_legendre(int n) { return gauss_legendre_cached(n); }

const Rule& gauss_legendre_cached(int n)
{
  static std::vector<std::unique_ptr<Rule>> cache;
  if (n < 1)
    throw std::invalid_argument("gauss_legendre: n must be >= 1, got " + std::to_string(n));
  return cached(cache, n, make_gauss_legendre);
}

const Rule& simplex(int dim, int degree)
{
  static std::array<std::vector<std::unique_ptr<Rule>>, 4> cache;
  if (dim < 1 or dim > 3)
    throw std::invalid_argument("simplex quadrature: dimension must be 1, 2 or 3, got " + std::to_string(dim));
  if (degree < 0)
    throw std::invalid_argument("simplex quadrature: degree must be >= 0, got " + std::to_string(degree));
  return cached(cache[dim], degree, [dim](int p) { return make_simplex(dim, p); });
}

Rule triangle(int degree) { return simplex(2, degree); }

Rule tetrahedron(int degree) { return simplex(3, degree); }

const Rule& tetrahedron_cached(int degree) { return simplex(3, degree); }

Rule triangle_product(int n)
{
  if (n < 1)
    throw std::invalid_argument("triangle_product: n must be >= 1");
  const std::array<int, 2> counts = {n, n};
  return collapsed_product(counts);
}

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
