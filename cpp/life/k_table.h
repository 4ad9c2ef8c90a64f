// K per unit load against crack size, the geometry input of a life: a beta
// table, a handbook solution tabulated finely, or the K a growth run
// measured at each step. One size (a through crack: K at its tip against
// a) or two (a surface or corner crack: K at the deepest point and at the
// surface against (a, c)); each with one column per load case.
//
// Interpolation: K / sqrt(a) is linear in a between table sizes (beta,
// piecewise linear: the same as cracklip grow between two growth steps,
// exact for K proportional to sqrt(a)); two sizes: bilinear in (a, c).
#pragma once

#include <cstddef>
#include <vector>

namespace cracklip::life
{
/// One size: K_g(a) of load case g at the tip.
class KTable1
{
public:
  static constexpr int sizes = 1;
  KTable1() = default;
  /// a (n >= 2, ascending, > 0); K (n x cases, row major): K per unit load of
  /// each case at a[i].
  KTable1(std::vector<double> a, const std::vector<double>& K, int cases);
  int cases() const { return cases_; }
  /// The table's range of sizes (size 0: a; no second size).
  double lower(int) const { return a_.front(); }
  double upper(int) const { return a_.back(); }
  /// K (points x cases, here 1 x cases) at sizes s[0] = a; a outside the
  /// table is clamped to its ends. The last interval found is kept as a
  /// hint: K along a growing crack costs O(1) per call.
  void evaluate(const double* s, double* K) const;
  const std::vector<double>& sizes_of(int) const { return a_; }

private:
  std::vector<double> a_;
  std::vector<double> kr_;    ///< K / sqrt(a), (n x cases)
  std::vector<double> inv_w_; ///< 1 / (a[i + 1] - a[i])
  int cases_ = 0;
  mutable std::size_t hint_ = 0;
};

/// Two sizes: K at point 0 (the deepest point, grows a) and point 1 (the
/// surface point, grows c) against (a, c) on a grid.
class KTable2
{
public:
  static constexpr int sizes = 2;
  KTable2() = default;
  /// a (na >= 2), c (nc >= 2), both ascending and > 0; K (na x nc x 2 x
  /// cases, row major): K per unit load at (a[i], c[j]) of point p, case g.
  KTable2(std::vector<double> a, std::vector<double> c, const std::vector<double>& K, int cases);
  int cases() const { return cases_; }
  double lower(int d) const { return d == 0 ? a_.front() : c_.front(); }
  double upper(int d) const { return d == 0 ? a_.back() : c_.back(); }
  /// K (2 x cases) at sizes s = (a, c), bilinear in the grid cell (sizes
  /// clamped to the grid).
  void evaluate(const double* s, double* K) const;
  const std::vector<double>& sizes_of(int d) const { return d == 0 ? a_ : c_; }

private:
  std::vector<double> a_, c_;
  std::vector<double> kr_; ///< K / sqrt(a), (na x nc x 2 x cases)
  int cases_ = 0;
  mutable std::size_t hint_a_ = 0, hint_c_ = 0;
};
} // namespace cracklip::life
