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

/// Irwin's plastic zone (K_max / sigma_ys)^2 / (beta pi); 0 for K_max <= 0.
inline double plastic_zone(double K_max, double sigma_ys, double beta)
{
  const double q = std::max(K_max, 0.0) / sigma_ys;
  return q * q / (beta * M_PI);
}

/// da/dN of one cycle at crack size a with retardation; updates the state.
double retarded_rate(const GrowthLaw& law, const Retardation& ret, OverloadState& state, double a, double K_max,
                     double K_min);
} // namespace cracklip::life
