// Bindings: tip enrichment functions, interaction integral.
#include "array.h"

#include "quadrature/cell_quadrature_2d.h"
#include "fracture/interaction_integral_2d.h"
#include "fracture/interaction_integral_3d.h"
#include <pybind11/stl.h>

#include <algorithm>
#include <optional>
#include "enrichment/tip_functions_2d.h"

namespace cracklip_wrappers
{
using namespace cracklip;
using Cracks = std::vector<const CrackGeometry*>;

namespace
{
/// Per-point curvatures (n, 4) kappa_f, kappa_11, kappa_33, tau from (n)
/// (kappa_f alone: a planar crack) or (n, 4).
std::vector<double> front_curvatures(const carray<double>& k, py::ssize_t n)
{
  std::vector<double> out(4 * n, 0.0);
  if (k.ndim() == 1 and k.shape(0) == n)
    for (py::ssize_t p = 0; p < n; ++p)
      out[4 * p] = k.data()[p];
  else if (k.ndim() == 2 and k.shape(0) == n and k.shape(1) == 4)
    std::copy(k.data(), k.data() + 4 * n, out.begin());
  else
    throw std::invalid_argument("curvature must be (n) (the front's, a planar crack) or (n, 4) (kappa_f, "
                                "kappa_11, kappa_33, tau) for n = " + std::to_string(n) + " points");
  return out;
}

FrontDomainTable domain_table(const carray<std::int32_t>& offsets, const carray<std::int32_t>& point,
                              const carray<double>& q)
{
  if (q.ndim() != 3 or q.shape(1) != 4)
    throw std::invalid_argument("table q must be (m, 4, num_domains)");
  return {as_span(offsets), as_span(point), as_span(q), static_cast<int>(q.shape(2))};
}

TipFrame frame(std::array<double, 2> tip, std::array<double, 2> e1, int orientation)
{
  if (orientation != 1 and orientation != -1)
    throw std::invalid_argument("tip orientation must be +1 or -1");
  return TipFrame{tip, e1, orientation};
}
} // namespace

void declare_fracture(py::module& m)
{
  m.def(
      "tip_cell_rule",
      [](const carray<double>& polygon, std::array<double, 2> apex, const QuadratureOptions& options)
      {
        std::vector<Point2> poly(polygon.size() / 2);
        for (std::size_t k = 0; k < poly.size(); ++k)
          poly[k] = {polygon.data()[2 * k], polygon.data()[2 * k + 1]};
        std::vector<double> pts, w;
        tip_polygon_rule(apex, poly, options, pts, w);
        const py::ssize_t n = w.size();
        return py::make_tuple(as_pyarray(std::move(pts), {n, 2}), as_pyarray(std::move(w)));
      },
      py::arg("polygon"), py::arg("apex"), py::arg("options"),
      "Rule over a polygon fanned from a tip inside it (collapsed, or the paper's plain Gauss "
      "per options.tip_rule): points (n, 2), weights.");

  m.def(
      "branch_functions",
      [](std::array<double, 2> tip, std::array<double, 2> e1, const carray<double>& points,
         const carray<std::int8_t>& sides, int orientation)
      {
        const py::ssize_t n = points.size() / 2;
        std::vector<double> F(4 * n), dF(8 * n);
        std::array<double, 4> f;
        std::array<std::array<double, 2>, 4> df;
        for (py::ssize_t p = 0; p < n; ++p)
        {
          branch_functions(frame(tip, e1, orientation), {points.data()[2 * p], points.data()[2 * p + 1]},
                           sides.data()[p], f, df);
          for (int l = 0; l < 4; ++l)
          {
            F[4 * p + l] = f[l];
            dF[8 * p + 2 * l] = df[l][0];
            dF[8 * p + 2 * l + 1] = df[l][1];
          }
        }
        return py::make_tuple(as_pyarray(std::move(F), {n, 4}), as_pyarray(std::move(dF), {n, 4, 2}));
      },
      py::arg("tip"), py::arg("e1"), py::arg("points"), py::arg("sides"), py::arg("orientation") = 1,
      "Scalar branch functions (n, 4) and global gradients (n, 4, 2).");

  m.def(
      "williams_displacement",
      [](std::array<double, 2> tip, std::array<double, 2> e1, double kappa,
         const carray<double>& points, const carray<std::int8_t>& sides, int orientation)
      {
        const py::ssize_t n = points.size() / 2;
        std::vector<double> U(4 * n), dU(8 * n);
        std::array<std::array<double, 2>, 2> u;
        std::array<std::array<std::array<double, 2>, 2>, 2> du;
        for (py::ssize_t p = 0; p < n; ++p)
        {
          williams_displacement(frame(tip, e1, orientation), {points.data()[2 * p], points.data()[2 * p + 1]},
                                sides.data()[p], kappa, u, du);
          for (int mo = 0; mo < 2; ++mo)
            for (int i = 0; i < 2; ++i)
            {
              U[4 * p + 2 * mo + i] = u[mo][i];
              for (int j = 0; j < 2; ++j)
                dU[8 * p + 4 * mo + 2 * i + j] = du[mo][i][j];
            }
        }
        return py::make_tuple(as_pyarray(std::move(U), {n, 2, 2}), as_pyarray(std::move(dU), {n, 2, 2, 2}));
      },
      py::arg("tip"), py::arg("e1"), py::arg("kappa"), py::arg("points"), py::arg("sides"),
      py::arg("orientation") = 1,
      "Williams vector functions without K/(2 mu sqrt(2 pi)): U (n, mode, comp), dU (n, mode, comp, d/dx_j).");

  m.def(
      "interaction_integral",
      [](std::array<double, 2> tip, std::array<double, 2> e1, double E, double nu,
         const carray<double>& points, const carray<double>& weights, const carray<double>& grad_q,
         const carray<double>& grad_u, const carray<std::int8_t>& sides, int orientation)
      {
        return interaction_integral(frame(tip, e1, orientation), E, nu, as_span(points), as_span(weights),
                                    as_span(grad_q), as_span(grad_u), as_span(sides));
      },
      py::arg("tip"), py::arg("e1"), py::arg("E"), py::arg("nu"), py::arg("points"),
      py::arg("weights"), py::arg("grad_q"), py::arg("grad_u"), py::arg("sides"),
      py::arg("orientation") = 1,
      "Interaction integrals (I_mode_I, I_mode_II) from values at points; K = E* I / 2.");

  m.def(
      "compute_domain_points",
      [](const carray<double>& x, const carray<std::int32_t>& cells, const EnrichmentLayout& layout,
         const Cracks& cracks, std::array<double, 2> tip, std::array<double, 2> e1, double radius,
         const QuadratureOptions& options, bool interior, std::optional<double> inner_radius)
      {
        DomainPoints d = compute_domain_points(as_span(x), as_span(cells), layout, cracks,
                                               frame(tip, e1, 1), radius, options, interior, inner_radius);
        const py::ssize_t n = d.weight.size();
        py::dict out;
        out["cell"] = as_pyarray(std::move(d.cell));
        out["ref"] = as_pyarray(std::move(d.ref), {n, 2});
        out["x"] = as_pyarray(std::move(d.x), {n, 2});
        out["weight"] = as_pyarray(std::move(d.weight));
        out["side"] = as_pyarray(std::move(d.side));
        out["q"] = as_pyarray(std::move(d.q));
        out["grad_q"] = as_pyarray(std::move(d.grad_q), {n, 2});
        return out;
      },
      py::arg("x"), py::arg("cells"), py::arg("layout"), py::arg("cracks"), py::arg("tip"),
      py::arg("e1"), py::arg("radius"), py::arg("options"), py::arg("interior") = false,
      py::arg("inner_radius") = py::none(),
      "Quadrature points of the ring where q has a gradient (interior: of every cell where q != 0): "
      "the plateau q of `radius`, or with inner_radius < radius the ring q (1 within inner_radius, "
      "0 beyond radius, linear between).");

  m.def(
      "auxiliary_fields_3d",
      [](double E, double nu, const carray<double>& frames, const carray<double>& curvature, const carray<double>& x,
         const carray<std::int8_t>& sides)
      {
        const py::ssize_t n = sides.size();
        std::vector<double> U(9 * n), G(27 * n), local(9 * n), div(9 * n);
        auxiliary_fields_3d(E, nu, as_span(frames), front_curvatures(curvature, n), as_span(x), as_span(sides), U, G,
                            local, div);
        py::dict d;
        d["U"] = as_pyarray(std::move(U), {n, 3, 3});
        d["G"] = as_pyarray(std::move(G), {n, 3, 3, 3});
        d["local"] = as_pyarray(std::move(local), {n, 3, 3});
        d["div_sigma"] = as_pyarray(std::move(div), {n, 3, 3});
        return d;
      },
      py::arg("E"), py::arg("nu"), py::arg("frames"), py::arg("curvature"), py::arg("x"), py::arg("sides"),
      "Unit-K auxiliary fields of curved fronts at points: U (n, mode, i), true gradient G (n, mode, i, j), "
      "local components (n, mode, k) along e1, e2, e3, stress divergence (n, mode, i). frames (n, 12): origin, "
      "e1, e2, e3 of each point's nearest front point; curvature there: (n) the front's (a planar crack) or "
      "(n, 4) kappa_f, kappa_11, kappa_33, tau (interaction_integral_3d.h).");

  m.def(
      "interaction_integrand_3d",
      [](double E, double nu, const carray<double>& frames, const carray<double>& curvature, const carray<double>& x,
         const carray<double>& grad_u, const carray<std::int8_t>& sides, const std::optional<carray<double>>& body)
      {
        const py::ssize_t n = sides.size();
        std::vector<double> T(27 * n), D(9 * n);
        std::vector<double> b;
        if (body)
          b.assign(body->data(), body->data() + body->size());
        interaction_integrand_3d(E, nu, as_span(frames), front_curvatures(curvature, n), as_span(x),
                                 as_span(grad_u), as_span(sides), b, T, D);
        return py::make_tuple(as_pyarray(std::move(T), {n, 3, 3, 3}), as_pyarray(std::move(D), {n, 3, 3}));
      },
      py::arg("E"), py::arg("nu"), py::arg("frames"), py::arg("curvature"), py::arg("x"), py::arg("grad_u"),
      py::arg("sides"), py::arg("body") = py::none(),
      "Integrands of the curved-front interaction integral: T (n, mode, j, l), D (n, mode, l); "
      "I_m int q_s (e1.d) ds = sum w (grad q . T_m d + q D_m . d) + lip terms. curvature (n) or (n, 4) as "
      "auxiliary_fields_3d.");

  m.def(
      "front_sifs_3d",
      [](double E, double nu, const carray<double>& I, const carray<double>& q_e1, const carray<double>& q_e2)
      {
        require_columns(I, 3, "I");
        const py::ssize_t n = I.shape(0);
        if (q_e1.size() != n or q_e2.size() != n)
          throw std::invalid_argument("front_sifs_3d: q_e1 and q_e2 need one value per row of I");
        std::vector<double> K(3 * n);
        for (py::ssize_t k = 0; k < n; ++k)
        {
          const auto v = front_sifs_3d(E, nu, {I.data()[3 * k], I.data()[3 * k + 1], I.data()[3 * k + 2]},
                                       q_e1.data()[k], q_e2.data()[k]);
          std::copy(v.begin(), v.end(), K.begin() + 3 * k);
        }
        return as_pyarray(std::move(K), {n, 3});
      },
      py::arg("E"), py::arg("nu"), py::arg("I"), py::arg("q_e1"), py::arg("q_e2"),
      "K (n, 3) from interaction integrals I (n, 3) and int q (e1 . d) ds, int q (e2 . d) ds (n) "
      "(interaction_integral_3d.h front_sifs_3d).");

  m.def(
      "front_domain_integrals_3d",
      [](double E, double nu, const carray<double>& frames, const carray<double>& curvature, const carray<double>& x,
         const carray<double>& grad_u, const carray<std::int8_t>& sides, const std::optional<carray<double>>& body,
         const carray<double>& weights, const carray<std::int32_t>& point_cell, const carray<double>& shape,
         const carray<double>& cell_gradients, const carray<std::int32_t>& offsets,
         const carray<std::int32_t>& point, const carray<double>& q, const carray<double>& directions,
         py::array_t<double, py::array::c_style> I)
      {
        const py::ssize_t n = sides.size();
        std::vector<double> b;
        if (body)
          b.assign(body->data(), body->data() + body->size());
        const auto k = front_curvatures(curvature, n);
        std::span<double> out(I.mutable_data(), static_cast<std::size_t>(I.size()));
        py::gil_scoped_release release;
        front_domain_integrals_3d(E, nu, as_span(frames), k, as_span(x), as_span(grad_u), as_span(sides), b,
                                  as_span(weights), as_span(point_cell), as_span(shape), as_span(cell_gradients),
                                  domain_table(offsets, point, q), as_span(directions), out);
      },
      py::arg("E"), py::arg("nu"), py::arg("frames"), py::arg("curvature"), py::arg("x"), py::arg("grad_u"),
      py::arg("sides"), py::arg("body"), py::arg("weights"), py::arg("point_cell"), py::arg("shape"),
      py::arg("cell_gradients"), py::arg("offsets"), py::arg("point"), py::arg("q"), py::arg("directions"),
      py::arg("I"),
      "Adds to I (K, domains, 3) the volume interaction integrals of every front point whose domain reaches "
      "the points' cells (table offsets (c + 1), point (m), q (m, 4, domains)), in one pass over the points.");

  m.def(
      "front_domain_sums_3d",
      [](const carray<double>& values, const carray<double>& weights, const carray<std::int32_t>& point_cell,
         const carray<double>& shape, const carray<std::int32_t>& offsets, const carray<std::int32_t>& point,
         const carray<double>& q, const carray<double>& directions, py::array_t<double, py::array::c_style> I)
      {
        std::span<double> out(I.mutable_data(), static_cast<std::size_t>(I.size()));
        front_domain_sums_3d(as_span(values), as_span(weights), as_span(point_cell), as_span(shape),
                             static_cast<std::size_t>(offsets.size() - 1), domain_table(offsets, point, q),
                             as_span(directions), out);
      },
      py::arg("values"), py::arg("weights"), py::arg("point_cell"), py::arg("shape"), py::arg("offsets"),
      py::arg("point"), py::arg("q"), py::arg("directions"), py::arg("I"),
      "Adds to I (K, domains, 3) sum_p w_p q values_p . d_k over points and the table entries of their cells.");
}

} // namespace cracklip_wrappers
