#include "life/growth_rate.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace cracklip::life
{
namespace
{
constexpr double inf = std::numeric_limits<double>::infinity();
}

RateTable::RateTable(std::vector<double> R, const std::vector<double>& rates, const std::vector<double>& delta_K)
    : R_(std::move(R))
{
  const std::size_t nR = R_.size(), nr = rates.size();
  if (nR < 1 or nr < 2 or delta_K.size() != nr * nR)
    throw std::invalid_argument("tabular da/dN: needs at least one R and two rates, and one Delta K per rate and R");
  for (std::size_t j = 1; j < nR; ++j)
    if (!(R_[j] > R_[j - 1]))
      throw std::invalid_argument("tabular da/dN: the R values must be ascending");
  log_rate_.resize(nr);
  for (std::size_t i = 0; i < nr; ++i)
  {
    if (!(rates[i] > 0) or (i > 0 and !(rates[i] > rates[i - 1])))
      throw std::invalid_argument("tabular da/dN: the rates must be positive and ascending");
    log_rate_[i] = std::log(rates[i]);
  }
  log_dK_.resize(nr * nR);
  for (std::size_t j = 0; j < nR; ++j)
    for (std::size_t i = 0; i < nr; ++i)
    {
      const double k = delta_K[i * nR + j];
      if (!(k > 0) or (i > 0 and !(k > delta_K[(i - 1) * nR + j])))
        throw std::invalid_argument("tabular da/dN: every Delta K column must be positive and ascending");
      log_dK_[j * nr + i] = std::log(k);
    }
}

double RateTable::curve_rate(std::size_t j, double dK) const
{
  const std::size_t nr = log_rate_.size();
  const double* K = log_dK_.data() + j * nr;
  const double* d = log_rate_.data();
  const double x = std::log(std::max(dK, 1e-300));
  if (x < K[0])
    return 0.0;
  if (x > K[nr - 1])
  {
    const double slope = (d[nr - 1] - d[nr - 2]) / (K[nr - 1] - K[nr - 2]);
    return std::exp(d[nr - 1] + slope * (x - K[nr - 1]));
  }
  if (x == K[nr - 1])
    return std::exp(d[nr - 1]);
  // The segment [K[i], K[i+1]) holding x (as numpy.interp).
  const std::size_t i = static_cast<std::size_t>(std::upper_bound(K, K + nr, x) - K) - 1;
  const double slope = (d[i + 1] - d[i]) / (K[i + 1] - K[i]);
  return std::exp(slope * (x - K[i]) + d[i]);
}

double RateTable::rate(double dK, double R) const
{
  if (!(dK > 0))
    return 0.0;
  const std::size_t nR = R_.size();
  if (nR == 1)
    return curve_rate(0, dK);
  const double rc = std::clamp(R, R_.front(), R_.back());
  std::size_t j = static_cast<std::size_t>(std::upper_bound(R_.begin(), R_.end(), rc) - R_.begin());
  j = std::min(std::max<std::size_t>(j, 1) - 1, nR - 2);
  const double w = (rc - R_[j]) / (R_[j + 1] - R_[j]);
  return (1.0 - w) * curve_rate(j, dK) + w * curve_rate(j + 1, dK);
}

void newman_coefficients(double alpha, double smax_over_flow, double A[4])
{
  A[0] = (0.825 - 0.34 * alpha + 0.05 * alpha * alpha)
         * std::pow(std::cos(M_PI * smax_over_flow / 2.0), 1.0 / alpha);
  A[1] = (0.415 - 0.071 * alpha) * smax_over_flow;
  A[3] = 2.0 * A[0] + A[1] - 1.0;
  A[2] = 1.0 - A[0] - A[1] - A[3];
}

GrowthLaw::GrowthLaw(const LawConstants& c, RateTable table) : c_(c), table_(std::move(table))
{
  if (c_.kind == LawKind::tabular and table_.empty())
    throw std::invalid_argument("the tabular law needs its table");
  if (c_.closure == Closure::newman and c_.kind != LawKind::nasgro and c_.kind != LawKind::paris
      and c_.kind != LawKind::hartman_schijve)
    throw std::invalid_argument("Newman closure applies to the nasgro, paris and hartman_schijve laws only");
  newman_coefficients(c_.alpha, c_.smax_over_flow, A_);
  nasgro_newman_ = c_.kind == LawKind::nasgro and c_.closure == Closure::newman;
  newman_U_ = c_.closure == Closure::newman and (c_.kind == LawKind::paris or c_.kind == LawKind::hartman_schijve);
  pow_m_ = Power(c_.m);
  pow_n_ = Power(c_.n);
  pow_p_ = Power(c_.p);
  pow_q_ = Power(c_.q);
  pow_e_ = Power(c_.exponent);
}

double GrowthLaw::newman_f(double R) const
{
  if (R >= 0.0)
    return std::max(R, A_[0] + A_[1] * R + A_[2] * (R * R) + A_[3] * std::pow(R, 3.0));
  if (R >= -2.0)
    return A_[0] + A_[1] * R;
  return A_[0] - 2.0 * A_[1];
}

double GrowthLaw::nasgro_threshold(double R, double a, double f) const
{
  const double cth = R >= 0.0 ? c_.C_th_plus : c_.C_th_minus;
  const double small = c_.a0 > 0.0 ? std::sqrt(a / (a + c_.a0)) : 1.0;
  return c_.dK1 * small / std::pow((1.0 - f) / ((1.0 - A_[0]) * (1.0 - R)), 1.0 + cth * R);
}

double GrowthLaw::other_rate(double dK, double R, double K_max, double a) const
{
  switch (c_.kind)
  {
  case LawKind::paris:
    return dK > 0.0 ? c_.C * pow_m_(dK) : 0.0;
  case LawKind::walker:
  {
    if (!(dK > 0.0))
      return 0.0;
    const double k = R < 1.0 ? dK / std::pow(1.0 - R, 1.0 - c_.gamma) : dK;
    return c_.C * pow_m_(std::max(k, 0.0));
  }
  case LawKind::forman:
  {
    // (1 - R) K_f - dK = (1 - R) (K_f - K_max): the rate diverges at K_max = K_f for any R (clamping a
    // negative R at 0 made it diverge at K_max = K_f / (1 - R), half K_f at R = -1).
    const double den = (1.0 - R) * c_.K_f - dK;
    if (dK <= 0.0)
      return 0.0;
    if (den <= 0.0)
      return inf;
    return c_.C * pow_n_(dK) / den;
  }
  case LawKind::nasgro:
  {
    const double room = 1.0 - K_max / c_.K_crit;
    if (room <= 0.0)
      return inf;
    if (dK <= 0.0)
      return 0.0;
    const double f = nasgro_newman_ ? newman_f(R) : R;
    const double th = nasgro_threshold(R, a, f);
    if (dK <= th)
      return 0.0;
    const double eff = (1.0 - f) / (1.0 - R) * dK;
    const double above = std::max(1.0 - th / dK, 0.0);
    return c_.C * pow_n_(std::max(eff, 0.0)) * pow_p_(above) / pow_q_(std::max(room, 1e-300));
  }
  case LawKind::hartman_schijve:
  {
    if (dK <= c_.dK_thr)
      return 0.0;
    const double room = 1.0 - K_max / c_.A;
    if (room <= 0.0)
      return inf;
    return c_.D * pow_e_(std::max(dK - c_.dK_thr, 0.0) / std::sqrt(std::max(room, 1e-300)));
  }
  case LawKind::tabular:
    return table_.rate(dK, R);
  }
  return 0.0;
}

double GrowthLaw::law_threshold(double K_max, double K_min, double a) const
{
  if (c_.kind != LawKind::nasgro)
    return c_.threshold;
  double dK, R;
  effective(K_max, K_min, dK, R);
  const double r = std::min(R, 0.99);
  return nasgro_threshold(r, a, nasgro_newman_ ? newman_f(r) : r);
}

double GrowthLaw::critical_k() const
{
  switch (c_.kind)
  {
  case LawKind::forman:
    return c_.K_f;
  case LawKind::nasgro:
    return c_.K_crit;
  case LawKind::hartman_schijve:
    return c_.A;
  default:
    return inf;
  }
}
} // namespace cracklip::life
