// The 3D interaction integral on exact straight-front fields: it returns
// the K of each mode, whatever the mix, on a ring domain and with a hat
// along the front.
#include "fracture/interaction_integral_3d.h"
#include "quadrature/rules.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <vector>

using namespace cracklip;

namespace
{
constexpr double E = 2.0, nu = 0.3;
const double mu = E / (2.0 * (1.0 + nu)), Eprime = E / (1.0 - nu * nu);

FrontFrame oblique()
{
  const double a = 0.4, b = 0.9;
  const Point3 e1 = {std::cos(a) * std::cos(b), std::sin(a) * std::cos(b), std::sin(b)};
  Point3 e2 = {-std::sin(a), std::cos(a), 0.0};
  const Point3 e3 = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  return {{0.2, -0.1, 0.3}, e1, e2, e3};
}

// The exact field u = sum_m K_m U_m / (2 mu sqrt(2 pi)): its gradient at x.
std::array<std::array<double, 3>, 3> exact_gradient(const FrontFrame& f, const Point3& x, const double K[3])
{
  std::array<Point3, 3> U;
  std::array<std::array<Point3, 3>, 3> dU;
  front_vector_functions(f, x, 0, 3.0 - 4.0 * nu, U, dU);
  const double s = 1.0 / (2.0 * mu * std::sqrt(2.0 * std::numbers::pi));
  std::array<std::array<double, 3>, 3> g{};
  for (int m = 0; m < 3; ++m)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        g[i][j] += K[m] * s * dU[m][i][j];
  return g;
}

// Points of a tensor Gauss rule on r in [r0, r1], theta in (-pi, pi), x3 in
// [-l, l] around the front, with q = q_r(r) q_s(x3): q_r = 1 below R1, linear
// to 0 at R2; q_s = 1 (hat = false) or 1 - |x3| / l (hat = true).
std::array<double, 3> integrate(const FrontFrame& f, const double K[3], double R1, double R2, double l, bool hat)
{
  const auto gr = quadrature::gauss_legendre(24), gt = quadrature::gauss_legendre(48), gz = quadrature::gauss_legendre(8);
  std::vector<double> frames, x, w, gq, gu;
  std::vector<std::int8_t> sides;
  // r in [R1, R2] (the ring), and for the hat also [0, R1] (q_r = 1 there):
  // one rule per piece where q is smooth; the hat's kink at x3 = 0 splits z.
  std::vector<std::array<double, 2>> pieces = {{R1, R2}};
  if (hat)
    pieces.push_back({0.0, R1});
  for (const auto& [r0, r1] : pieces)
    for (int half = 0; half < (hat ? 2 : 1); ++half)
      for (int ir = 0; ir < gr.size(); ++ir)
        for (int it = 0; it < gt.size(); ++it)
          for (int iz = 0; iz < gz.size(); ++iz)
          {
            const double r = r0 + (r1 - r0) * gr.points[ir];
            const double t = std::numbers::pi * (2.0 * gt.points[it] - 1.0);
            const double z = hat ? (half == 0 ? -l + l * gz.points[iz] : l * gz.points[iz])
                                 : -l + 2 * l * gz.points[iz];
            const double dz = hat ? l : 2 * l;
            const double weight = gr.weights[ir] * (r1 - r0) * gt.weights[it] * 2 * std::numbers::pi
                                  * gz.weights[iz] * dz * r;
            const double x1 = r * std::cos(t), x2 = r * std::sin(t);
            Point3 p;
            for (int i = 0; i < 3; ++i)
              p[i] = f.origin[i] + x1 * f.e1[i] + x2 * f.e2[i] + z * f.e3[i];
            const double qr = r < R1 ? 1.0 : (R2 - r) / (R2 - R1), dqr = r < R1 ? 0.0 : -1.0 / (R2 - R1);
            const double qs = hat ? 1.0 - std::abs(z) / l : 1.0, dqs = hat ? (z < 0 ? 1.0 / l : -1.0 / l) : 0.0;
            for (int i = 0; i < 3; ++i)
              gq.push_back(dqr * qs * (std::cos(t) * f.e1[i] + std::sin(t) * f.e2[i]) + qr * dqs * f.e3[i]);
            const auto g = exact_gradient(f, p, K);
            for (int i = 0; i < 3; ++i)
              for (int j = 0; j < 3; ++j)
                gu.push_back(g[i][j]);
            for (const auto& v : {f.origin, f.e1, f.e2, f.e3})
              frames.insert(frames.end(), v.begin(), v.end());
            x.insert(x.end(), p.begin(), p.end());
            w.push_back(weight);
            sides.push_back(0);
          }
  return interaction_integral_3d(E, nu, f.e1, frames, x, w, gq, gu, sides);
}
} // namespace

TEST(InteractionIntegral3D, RingDomainGivesEachK)
{
  const FrontFrame f = oblique();
  const double K[3] = {1.3, -0.7, 0.4};
  const double l = 0.25;
  const auto I = integrate(f, K, 0.1, 0.3, l, false);
  const double weight = 2 * l; // int q_s ds
  EXPECT_NEAR(0.5 * Eprime * I[0] / weight, K[0], 1e-10);
  EXPECT_NEAR(0.5 * Eprime * I[1] / weight, K[1], 1e-10);
  EXPECT_NEAR(mu * I[2] / weight, K[2], 1e-10);
}

TEST(InteractionIntegral3D, HatAlongTheFrontGivesEachK)
{
  // q_s = 1 - |x3| / l: q varies along the front too, and the integral runs
  // down to the front (r from 0, where the integrand ~ 1/r times r dr).
  const FrontFrame f = oblique();
  for (const auto& K : {std::array<double, 3>{1.0, 0.0, 0.0}, std::array<double, 3>{0.0, 1.0, 0.0},
                        std::array<double, 3>{0.0, 0.0, 1.0}, std::array<double, 3>{0.6, -0.2, 0.9}})
  {
    const double l = 0.2;
    const auto I = integrate(f, K.data(), 0.1, 0.3, l, true);
    const double weight = l; // int (1 - |s| / l) ds over [-l, l]
    EXPECT_NEAR(0.5 * Eprime * I[0] / weight, K[0], 1e-10);
    EXPECT_NEAR(0.5 * Eprime * I[1] / weight, K[1], 1e-10);
    EXPECT_NEAR(mu * I[2] / weight, K[2], 1e-10);
  }
}

// ---------------------------------------------------------------------------
// Curved fronts: the auxiliary fields that follow a circular front (radius
// a, in the plane z = 0, the crack inside it for sign = +1, outside for
// sign = -1), their true gradient and stress divergence against finite
// differences, and the domain integral's identity on a tube around the
// front: a field made of these fields with given K (not in equilibrium: it
// carries the body force -div sigma and tractions on its lips) gives back
// its K exactly once the curvature terms are in, and misses them without.
namespace
{
constexpr double a_circle = 1.5;

struct CircleFrame
{
  FrontFrame f;
  double kappa;
};

// The frame of the point of the circle nearest to x: e1 radial (out of the
// crack), e2 = +z, e3 = e1 x e2; the curvature 1 / a (sign +1) or -1 / a.
CircleFrame circle_frame(const Point3& x, int sign)
{
  const double rho = std::hypot(x[0], x[1]);
  const Point3 er = {x[0] / rho, x[1] / rho, 0.0};
  CircleFrame c;
  c.f.origin = {a_circle * er[0], a_circle * er[1], 0.0};
  c.f.e1 = {sign * er[0], sign * er[1], 0.0};
  c.f.e2 = {0.0, 0.0, 1.0};
  c.f.e3 = {c.f.e1[1], -c.f.e1[0], 0.0}; // e1 x e2
  c.kappa = sign / a_circle;
  return c;
}

std::vector<double> frame_row(const FrontFrame& f)
{
  std::vector<double> v;
  for (const auto& p : {f.origin, f.e1, f.e2, f.e3})
    v.insert(v.end(), p.begin(), p.end());
  return v;
}

struct Aux
{
  std::vector<double> U, G, local, div;
};

Aux aux_at(const Point3& x, int side, int sign, bool curved = true)
{
  const CircleFrame c = circle_frame(x, sign);
  const std::vector<double> fr = frame_row(c.f);
  const std::vector<double> k = {curved ? c.kappa : 0.0, 0.0, 0.0, 0.0};
  const std::vector<std::int8_t> s = {static_cast<std::int8_t>(side)};
  Aux r{std::vector<double>(9), std::vector<double>(27), std::vector<double>(9), std::vector<double>(9)};
  auxiliary_fields_3d(E, nu, fr, k, x, s, r.U, r.G, r.local, r.div);
  return r;
}

void stress_of(const double* g, double s[3][3])
{
  const double lm = E * nu / ((1 + nu) * (1 - 2 * nu)), tr = g[0] + g[4] + g[8];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      s[i][j] = mu * (g[3 * i + j] + g[3 * j + i]) + (i == j ? lm * tr : 0.0);
}

// On a lip with outward normal n_out, the solution's gradient g (3, 3) and
// the auxiliary gradients auxG (3 modes, 3, 3), per mode m: the traction
// terms t . (G_m d) + t_aux,m . (g d) (t = sigma(g) n_out) and sigma(g) :
// eps_aux,m.
struct LipIntegrand
{
  std::array<double, 3> traction{}, energy{};
};
LipIntegrand lip_integrand(const double* g, const double* auxG, const double* n_out, const double* d)
{
  double sig[3][3];
  stress_of(g, sig);
  double t[3], gd[3];
  for (int i = 0; i < 3; ++i)
  {
    t[i] = sig[i][0] * n_out[0] + sig[i][1] * n_out[1] + sig[i][2] * n_out[2];
    gd[i] = g[3 * i] * d[0] + g[3 * i + 1] * d[1] + g[3 * i + 2] * d[2];
  }
  LipIntegrand out;
  for (int m = 0; m < 3; ++m)
  {
    const double* G = auxG + 9 * m;
    double sa[3][3];
    stress_of(G, sa);
    for (int i = 0; i < 3; ++i)
    {
      const double ta = sa[i][0] * n_out[0] + sa[i][1] * n_out[1] + sa[i][2] * n_out[2];
      const double Gd = G[3 * i] * d[0] + G[3 * i + 1] * d[1] + G[3 * i + 2] * d[2];
      out.traction[m] += t[i] * Gd + ta * gd[i];
      for (int j = 0; j < 3; ++j)
        out.energy[m] += sig[i][j] * 0.5 * (G[3 * i + j] + G[3 * j + i]);
    }
  }
  return out;
}

const std::vector<Point3> probe_points = {{1.62, 0.31, 0.05}, {-0.9, 1.1, -0.13}, {1.2, -0.85, 0.21},
                                          {0.3, 1.35, -0.02}};
} // namespace

TEST(InteractionIntegral3D, CurvedAuxiliaryGradientIsTheFieldsGradient)
{
  for (int sign : {1, -1})
    for (const Point3& x : probe_points)
    {
      const Aux a = aux_at(x, 0, sign);
      const double h = 1e-6;
      for (int j = 0; j < 3; ++j)
      {
        Point3 xp = x, xm = x;
        xp[j] += h, xm[j] -= h;
        const Aux ap = aux_at(xp, 0, sign), am = aux_at(xm, 0, sign);
        for (int m = 0; m < 3; ++m)
          for (int i = 0; i < 3; ++i)
          {
            const double fd = (ap.U[3 * m + i] - am.U[3 * m + i]) / (2 * h);
            EXPECT_NEAR(a.G[9 * m + 3 * i + j], fd, 1e-7) << "sign " << sign << " mode " << m;
          }
      }
      // Without the hoop terms the gradient misses by O(u / R).
      const Aux flat = aux_at(x, 0, sign, false);
      double miss = 0.0;
      for (int k = 0; k < 27; ++k)
        miss = std::max(miss, std::abs(flat.G[k] - a.G[k]));
      EXPECT_GT(miss, 1e-3);
    }
}

TEST(InteractionIntegral3D, CurvedAuxiliaryStressDivergence)
{
  for (int sign : {1, -1})
    for (const Point3& x : probe_points)
    {
      const Aux a = aux_at(x, 0, sign);
      const double h = 1e-5;
      double div[3][3] = {};
      for (int j = 0; j < 3; ++j)
      {
        Point3 xp = x, xm = x;
        xp[j] += h, xm[j] -= h;
        const Aux ap = aux_at(xp, 0, sign), am = aux_at(xm, 0, sign);
        for (int m = 0; m < 3; ++m)
        {
          double sp[3][3], sm[3][3];
          stress_of(&ap.G[9 * m], sp);
          stress_of(&am.G[9 * m], sm);
          for (int i = 0; i < 3; ++i)
            div[m][i] += (sp[i][j] - sm[i][j]) / (2 * h);
        }
      }
      double scale = 0.0;
      for (int k = 0; k < 9; ++k)
        scale = std::max(scale, std::abs(a.div[k]));
      EXPECT_GT(scale, 1e-3);
      for (int m = 0; m < 3; ++m)
        for (int i = 0; i < 3; ++i)
          EXPECT_NEAR(a.div[3 * m + i], div[m][i], 1e-5 * scale) << "sign " << sign << " mode " << m;
    }
}

namespace
{
// The domain integral of the curved-front field with stress intensity
// factors K around the circle, over the tube r < R, |s| < l around the
// front point (a, 0, 0) (sign +1) with q = (1 - (r/R)^2)^2 (1 - (s/l)^2)^2
// and d = e1 there: volume, body-force and lip terms; curved = false drops
// every curvature term (the straight-front auxiliary fields of the nearest
// front point). Returns K recovered per mode.
// The domain integrand (grad q . T_m + q D_m) . d of the three modes at a
// point (T (3, 3, 3), D (3, 3) of interaction_integrand_3d).
std::array<double, 3> domain_integrand(const std::vector<double>& T, const std::vector<double>& D, const Point3& gq,
                                       double q, const Point3& d)
{
  std::array<double, 3> v = {0.0, 0.0, 0.0};
  for (int m = 0; m < 3; ++m)
  {
    for (int j = 0; j < 3; ++j)
      for (int ll = 0; ll < 3; ++ll)
        v[m] += gq[j] * T[9 * m + 3 * j + ll] * d[ll];
    for (int ll = 0; ll < 3; ++ll)
      v[m] += q * D[3 * m + ll] * d[ll];
  }
  return v;
}

std::array<double, 3> circle_domain_integral(const double K[3], int sign, double R, double l, bool curved)
{
  const auto gr = quadrature::gauss_legendre(16), gt = quadrature::gauss_legendre(40),
             gs = quadrature::gauss_legendre(16);
  const double pi = std::numbers::pi, kappa = sign / a_circle;
  const Point3 d = {1.0 * sign, 0.0, 0.0};
  std::array<double, 3> I = {0.0, 0.0, 0.0};
  double Q = 0.0;
  auto qs_of = [&](double s, double& dqs)
  {
    const double u = s / l;
    dqs = -4.0 * u * (1 - u * u) / l;
    return (1 - u * u) * (1 - u * u);
  };
  for (int is = 0; is < gs.size(); ++is)
  {
    const double s = l * (2 * gs.points[is] - 1), ws = 2 * l * gs.weights[is];
    const double phi = sign * s / a_circle;
    double dqs;
    const double qs = qs_of(s, dqs);
    const Point3 er = {std::cos(phi), std::sin(phi), 0.0};
    Q += ws * qs * (sign * er[0] * d[0] + sign * er[1] * d[1]);
    const Point3 e1 = {sign * er[0], sign * er[1], 0.0}, e2 = {0, 0, 1};
    for (int ir = 0; ir < gr.size(); ++ir)
    {
      const double tau = gr.points[ir], r = R * tau * tau, dr = 2 * R * tau * gr.weights[ir];
      const double qr = (1 - r * r / (R * R)) * (1 - r * r / (R * R)), dqr = -4 * r / (R * R) * (1 - r * r / (R * R));
      auto point = [&](double t)
      {
        const double x1 = r * std::cos(t), x2 = r * std::sin(t);
        Point3 p;
        for (int i = 0; i < 3; ++i)
          p[i] = a_circle * er[i] + x1 * e1[i] + x2 * e2[i];
        return p;
      };
      for (int it = 0; it < gt.size(); ++it)
      {
        const double t = pi * (2 * gt.points[it] - 1), wt = 2 * pi * gt.weights[it];
        const double x1 = r * std::cos(t);
        const double jac = (1 + kappa * x1) * r; // dV = (1 + kappa x1) r dr dtheta ds
        const Point3 p = point(t);
        // grad s = sign e_phi / (1 + kappa x1): s = sign a phi, the hoop radius a (1 + kappa x1).
        const Point3 es = {-er[1], er[0], 0.0};
        Point3 gq;
        for (int i = 0; i < 3; ++i)
          gq[i] = dqr * qs * (std::cos(t) * e1[i] + std::sin(t) * e2[i])
                  + qr * dqs * sign * es[i] / (1 + kappa * x1);
        const double q = qr * qs;
        // The field: u = sum_m K_m U_m (curved), its gradient and body force.
        const Aux real = aux_at(p, 0, sign);
        std::vector<double> g(9, 0.0), body(3, 0.0);
        for (int m = 0; m < 3; ++m)
          for (int k = 0; k < 9; ++k)
            g[k] += K[m] * real.G[9 * m + k];
        for (int m = 0; m < 3; ++m)
          for (int i = 0; i < 3; ++i)
            body[i] -= K[m] * real.div[3 * m + i];
        const CircleFrame c = circle_frame(p, sign);
        const std::vector<double> fr = frame_row(c.f), kk = {curved ? c.kappa : 0.0, 0.0, 0.0, 0.0};
        const std::vector<std::int8_t> sd = {0};
        std::vector<double> T(27), D(9);
        interaction_integrand_3d(E, nu, fr, kk, p, g, sd, body, T, D);
        const std::array<double, 3> v = domain_integrand(T, D, gq, q, d);
        for (int m = 0; m < 3; ++m)
          I[m] += ws * dr * wt * jac * v[m];
      }
      // Lips: x1 = -r, x2 = 0; the + lip (side +1) has outward normal -e2.
      for (int side : {1, -1})
      {
        const Point3 p = point(side * pi);
        const double jac = 1 - kappa * r;
        const double q = qr * qs;
        const Aux real = aux_at(p, side, sign);
        const Aux aux = aux_at(p, side, sign, curved);
        double g[9] = {};
        for (int m = 0; m < 3; ++m)
          for (int k = 0; k < 9; ++k)
            g[k] += K[m] * real.G[9 * m + k];
        const double n_out[3] = {0, 0, -1.0 * side};
        const LipIntegrand lip = lip_integrand(g, aux.G.data(), n_out, d.data());
        for (int m = 0; m < 3; ++m)
          I[m] -= ws * dr * jac * q * lip.traction[m];
      }
    }
  }
  return {0.5 * Eprime * I[0] / Q, 0.5 * Eprime * I[1] / Q, mu * I[2] / Q};
}
} // namespace

TEST(InteractionIntegral3D, CurvedFrontDomainIntegralGivesEachK)
{
  for (int sign : {1, -1})
    for (const auto& K : {std::array<double, 3>{1.0, 0.0, 0.0}, std::array<double, 3>{0.0, 1.0, 0.0},
                          std::array<double, 3>{0.0, 0.0, 1.0}, std::array<double, 3>{0.6, -0.2, 0.9}})
    {
      for (const double R : {0.15, 0.4})
      {
        const auto k = circle_domain_integral(K.data(), sign, R, 0.3, true);
        for (int m = 0; m < 3; ++m)
          EXPECT_NEAR(k[m], K[m], 1e-8) << "sign " << sign << " R " << R << " mode " << m;
      }
      // Without the curvature terms K misses by O(R / a): measured 3.4 % (mode
      // I) to 11 % (mode II) at R / a = 0.27.
      const auto k = circle_domain_integral(K.data(), sign, 0.4, 0.3, false);
      double miss = 0.0;
      for (int m = 0; m < 3; ++m)
        miss = std::max(miss, std::abs(k[m] - K[m]));
      EXPECT_GT(miss, 0.01) << "sign " << sign;
    }
}

// ---------------------------------------------------------------------------
// Curved crack surfaces. A front whose Darboux frame turns at constant rates
// along it, e_i' = omega x e_i with omega = -kappa_33 e1 - kappa_f e2 + tau e3
// (interaction_integral_3d.h), is a helix (a circle when tau = 0); with the
// surface's curvature kappa_11 across it the auxiliary field's frame
// components depend on (x1, x2) only. The spherical tube: the circle of
// latitude at 45 degrees on a sphere of radius R = sqrt(2) (the front of a
// spherical cap of base radius a = 1), kappa_f = cos(alpha) / a, kappa_11 =
// kappa_33 = 1 / R, tau = 0 (e2 toward the sphere's centre); a twisted tube
// (tau != 0, kappa_11 != kappa_33) checks the torsion terms. The field made
// of these fields with given K (body force -div sigma and tractions on its
// lips xi2 = 0) gives back its K from the domain integral with every term,
// and misses it without each.
namespace
{
struct Darboux
{
  FrontCurvatures k;
  FrontFrame f0; ///< the frame at s = 0
};

Point3 cross3(const Point3& a, const Point3& b)
{
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

double dot3(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/// The front point and frame at arc length s (rotation about omega).
FrontFrame darboux_frame(const Darboux& D, double s)
{
  const FrontFrame& f = D.f0;
  Point3 w;
  for (int i = 0; i < 3; ++i)
    w[i] = -D.k.along * f.e1[i] - D.k.front * f.e2[i] + D.k.torsion * f.e3[i];
  const double wn = std::sqrt(dot3(w, w));
  FrontFrame out = f;
  if (wn == 0.0)
  {
    for (int i = 0; i < 3; ++i)
      out.origin[i] += s * f.e3[i];
    return out;
  }
  const Point3 k = {w[0] / wn, w[1] / wn, w[2] / wn};
  const double t = wn * s, c = std::cos(t), sn = std::sin(t);
  auto rot = [&](const Point3& v)
  {
    const Point3 kv = cross3(k, v);
    const double kd = dot3(k, v);
    return Point3{v[0] * c + kv[0] * sn + k[0] * kd * (1 - c), v[1] * c + kv[1] * sn + k[1] * kd * (1 - c),
                  v[2] * c + kv[2] * sn + k[2] * kd * (1 - c)};
  };
  out.e1 = rot(f.e1), out.e2 = rot(f.e2), out.e3 = rot(f.e3);
  // p(s) = p(0) + int_0^s e3.
  const Point3 kv = cross3(k, f.e3);
  const double kd = dot3(k, f.e3);
  for (int i = 0; i < 3; ++i)
    out.origin[i] += f.e3[i] * sn / wn + kv[i] * (1 - c) / wn + k[i] * kd * (s - sn / wn);
  return out;
}

Darboux spherical_tube()
{
  const double alpha = std::numbers::pi / 4, a = 1.0, R = a / std::sin(alpha);
  Darboux D;
  D.k = {std::cos(alpha) / a, 1.0 / R, 1.0 / R, 0.0};
  D.f0.origin = {a, 0.0, R - R * std::cos(alpha)};
  D.f0.e1 = {std::cos(alpha), 0.0, std::sin(alpha)};
  D.f0.e2 = {-std::sin(alpha), 0.0, std::cos(alpha)};
  D.f0.e3 = cross3(D.f0.e1, D.f0.e2);
  return D;
}

Darboux twisted_tube()
{
  Darboux D;
  D.k = {0.5, -0.8, 0.6, 0.4};
  D.f0 = oblique();
  return D;
}

/// The point at tube coordinates (x1, x2, s).
Point3 tube_point(const Darboux& D, double x1, double x2, double s)
{
  const FrontFrame f = darboux_frame(D, s);
  Point3 p;
  for (int i = 0; i < 3; ++i)
    p[i] = f.origin[i] + x1 * f.e1[i] + x2 * f.e2[i];
  return p;
}

Aux tube_aux(const Darboux& D, const FrontCurvatures& k, double x1, double x2, double s, int side)
{
  const FrontFrame f = darboux_frame(D, s);
  const std::vector<double> fr = frame_row(f), kk = {k.front, k.across, k.along, k.torsion};
  const Point3 p = tube_point(D, x1, x2, s);
  const std::vector<std::int8_t> sd = {static_cast<std::int8_t>(side)};
  Aux r{std::vector<double>(9), std::vector<double>(27), std::vector<double>(9), std::vector<double>(9)};
  auxiliary_fields_3d(E, nu, fr, kk, p, sd, r.U, r.G, r.local, r.div);
  return r;
}

/// d x / d c at tube coordinates c = (x1, x2, s), by central differences of
/// the position (columns of the Jacobian).
std::array<Point3, 3> tube_jacobian(const Darboux& D, double x1, double x2, double s, double h)
{
  std::array<Point3, 3> J;
  for (int c = 0; c < 3; ++c)
  {
    const Point3 pp = tube_point(D, x1 + (c == 0) * h, x2 + (c == 1) * h, s + (c == 2) * h);
    const Point3 pm = tube_point(D, x1 - (c == 0) * h, x2 - (c == 1) * h, s - (c == 2) * h);
    for (int i = 0; i < 3; ++i)
      J[c][i] = (pp[i] - pm[i]) / (2 * h);
  }
  return J;
}

const std::vector<std::array<double, 3>> tube_probes = {{0.21, 0.05, 0.1}, {-0.3, 0.12, -0.2}, {0.05, -0.27, 0.3},
                                                        {-0.15, -0.04, 0.0}};

/// What the tube integral keeps (all by default).
struct Terms
{
  bool across = true, along = true, torsion = true, lip_energy = true, normal_extension = true;
};

/// A uniform displacement gradient added to the field (a T-stress and more:
/// no K, no body force, tractions on the lips).
constexpr double uniform_gradient[9] = {0.3, -0.1, 0.05, 0.2, -0.15, 0.1, -0.05, 0.25, 0.12};

/// K recovered from the domain integral of the field with stress intensity
/// factors K (plus uniform_gradient) over the tube r < R, |s| < l (r = |(xi1, xi2)|) with q = (1 -
/// (r/R)^2)^2 (1 - (s/l)^2)^2 and d = e1(0): volume, body-force and lip
/// terms; the auxiliary fields without the curvature terms `terms` drops.
std::array<double, 3> tube_integral(const Darboux& D, const double K[3], double R, double l, const Terms& terms = {})
{
  const auto gr = quadrature::gauss_legendre(16), gt = quadrature::gauss_legendre(40),
             gs = quadrature::gauss_legendre(16);
  const double pi = std::numbers::pi;
  const FrontCurvatures& k = D.k;
  const FrontCurvatures ka = {k.front, terms.across ? k.across : 0.0, terms.along ? k.along : 0.0,
                              terms.torsion ? k.torsion : 0.0};
  const Point3 d = D.f0.e1;
  std::array<double, 3> I = {0.0, 0.0, 0.0};
  double Q = 0.0, Q2 = 0.0;
  for (int is = 0; is < gs.size(); ++is)
  {
    const double s = l * (2 * gs.points[is] - 1), ws = 2 * l * gs.weights[is];
    const double u = s / l, qs = (1 - u * u) * (1 - u * u), dqs = -4.0 * u * (1 - u * u) / l;
    const FrontFrame f = darboux_frame(D, s);
    Q += ws * qs * dot3(f.e1, d);
    Q2 += ws * qs * dot3(f.e2, d);
    for (int ir = 0; ir < gr.size(); ++ir)
    {
      const double tt = gr.points[ir], r = R * tt * tt, dr = 2 * R * tt * gr.weights[ir];
      const double qr = (1 - r * r / (R * R)) * (1 - r * r / (R * R)), dqr = -4 * r / (R * R) * (1 - r * r / (R * R));
      const double q = qr * qs;
      // grad x1, grad x2, grad xi2, grad s at (x1, x2) (header).
      auto gradients = [&](double x1, double x2, Point3& g1, Point3& gxi2, Point3& gs_)
      {
        const double h = 1 + k.front * x1 - k.along * x2;
        for (int i = 0; i < 3; ++i)
        {
          g1[i] = f.e1[i] + k.torsion * x2 / h * f.e3[i];
          const double g2 = f.e2[i] - k.torsion * x1 / h * f.e3[i];
          gxi2[i] = g2 - k.across * x1 * g1[i];
          gs_[i] = f.e3[i] / h;
        }
        return h;
      };
      for (int it = 0; it < gt.size(); ++it)
      {
        const double t = pi * (2 * gt.points[it] - 1), wt = 2 * pi * gt.weights[it];
        const double xi1 = r * std::cos(t), xi2 = r * std::sin(t);
        const double x1 = xi1, x2 = xi2 + 0.5 * k.across * xi1 * xi1;
        Point3 g1, gxi2, gsv;
        const double h = gradients(x1, x2, g1, gxi2, gsv);
        Point3 gq;
        for (int i = 0; i < 3; ++i)
          gq[i] = dqr * qs * (std::cos(t) * g1[i] + std::sin(t) * gxi2[i]) + qr * dqs * gsv[i];
        const Aux real = tube_aux(D, k, x1, x2, s, 0);
        std::vector<double> g(uniform_gradient, uniform_gradient + 9), body(3, 0.0);
        for (int m = 0; m < 3; ++m)
          for (int c = 0; c < 9; ++c)
            g[c] += K[m] * real.G[9 * m + c];
        for (int m = 0; m < 3; ++m)
          for (int i = 0; i < 3; ++i)
            body[i] -= K[m] * real.div[3 * m + i];
        const std::vector<double> fr = frame_row(f), kk = {ka.front, ka.across, ka.along, ka.torsion};
        const Point3 p = tube_point(D, x1, x2, s);
        const std::vector<std::int8_t> sd = {0};
        std::vector<double> T(27), Dv(9);
        interaction_integrand_3d(E, nu, fr, kk, p, g, sd, body, T, Dv);
        const std::array<double, 3> v = domain_integrand(T, Dv, gq, q, d);
        for (int m = 0; m < 3; ++m)
          I[m] += ws * dr * wt * h * r * v[m];
      }
      // The lips xi2 = 0, xi1 = -r: dA = h |grad xi2| dr ds, n_out = -side
      // grad xi2 / |grad xi2|.
      const double x1 = -r, x2 = 0.5 * k.across * r * r;
      Point3 g1, gxi2, gsv;
      const double h = gradients(x1, x2, g1, gxi2, gsv);
      const double gn = std::sqrt(dot3(gxi2, gxi2));
      for (int side : {1, -1})
      {
        const Aux real = tube_aux(D, k, x1, x2, s, side);
        const Aux aux = tube_aux(D, ka, x1, x2, s, side);
        double g[9];
        std::copy(uniform_gradient, uniform_gradient + 9, g);
        for (int m = 0; m < 3; ++m)
          for (int c = 0; c < 9; ++c)
            g[c] += K[m] * real.G[9 * m + c];
        Point3 n_out;
        for (int i = 0; i < 3; ++i)
          n_out[i] = -side * gxi2[i] / gn;
        const LipIntegrand lip = lip_integrand(g, aux.G.data(), n_out.data(), d.data());
        for (int m = 0; m < 3; ++m)
        {
          double v = -lip.traction[m];
          if (terms.lip_energy)
            v += lip.energy[m] * dot3(n_out, d);
          I[m] += ws * dr * h * gn * q * v;
        }
      }
    }
  }
  return front_sifs_3d(E, nu, I, Q, terms.normal_extension ? Q2 : 0.0);
}
} // namespace

TEST(InteractionIntegral3D, DarbouxFrameIsTheSphereFront)
{
  // The spherical tube's front stays on the sphere (centre (0, 0, R)) at
  // radius a from its axis, e2 pointing to the centre.
  const Darboux D = spherical_tube();
  const double R = std::sqrt(2.0);
  for (double s : {-0.7, 0.3, 2.1})
  {
    const FrontFrame f = darboux_frame(D, s);
    const Point3 c = {0.0, 0.0, R};
    EXPECT_NEAR(std::hypot(f.origin[0] - c[0], f.origin[1] - c[1], f.origin[2] - c[2]), R, 1e-12);
    EXPECT_NEAR(std::hypot(f.origin[0], f.origin[1]), 1.0, 1e-12);
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(f.e2[i], (c[i] - f.origin[i]) / R, 1e-12);
  }
}

TEST(InteractionIntegral3D, CurvedSurfaceGradientIsTheFieldsGradient)
{
  // G . dx/dc equals dU/dc along the tube coordinates c = (x1, x2, s) (the
  // position's derivatives by differences too: no gradient formula used).
  for (const Darboux& D : {spherical_tube(), twisted_tube()})
    for (const auto& c0 : tube_probes)
    {
      const Aux a = tube_aux(D, D.k, c0[0], c0[1], c0[2], 0);
      const double h = 1e-6;
      const auto J = tube_jacobian(D, c0[0], c0[1], c0[2], h);
      for (int c = 0; c < 3; ++c)
      {
        auto at = [&](double sign)
        { return tube_aux(D, D.k, c0[0] + sign * (c == 0) * h, c0[1] + sign * (c == 1) * h, c0[2] + sign * (c == 2) * h, 0); };
        const Aux ap = at(1.0), am = at(-1.0);
        for (int m = 0; m < 3; ++m)
          for (int i = 0; i < 3; ++i)
          {
            const double fd = (ap.U[3 * m + i] - am.U[3 * m + i]) / (2 * h);
            const double an = a.G[9 * m + 3 * i] * J[c][0] + a.G[9 * m + 3 * i + 1] * J[c][1]
                              + a.G[9 * m + 3 * i + 2] * J[c][2];
            EXPECT_NEAR(an, fd, 1e-7) << "coordinate " << c << " mode " << m;
          }
      }
    }
}

TEST(InteractionIntegral3D, CurvedSurfaceStressDivergence)
{
  // div sigma_aux against differences of the stress along the tube
  // coordinates, mapped by the inverse of the (differenced) Jacobian.
  for (const Darboux& D : {spherical_tube(), twisted_tube()})
    for (const auto& c0 : tube_probes)
    {
      const Aux a = tube_aux(D, D.k, c0[0], c0[1], c0[2], 0);
      const double h = 1e-5;
      const auto J = tube_jacobian(D, c0[0], c0[1], c0[2], 1e-6);
      // inverse of the matrix with columns J[c]: rows are grad c.
      const Point3 r0 = cross3(J[1], J[2]), r1 = cross3(J[2], J[0]), r2 = cross3(J[0], J[1]);
      const double det = dot3(J[0], r0);
      const Point3 grad[3] = {{r0[0] / det, r0[1] / det, r0[2] / det}, {r1[0] / det, r1[1] / det, r1[2] / det},
                              {r2[0] / det, r2[1] / det, r2[2] / det}};
      double div[3][3] = {};
      for (int c = 0; c < 3; ++c)
      {
        auto at = [&](double sign)
        { return tube_aux(D, D.k, c0[0] + sign * (c == 0) * h, c0[1] + sign * (c == 1) * h, c0[2] + sign * (c == 2) * h, 0); };
        const Aux ap = at(1.0), am = at(-1.0);
        for (int m = 0; m < 3; ++m)
        {
          double sp[3][3], sm[3][3];
          stress_of(&ap.G[9 * m], sp);
          stress_of(&am.G[9 * m], sm);
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
              div[m][i] += (sp[i][j] - sm[i][j]) / (2 * h) * grad[c][j];
        }
      }
      double scale = 0.0;
      for (int c = 0; c < 9; ++c)
        scale = std::max(scale, std::abs(a.div[c]));
      EXPECT_GT(scale, 1e-3);
      for (int m = 0; m < 3; ++m)
        for (int i = 0; i < 3; ++i)
          EXPECT_NEAR(a.div[3 * m + i], div[m][i], 1e-5 * scale) << "mode " << m << " component " << i;
    }
}

TEST(InteractionIntegral3D, SurfaceDivergenceDifferencesMatchTheClosedForm)
{
  // The central differences of a curved surface's div sigma_aux, at a
  // curvature kappa_11 of 1e-30 (a plane to round-off), equal the planar
  // crack's closed form.
  const Darboux D = spherical_tube();
  const FrontCurvatures planar = {D.k.front, 0.0, 0.0, 0.0}, nearly = {D.k.front, 1e-30, 0.0, 0.0};
  for (const auto& c0 : tube_probes)
    for (int side : {0, 1, -1})
    {
      const Aux a = tube_aux(D, planar, c0[0], c0[1], c0[2], side);
      const Aux b = tube_aux(D, nearly, c0[0], c0[1], c0[2], side);
      double scale = 0.0;
      for (int c = 0; c < 9; ++c)
        scale = std::max(scale, std::abs(a.div[c]));
      for (int c = 0; c < 9; ++c)
        EXPECT_NEAR(b.div[c], a.div[c], 1e-7 * scale);
    }
}

TEST(InteractionIntegral3D, CurvedSurfaceDomainIntegralGivesEachK)
{
  const double R = std::sqrt(2.0);
  for (const Darboux& D : {spherical_tube(), twisted_tube()})
    for (const auto& K : {std::array<double, 3>{1.0, 0.0, 0.0}, std::array<double, 3>{0.0, 1.0, 0.0},
                          std::array<double, 3>{0.0, 0.0, 1.0}, std::array<double, 3>{0.6, -0.2, 0.9}})
      for (const double Rd : {0.05 * R, 0.2 * R, 0.5 * R})
      {
        const auto k = tube_integral(D, K.data(), Rd, 0.3);
        for (int m = 0; m < 3; ++m)
          EXPECT_NEAR(k[m], K[m], 1e-6) << "kappa_11 " << D.k.across << " R_d " << Rd << " mode " << m;
      }
}

TEST(InteractionIntegral3D, EachCurvedSurfaceTermMatters)
{
  // Without the surface's curvature across the front in the map, along it
  // in the frame's turning, the torsion, or the lip term (sigma :
  // eps_aux)(n . d) (it pairs the uniform stress with the auxiliary strain
  // on the lips), K misses by O(kappa R_d): more than 0.5 % at R_d = 0.2 R.
  // Without the virtual extension's component along e2 of the front points
  // away from s = 0 (int q (e2 . d) ds), K_I and K_II mix by O((kappa_f
  // kappa_33 l)^2): 3.2e-3 on the sphere at l = 0.3.
  const double K[3] = {0.6, -0.2, 0.9};
  for (const Darboux& D : {spherical_tube(), twisted_tube()})
  {
    const double Rd = 0.2 * std::sqrt(2.0);
    std::vector<std::pair<Terms, double>> drops = {{{false, true, true, true, true}, 5e-3},
                                                   {{true, false, true, true, true}, 5e-3},
                                                   {{true, true, true, false, true}, 5e-3},
                                                   {{true, true, true, true, false}, 1e-3}};
    if (D.k.torsion != 0.0)
      drops.push_back({{true, true, false, true, true}, 5e-3});
    for (const auto& [t, bound] : drops)
    {
      const auto k = tube_integral(D, K, Rd, 0.3, t);
      double miss = 0.0;
      for (int m = 0; m < 3; ++m)
        miss = std::max(miss, std::abs(k[m] - K[m]));
      EXPECT_GT(miss, bound) << "kappa_11 " << D.k.across << " drops " << t.across << t.along << t.torsion
                             << t.lip_energy << t.normal_extension;
    }
  }
}

TEST(InteractionIntegral3D, BodyForcePerPointIsEachPointsOwn)
{
  // A body force per point (n, 3) (an initial stress's divergence) gives
  // each point the D of its own body force, as a constant body force on
  // that point alone does; T does not see the body force.
  const std::vector<double> frame = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  std::vector<double> frames, x = {0.3, 0.2, 0.1, -0.2, 0.4, -0.1}, g(18), kk(8, 0.0);
  for (int p = 0; p < 2; ++p)
    frames.insert(frames.end(), frame.begin(), frame.end());
  for (int k = 0; k < 18; ++k)
    g[k] = 0.01 * (k + 1) * (k % 3 == 0 ? -1.0 : 1.0);
  const std::vector<std::int8_t> sides = {0, 0};
  const std::vector<double> body = {1.0, -2.0, 0.5, -0.3, 0.7, 2.0};
  std::vector<double> T(54), D(18);
  interaction_integrand_3d(2.0, 0.3, frames, kk, x, g, sides, body, T, D);
  for (int p = 0; p < 2; ++p)
  {
    std::vector<double> T1(27), D1(9), D0(9), T0(27);
    const auto at = [p](const std::vector<double>& v, std::size_t k)
    { return std::vector<double>(v.begin() + k * p, v.begin() + k * (p + 1)); };
    const std::vector<std::int8_t> one = {0};
    interaction_integrand_3d(2.0, 0.3, at(frames, 12), std::vector<double>(4, 0.0), at(x, 3), at(g, 9), one,
                             at(body, 3), T1, D1);
    interaction_integrand_3d(2.0, 0.3, at(frames, 12), std::vector<double>(4, 0.0), at(x, 3), at(g, 9), one, {}, T0,
                             D0);
    double change = 0.0;
    for (int k = 0; k < 9; ++k)
    {
      EXPECT_DOUBLE_EQ(D[9 * p + k], D1[k]);
      change = std::max(change, std::abs(D1[k] - D0[k]));
    }
    for (int k = 0; k < 27; ++k)
      EXPECT_DOUBLE_EQ(T[27 * p + k], T1[k]);
    EXPECT_GT(change, 1e-3); // (the body force is in D)
  }
}
