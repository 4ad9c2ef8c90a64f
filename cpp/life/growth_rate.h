// Fatigue crack growth rates of one cycle from its K_max and K_min: the
// laws (Paris, Walker, Forman, NASGRO with Newman's opening function and
// its threshold, Hartman-Schijve, tabular da/dN against Delta K at several
// R) and the closure applied before them (contact, Newman, none). The same
// formulas as cracklip.fracture.laws / cracklip.fracture.life.LifeLaw
// (docs/life.md has them and their sources); a Python test compares both
// over random cycles.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace cracklip::life
{
/// x^e for x >= 0 with the exponent's kind found once: small integers by
/// multiplication, half-integers by multiplication and one sqrt, others by
/// std::pow (the rates of a life call this once or twice per cycle).
class Power
{
public:
  Power() = default;
  explicit Power(double e) : e_(e)
  {
    const double twice = 2.0 * e;
    if (e == std::round(e) and std::abs(e) <= 16.0)
      kind_ = 1, k_ = static_cast<int>(e);
    else if (twice == std::round(twice) and std::abs(e) <= 16.0)
      kind_ = 2, k_ = static_cast<int>(std::floor(e));
  }
  double operator()(double x) const
  {
    if (kind_ == 0)
      return std::pow(x, e_);
    double r = 1.0;
    for (int i = 0; i < std::abs(k_); ++i)
      r *= x;
    if (k_ < 0)
      r = 1.0 / r;
    return kind_ == 1 ? r : r * std::sqrt(x);
  }

private:
  double e_ = 1.0;
  int kind_ = 0; ///< 0 general, 1 integer, 2 half-integer
  int k_ = 0;
};

enum class LawKind
{
  paris,           ///< C dK^m
  walker,          ///< C [dK / (1 - R)^(1 - gamma)]^m
  forman,          ///< C dK^n / ((1 - R) K_f - dK): +inf at K_max >= K_f, for any R
  nasgro,          ///< C [((1 - f)/(1 - R)) dK]^n (1 - dK_th/dK)^p / (1 - K_max/K_crit)^q
  hartman_schijve, ///< D [(dK - dK_thr) / sqrt(1 - K_max/A)]^alpha
  tabular          ///< log-log in dK along each R curve, linear in R between curves
};

enum class Closure
{
  contact, ///< K as given (contact solves gave K_min); NASGRO takes f = R
  newman,  ///< Newman's f(R): NASGRO's own, U = (1 - f)/(1 - R) for Paris and Hartman-Schijve
  none     ///< K as given, full range
};

/// da/dN against Delta K for several R, converted once: logs of the rates
/// and of every curve's Delta K (the tabular law's interpolation works on
/// them).
class RateTable
{
public:
  RateTable() = default;
  /// R (nR, ascending), rates (nr, ascending, > 0), delta_K (nr x nR, row
  /// major: delta_K[i * nR + j] gives rates[i] at R[j], ascending in i).
  RateTable(std::vector<double> R, const std::vector<double>& rates, const std::vector<double>& delta_K);
  /// The rate of one curve at dK: 0 below its first Delta K, the last
  /// segment extended above its last.
  double curve_rate(std::size_t j, double dK) const;
  /// The rate at (dK, R): R clipped to the table's range, linear in R
  /// between the two curves around it; 0 for dK <= 0.
  double rate(double dK, double R) const;
  bool empty() const { return R_.empty(); }

private:
  std::vector<double> R_;
  std::vector<double> log_rate_; ///< (nr)
  std::vector<double> log_dK_;   ///< (nR x nr): curve j's row j
};

/// Newman's A0..A3 (alpha: constraint factor; smax_over_flow: S_max / sigma_0).
void newman_coefficients(double alpha, double smax_over_flow, double A[4]);

/// The constants of a law and its closure; unused fields are ignored.
struct LawConstants
{
  LawKind kind = LawKind::paris;
  Closure closure = Closure::none;
  double C = 0, m = 0;                     // paris, walker (C, m), forman and nasgro (C, n)
  double gamma = 1;                        // walker
  double n = 0, K_f = 0;                   // forman, nasgro (n)
  double p = 0, q = 0, dK1 = 0;            // nasgro
  double C_th_plus = 0, C_th_minus = 0;    // nasgro
  double alpha = 2.0, smax_over_flow = 0.3; // Newman's f (nasgro; closure newman)
  double a0 = 0;                           // nasgro small-crack length (0: none)
  double K_crit = std::numeric_limits<double>::infinity(); // nasgro denominator
  double D = 0, dK_thr = 0, A = 0, exponent = 0;          // hartman_schijve
  double threshold = 0;                    // extra: no growth at or below this Delta K (any law)
};

/// A law with its closure: the rate of one cycle (cracklip.fracture.life.LifeLaw).
class GrowthLaw
{
public:
  GrowthLaw() = default;
  GrowthLaw(const LawConstants& c, RateTable table = {});

  /// da/dN of a cycle (K_max, K_min) at crack size a: 0 where K_max <= 0 or
  /// the range is at or below a threshold; +inf at or beyond the law's
  /// critical K.
  double rate(double K_max, double K_min, double a) const
  {
    if (!(K_max > 0.0))
      return 0.0;
    if (c_.kind == LawKind::paris and !newman_U_)
    {
      // Paris without Newman's U needs no R.
      const double range = K_max - K_min;
      return range > c_.threshold and range > 0.0 ? c_.C * pow_m_(range) : 0.0;
    }
    double dK, R;
    effective(K_max, K_min, dK, R);
    if (!(dK > c_.threshold))
      return 0.0;
    return law_rate(dK, R, K_max, a);
  }
  /// The threshold Delta K of a cycle (Willenborg's phi): NASGRO's Delta
  /// K_th at R = min(R, 0.99), else the constant threshold.
  double law_threshold(double K_max, double K_min, double a) const;
  /// Delta K as the law sees it and R: the range, times U for Newman
  /// closure on a law without its own f.
  void effective(double K_max, double K_min, double& dK, double& R) const
  {
    if (!(K_max > 0.0))
    {
      dK = 0.0;
      R = 0.0;
      return;
    }
    R = K_min / K_max;
    dK = K_max - K_min;
    if (newman_U_)
      dK = dK * (R < 1.0 ? (1.0 - newman_f(R)) / (1.0 - R) : 1.0);
  }
  /// The law alone at (dK as the law sees it, R, K_max, a).
  double law_rate(double dK, double R, double K_max, double a) const
  {
    if (c_.kind == LawKind::paris)
      return dK > 0.0 ? c_.C * pow_m_(dK) : 0.0;
    return other_rate(dK, R, K_max, a);
  }
  /// The K at which the rate diverges (inf: none).
  double critical_k() const;
  const LawConstants& constants() const { return c_; }

private:
  double other_rate(double dK, double R, double K_max, double a) const;
  double newman_f(double R) const;
  double nasgro_threshold(double R, double a, double f) const;
  LawConstants c_;
  RateTable table_;
  double A_[4] = {0, 0, 0, 0};
  bool nasgro_newman_ = false;
  bool newman_U_ = false; ///< closure newman on paris / hartman_schijve: U Delta K
  Power pow_m_, pow_n_, pow_p_, pow_q_, pow_e_;
};
} // namespace cracklip::life
