// The dimension-generic building blocks against closed forms, in 2D and 3D:
// the P1 simplex (affine map, inverse, shape gradients, measure) and
// Hooke's law in Voigt form against its tensor form.
#include "assembly/elasticity.h"
#include "fracture/interaction_density.h"
#include "geometry/p1_simplex.h"

#include <cmath>
#include <gtest/gtest.h>

using namespace cracklip;

namespace
{
template <int dim>
void check_simplex()
{
  // x = x0 + A xi with A upper triangular: measure det(A) / dim!.
  const double x3[12] = {0.3, -0.2, 0.5, 1.3, -0.2, 0.5, 0.7, 0.6, 0.5, 0.4, 0.1, 1.25};
  const double x2[6] = {0.3, -0.2, 1.8, -0.2, 0.7, 1.3};
  std::array<double, dim*(dim + 1)> xc;
  for (int k = 0; k < dim * (dim + 1); ++k)
    xc[k] = dim == 2 ? x2[k] : x3[k];
  const P1Simplex<dim> T{std::span<const double, dim*(dim + 1)>(xc)};
  EXPECT_NEAR(T.volume(), dim == 2 ? 1.5 * 1.5 / 2 : 1.0 * 0.8 * 0.75 / 6, 1e-15);
  // A linear function f = c . x + c0: nodal values -> exact gradient, and
  // interpolation by the shape functions at any reference point.
  const double c[3] = {0.7, -1.1, 0.4}, c0 = 0.25;
  std::array<double, dim + 1> f;
  for (int a = 0; a <= dim; ++a)
  {
    f[a] = c0;
    for (int i = 0; i < dim; ++i)
      f[a] += c[i] * T.xv[a][i];
  }
  const auto g = T.gradient(f);
  for (int i = 0; i < dim; ++i)
    EXPECT_NEAR(g[i], c[i], 1e-14);
  std::array<double, dim> r;
  for (int i = 0; i < dim; ++i)
    r[i] = 0.1 + 0.15 * i;
  const auto p = T.physical(r);
  const auto N = P1Simplex<dim>::shape(r);
  double fp = 0.0, fx = c0, sum = 0.0;
  for (int a = 0; a <= dim; ++a)
    fp += N[a] * f[a], sum += N[a];
  for (int i = 0; i < dim; ++i)
    fx += c[i] * p[i];
  EXPECT_NEAR(sum, 1.0, 1e-15);
  EXPECT_NEAR(fp, fx, 1e-14);
  const auto rb = T.reference(p);
  for (int i = 0; i < dim; ++i)
    EXPECT_NEAR(rb[i], r[i], 1e-14);
}

template <int dim>
void check_hooke()
{
  const double E = 2.5, nu = 0.28;
  const double lmbda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  const IsotropicElasticity<dim> el(E, nu, "test");
  EXPECT_NEAR(el.mu, mu, 1e-15);
  EXPECT_NEAR(el.kappa, 3 - 4 * nu, 1e-15);
  double g[dim][dim], s[dim][dim];
  for (int i = 0; i < dim; ++i)
    for (int j = 0; j < dim; ++j)
      g[i][j] = 0.3 * (i + 1) - 0.7 * j + 0.1 * i * j;
  el.stress(g, s);
  double tr = 0.0;
  for (int i = 0; i < dim; ++i)
    tr += g[i][i];
  for (int i = 0; i < dim; ++i)
    for (int j = 0; j < dim; ++j)
      EXPECT_NEAR(s[i][j], mu * (g[i][j] + g[j][i]) + (i == j ? lmbda * tr : 0.0), 1e-14) << dim << i << j;
  // D is symmetric positive definite and its shear block is mu.
  const auto D = elasticity_matrix<dim>(E, nu);
  constexpr int nv = voigt_size<dim>;
  for (int k = 0; k < nv; ++k)
    for (int l = 0; l < nv; ++l)
      EXPECT_EQ(D[nv * k + l], D[nv * l + k]);
  for (int k = dim; k < nv; ++k)
    EXPECT_NEAR(D[nv * k + k], mu, 1e-15);
}
} // namespace

TEST(P1Simplex, ClosedFormsOnATriangle) { check_simplex<2>(); }
TEST(P1Simplex, ClosedFormsOnATetrahedron) { check_simplex<3>(); }
TEST(Elasticity, VoigtFormIsHookesLawIn2D) { check_hooke<2>(); }
TEST(Elasticity, VoigtFormIsHookesLawIn3D) { check_hooke<3>(); }

TEST(Elasticity, RefusesImpossibleMaterials)
{
  EXPECT_THROW(elasticity_matrix<2>(1.0, 0.5), std::invalid_argument);
  EXPECT_THROW(elasticity_matrix<3>(-1.0, 0.3), std::invalid_argument);
}
