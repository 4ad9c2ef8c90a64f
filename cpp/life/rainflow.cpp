#include "life/rainflow.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace cracklip::life
{
std::vector<std::int64_t> reversal_indices(std::span<const double> v)
{
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(v[i]))
    {
      std::ostringstream s;
      s << "the load history has a non-finite value " << v[i] << " at point " << i;
      throw std::invalid_argument(s.str());
    }
  // The first point of every plateau.
  std::vector<std::int64_t> keep;
  keep.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    if (i == 0 or v[i] != v[i - 1])
      keep.push_back(static_cast<std::int64_t>(i));
  if (keep.size() < 2)
    throw std::invalid_argument("the load history has no reversal: it needs at least two different values");
  std::vector<std::int64_t> out{keep[0]};
  for (std::size_t k = 1; k + 1 < keep.size(); ++k)
  {
    const bool up_before = v[keep[k]] > v[keep[k - 1]];
    const bool up_after = v[keep[k + 1]] > v[keep[k]];
    if (up_before != up_after)
      out.push_back(keep[k]);
  }
  out.push_back(keep.back());
  return out;
}

namespace
{
struct Range
{
  std::int64_t i, j;
  double count;
};

/// The three-point rule on a reversal sequence w: the counted ranges (indices
/// into w) and the residue. The stack keeps a moving bottom (`base`) so that
/// the starting-point rule's "drop the first point" is O(1).
void three_point(std::span<const double> w, bool start_rule, std::vector<Range>& out,
                 std::vector<std::int64_t>& residue)
{
  std::vector<std::int64_t> stack;
  stack.reserve(w.size());
  std::size_t base = 0;
  for (std::size_t k = 0; k < w.size(); ++k)
  {
    stack.push_back(static_cast<std::int64_t>(k));
    while (stack.size() - base >= 3)
    {
      const std::size_t s = stack.size();
      const double x = std::abs(w[stack[s - 1]] - w[stack[s - 2]]);
      const double y = std::abs(w[stack[s - 2]] - w[stack[s - 3]]);
      if (x < y)
        break;
      if (start_rule and s - base == 3)
      {
        // Y holds the starting point: half a cycle, the start moves on.
        out.push_back({stack[base], stack[base + 1], 0.5});
        ++base;
      }
      else
      {
        out.push_back({stack[s - 3], stack[s - 2], 1.0});
        stack[s - 3] = stack[s - 1];
        stack.resize(s - 2);
      }
    }
  }
  residue.assign(stack.begin() + static_cast<std::ptrdiff_t>(base), stack.end());
}

void append(CountedCycles& c, std::span<const double> w, const std::vector<Range>& ranges,
            std::span<const std::int64_t> index)
{
  for (const Range& r : ranges)
  {
    const bool up = w[r.i] <= w[r.j];
    c.lo.push_back(index[up ? r.i : r.j]);
    c.hi.push_back(index[up ? r.j : r.i]);
    c.count.push_back(r.count);
  }
}

void rises(CountedCycles& c, std::span<const double> w, std::span<const std::int64_t> index)
{
  for (std::size_t k = 0; k + 1 < w.size(); ++k)
    if (w[k + 1] > w[k])
    {
      c.lo.push_back(index[k]);
      c.hi.push_back(index[k + 1]);
      c.count.push_back(1.0);
    }
}
} // namespace

CountedCycles count_cycles(std::span<const double> values, Counting method, bool repeated)
{
  const std::vector<std::int64_t> rev = reversal_indices(values);
  std::vector<double> v(rev.size());
  for (std::size_t k = 0; k < rev.size(); ++k)
    v[k] = values[rev[k]];
  CountedCycles c;
  std::vector<Range> ranges;
  std::vector<std::int64_t> residue;
  if (repeated)
  {
    // Start at the largest absolute value and close the loop on it (E1049
    // 5.4.5); the joint (the last point, then the first) may not be a
    // reversal: such points drop out.
    std::size_t k = 0;
    for (std::size_t i = 1; i < v.size(); ++i)
      if (std::abs(v[i]) > std::abs(v[k]))
        k = i;
    std::vector<std::int64_t> order;
    order.reserve(v.size() + 1);
    for (std::size_t i = k; i < v.size(); ++i)
      order.push_back(static_cast<std::int64_t>(i));
    for (std::size_t i = 0; i < k; ++i)
      order.push_back(static_cast<std::int64_t>(i));
    order.push_back(static_cast<std::int64_t>(k));
    std::vector<double> w(order.size());
    for (std::size_t i = 0; i < order.size(); ++i)
      w[i] = v[order[i]];
    const std::vector<std::int64_t> keep = reversal_indices(w);
    std::vector<std::int64_t> index(keep.size());
    std::vector<double> ww(keep.size());
    for (std::size_t i = 0; i < keep.size(); ++i)
    {
      index[i] = rev[order[keep[i]]];
      ww[i] = w[keep[i]];
    }
    if (method == Counting::valley_to_peak)
      rises(c, ww, index);
    else
    {
      three_point(ww, false, ranges, residue);
      append(c, ww, ranges, index);
    }
    return c;
  }
  if (method == Counting::valley_to_peak)
  {
    rises(c, v, rev);
    return c;
  }
  three_point(v, method == Counting::rainflow, ranges, residue);
  for (std::size_t i = 0; i + 1 < residue.size(); ++i)
    ranges.push_back({residue[i], residue[i + 1], 0.5});
  append(c, v, ranges, rev);
  return c;
}
} // namespace cracklip::life
