// Fatigue life integration on a K table (cracklip.fracture.life_kernels is
// the Python side):
//
// - cycle by cycle: the cycles of a pass of the spectrum in the order they
//   close, pass after pass; K at each cycle from the table at the current
//   crack size(s), the law's rate, retardation (each point its own overload
//   state); stops at a size limit, at K_max >= K_crit (or a rate that
//   diverges), at arrest (a pass without growth) or after a number of
//   passes, and pauses after a number of cycles (the caller prints progress
//   and resumes where it paused);
// - in blocks, without sequence effects: the growth per pass summed over
//   the distinct cycles of a pass (equal cycles merged), and the passes
//   between two sizes by Gauss-Legendre quadrature of da / (growth per pass)
//   in ln a, on pieces between the table's sizes (K is smooth inside each);
//   two sizes (a, c): the system d(a, c)/dP = growth per pass, classical
//   Runge-Kutta in the passes P with steps that grow each size by at most a
//   given fraction.
//
// Load: K of point p at load state s is sum_g F[s, g] K_pg(sizes), F the
// factors (states x cases) of each load case at each state.
#pragma once

#include "life/growth_rate.h"
#include "life/k_table.h"
#include "life/retardation.h"

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip::life
{
/// The cycles of one pass and the load states they run between.
struct Cycles
{
  std::span<const double> F;              ///< (states x cases) factors, row major
  int cases = 1;                          ///< load cases (columns of F)
  std::span<const std::int64_t> lo, hi;   ///< each cycle's minimum and maximum state
  std::span<const double> count;          ///< weight (0.5, 1); > 1: that many cycles in a row
  bool clamp_min = false;                 ///< K_min = max(K_min, 0): lips closed at the tip carry no negative K
};

enum class Stop
{
  reached = 0,    ///< a size reached its limit
  failure = 1,    ///< K_max reached K_crit (or the law's rate diverged)
  arrest = 2,     ///< a whole pass without growth
  max_passes = 3, ///< the pass limit
  paused = 4      ///< the cycle budget of this call is spent (resume from here)
};

/// Where a cycle-by-cycle run is: sizes, cycles so far, position in the
/// spectrum (pass, entry of the pass, cycles done of a multi-cycle entry),
/// the overload state of each point, and why it stopped (after a call).
struct CycleRun
{
  double size[2] = {0.0, 0.0};
  double cycles = 0.0;
  std::int64_t pass = 0;
  std::int64_t entry = 0;
  std::int64_t done = 0;
  OverloadState state[2];
  double pass_start[2] = {0.0, 0.0}; ///< sizes when the current pass began (arrest: a pass without growth)
  Stop stop = Stop::paused;
  int point = 0;       ///< the point that reached its limit or failed
  double K_max = 0.0;  ///< K_max of the failing cycle
};

struct CycleLimits
{
  double size_end[2] = {0.0, 0.0};  ///< stop when size p reaches size_end[p]
  double K_crit = 0.0;              ///< failure at K_max >= K_crit (inf: none)
  double max_passes = 0.0;
  double max_cycles = 0.0;          ///< pause after this many cycles in this call
};

/// Cycle by cycle from `run` (module doc).
template <class Table>
CycleRun integrate_cycles(const Table& table, const Cycles& cycles, const GrowthLaw& law, const Retardation& ret,
                          CycleRun run, const CycleLimits& limits);

/// Growth per pass of each point at sizes s (no sequence effects): sum over
/// the (distinct) cycles of count x rate; +inf when a rate diverges.
template <class Table>
void growth_per_pass(const Table& table, const Cycles& cycles, const GrowthLaw& law, const double* s, double* g);

/// Passes from a[0] to each a[k] (one size, a ascending): cumulative, +inf
/// from where the growth per pass vanishes. `order` Gauss points per piece,
/// pieces at most max_width wide in ln a, never across a table size nor
/// across a size where a cycle starts or stops growing (found by bisection).
std::vector<double> passes_to(const KTable1& table, const Cycles& cycles, const GrowthLaw& law,
                              std::span<const double> a, int order = 10, double max_width = 0.05);

/// The two-size block integration's path: passes, a, c at every step.
struct BlockPath
{
  std::vector<double> passes, a, c;
  Stop stop = Stop::reached;
  int point = 0;
};

/// Two sizes (a, c) from (a0, c0) until a size reaches its limit, K_max
/// reaches K_crit (located by bisection of the last step), the growth
/// stops, or max_passes: RK4 in the passes, each step growing a size by at
/// most `fraction` of it.
BlockPath grow_blocks(const KTable2& table, const Cycles& cycles, const GrowthLaw& law, double a0, double c0,
                      const CycleLimits& limits, double fraction = 2e-3);

/// K_max over the load states of each point at sizes s (points x 1).
template <class Table>
void state_k_max(const Table& table, const Cycles& cycles, const double* s, double* K_max);
} // namespace cracklip::life
