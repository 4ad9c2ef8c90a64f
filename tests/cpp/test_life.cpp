// Life kernels (layer a): rainflow against ASTM E1049's worked example,
// laws against closed forms and the notes' NASGRO check values, block and
// cycle-by-cycle integration against closed-form Paris lives and a plain
// cycle-by-cycle Wheeler loop.
#include "life/cycle_integration.h"
#include "life/rainflow.h"

#include <cmath>
#include <gtest/gtest.h>
#include <map>
#include <random>

using namespace cracklip::life;

namespace
{
const std::vector<double> E1049 = {-2, 1, -3, 5, -1, 3, -4, 4, -2};

std::map<double, double> table_of(const CountedCycles& c, const std::vector<double>& v)
{
  std::map<double, double> t;
  for (std::size_t k = 0; k < c.lo.size(); ++k)
    t[v[c.hi[k]] - v[c.lo[k]]] += c.count[k];
  return t;
}

/// A Griffith crack's table: K = S sqrt(pi a) per unit factor (S = 1).
KTable1 griffith(double a0, double a1)
{
  return KTable1({a0, a1}, {std::sqrt(M_PI * a0), std::sqrt(M_PI * a1)}, 1);
}

GrowthLaw paris(double C, double m)
{
  LawConstants c;
  c.kind = LawKind::paris;
  c.C = C;
  c.m = m;
  return GrowthLaw(c);
}
} // namespace

// ASTM E1049-85 section 5.4.4, its own example (Fig. 6): ranges 3, 4, 6, 8,
// 9 with counts 1/2, 3/2, 1/2, 1, 1/2; the order in which the three-point rule
// closes them, worked by hand.
TEST(Rainflow, AstmE1049Example)
{
  const CountedCycles c = count_cycles(E1049, Counting::rainflow, false);
  const std::map<double, double> want = {{3, 0.5}, {4, 1.5}, {6, 0.5}, {8, 1.0}, {9, 0.5}};
  EXPECT_EQ(table_of(c, E1049), want);
  const std::vector<std::pair<double, double>> order = {{-2, 1}, {-3, 1}, {-1, 3}, {-3, 5}, {-4, 5}, {-4, 4}, {-2, 4}};
  ASSERT_EQ(c.lo.size(), order.size());
  for (std::size_t k = 0; k < order.size(); ++k)
  {
    EXPECT_EQ(E1049[c.lo[k]], order[k].first) << k;
    EXPECT_EQ(E1049[c.hi[k]], order[k].second) << k;
  }
}

// Repeated without end (E1049 5.4.5, start and close at the largest peak):
// full cycles of 3, 4, 7, 9, no residue; range-pair repeated is the same;
// valley-to-peak counts every rise once.
TEST(Rainflow, RepeatedHistoryAndOtherMethods)
{
  const std::map<double, double> closed = {{3, 1}, {4, 1}, {7, 1}, {9, 1}};
  EXPECT_EQ(table_of(count_cycles(E1049, Counting::rainflow, true), E1049), closed);
  EXPECT_EQ(table_of(count_cycles(E1049, Counting::range_pair, true), E1049), closed);
  const std::map<double, double> rises = {{3, 1}, {4, 1}, {8, 2}};
  EXPECT_EQ(table_of(count_cycles(E1049, Counting::valley_to_peak, false), E1049), rises);
  const std::map<double, double> pairs = {{3, 1}, {4, 1}, {6, 0.5}, {8, 1.5}};
  EXPECT_EQ(table_of(count_cycles(E1049, Counting::range_pair, false), E1049), pairs);
}

// A long random history repeated: every closed loop's range, summed with its
// count, is half the history's total variation around the closed loop (each
// rise and fall belongs to exactly one cycle); plateaus collapse.
TEST(Rainflow, LongHistoryClosesEveryLoop)
{
  std::mt19937 gen(7);
  std::normal_distribution<double> d(0.0, 1.0);
  std::vector<double> v(200000);
  for (double& x : v)
    x = std::round(10.0 * d(gen)) / 10.0;
  const CountedCycles c = count_cycles(v, Counting::rainflow, true);
  double sum = 0.0, variation = 0.0;
  for (std::size_t k = 0; k < c.lo.size(); ++k)
  {
    EXPECT_EQ(c.count[k], 1.0);
    EXPECT_LT(v[c.lo[k]], v[c.hi[k]]);
    sum += v[c.hi[k]] - v[c.lo[k]];
  }
  for (std::size_t i = 0; i < v.size(); ++i)
    variation += std::abs(v[(i + 1) % v.size()] - v[i]);
  EXPECT_NEAR(sum, 0.5 * variation, 1e-9 * variation);
  EXPECT_THROW(reversal_indices(std::vector<double>{1.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(reversal_indices(std::vector<double>{0.0, NAN, 1.0}), std::invalid_argument);
}

// Laws: Paris by hand; the notes' NASGRO check values for 7075-T6 L-T, t =
// 0.1 in (K_c = 57.942 ksi sqrt(in)): 9.4118e-6 in/cycle at Delta K = 10, R =
// 0.1 and 1.9932e-5 at R = 0.5; Newman's f at alpha = 2 (0.54807 at R = 0.5);
// a tabular law exact at its points and log-log in between.
TEST(GrowthRate, LawsAgainstHandValues)
{
  EXPECT_DOUBLE_EQ(paris(1e-10, 3.0).rate(20.0, 10.0, 1.0), 1e-10 * 1000.0);
  EXPECT_EQ(paris(1e-10, 3.0).rate(0.0, -5.0, 1.0), 0.0);
  LawConstants c;
  c.kind = LawKind::nasgro;
  c.closure = Closure::newman;
  c.C = 7.0e-8;
  c.n = 2.4;
  c.p = 1.0;
  c.q = 1.0;
  c.dK1 = 0.9;
  c.C_th_plus = 1.5;
  c.C_th_minus = 0.1;
  c.K_crit = 57.942;
  const GrowthLaw nasgro(c);
  EXPECT_NEAR(nasgro.rate(10.0 / 0.9, 1.0 / 0.9, 1.0) / 9.4118e-6, 1.0, 1e-4);
  EXPECT_NEAR(nasgro.rate(20.0, 10.0, 1.0) / 1.9932e-5, 1.0, 1e-4);
  EXPECT_TRUE(std::isinf(nasgro.rate(60.0, 30.0, 1.0)));
  double A[4];
  newman_coefficients(2.0, 0.3, A);
  EXPECT_NEAR(A[0], 0.32566, 6e-6);
  EXPECT_NEAR(A[0] + A[1] * 0.5 + A[2] * 0.25 + A[3] * 0.125, 0.54807, 6e-6);
  LawConstants t;
  t.kind = LawKind::tabular;
  const GrowthLaw tab(t, RateTable({0.0, 0.5}, {1e-9, 1e-7}, {2.0, 1.0, 20.0, 10.0}));
  EXPECT_NEAR(tab.rate(2.0, 0.0, 1.0) / 1e-9, 1.0, 1e-12);
  EXPECT_NEAR(tab.rate(std::sqrt(40.0), 0.0, 1.0) / 1e-8, 1.0, 1e-12); // halfway in log-log
  EXPECT_NEAR(tab.rate(2.0 * std::sqrt(10.0), std::sqrt(10.0), 1.0) / 1e-8, 1.0, 1e-12); // R = 0.5 curve
  EXPECT_NEAR(tab.rate(4.0 * std::sqrt(10.0), 3.0 * std::sqrt(10.0), 1.0) / 1e-8, 1.0, 1e-12); // R = 0.75: its last curve
  EXPECT_EQ(tab.rate(1.9, 0.0, 1.0), 0.0);                             // below the curve: no growth
  EXPECT_THROW(RateTable({0.0}, {1e-9, 1e-7}, {2.0, 1.5}), std::invalid_argument); // Delta K falls
}

// Block life of a Griffith crack under the E1049 block x 10 MPa (counted
// once), Paris C = 1e-12 m/cycle, m = 3, a = 1 -> 10 mm: the closed form
// [a^(1 - m/2)] / ((1 - m/2) C pi^(m/2) sum n dS^m) = 7.09904e6 blocks.
TEST(CycleIntegration, BlockLifeIsTheClosedForm)
{
  const CountedCycles cc = count_cycles(E1049, Counting::rainflow, false);
  std::vector<double> F(E1049.size());
  for (std::size_t i = 0; i < F.size(); ++i)
    F[i] = 10.0 * E1049[i];
  const Cycles cy{F, 1, cc.lo, cc.hi, cc.count};
  const double sum = 0.5 * 27e3 + 1.5 * 64e3 + 0.5 * 216e3 + 512e3 + 0.5 * 729e3;
  const double exact = (std::pow(1e-2, -0.5) - std::pow(1e-3, -0.5)) / (-0.5 * 1e-12 * std::pow(M_PI, 1.5) * sum);
  EXPECT_NEAR(exact, 7.09904e6, 10.0);
  const std::vector<double> a = {1e-3, 4e-3, 1e-2};
  const auto P = passes_to(griffith(1e-4, 1.0), cy, paris(1e-12, 3.0), a);
  EXPECT_NEAR(P[2] / exact, 1.0, 1e-12);
  const double at4 = (std::pow(4e-3, -0.5) - std::pow(1e-3, -0.5)) / (-0.5 * 1e-12 * std::pow(M_PI, 1.5) * sum);
  EXPECT_NEAR(P[1] / at4, 1.0, 1e-12);
}

// Cycle by cycle: constant amplitude 0 -> 100 MPa on a Griffith crack, 5 ->
// 6 mm, Paris 1e-12, 3 (closed form 442,571.3: the cycle count is the
// integer after it); and the notes' Wheeler check (sigma_ys 400, beta 2,
// gamma 1.5, one 0 -> 150 overload first), against a plain loop written
// here, cycle for cycle.
TEST(CycleIntegration, CycleByCycleMatchesPlainLoops)
{
  auto plain = [](bool overload)
  {
    double a = 0.005, zone = -1.0;
    long N = 0;
    if (overload)
    {
      const double K = 150 * std::sqrt(M_PI * a);
      zone = a + std::pow(K / 400.0, 2) / (2 * M_PI);
      a += 1e-12 * std::pow(K, 3);
      ++N;
    }
    while (a < 0.006)
    {
      const double K = 100 * std::sqrt(M_PI * a);
      const double r = std::pow(K / 400.0, 2) / (2 * M_PI);
      double cp = 1.0;
      if (a + r < zone)
        cp = std::pow(r / (zone - a), 1.5);
      else
        zone = a + r;
      a += cp * 1e-12 * std::pow(K, 3);
      ++N;
    }
    return N;
  };
  const long ca = plain(false), ol = plain(true);
  EXPECT_EQ(ca, 442572);
  EXPECT_EQ(ol, 546061);
  const std::vector<double> F = {0.0, 100.0, 150.0};
  const std::vector<std::int64_t> lo1 = {0}, hi1 = {1}, lo2 = {0, 0}, hi2 = {2, 1};
  const std::vector<double> n1 = {1.0}, n2 = {1.0, 1e9};
  Retardation ret{RetardationModel::wheeler, 400.0, 2.0, 1.5, 3.0};
  CycleLimits lim;
  lim.size_end[0] = 0.006;
  lim.K_crit = INFINITY;
  lim.max_passes = 1e9;
  lim.max_cycles = 1e12;
  CycleRun run;
  run.size[0] = 0.005;
  const KTable1 k = griffith(1e-3, 1e-2);
  const CycleRun r1 = integrate_cycles(k, Cycles{F, 1, lo1, hi1, n1}, paris(1e-12, 3.0), ret, run, lim);
  EXPECT_EQ(r1.stop, Stop::reached);
  EXPECT_NEAR(r1.cycles, static_cast<double>(ca), 1.0);
  // The overload, then the 100 MPa cycles as one entry of 1e9 cycles in a row.
  const CycleRun r2 = integrate_cycles(k, Cycles{F, 1, lo2, hi2, n2}, paris(1e-12, 3.0), ret, run, lim);
  EXPECT_EQ(r2.stop, Stop::reached);
  EXPECT_NEAR(r2.cycles, static_cast<double>(ol), 1.0);
  // Paused and resumed: the same count.
  lim.max_cycles = 12345;
  CycleRun r3 = run;
  int calls = 0;
  do
  {
    r3 = integrate_cycles(k, Cycles{F, 1, lo2, hi2, n2}, paris(1e-12, 3.0), ret, r3, lim);
    ++calls;
  } while (r3.stop == Stop::paused);
  EXPECT_EQ(r3.stop, Stop::reached);
  EXPECT_EQ(r3.cycles, r2.cycles);
  EXPECT_GT(calls, 40);
}

// Failure and arrest: K_max reaching K_crit stops before that cycle; a
// Willenborg overload of the shut-off ratio right behind the tip, with a
// threshold law, arrests growth (a whole pass without growth).
TEST(CycleIntegration, FailureAndArrest)
{
  const std::vector<double> F = {0.0, 100.0};
  const std::vector<std::int64_t> lo = {0}, hi = {1};
  const std::vector<double> n = {1.0};
  CycleLimits lim;
  lim.size_end[0] = 0.5;
  lim.K_crit = 100.0 * std::sqrt(M_PI * 0.02);
  lim.max_passes = 1e12;
  lim.max_cycles = 1e12;
  CycleRun run;
  run.size[0] = 0.01;
  const CycleRun r = integrate_cycles(griffith(1e-3, 1.0), Cycles{F, 1, lo, hi, n}, paris(1e-10, 3.0), Retardation{},
                                      run, lim);
  EXPECT_EQ(r.stop, Stop::failure);
  EXPECT_NEAR(r.size[0], 0.02, 1e-4);
  EXPECT_GE(r.K_max, lim.K_crit);

  // Arrest: every range below the threshold.
  LawConstants c;
  c.kind = LawKind::paris;
  c.C = 1e-9;
  c.m = 3.0;
  c.threshold = 1.0;
  const GrowthLaw law(c);
  const KTable1 unit({0.01, 0.011}, {1.0, 1.0}, 1); // K = 1 per unit factor at a = 0.01
  const std::vector<double> Fa = {0.0, 0.5};
  lim.K_crit = INFINITY;
  CycleRun start;
  start.size[0] = 0.01;
  const CycleRun r1 = integrate_cycles(unit, Cycles{Fa, 1, lo, hi, n}, law, Retardation{}, start, lim);
  EXPECT_EQ(r1.stop, Stop::arrest);
  EXPECT_EQ(r1.pass, 1);
  EXPECT_EQ(r1.cycles, 1.0);
  // Willenborg: after an overload of 2.2 x K_max (shut-off ratio 2) no cycle grows: one pass of the
  // overload and 1e5 cycles grows the crack by the overload's own growth, 1e-9 x 22^3.
  const std::vector<double> F2 = {0.0, 10.0, 22.0};
  const std::vector<std::int64_t> lo2 = {0, 0}, hi2 = {2, 1};
  const std::vector<double> n2 = {1.0, 1e5};
  Retardation ret{RetardationModel::willenborg, 400.0, 2.0, 1.0, 2.0};
  lim.max_passes = 1.0;
  const CycleRun r2 = integrate_cycles(unit, Cycles{F2, 1, lo2, hi2, n2}, law, ret, start, lim);
  EXPECT_EQ(r2.stop, Stop::max_passes);
  EXPECT_EQ(r2.cycles, 1.0 + 1e5);
  EXPECT_NEAR((r2.size[0] - 0.01) / (1e-9 * 22 * 22 * 22), 1.0, 1e-9);
  // Without retardation the same pass grows by the overload's and the cycles' own growth.
  const CycleRun r3 = integrate_cycles(unit, Cycles{F2, 1, lo2, hi2, n2}, law, Retardation{}, start, lim);
  EXPECT_GT(r3.size[0] - 0.01, 1e5 * 1e-9 * 1000 * 0.99);
}

// Two sizes with K of a Griffith crack of size a at both points (K / sqrt(a)
// constant: the bilinear table is exact): a follows the closed form, c grows
// by as much as a; the last step lands on the size limit.
TEST(CycleIntegration, TwoSizeBlocksFollowTheirClosedForms)
{
  const std::vector<double> a = {1e-3, 2e-3, 5e-3, 1e-2}, c = {1e-3, 3e-3, 1e-2, 3e-2};
  std::vector<double> K;
  for (double x : a)
    for (double y : c)
    {
      K.push_back(std::sqrt(M_PI * x)); // deepest point
      K.push_back(std::sqrt(M_PI * x)); // surface point: the same K, so c grows as much as a
      (void)y;
    }
  const KTable2 t(a, c, K, 1);
  const std::vector<double> F = {0.0, 100.0};
  const std::vector<std::int64_t> lo = {0}, hi = {1};
  const std::vector<double> n = {1.0};
  CycleLimits lim;
  lim.size_end[0] = 8e-3;
  lim.size_end[1] = 1.0;
  lim.K_crit = INFINITY;
  lim.max_passes = 1e15;
  const BlockPath path = grow_blocks(t, Cycles{F, 1, lo, hi, n}, paris(1e-12, 3.0), 1.5e-3, 2e-3, lim);
  EXPECT_EQ(path.stop, Stop::reached);
  EXPECT_EQ(path.point, 0);
  EXPECT_NEAR(path.a.back(), 8e-3, 1e-13);
  const double N = (std::pow(8e-3, -0.5) - std::pow(1.5e-3, -0.5)) / (-0.5 * 1e-12 * std::pow(100.0 * std::sqrt(M_PI), 3));
  EXPECT_NEAR(path.passes.back() / N, 1.0, 1e-9);
  EXPECT_NEAR(path.c.back() - 2e-3, path.a.back() - 1.5e-3, 1e-15);
}
