#include "life/retardation.h"

#include <algorithm>

namespace cracklip::life
{
double willenborg_rate(const GrowthLaw& law, const Retardation& ret, const OverloadState& state, double a,
                       double K_max, double K_min)
{
  double kr = 0.0;
  if (state.r_OL > 0.0)
  {
    const double depth = std::clamp(1.0 - (a - state.a_OL) / state.r_OL, 0.0, 1.0);
    const double kw = std::max(state.K_OL * std::sqrt(depth) - K_max, 0.0);
    const double dk = K_max - K_min;
    const double th = law.law_threshold(K_max, K_min, a);
    const double phi = std::clamp(1.0 - th / (dk > 0.0 ? dk : std::numeric_limits<double>::infinity()), 0.0, 1.0)
                       / (ret.shutoff - 1.0);
    kr = phi * kw;
  }
  const double kx = K_max - kr;
  const double kn = std::max(K_min - kr, 0.0);
  return kx > 0.0 ? law.rate(kx, kn, a) : 0.0;
}
} // namespace cracklip::life
