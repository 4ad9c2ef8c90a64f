#include "life/k_table.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace cracklip::life
{
namespace
{
void check_sizes(const std::vector<double>& x, const char* what)
{
  if (x.size() < 2)
    throw std::invalid_argument(std::string("K table: needs at least two ") + what);
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!(x[i] > 0.0) or !std::isfinite(x[i]) or (i > 0 and !(x[i] > x[i - 1])))
      throw std::invalid_argument(std::string("K table: the ") + what + " must be positive, finite and ascending");
}

/// The interval [x[i], x[i+1]] holding v (clamped), starting the search at hint.
std::size_t locate(const std::vector<double>& x, double v, std::size_t& hint)
{
  const std::size_t n = x.size();
  std::size_t i = std::min(hint, n - 2);
  if (v >= x[i] and v <= x[i + 1])
    return i;
  if (i + 2 < n and v >= x[i + 1] and v <= x[i + 2])
    return hint = i + 1;
  if (v <= x.front())
    return hint = 0;
  if (v >= x.back())
    return hint = n - 2;
  i = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), v) - x.begin()) - 1;
  return hint = std::min(i, n - 2);
}
} // namespace

KTable1::KTable1(std::vector<double> a, const std::vector<double>& K, int cases) : a_(std::move(a)), cases_(cases)
{
  check_sizes(a_, "crack sizes");
  if (cases < 1 or K.size() != a_.size() * static_cast<std::size_t>(cases))
    throw std::invalid_argument("K table: one K per size and load case");
  kr_.resize(K.size());
  for (std::size_t i = 0; i < a_.size(); ++i)
    for (int g = 0; g < cases; ++g)
    {
      const double k = K[i * cases + g];
      if (!std::isfinite(k))
        throw std::invalid_argument("K table: a K is not finite");
      kr_[i * cases + g] = k / std::sqrt(a_[i]);
    }
  inv_w_.resize(a_.size() - 1);
  for (std::size_t i = 0; i + 1 < a_.size(); ++i)
    inv_w_[i] = 1.0 / (a_[i + 1] - a_[i]);
}

void KTable1::evaluate(const double* s, double* K) const
{
  const double a = std::clamp(s[0], a_.front(), a_.back());
  const std::size_t i = locate(a_, a, hint_);
  const double t = (a - a_[i]) * inv_w_[i];
  const double r = std::sqrt(a);
  const double* k0 = kr_.data() + i * cases_;
  const double* k1 = k0 + cases_;
  for (int g = 0; g < cases_; ++g)
    K[g] = r * ((1.0 - t) * k0[g] + t * k1[g]);
}

KTable2::KTable2(std::vector<double> a, std::vector<double> c, const std::vector<double>& K, int cases)
    : a_(std::move(a)), c_(std::move(c)), cases_(cases)
{
  check_sizes(a_, "depths a");
  check_sizes(c_, "lengths c");
  const std::size_t na = a_.size(), nc = c_.size();
  if (cases < 1 or K.size() != na * nc * 2 * static_cast<std::size_t>(cases))
    throw std::invalid_argument("K table: one K per (a, c), point and load case");
  kr_.resize(K.size());
  for (std::size_t i = 0; i < na; ++i)
  {
    const double r = std::sqrt(a_[i]);
    for (std::size_t q = 0; q < nc * 2 * static_cast<std::size_t>(cases); ++q)
    {
      const double k = K[i * nc * 2 * cases + q];
      if (!std::isfinite(k))
        throw std::invalid_argument("K table: a K is not finite");
      kr_[i * nc * 2 * cases + q] = k / r;
    }
  }
}

void KTable2::evaluate(const double* s, double* K) const
{
  const double a = std::clamp(s[0], a_.front(), a_.back());
  const double c = std::clamp(s[1], c_.front(), c_.back());
  const std::size_t i = locate(a_, a, hint_a_), j = locate(c_, c, hint_c_);
  const double t = (a - a_[i]) / (a_[i + 1] - a_[i]);
  const double u = (c - c_[j]) / (c_[j + 1] - c_[j]);
  const std::size_t row = 2 * static_cast<std::size_t>(cases_), nc = c_.size();
  const double* k00 = kr_.data() + (i * nc + j) * row;
  const double* k01 = k00 + row;
  const double* k10 = k00 + nc * row;
  const double* k11 = k10 + row;
  const double r = std::sqrt(a);
  for (std::size_t q = 0; q < row; ++q)
    K[q] = r * ((1.0 - t) * ((1.0 - u) * k00[q] + u * k01[q]) + t * ((1.0 - u) * k10[q] + u * k11[q]));
}
} // namespace cracklip::life
