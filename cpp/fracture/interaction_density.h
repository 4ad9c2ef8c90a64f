// The domain interaction integral's density and its sum over points (layer
// a), in any dimension. For a virtual crack extension along d and a weight
// q (1 at the tip / front point, 0 outside its domain), mode m's integral is
//
//   I_m = sum_p w_p [ (sigma grad q) . (grad u_aux d) + (sigma_aux grad q) . (grad u d)
//                     - (sigma : eps_aux) (d . grad q) ]
//
// with u the field whose stress intensity factors are sought and u_aux the
// unit-K auxiliary field of mode m (the Williams fields of williams_local.h
// times 1 / (2 mu sqrt(2 pi))). Where the auxiliary fields come from is the
// geometry's business: a tip frame in 2D (interaction_integral_2d.h), each
// point's front frame in 3D (interaction_integral_3d.h).
#pragma once

#include "assembly/elasticity.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <stdexcept>
#include <string>

namespace cracklip
{

/// An isotropic material as the auxiliary fields need it (plane strain in
/// 2D): mu, lambda, kappa = 3 - 4 nu, the unit-K scale 1 / (2 mu sqrt(2 pi)),
/// and the stress of a displacement gradient (Hooke's law in Voigt form,
/// elasticity.h, as the element kernels use it).
template <int dim>
struct IsotropicElasticity
{
  double mu, lmbda, kappa, scale;
  std::array<double, voigt_size<dim> * voigt_size<dim>> D;
  IsotropicElasticity(double E, double nu, const char* who)
  {
    if (!(E > 0.0) or !(nu > -1.0 and nu < 0.5))
      throw std::invalid_argument(std::string(who) + ": needs E > 0 and -1 < nu < 0.5");
    mu = E / (2.0 * (1.0 + nu));
    lmbda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    kappa = 3.0 - 4.0 * nu;
    scale = 1.0 / (2.0 * mu * std::sqrt(2.0 * std::numbers::pi));
    D = elasticity_matrix<dim>(E, nu);
  }
  /// s = D : eps(g) (g[i][j] = d u_i / d x_j).
  void stress(const double g[dim][dim], double s[dim][dim]) const
  {
    constexpr int nv = voigt_size<dim>;
    constexpr auto pairs = voigt_pairs<dim>();
    const auto e = voigt_strain<dim>(&g[0][0]);
    for (int k = 0; k < nv; ++k)
    {
      double v = D[nv * k] * e[0];
      for (int l = 1; l < nv; ++l)
        v += D[nv * k + l] * e[l];
      const auto [i, j] = pairs[k];
      s[i][j] = s[j][i] = v;
    }
  }
};

/// The density at one point: sig = sigma(grad u) with gu = grad u, ga =
/// grad u_aux and siga its stress, gq = grad q, d the extension direction.
template <int dim>
double interaction_density(const double sig[dim][dim], const double gu[dim][dim], const double ga[dim][dim],
                           const double siga[dim][dim], const double gq[dim], const double d[dim])
{
  auto dot = [](const double* a, const double* b)
  {
    double s = a[0] * b[0];
    for (int k = 1; k < dim; ++k)
      s += a[k] * b[k];
    return s;
  };
  double t1 = 0.0, t2 = 0.0, w = 0.0;
  for (int i = 0; i < dim; ++i)
  {
    const double ua = dot(ga[i], d); // (grad u_aux d)_i
    const double ud = dot(gu[i], d);
    t1 += dot(sig[i], gq) * ua;
    t2 += dot(siga[i], gq) * ud;
    for (int j = 0; j < dim; ++j)
      w += sig[i][j] * 0.5 * (ga[i][j] + ga[j][i]);
  }
  return t1 + t2 - w * dot(d, gq);
}

/// (I_1, ..., I_dim) (modes I, II, III in 3D) from values at points:
/// weights (n), grad_q (n, dim), grad_u (n, dim, dim) of the field whose K
/// are sought; aux(p, dU) fills the unscaled Williams gradients dU[m][i][j]
/// (std::array<std::array<std::array<double, dim>, dim>, dim>) at point p.
/// Points where grad q vanishes are skipped.
template <int dim, typename Aux>
std::array<double, dim> interaction_sum(const IsotropicElasticity<dim>& el, const double d[dim],
                                        std::span<const double> weights, std::span<const double> grad_q,
                                        std::span<const double> grad_u, Aux&& aux)
{
  std::array<double, dim> I{};
  std::array<std::array<std::array<double, dim>, dim>, dim> dU;
  for (std::size_t p = 0; p < weights.size(); ++p)
  {
    double gq[dim];
    bool zero = true;
    for (int j = 0; j < dim; ++j)
      gq[j] = grad_q[dim * p + j], zero = zero and gq[j] == 0.0;
    if (zero)
      continue;
    double gu[dim][dim], sig[dim][dim];
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j)
        gu[i][j] = grad_u[dim * dim * p + dim * i + j];
    el.stress(gu, sig);
    aux(p, dU);
    for (int m = 0; m < dim; ++m)
    {
      double ga[dim][dim], siga[dim][dim];
      for (int i = 0; i < dim; ++i)
        for (int j = 0; j < dim; ++j)
          ga[i][j] = el.scale * dU[m][i][j];
      el.stress(ga, siga);
      I[m] += weights[p] * interaction_density<dim>(sig, gu, ga, siga, gq, d);
    }
  }
  return I;
}

} // namespace cracklip
