// Isotropic linear elasticity in Voigt notation (layer a), in any dimension:
// plane strain in 2D (components xx, yy, xy), the full law in 3D (xx, yy,
// zz, yz, xz, xy), engineering shear strains (2 eps_ij) in both.
#pragma once

#include <array>
#include <stdexcept>

namespace cracklip
{

/// Number of Voigt components: 3 in 2D, 6 in 3D.
template <int dim>
constexpr int voigt_size = dim * (dim + 1) / 2;

/// The index pairs (i, j) of the Voigt components: the normal ones first,
/// then the shears (2D: xy; 3D: yz, xz, xy).
template <int dim>
constexpr std::array<std::array<int, 2>, voigt_size<dim>> voigt_pairs()
{
  if constexpr (dim == 2)
    return {{{0, 0}, {1, 1}, {0, 1}}};
  else
    return {{{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}}};
}

/// Elasticity matrix D (voigt_size x voigt_size, row-major): lambda + 2 mu
/// on the normal diagonal, lambda off it, mu on the shear diagonal.
template <int dim>
std::array<double, voigt_size<dim> * voigt_size<dim>> elasticity_matrix(double E, double nu)
{
  if (!(E > 0.0) or !(nu > -1.0 and nu < 0.5))
    throw std::invalid_argument(dim == 2 ? "plane strain needs E > 0 and -1 < nu < 0.5"
                                         : "3D elasticity needs E > 0 and -1 < nu < 0.5");
  constexpr int nv = voigt_size<dim>;
  const double lmbda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), mu = E / (2.0 * (1.0 + nu));
  std::array<double, nv * nv> D{};
  for (int i = 0; i < dim; ++i)
  {
    for (int j = 0; j < dim; ++j)
      D[nv * i + j] = lmbda;
    D[nv * i + i] += 2.0 * mu;
  }
  for (int i = dim; i < nv; ++i)
    D[nv * i + i] = mu;
  return D;
}

/// Voigt strain (engineering shears) of a displacement gradient g (dim x
/// dim, row-major: g[i dim + j] = d u_i / d x_j).
template <int dim>
std::array<double, voigt_size<dim>> voigt_strain(const double* g)
{
  constexpr auto pairs = voigt_pairs<dim>();
  std::array<double, voigt_size<dim>> e;
  for (int k = 0; k < voigt_size<dim>; ++k)
  {
    const auto [i, j] = pairs[k];
    e[k] = i == j ? g[dim * i + i] : g[dim * i + j] + g[dim * j + i];
  }
  return e;
}

} // namespace cracklip
