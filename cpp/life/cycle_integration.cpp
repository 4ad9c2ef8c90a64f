#include "life/cycle_integration.h"

#include "quadrature/rules.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace cracklip::life
{
namespace
{
constexpr double inf = std::numeric_limits<double>::infinity();

/// K_max and K_min of point p of a cycle from the table's K (points x cases).
inline void cycle_k(const Cycles& cy, const double* K, int p, std::int64_t lo, std::int64_t hi, double& kmax,
                    double& kmin)
{
  const int G = cy.cases;
  const double* fh = cy.F.data() + hi * G;
  const double* fl = cy.F.data() + lo * G;
  const double* k = K + p * G;
  kmax = 0.0;
  kmin = 0.0;
  for (int g = 0; g < G; ++g)
  {
    kmax += fh[g] * k[g];
    kmin += fl[g] * k[g];
  }
  if (cy.clamp_min)
    kmin = std::max(kmin, 0.0);
}

void check_cycles(const Cycles& cy)
{
  if (cy.cases < 1 or cy.F.size() % static_cast<std::size_t>(cy.cases) != 0)
    throw std::invalid_argument("life integration: the factors must be (states x cases)");
  const auto states = static_cast<std::int64_t>(cy.F.size() / cy.cases);
  if (cy.lo.size() != cy.hi.size() or cy.lo.size() != cy.count.size())
    throw std::invalid_argument("life integration: lo, hi and count must have one entry per cycle");
  for (std::size_t k = 0; k < cy.lo.size(); ++k)
  {
    if (cy.lo[k] < 0 or cy.lo[k] >= states or cy.hi[k] < 0 or cy.hi[k] >= states)
      throw std::invalid_argument("life integration: a cycle refers to a load state that does not exist");
    if (!(cy.count[k] > 0.0) or !std::isfinite(cy.count[k]))
      throw std::invalid_argument("life integration: cycle counts must be positive and finite");
  }
}
/// Which cycles grow (rate > 0) at size s of a one-size table, as (how many,
/// sum of their indices + 1): where it changes, the growth per pass jumps (a
/// cycle crossing a threshold or a tabular curve's first Delta K).
std::pair<std::int64_t, std::int64_t> growing_cycles(const KTable1& table, const Cycles& cy, const GrowthLaw& law,
                                                     double s, std::vector<double>& K)
{
  table.evaluate(&s, K.data());
  std::int64_t n = 0, sum = 0;
  for (std::size_t k = 0; k < cy.lo.size(); ++k)
  {
    double kmax, kmin;
    cycle_k(cy, K.data(), 0, cy.lo[k], cy.hi[k], kmax, kmin);
    if (law.rate(kmax, kmin, s) > 0.0)
    {
      ++n;
      sum += static_cast<std::int64_t>(k) + 1;
    }
  }
  return {n, sum};
}
} // namespace

template <class Table>
CycleRun integrate_cycles(const Table& table, const Cycles& cy, const GrowthLaw& law, const Retardation& ret,
                          CycleRun run, const CycleLimits& limits)
{
  constexpr int P = Table::sizes;
  check_cycles(cy);
  const int G = cy.cases;
  if (table.cases() != G)
    throw std::invalid_argument("life integration: the K table and the factors have different load cases");
  const auto n = static_cast<std::int64_t>(cy.lo.size());
  if (n == 0)
  {
    run.stop = Stop::arrest;
    return run;
  }
  std::vector<double> K(static_cast<std::size_t>(P * G));
  const bool retarded = ret.model != RetardationModel::none;
  const RetardationKernel rk(ret);
  const double* F = cy.F.data();
  const std::int64_t* LO = cy.lo.data();
  const std::int64_t* HI = cy.hi.data();
  const double* W = cy.count.data();
  // The run's state in locals (kept in registers in the hot loop), written back on every exit.
  double size[P], start[P];
  OverloadState state[P];
  for (int p = 0; p < P; ++p)
  {
    size[p] = run.size[p];
    start[p] = (run.entry == 0 and run.done == 0) ? run.size[p] : run.pass_start[p];
    state[p] = run.state[p];
  }
  double cycles = run.cycles, spent = 0.0;
  std::int64_t pass = run.pass, entry = run.entry, done = run.done;
  auto finish = [&](Stop stop)
  {
    for (int p = 0; p < P; ++p)
    {
      run.size[p] = size[p];
      run.pass_start[p] = start[p];
      run.state[p] = state[p];
    }
    run.cycles = cycles;
    run.pass = pass;
    run.entry = entry;
    run.done = done;
    run.stop = stop;
    return run;
  };
  while (true)
  {
    if (static_cast<double>(pass) >= limits.max_passes)
      return finish(Stop::max_passes);
    for (; entry < n; ++entry)
    {
      const std::int64_t lo = LO[entry], hi = HI[entry];
      const double w = W[entry];
      const double whole = w > 1.0 ? std::floor(w) : 1.0;
      const std::int64_t reps = static_cast<std::int64_t>(whole) + (w > whole ? 1 : 0);
      for (; done < reps; ++done)
      {
        if (spent >= limits.max_cycles)
          return finish(Stop::paused);
        const double wt = w <= 1.0 ? w : (done < static_cast<std::int64_t>(whole) ? 1.0 : w - whole);
        table.evaluate(size, K.data());
        double da[P];
        for (int p = 0; p < P; ++p)
        {
          double kmax = 0.0, kmin = 0.0;
          for (int g = 0; g < G; ++g)
          {
            kmax += F[hi * G + g] * K[p * G + g];
            kmin += F[lo * G + g] * K[p * G + g];
          }
          if (cy.clamp_min)
            kmin = std::max(kmin, 0.0);
          const double rate = kmax >= limits.K_crit ? std::numeric_limits<double>::infinity()
                              : retarded       ? retarded_rate(law, rk, state[p], size[p], kmax, kmin)
                                               : law.rate(kmax, kmin, size[p]);
          if (!std::isfinite(rate))
          {
            run.point = p;
            run.K_max = kmax;
            return finish(Stop::failure);
          }
          da[p] = wt * rate;
        }
        cycles += wt;
        spent += wt;
        int reached = -1;
        for (int p = 0; p < P; ++p)
        {
          size[p] += da[p];
          if (size[p] >= limits.size_end[p] and reached < 0)
            reached = p;
        }
        if (reached >= 0)
        {
          // Position after this cycle.
          if (++done >= reps)
          {
            done = 0;
            if (++entry >= n)
            {
              entry = 0;
              ++pass;
            }
          }
          run.point = reached;
          return finish(Stop::reached);
        }
      }
      done = 0;
    }
    entry = 0;
    ++pass;
    bool grew = false;
    for (int p = 0; p < P; ++p)
    {
      grew = grew or size[p] != start[p];
      start[p] = size[p];
    }
    if (!grew)
      return finish(Stop::arrest);
  }
}

template <class Table>
void growth_per_pass(const Table& table, const Cycles& cy, const GrowthLaw& law, const double* s, double* g)
{
  constexpr int P = Table::sizes;
  std::vector<double> K(static_cast<std::size_t>(P * cy.cases));
  table.evaluate(s, K.data());
  for (int p = 0; p < P; ++p)
  {
    double sum = 0.0;
    for (std::size_t k = 0; k < cy.lo.size(); ++k)
    {
      double kmax, kmin;
      cycle_k(cy, K.data(), p, cy.lo[k], cy.hi[k], kmax, kmin);
      sum += cy.count[k] * law.rate(kmax, kmin, s[p]);
    }
    g[p] = sum;
  }
}

template <class Table>
void state_k_max(const Table& table, const Cycles& cy, const double* s, double* K_max)
{
  constexpr int P = Table::sizes;
  const int G = cy.cases;
  std::vector<double> K(static_cast<std::size_t>(P * G));
  table.evaluate(s, K.data());
  const std::size_t states = cy.F.size() / static_cast<std::size_t>(G);
  for (int p = 0; p < P; ++p)
  {
    double best = -inf;
    for (std::size_t st = 0; st < states; ++st)
    {
      double k = 0.0;
      for (int g = 0; g < G; ++g)
        k += cy.F[st * G + g] * K[p * G + g];
      best = std::max(best, k);
    }
    K_max[p] = best;
  }
}

std::vector<double> passes_to(const KTable1& table, const Cycles& cy, const GrowthLaw& law, std::span<const double> a,
                              int order, double max_width)
{
  check_cycles(cy);
  const quadrature::Rule& rule = quadrature::gauss_legendre_cached(order);
  const std::vector<double>& nodes = table.sizes_of(0);
  std::vector<double> K(static_cast<std::size_t>(cy.cases));
  std::vector<double> out(a.size(), 0.0);
  double total = 0.0;
  for (std::size_t k = 1; k < a.size(); ++k)
  {
    if (!(a[k] >= a[k - 1]) or !(a[k - 1] > 0.0))
      throw std::invalid_argument("passes_to: the sizes must be positive and ascending");
    // Breaks: the interval's ends and the table's sizes inside it.
    std::vector<double> brk{a[k - 1]};
    for (double x : nodes)
      if (x > a[k - 1] and x < a[k])
        brk.push_back(x);
    brk.push_back(a[k]);
    for (std::size_t b = 0; b + 1 < brk.size() and std::isfinite(total); ++b)
    {
      const double x0 = std::log(brk[b]), x1 = std::log(brk[b + 1]);
      if (!(x1 > x0))
        continue;
      const int pieces = std::max(1, static_cast<int>(std::ceil((x1 - x0) / max_width)));
      const double h = (x1 - x0) / pieces;
      // Each piece is cut where the set of growing cycles changes (the growth per pass jumps there; a rule
      // across the jump converged slowly: 6e-5 of a Paris life with a threshold in tests/test_table_life.py).
      // (The set at a sub-piece's end is the next one's start: one evaluation per sub-piece.)
      auto which = [&](double x) { return growing_cycles(table, cy, law, std::exp(x), K); };
      auto set_lo = which(x0);
      for (int q = 0; q < pieces and std::isfinite(total); ++q)
      {
        const double p1 = q + 1 == pieces ? x1 : x0 + h * (q + 1);
        double lo = x0 + h * q;
        for (int cut = 0; lo < p1 and std::isfinite(total); ++cut)
        {
          double hi = p1;
          auto set_hi = which(hi);
          if (cut < 1000 and set_hi != set_lo)
          {
            double l = lo;  // bisection for the first change: which(l) == set_lo != which(hi) == set_hi
            for (int it = 0; it < 200 and hi - l > 1e-15 * std::max(1.0, std::abs(hi)); ++it)
            {
              const double m = 0.5 * (l + hi);
              const auto set_m = which(m);
              if (set_m == set_lo)
                l = m;
              else
              {
                hi = m;
                set_hi = set_m;
              }
            }
          }
          const double w = hi - lo;
          for (int i = 0; i < rule.size() and std::isfinite(total); ++i)
          {
            const double s = std::exp(lo + w * rule.points[i]);
            double g;
            growth_per_pass(table, cy, law, &s, &g);
            total = g > 0.0 ? total + rule.weights[i] * w * s / g : inf;
          }
          lo = hi;
          set_lo = set_hi;
        }
      }
    }
    out[k] = total;
  }
  return out;
}

BlockPath grow_blocks(const KTable2& table, const Cycles& cy, const GrowthLaw& law, double a0, double c0,
                      const CycleLimits& limits, double fraction)
{
  check_cycles(cy);
  if (table.cases() != cy.cases)
    throw std::invalid_argument("life integration: the K table and the factors have different load cases");
  const double Kc = std::min(limits.K_crit, law.critical_k());
  BlockPath path;
  double y[2] = {a0, c0};
  double P = 0.0;
  auto f = [&](const double* s, double* g) { growth_per_pass(table, cy, law, s, g); };
  auto kmax = [&](const double* s)
  {
    double k[2];
    state_k_max(table, cy, s, k);
    return std::max(k[0], k[1]);
  };
  auto step = [&](const double* y0, const double* g0, double h, double* out)
  {
    double k2[2], k3[2], k4[2], t[2];
    for (int p = 0; p < 2; ++p)
      t[p] = y0[p] + 0.5 * h * g0[p];
    f(t, k2);
    for (int p = 0; p < 2; ++p)
      t[p] = y0[p] + 0.5 * h * k2[p];
    f(t, k3);
    for (int p = 0; p < 2; ++p)
      t[p] = y0[p] + h * k3[p];
    f(t, k4);
    for (int p = 0; p < 2; ++p)
      out[p] = y0[p] + h / 6.0 * (g0[p] + 2.0 * k2[p] + 2.0 * k3[p] + k4[p]);
  };
  path.passes.push_back(0.0);
  path.a.push_back(a0);
  path.c.push_back(c0);
  if (kmax(y) >= Kc)
  {
    path.stop = Stop::failure;
    return path;
  }
  while (true)
  {
    double g0[2];
    f(y, g0);
    if (!std::isfinite(g0[0]) or !std::isfinite(g0[1]))
    {
      path.stop = Stop::failure;
      return path;
    }
    double h = inf;
    for (int p = 0; p < 2; ++p)
      if (g0[p] > 0.0)
        h = std::min(h, fraction * y[p] / g0[p]);
    if (!std::isfinite(h))
    {
      path.stop = Stop::arrest;
      return path;
    }
    bool last_passes = false;
    if (P + h >= limits.max_passes)
    {
      h = limits.max_passes - P;
      last_passes = true;
    }
    double yn[2];
    step(y, g0, h, yn);
    // A size limit inside the step: shorten it onto the limit.
    int hit = -1;
    for (int it = 0; it < 60; ++it)
    {
      hit = -1;
      double worst = 1.0;
      for (int p = 0; p < 2; ++p)
        if (yn[p] > limits.size_end[p] and yn[p] > y[p])
        {
          const double ratio = (limits.size_end[p] - y[p]) / (yn[p] - y[p]);
          if (ratio < worst)
          {
            worst = ratio;
            hit = p;
          }
        }
      if (hit < 0)
        break;
      if (std::abs(yn[hit] - limits.size_end[hit]) <= 1e-13 * limits.size_end[hit])
        break;
      h *= worst;
      step(y, g0, h, yn);
      last_passes = false;
    }
    for (int p = 0; p < 2; ++p)
      if (std::abs(yn[p] - limits.size_end[p]) <= 1e-13 * limits.size_end[p] or yn[p] >= limits.size_end[p])
        hit = hit < 0 ? p : hit;
    // K_crit inside the step: bisection on the step length.
    if (kmax(yn) >= Kc)
    {
      double lo = 0.0, hi = h;
      for (int it = 0; it < 100 and hi - lo > 1e-14 * (P + hi); ++it)
      {
        const double mid = 0.5 * (lo + hi);
        step(y, g0, mid, yn);
        (kmax(yn) >= Kc ? hi : lo) = mid;
      }
      step(y, g0, hi, yn);
      P += hi;
      path.passes.push_back(P);
      path.a.push_back(yn[0]);
      path.c.push_back(yn[1]);
      path.stop = Stop::failure;
      return path;
    }
    P += h;
    y[0] = yn[0];
    y[1] = yn[1];
    path.passes.push_back(P);
    path.a.push_back(y[0]);
    path.c.push_back(y[1]);
    if (hit >= 0)
    {
      path.stop = Stop::reached;
      path.point = hit;
      return path;
    }
    if (last_passes)
    {
      path.stop = Stop::max_passes;
      return path;
    }
  }
}

template CycleRun integrate_cycles<KTable1>(const KTable1&, const Cycles&, const GrowthLaw&, const Retardation&,
                                            CycleRun, const CycleLimits&);
template CycleRun integrate_cycles<KTable2>(const KTable2&, const Cycles&, const GrowthLaw&, const Retardation&,
                                            CycleRun, const CycleLimits&);
template void growth_per_pass<KTable1>(const KTable1&, const Cycles&, const GrowthLaw&, const double*, double*);
template void growth_per_pass<KTable2>(const KTable2&, const Cycles&, const GrowthLaw&, const double*, double*);
template void state_k_max<KTable1>(const KTable1&, const Cycles&, const double*, double*);
template void state_k_max<KTable2>(const KTable2&, const Cycles&, const double*, double*);
} // namespace cracklip::life
