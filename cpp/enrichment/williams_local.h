// The crack-tip fields in the tip's own frame (layer a), the same in 2D and
// 3D: the Williams displacement fields of modes I and II (plane strain in
// the plane (e1, e2) normal to the front) and the anti-plane mode III field
// (along e3, 3D only), and the four scalar branch functions, as functions of
// the polar coordinates (r, theta) of the plane normal to the front.
//
// Every field is sqrt(r) h(theta); without the factor K / (2 mu sqrt(2 pi)):
//   mode I  : sqrt(r) (cos(t/2) (kappa - cos t) e1 + sin(t/2) (kappa - cos t) e2)
//   mode II : sqrt(r) (sin(t/2) (kappa + 2 + cos t) e1 - cos(t/2) (kappa - 2 + cos t) e2)
//   mode III: sqrt(r) 4 sin(t/2) e3
//   branch  : sqrt(r) {sin(t/2), cos(t/2), sin(t/2) sin t, cos(t/2) sin t}
// The 2D tip functions (tip_functions_2d) and the 3D front functions
// (front_functions_3d) only rotate these local values and derivatives into
// the global frame.
#pragma once

#include <array>
#include <cmath>

namespace cracklip
{

/// Angular parts of the Williams fields at theta: h[m][k] is local component
/// k (0: e1, 1: e2, 2: e3) of mode m (0: I, 1: II, 2: III) and ht[m][k] its
/// derivative in theta. sh, ch = sin(theta/2), cos(theta/2); c, s = cos
/// theta, sin theta.
struct WilliamsAngular
{
  double h[3][3];
  double ht[3][3];
};

inline WilliamsAngular williams_angular(double sh, double ch, double c, double s, double kappa)
{
  return {{{ch * (kappa - c), sh * (kappa - c), 0.0},
           {sh * (kappa + 2.0 + c), -ch * (kappa - 2.0 + c), 0.0},
           {0.0, 0.0, 4.0 * sh}},
          {{-0.5 * sh * (kappa - c) + ch * s, 0.5 * ch * (kappa - c) + sh * s, 0.0},
           {0.5 * ch * (kappa + 2.0 + c) - sh * s, 0.5 * sh * (kappa - 2.0 + c) + ch * s, 0.0},
           {0.0, 0.0, 2.0 * ch}}};
}

/// Angular parts of the four branch functions (h) and their theta
/// derivatives (ht).
struct BranchAngular
{
  std::array<double, 4> h, ht;
};

inline BranchAngular branch_angular(double sh, double ch, double c, double s)
{
  return {{sh, ch, sh * s, ch * s}, {0.5 * ch, -0.5 * sh, 0.5 * ch * s + sh * c, -0.5 * sh * s + ch * c}};
}

/// Derivatives (d/dx1, d/dx2) in the tip frame of a function of (r, theta)
/// whose polar derivatives are g_r and g_t, at (r, theta) with c, s = cos,
/// sin theta (r > 0).
inline std::array<double, 2> polar_to_local(double r, double c, double s, double g_r, double g_t)
{
  return {c * g_r - s / r * g_t, s * g_r + c / r * g_t};
}

} // namespace cracklip
