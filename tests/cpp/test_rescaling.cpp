#include "solvers/rescaling.h"

#include <cmath>
#include <gtest/gtest.h>
#include <random>

using namespace cracklip;

namespace
{
// A random SPD matrix with a wide range of scales: G^T G + diag.
std::vector<double> spd(int n, std::mt19937& gen)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> g(n * n), k(n * n, 0.0);
  for (auto& v : g)
    v = u(gen);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
    {
      for (int l = 0; l < n; ++l)
        k[i * n + j] += g[l * n + i] * g[l * n + j] * std::pow(10.0, i + j - n);
      if (i == j)
        k[i * n + j] += 1e-3 * std::pow(10.0, 2 * i - n);
    }
  return k;
}
} // namespace

TEST(Rescaling, InverseCholeskyGivesIdentityBlock)
{
  std::mt19937 gen(3);
  for (int n : {1, 2, 5, 10})
  {
    const std::vector<double> k = spd(n, gen);
    std::vector<double> a = k, x;
    ASSERT_TRUE(inverse_cholesky_transpose(a, n, x));
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
      {
        if (i > j)
          EXPECT_EQ(x[i * n + j], 0.0); // upper triangular
        double s = 0.0;                 // (X^T K X)_ij
        for (int p = 0; p < n; ++p)
          for (int q = 0; q < n; ++q)
            s += x[p * n + i] * k[p * n + q] * x[q * n + j];
        EXPECT_NEAR(s, i == j ? 1.0 : 0.0, 1e-9);
      }
  }
}

TEST(Rescaling, RejectsIndefiniteBlock)
{
  std::vector<double> a = {1.0, 2.0, 2.0, 1.0}, x; // eigenvalues 3, -1
  EXPECT_FALSE(inverse_cholesky_transpose(a, 2, x));
}

TEST(Rescaling, TransformOnCsrGroupsAndJacobi)
{
  // K = [[4, 1, 0], [1, 9, 2], [0, 2, 16]]: group {1, 2}, dof 0 Jacobi.
  const std::vector<std::int32_t> indptr = {0, 2, 5, 7}, indices = {0, 1, 0, 1, 2, 1, 2};
  const std::vector<double> data = {4, 1, 1, 9, 2, 2, 16};
  const std::vector<std::int32_t> offsets = {0, 2}, dofs = {1, 2};
  BlockTransform T = nodal_block_transform(indptr, indices, data, offsets, dofs);
  double t[3][3] = {};
  for (std::size_t e = 0; e < T.values.size(); ++e)
    t[T.rows[e]][T.cols[e]] = T.values[e];
  EXPECT_DOUBLE_EQ(t[0][0], 0.5);
  const double K[3][3] = {{4, 1, 0}, {1, 9, 2}, {0, 2, 16}};
  for (int i = 1; i < 3; ++i)
    for (int j = 1; j < 3; ++j)
    {
      double s = 0.0;
      for (int p = 0; p < 3; ++p)
        for (int q = 0; q < 3; ++q)
          s += t[p][i] * K[p][q] * t[q][j];
      EXPECT_NEAR(s, i == j ? 1.0 : 0.0, 1e-14);
    }
  EXPECT_THROW(nodal_block_transform(indptr, indices, data, offsets, std::vector<std::int32_t>{1, 3}),
               std::invalid_argument);
}
