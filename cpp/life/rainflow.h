// Cycle counting of a load history (ASTM E1049-85): reversals, the
// three-point rainflow rule with its starting-point rule (5.4.4), range-pair,
// valley-to-peak, and the repeated history closed on its largest value
// (5.4.5). One pass over the reversals with a stack: O(n) time and memory.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace cracklip::life
{
enum class Counting
{
  rainflow,       ///< three-point rule with the starting-point rule (E1049 5.4.4)
  range_pair,     ///< three-point rule, every closed range a full cycle
  valley_to_peak  ///< every rise from a valley to the next peak is one cycle
};

/// Indices of the turning points of a history: the first and the last
/// point and every point where the slope changes sign (of a plateau, its
/// first point). Throws std::invalid_argument on a non-finite value or a
/// history with fewer than two different values.
std::vector<std::int64_t> reversal_indices(std::span<const double> values);

/// Counted cycles, in the order they close (a residue's half cycles last).
/// lo[k], hi[k]: indices into the counted values of cycle k's minimum and
/// maximum; count[k]: 1 (full) or 0.5 (half).
struct CountedCycles
{
  std::vector<std::int64_t> lo;
  std::vector<std::int64_t> hi;
  std::vector<double> count;
};

/// Count the cycles of a history. repeated: the history repeats without
/// end, so it is started at its largest absolute value and closed on it
/// (full cycles only, E1049 5.4.5); otherwise counted once (the residue as
/// half cycles; valley_to_peak has none). Indices refer to `values`.
CountedCycles count_cycles(std::span<const double> values, Counting method, bool repeated);
} // namespace cracklip::life
