// Bindings: fatigue life kernels (cycle counting, growth laws, K tables,
// cycle-by-cycle and block integration). Conversions only.
#include "array.h"

#include "life/cycle_integration.h"
#include "life/rainflow.h"

#include <pybind11/stl.h>

#include <map>
#include <string>

namespace cracklip_wrappers
{
using namespace cracklip::life;

namespace
{
template <class E>
E choice(const std::string& name, const std::map<std::string, E>& options, const char* what)
{
  auto it = options.find(name);
  if (it == options.end())
    throw std::invalid_argument(std::string("unknown ") + what + " '" + name + "'");
  return it->second;
}

Counting counting(const std::string& s)
{
  return choice<Counting>(s, {{"rainflow", Counting::rainflow}, {"range_pair", Counting::range_pair},
                              {"valley_to_peak", Counting::valley_to_peak}}, "cycle counting");
}

GrowthLaw make_law(const std::string& kind, const std::string& closure, const std::map<std::string, double>& k,
                   const std::vector<double>& R, const std::vector<double>& rates, const std::vector<double>& dK)
{
  LawConstants c;
  c.kind = choice<LawKind>(kind, {{"paris", LawKind::paris}, {"walker", LawKind::walker}, {"forman", LawKind::forman},
                                  {"nasgro", LawKind::nasgro}, {"hartman_schijve", LawKind::hartman_schijve},
                                  {"tabular", LawKind::tabular}}, "growth law");
  c.closure = choice<Closure>(closure, {{"contact", Closure::contact}, {"newman", Closure::newman},
                                        {"none", Closure::none}}, "closure");
  const std::map<std::string, double LawConstants::*> fields = {
      {"C", &LawConstants::C}, {"m", &LawConstants::m}, {"gamma", &LawConstants::gamma}, {"n", &LawConstants::n},
      {"K_f", &LawConstants::K_f}, {"p", &LawConstants::p}, {"q", &LawConstants::q}, {"dK1", &LawConstants::dK1},
      {"C_th_plus", &LawConstants::C_th_plus}, {"C_th_minus", &LawConstants::C_th_minus},
      {"alpha", &LawConstants::alpha}, {"smax_over_flow", &LawConstants::smax_over_flow}, {"a0", &LawConstants::a0},
      {"K_crit", &LawConstants::K_crit}, {"D", &LawConstants::D}, {"dK_thr", &LawConstants::dK_thr},
      {"A", &LawConstants::A}, {"exponent", &LawConstants::exponent}, {"threshold", &LawConstants::threshold}};
  for (const auto& [name, value] : k)
    c.*choice<double LawConstants::*>(name, fields, "law constant") = value;
  return c.kind == LawKind::tabular ? GrowthLaw(c, RateTable(R, rates, dK)) : GrowthLaw(c);
}

Cycles cycles_of(const carray<double>& F, const carray<std::int64_t>& lo, const carray<std::int64_t>& hi,
                 const carray<double>& count, bool clamp_min)
{
  if (F.ndim() != 2)
    throw std::invalid_argument("the factors must be (states, cases)");
  return Cycles{as_span(F), static_cast<int>(F.shape(1)), as_span(lo), as_span(hi), as_span(count), clamp_min};
}

py::dict run_dict(const CycleRun& r)
{
  py::dict d;
  d["size"] = py::make_tuple(r.size[0], r.size[1]);
  d["cycles"] = r.cycles;
  d["pass"] = r.pass;
  d["entry"] = r.entry;
  d["done"] = r.done;
  d["state"] = py::make_tuple(py::make_tuple(r.state[0].a_OL, r.state[0].r_OL, r.state[0].K_OL),
                              py::make_tuple(r.state[1].a_OL, r.state[1].r_OL, r.state[1].K_OL));
  d["pass_start"] = py::make_tuple(r.pass_start[0], r.pass_start[1]);
  d["stop"] = static_cast<int>(r.stop);
  d["point"] = r.point;
  d["K_max"] = r.K_max;
  return d;
}

/// Up to two numbers of a dict entry into out (sizes of one or two points).
void pair_of(const py::dict& d, const char* key, double out[2])
{
  const auto v = d[key].cast<std::vector<double>>();
  for (std::size_t p = 0; p < v.size() and p < 2; ++p)
    out[p] = v[p];
}

CycleRun run_of(const py::dict& d)
{
  CycleRun r;
  pair_of(d, "size", r.size);
  pair_of(d, "pass_start", r.pass_start);
  r.cycles = d["cycles"].cast<double>();
  r.pass = d["pass"].cast<std::int64_t>();
  r.entry = d["entry"].cast<std::int64_t>();
  r.done = d["done"].cast<std::int64_t>();
  auto st = d["state"].cast<std::vector<std::vector<double>>>();
  for (std::size_t p = 0; p < st.size() and p < 2; ++p)
    r.state[p] = {st[p].at(0), st[p].at(1), st[p].at(2)};
  return r;
}

CycleLimits limits_of(const py::dict& d)
{
  CycleLimits l;
  pair_of(d, "size_end", l.size_end);
  l.K_crit = d["K_crit"].cast<double>();
  l.max_passes = d["max_passes"].cast<double>();
  l.max_cycles = d["max_cycles"].cast<double>();
  return l;
}

template <class Table>
void declare_table_functions(py::module& m)
{
  m.def(
      "integrate_cycles",
      [](const Table& t, const carray<double>& F, const carray<std::int64_t>& lo, const carray<std::int64_t>& hi,
         const carray<double>& count, const GrowthLaw& law, const Retardation& ret, const py::dict& run,
         const py::dict& limits, bool clamp_min)
      {
        const Cycles cy = cycles_of(F, lo, hi, count, clamp_min);
        const CycleRun start = run_of(run);
        const CycleLimits lim = limits_of(limits);
        CycleRun out;
        {
          py::gil_scoped_release release;
          out = integrate_cycles(t, cy, law, ret, start, lim);
        }
        return run_dict(out);
      },
      py::arg("table"), py::arg("F"), py::arg("lo"), py::arg("hi"), py::arg("count"), py::arg("law"),
      py::arg("retardation"), py::arg("run"), py::arg("limits"), py::arg("clamp_min") = false,
      "Cycle by cycle from run (a dict: size, cycles, pass, entry, done, state, pass_start) within limits "
      "(size_end, K_crit, max_passes, max_cycles); returns the run where it stopped, with stop (0 reached, 1 "
      "failure, 2 arrest, 3 max_passes, 4 paused), point and K_max.");
  m.def(
      "growth_per_pass",
      [](const Table& t, const carray<double>& F, const carray<std::int64_t>& lo, const carray<std::int64_t>& hi,
         const carray<double>& count, const GrowthLaw& law, const std::vector<double>& sizes, bool clamp_min)
      {
        std::vector<double> g(Table::sizes);
        growth_per_pass(t, cycles_of(F, lo, hi, count, clamp_min), law, sizes.data(), g.data());
        return g;
      },
      py::arg("table"), py::arg("F"), py::arg("lo"), py::arg("hi"), py::arg("count"), py::arg("law"),
      py::arg("sizes"), py::arg("clamp_min") = false, "Growth per pass of each point at the sizes (distinct cycles, counts summed).");
  m.def(
      "state_k_max",
      [](const Table& t, const carray<double>& F, const std::vector<double>& sizes)
      {
        std::vector<double> k(Table::sizes);
        const std::vector<std::int64_t> none;
        const std::vector<double> nothing;
        const Cycles cy{as_span(F), static_cast<int>(F.shape(1)), none, none, nothing};
        state_k_max(t, cy, sizes.data(), k.data());
        return k;
      },
      py::arg("table"), py::arg("F"), py::arg("sizes"), "K_max over the load states of each point at the sizes.");
}
} // namespace

void declare_life(py::module& m)
{
  m.def(
      "reversal_indices", [](const carray<double>& v) { return as_pyarray(reversal_indices(as_span(v))); },
      py::arg("values"), "Indices of the turning points of a history (plateaus: their first point).");
  m.def(
      "count_cycles",
      [](const carray<double>& v, const std::string& method, bool repeated)
      {
        CountedCycles c = count_cycles(as_span(v), counting(method), repeated);
        return py::make_tuple(as_pyarray(std::move(c.lo)), as_pyarray(std::move(c.hi)),
                              as_pyarray(std::move(c.count)));
      },
      py::arg("values"), py::arg("method"), py::arg("repeated"),
      "Counted cycles of a history (ASTM E1049): (lo, hi, count) in closing order.");

  py::class_<GrowthLaw>(m, "GrowthLaw", "A growth law with its closure (C++).")
      .def(py::init(&make_law), py::arg("kind"), py::arg("closure"), py::arg("constants"),
           py::arg("table_R") = std::vector<double>{}, py::arg("table_rates") = std::vector<double>{},
           py::arg("table_delta_K") = std::vector<double>{})
      .def(
          "rates",
          [](const GrowthLaw& law, const carray<double>& K_max, const carray<double>& K_min, const carray<double>& a)
          {
            const py::ssize_t n = K_max.size();
            if (K_min.size() != n or (a.size() != n and a.size() != 1))
              throw std::invalid_argument("rates: K_max, K_min and a must have the same length");
            std::vector<double> out(n);
            for (py::ssize_t i = 0; i < n; ++i)
              out[i] = law.rate(K_max.data()[i], K_min.data()[i], a.data()[a.size() == 1 ? 0 : i]);
            return as_pyarray(std::move(out));
          },
          py::arg("K_max"), py::arg("K_min"), py::arg("a"), "da/dN of each cycle.")
      .def("critical_k", &GrowthLaw::critical_k);

  py::class_<Retardation>(m, "Retardation", "Retardation settings (C++).")
      .def(py::init(
               [](const std::string& model, double sigma_ys, double beta, double gamma, double shutoff)
               {
                 return Retardation{choice<RetardationModel>(model, {{"none", RetardationModel::none},
                                                                     {"wheeler", RetardationModel::wheeler},
                                                                     {"willenborg", RetardationModel::willenborg}},
                                                             "retardation"),
                                    sigma_ys, beta, gamma, shutoff};
               }),
           py::arg("model"), py::arg("sigma_ys") = 1.0, py::arg("beta") = 2.0, py::arg("gamma") = 1.0,
           py::arg("shutoff") = 3.0);

  py::class_<KTable1>(m, "KTable1", "K per unit load against one crack size (C++).")
      .def(py::init(
               [](const std::vector<double>& a, const carray<double>& K)
               {
                 if (K.ndim() != 2)
                   throw std::invalid_argument("KTable1: K must be (sizes, cases)");
                 return KTable1(a, std::vector<double>(K.data(), K.data() + K.size()), static_cast<int>(K.shape(1)));
               }),
           py::arg("a"), py::arg("K"))
      .def(
          "evaluate",
          [](const KTable1& t, const carray<double>& a)
          {
            const py::ssize_t n = a.size(), G = t.cases();
            std::vector<double> out(n * G);
            for (py::ssize_t i = 0; i < n; ++i)
              t.evaluate(a.data() + i, out.data() + i * G);
            return as_pyarray(std::move(out), {n, G});
          },
          py::arg("a"), "K (n, cases) at the sizes a (clamped to the table).");
  py::class_<KTable2>(m, "KTable2", "K per unit load at two points against two crack sizes (C++).")
      .def(py::init(
               [](const std::vector<double>& a, const std::vector<double>& c, const carray<double>& K)
               {
                 if (K.ndim() != 4 or K.shape(2) != 2)
                   throw std::invalid_argument("KTable2: K must be (a, c, 2 points, cases)");
                 return KTable2(a, c, std::vector<double>(K.data(), K.data() + K.size()), static_cast<int>(K.shape(3)));
               }),
           py::arg("a"), py::arg("c"), py::arg("K"))
      .def(
          "evaluate",
          [](const KTable2& t, const carray<double>& a, const carray<double>& c)
          {
            const py::ssize_t n = a.size(), G = t.cases();
            if (c.size() != n)
              throw std::invalid_argument("KTable2.evaluate: a and c must have the same length");
            std::vector<double> out(n * 2 * G);
            for (py::ssize_t i = 0; i < n; ++i)
            {
              const double s[2] = {a.data()[i], c.data()[i]};
              t.evaluate(s, out.data() + i * 2 * G);
            }
            return as_pyarray(std::move(out), {n, 2, G});
          },
          py::arg("a"), py::arg("c"), "K (n, 2, cases) at the sizes (clamped to the grid).");

  declare_table_functions<KTable1>(m);
  declare_table_functions<KTable2>(m);
  m.def(
      "passes_to",
      [](const KTable1& t, const carray<double>& F, const carray<std::int64_t>& lo, const carray<std::int64_t>& hi,
         const carray<double>& count, const GrowthLaw& law, const carray<double>& a, int order, double max_width,
         bool clamp_min)
      {
        const Cycles cy = cycles_of(F, lo, hi, count, clamp_min);
        std::vector<double> out;
        {
          py::gil_scoped_release release;
          out = passes_to(t, cy, law, as_span(a), order, max_width);
        }
        return as_pyarray(std::move(out));
      },
      py::arg("table"), py::arg("F"), py::arg("lo"), py::arg("hi"), py::arg("count"), py::arg("law"), py::arg("a"),
      py::arg("order") = 10, py::arg("max_width") = 0.05, py::arg("clamp_min") = false,
      "Passes from a[0] to each a[k] without sequence effects (inf past an arrest).");
  m.def(
      "grow_blocks",
      [](const KTable2& t, const carray<double>& F, const carray<std::int64_t>& lo, const carray<std::int64_t>& hi,
         const carray<double>& count, const GrowthLaw& law, double a0, double c0, const py::dict& limits,
         double fraction, bool clamp_min)
      {
        const Cycles cy = cycles_of(F, lo, hi, count, clamp_min);
        const CycleLimits lim = limits_of(limits);
        BlockPath p;
        {
          py::gil_scoped_release release;
          p = grow_blocks(t, cy, law, a0, c0, lim, fraction);
        }
        py::dict d;
        d["passes"] = as_pyarray(std::move(p.passes));
        d["a"] = as_pyarray(std::move(p.a));
        d["c"] = as_pyarray(std::move(p.c));
        d["stop"] = static_cast<int>(p.stop);
        d["point"] = p.point;
        return d;
      },
      py::arg("table"), py::arg("F"), py::arg("lo"), py::arg("hi"), py::arg("count"), py::arg("law"), py::arg("a0"),
      py::arg("c0"), py::arg("limits"), py::arg("fraction") = 2e-3, py::arg("clamp_min") = false,
      "Two sizes in blocks (RK4 in the passes): passes, a, c per step, stop, point.");
}
} // namespace cracklip_wrappers
