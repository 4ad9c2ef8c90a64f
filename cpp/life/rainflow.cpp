#include "life/rainflow.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace cracklip::life
{
namespace
{
/// Turning points of v into out (indices into v): one pass, plateaus keep
/// their first point. Returns false if v has fewer than two distinct values.
bool turning_points(std::span<const double> v, std::vector<std::int64_t>& out)
{
  const std::size_t n = v.size();
  out.clear();
  out.reserve(n);
  std::size_t last = 0; // the last distinct point kept so far (first of its plateau)
  int dir = 0;          // direction from out.back() to last: +1 up, -1 down, 0 none yet
  out.push_back(0);
  for (std::size_t i = 1; i < n; ++i)
  {
    if (v[i] == v[last])
      continue;
    const int d = v[i] > v[last] ? 1 : -1;
    if (dir != 0 and d != dir)
      out.push_back(static_cast<std::int64_t>(last));
    dir = d;
    last = i;
  }
  if (dir == 0)
    return false;
  out.push_back(static_cast<std::int64_t>(last));
  return true;
}

void check_finite(std::span<const double> v)
{
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]))
    {
      std::ostringstream s;
      s << "the load history has a non-finite value " << v[i] << " at point " << i;
      throw std::invalid_argument(s.str());
    }
}

/// The three-point rule on the reversals w (their indices into the history:
/// index): counted ranges go into c, the residue (positions in w) stays. The
/// stack keeps the values beside the positions and a moving bottom (`base`)
/// so that the starting-point rule's "drop the first point" is O(1).
void three_point(std::span<const double> w, std::span<const std::int64_t> index, bool start_rule, CountedCycles& c,
                 std::vector<std::int64_t>& residue)
{
  std::vector<std::int64_t> pos;
  std::vector<double> val;
  pos.reserve(w.size());
  val.reserve(w.size());
  std::size_t base = 0;
  auto emit = [&](std::size_t i, std::size_t j, double count)
  {
    const bool up = val[i] <= val[j];
    c.lo.push_back(index[pos[up ? i : j]]);
    c.hi.push_back(index[pos[up ? j : i]]);
    c.count.push_back(count);
  };
  for (std::size_t k = 0; k < w.size(); ++k)
  {
    pos.push_back(static_cast<std::int64_t>(k));
    val.push_back(w[k]);
    while (pos.size() - base >= 3)
    {
      const std::size_t s = pos.size();
      const double x = std::abs(val[s - 1] - val[s - 2]);
      const double y = std::abs(val[s - 2] - val[s - 3]);
      if (x < y)
        break;
      if (start_rule and s - base == 3)
      {
        // Y holds the starting point: half a cycle, the start moves on.
        emit(base, base + 1, 0.5);
        ++base;
      }
      else
      {
        emit(s - 3, s - 2, 1.0);
        pos[s - 3] = pos[s - 1];
        val[s - 3] = val[s - 1];
        pos.resize(s - 2);
        val.resize(s - 2);
      }
    }
  }
  residue.assign(pos.begin() + static_cast<std::ptrdiff_t>(base), pos.end());
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

std::vector<std::int64_t> reversal_indices(std::span<const double> v)
{
  check_finite(v);
  std::vector<std::int64_t> out;
  if (!turning_points(v, out))
    throw std::invalid_argument("the load history has no reversal: it needs at least two different values");
  return out;
}

CountedCycles count_cycles(std::span<const double> values, Counting method, bool repeated)
{
  std::vector<std::int64_t> rev = reversal_indices(values);
  CountedCycles c;
  c.lo.reserve(rev.size() / 2 + 1);
  c.hi.reserve(rev.size() / 2 + 1);
  c.count.reserve(rev.size() / 2 + 1);
  std::vector<std::int64_t> residue;
  std::vector<double> w;
  std::vector<std::int64_t> index;
  if (repeated)
  {
    // Start at the largest absolute value and close the loop on it (E1049
    // 5.4.5). The rotated sequence is made of reversals except perhaps at
    // the joint (the last point, then the first), where points that are no
    // longer turning points drop out.
    const std::size_t n = rev.size();
    std::size_t k = 0;
    for (std::size_t i = 1; i < n; ++i)
      if (std::abs(values[rev[i]]) > std::abs(values[rev[k]]))
        k = i;
    std::vector<double> rot(n + 1);
    std::vector<std::int64_t> rot_index(n + 1);
    for (std::size_t i = 0; i <= n; ++i)
    {
      const std::size_t j = i < n - k ? k + i : (i < n ? i - (n - k) : k);
      rot[i] = values[rev[j]];
      rot_index[i] = rev[j];
    }
    std::vector<std::int64_t> keep;
    turning_points(rot, keep);
    w.resize(keep.size());
    index.resize(keep.size());
    for (std::size_t i = 0; i < keep.size(); ++i)
    {
      w[i] = rot[keep[i]];
      index[i] = rot_index[keep[i]];
    }
    if (method == Counting::valley_to_peak)
      rises(c, w, index);
    else
      three_point(w, index, false, c, residue);
    return c;
  }
  w.resize(rev.size());
  for (std::size_t i = 0; i < rev.size(); ++i)
    w[i] = values[rev[i]];
  if (method == Counting::valley_to_peak)
  {
    rises(c, w, rev);
    return c;
  }
  three_point(w, rev, method == Counting::rainflow, c, residue);
  for (std::size_t i = 0; i + 1 < residue.size(); ++i)
  {
    const std::int64_t p = residue[i], q = residue[i + 1];
    const bool up = w[p] <= w[q];
    c.lo.push_back(rev[up ? p : q]);
    c.hi.push_back(rev[up ? q : p]);
    c.count.push_back(0.5);
  }
  return c;
}
} // namespace cracklip::life
