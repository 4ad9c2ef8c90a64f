// The 3D front functions against closed forms: gradients, the 2D fields in
// the plane normal to a straight front, traction-free lips, equilibrium,
// and the normalisation of K for each mode.
#include "enrichment/front_functions_3d.h"
#include "enrichment/tip_functions_2d.h"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <random>

using namespace cracklip;

namespace
{
constexpr double E = 1.0, nu = 0.3, kappa = 3.0 - 4.0 * nu;
const double mu = E / (2.0 * (1.0 + nu)), lmbda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));

// An oblique frame: e1, e2, e3 from two rotations, right-handed.
FrontFrame oblique()
{
  const double a = 0.7, b = -0.4;
  const Point3 e1 = {std::cos(a) * std::cos(b), std::sin(a) * std::cos(b), std::sin(b)};
  const Point3 e2 = {-std::sin(a), std::cos(a), 0.0};
  const Point3 e3 = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  return {{0.3, -0.2, 0.5}, e1, e2, e3};
}
const FrontFrame F = oblique();

Point3 at(double r, double t, double x3)
{
  const double x1 = r * std::cos(t), x2 = r * std::sin(t);
  Point3 x;
  for (int i = 0; i < 3; ++i)
    x[i] = F.origin[i] + x1 * F.e1[i] + x2 * F.e2[i] + x3 * F.e3[i];
  return x;
}

using Grad = std::array<Point3, 3>;
Grad stress(const Grad& g)
{
  const double tr = g[0][0] + g[1][1] + g[2][2];
  Grad s;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      s[i][j] = mu * (g[i][j] + g[j][i]) + (i == j ? lmbda * tr : 0.0);
  return s;
}

Grad mode_stress(int m, const Point3& x, int side)
{
  std::array<Point3, 3> U;
  std::array<std::array<Point3, 3>, 3> dU;
  front_vector_functions(F, x, side, kappa, U, dU);
  return stress(dU[m]);
}

double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
} // namespace

TEST(FrontFunctions3D, GradientsMatchFiniteDifferences)
{
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> ur(0.05, 1.0), ut(-3.0, 3.0), uz(-1.0, 1.0);
  for (int k = 0; k < 50; ++k)
  {
    const Point3 x = at(ur(gen), ut(gen), uz(gen));
    std::array<Point3, 3> U, Up, Um;
    std::array<std::array<Point3, 3>, 3> dU, tmp;
    std::array<double, 4> B, Bp, Bm;
    std::array<Point3, 4> dB, tmpB;
    front_vector_functions(F, x, 0, kappa, U, dU);
    front_branch_functions(F, x, 0, B, dB);
    const double h = 1e-6;
    for (int j = 0; j < 3; ++j)
    {
      Point3 xp = x, xm = x;
      xp[j] += h, xm[j] -= h;
      front_vector_functions(F, xp, 0, kappa, Up, tmp);
      front_vector_functions(F, xm, 0, kappa, Um, tmp);
      front_branch_functions(F, xp, 0, Bp, tmpB);
      front_branch_functions(F, xm, 0, Bm, tmpB);
      for (int m = 0; m < 3; ++m)
        for (int i = 0; i < 3; ++i)
          EXPECT_NEAR(dU[m][i][j], (Up[m][i] - Um[m][i]) / (2 * h), 2e-7);
      for (int l = 0; l < 4; ++l)
        EXPECT_NEAR(dB[l][j], (Bp[l] - Bm[l]) / (2 * h), 2e-7);
    }
  }
}

TEST(FrontFunctions3D, InThePlaneNormalToTheFrontTheyAreThe2DFields)
{
  // Frame e1 = x, e2 = y, e3 = z: modes I and II equal the 2D Williams
  // fields and the branch functions the 2D ones, at every x3; mode III is
  // 4 sqrt(r) sin(t/2) along z.
  const FrontFrame f{{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  const TipFrame t2{{0.0, 0.0}, {1.0, 0.0}, 1};
  for (const double th : {-2.9, -1.0, 0.0, 0.5, 2.0, 3.1})
    for (const double x3 : {-0.3, 0.0, 0.8})
    {
      const double r = 0.37;
      const Point3 x = {r * std::cos(th), r * std::sin(th), x3};
      std::array<Point3, 3> U;
      std::array<std::array<Point3, 3>, 3> dU;
      front_vector_functions(f, x, 0, kappa, U, dU);
      std::array<std::array<double, 2>, 2> U2;
      std::array<std::array<std::array<double, 2>, 2>, 2> dU2;
      williams_displacement(t2, {x[0], x[1]}, 0, kappa, U2, dU2);
      for (int m = 0; m < 2; ++m)
      {
        EXPECT_NEAR(U[m][2], 0.0, 1e-15);
        for (int i = 0; i < 2; ++i)
        {
          EXPECT_NEAR(U[m][i], U2[m][i], 1e-14);
          for (int j = 0; j < 2; ++j)
            EXPECT_NEAR(dU[m][i][j], dU2[m][i][j], 1e-13);
          EXPECT_NEAR(dU[m][i][2], 0.0, 1e-15);
        }
      }
      EXPECT_NEAR(U[2][2], 4.0 * std::sqrt(r) * std::sin(0.5 * th), 1e-14);
      std::array<double, 4> B;
      std::array<Point3, 4> dB;
      front_branch_functions(f, x, 0, B, dB);
      std::array<double, 4> B2;
      std::array<std::array<double, 2>, 4> dB2;
      branch_functions(t2, {x[0], x[1]}, 0, B2, dB2);
      for (int l = 0; l < 4; ++l)
        EXPECT_NEAR(B[l], B2[l], 1e-14);
    }
}

TEST(FrontFunctions3D, LipsAreTractionFree)
{
  // On both lips (theta = +-pi) the traction sigma e2 of every mode vanishes.
  for (int m = 0; m < 3; ++m)
    for (const int side : {1, -1})
      for (const double r : {0.01, 0.3})
      {
        const Point3 x = at(r, std::numbers::pi, 0.2); // on the crack plane behind the front
        const Grad s = mode_stress(m, x, side);
        Point3 t = {0.0, 0.0, 0.0};
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            t[i] += s[i][j] * F.e2[j];
        for (int i = 0; i < 3; ++i)
          EXPECT_NEAR(t[i], 0.0, 1e-12) << "mode " << m << " side " << side << " r " << r;
      }
}

TEST(FrontFunctions3D, FieldsAreInEquilibrium)
{
  // div sigma = 0 (fourth-order central differences of the stress, h = 1e-3:
  // truncation ~1e-8 at r >= 0.2, against derivative terms of order 10) away
  // from the front.
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> ur(0.2, 1.0), ut(-2.8, 2.8), uz(-1.0, 1.0);
  const double h = 1e-3;
  for (int k = 0; k < 20; ++k)
  {
    const Point3 x = at(ur(gen), ut(gen), uz(gen));
    for (int m = 0; m < 3; ++m)
    {
      Point3 div = {0.0, 0.0, 0.0};
      for (int j = 0; j < 3; ++j)
      {
        Point3 xp = x, xm = x, xpp = x, xmm = x;
        xp[j] += h, xm[j] -= h, xpp[j] += 2 * h, xmm[j] -= 2 * h;
        const Grad sp = mode_stress(m, xp, 0), sm = mode_stress(m, xm, 0);
        const Grad spp = mode_stress(m, xpp, 0), smm = mode_stress(m, xmm, 0);
        for (int i = 0; i < 3; ++i)
          div[i] += (-spp[i][j] + 8.0 * sp[i][j] - 8.0 * sm[i][j] + smm[i][j]) / (12.0 * h);
      }
      for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(div[i], 0.0, 1e-7) << "mode " << m;
    }
  }
}

TEST(FrontFunctions3D, EachModeCarriesItsK)
{
  // Ahead of the front (theta = 0), the field times K / (2 mu sqrt(2 pi))
  // has sigma_22 = K / sqrt(2 pi r) (I), sigma_12 (II), sigma_23 (III), and
  // nothing of the other two.
  const double r = 0.02, K = 1.0;
  const double scale = K / (2.0 * mu * std::sqrt(2.0 * std::numbers::pi)), exact = K / std::sqrt(2.0 * std::numbers::pi * r);
  const Point3 x = at(r, 0.0, 0.1);
  const Point3* e[3] = {&F.e1, &F.e2, &F.e3};
  auto local = [&](const Grad& s, int a, int b)
  {
    double v = 0.0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        v += (*e[a])[i] * s[i][j] * (*e[b])[j];
    return scale * v;
  };
  const Grad s1 = mode_stress(0, x, 0), s2 = mode_stress(1, x, 0), s3 = mode_stress(2, x, 0);
  EXPECT_NEAR(local(s1, 1, 1), exact, 1e-12 * exact);
  EXPECT_NEAR(local(s1, 0, 1), 0.0, 1e-12 * exact);
  EXPECT_NEAR(local(s1, 1, 2), 0.0, 1e-12 * exact);
  EXPECT_NEAR(local(s2, 0, 1), exact, 1e-12 * exact);
  EXPECT_NEAR(local(s2, 1, 1), 0.0, 1e-12 * exact);
  EXPECT_NEAR(local(s3, 1, 2), exact, 1e-12 * exact);
  EXPECT_NEAR(local(s3, 1, 1), 0.0, 1e-12 * exact);
  EXPECT_NEAR(local(s3, 0, 1), 0.0, 1e-12 * exact);
  (void)dot;
}

TEST(FrontFunctions3D, LevelSetCoordinatesGiveTheExactGradient)
{
  // x1 = psi(x), x2 = phi(x) linear (P1 level sets on a cell) and directions
  // e_k(x) = e_k0 + A_k x varying linearly (frames interpolated from the
  // nodes): the gradient of U = sum_k u_k(r, theta) e_k must be the exact
  // derivative of that function (finite differences), directions included.
  const Point3 gpsi = {0.9, 0.2, -0.1}, gphi = {-0.15, 0.95, 0.1};
  const double psi0 = 0.05, phi0 = -0.02;
  const double A[3][3][3] = {{{0.1, 0.0, 0.2}, {-0.1, 0.05, 0.0}, {0.0, 0.1, -0.2}},
                             {{0.0, 0.3, 0.0}, {0.1, 0.0, 0.1}, {0.2, 0.0, 0.0}},
                             {{-0.2, 0.0, 0.1}, {0.0, 0.0, 0.3}, {0.1, -0.1, 0.0}}};
  auto coords = [&](const Point3& x)
  {
    LocalCoordinates lc;
    lc.x1 = psi0 + gpsi[0] * x[0] + gpsi[1] * x[1] + gpsi[2] * x[2];
    lc.x2 = phi0 + gphi[0] * x[0] + gphi[1] * x[1] + gphi[2] * x[2];
    lc.g1 = gpsi;
    lc.g2 = gphi;
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i)
      {
        lc.e[k][i] = F.e1[i] * (k == 0) + F.e2[i] * (k == 1) + F.e3[i] * (k == 2);
        for (int j = 0; j < 3; ++j)
        {
          lc.e[k][i] += A[k][i][j] * x[j];
          lc.de[k][i][j] = A[k][i][j];
        }
      }
    return lc;
  };
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (int n = 0; n < 30; ++n)
  {
    const Point3 x = {u(gen), u(gen), u(gen)};
    std::array<Point3, 3> U, Up, Um;
    std::array<std::array<Point3, 3>, 3> dU, tmp;
    std::array<double, 4> B, Bp, Bm;
    std::array<Point3, 4> dB, tmpB;
    front_vector_functions(coords(x), 0, kappa, U, dU);
    front_branch_functions(coords(x), 0, B, dB);
    const double h = 1e-6;
    for (int j = 0; j < 3; ++j)
    {
      Point3 xp = x, xm = x;
      xp[j] += h, xm[j] -= h;
      front_vector_functions(coords(xp), 0, kappa, Up, tmp);
      front_vector_functions(coords(xm), 0, kappa, Um, tmp);
      front_branch_functions(coords(xp), 0, Bp, tmpB);
      front_branch_functions(coords(xm), 0, Bm, tmpB);
      for (int m = 0; m < 3; ++m)
        for (int i = 0; i < 3; ++i)
          EXPECT_NEAR(dU[m][i][j], (Up[m][i] - Um[m][i]) / (2 * h), 1e-6);
      for (int l = 0; l < 4; ++l)
        EXPECT_NEAR(dB[l][j], (Bp[l] - Bm[l]) / (2 * h), 1e-6);
    }
  }
}
