// Load interaction, cycle by cycle: Wheeler and generalized Willenborg
// retardation (cracklip.fracture.retardation has the formulas and their
// sources). The governing overload is the cycle whose plastic zone reaches
// farthest ahead (a + r_y largest so far); a cycle whose zone reaches to or
// past it becomes the new overload and is not retarded.
#pragma once

#include "life/growth_rate.h"

#include <cmath>
#include <limits>

namespace cracklip::life
{
enum class RetardationModel
{
  none,
  wheeler,   ///< da/dN = [r_y / (a_OL + r_OL - a)]^gamma (da/dN)_CA inside the overload zone
  willenborg ///< generalized Willenborg: residual K_R lowers K_max and K_min
};

/// Irwin's plastic zone r_y = (K_max / sigma_ys)^2 / (beta pi).
struct Retardation
{
  RetardationModel model = RetardationModel::none;
  double sigma_ys = 1.0; ///< yield stress of the plastic zone
  double beta = 2.0;     ///< 2 plane stress, 6 plane strain
  double gamma = 1.0;    ///< Wheeler's exponent
  double shutoff = 3.0;  ///< Willenborg's shut-off overload ratio (> 1)
};

/// The governing overload: crack size a_OL at it, its zone r_OL, its K_max.
struct OverloadState
{
  double a_OL = -std::numeric_limits<double>::infinity();
  double r_OL = 0.0;
  double K_OL = 0.0;
  double zone_end() const { return a_OL + r_OL; }
};

/// Generalized Willenborg inside the overload's zone: the residual K_R =
/// phi [K_OL sqrt(1 - (a - a_OL) / r_OL) - K_max] lowers K_max and K_min.
double willenborg_rate(const GrowthLaw& law, const Retardation& ret, const OverloadState& state, double a,
                       double K_max, double K_min);

/// What a cycle-by-cycle run needs of the retardation settings, worked out
/// once: x^gamma and the plastic zone's 1 / (sigma_ys^2 beta pi).
struct RetardationKernel
{
  explicit RetardationKernel(const Retardation& r)
      : ret(r), gamma_power(r.gamma), zone_coef(1.0 / (r.sigma_ys * r.sigma_ys * r.beta * M_PI))
  {
  }
  Retardation ret;
  Power gamma_power;
  double zone_coef;
};

/// da/dN of one cycle at crack size a with retardation; updates the state.
inline double retarded_rate(const GrowthLaw& law, const RetardationKernel& rk, OverloadState& state, double a,
                            double K_max, double K_min)
{
  const Retardation& ret = rk.ret;
  if (ret.model == RetardationModel::none)
    return law.rate(K_max, K_min, a);
  const double km = std::max(K_max, 0.0);
  const double r = km * km * rk.zone_coef;
  const double end = state.zone_end();
  if (a + r >= end)
  {
    // A new overload: its own rate (Willenborg still clamps K_min at 0).
    state = {a, r, km};
    if (ret.model == RetardationModel::wheeler)
      return law.rate(K_max, K_min, a);
    return K_max > 0.0 ? law.rate(K_max, std::max(K_min, 0.0), a) : 0.0;
  }
  if (ret.model == RetardationModel::wheeler)
  {
    const double room = std::max(end - a, 1e-300);
    return law.rate(K_max, K_min, a) * rk.gamma_power(std::clamp(r / room, 0.0, 1.0));
  }
  return willenborg_rate(law, ret, state, a, K_max, K_min);
}
} // namespace cracklip::life
