// Crack-tip enrichment functions and their gradients (layer a).
//
// Local tip frame: e1 along the crack's extension, e2 = e1 rotated by +90
// degrees (towards the + side of the crack); polar (r, theta), theta in
// (-pi, pi], lips at theta = +pi (+ side) and -pi (- side).
#pragma once

#include <array>

namespace cracklip
{

/// A crack tip: position, unit tangent e1 (pointing out of the crack) and
/// orientation: the side of the crack (sign of phi) on which theta -> +pi
/// (+1 if e2 points to the phi > 0 side, -1 otherwise).
struct TipFrame
{
  std::array<double, 2> tip;
  std::array<double, 2> e1;
  int orientation = 1;
};

/// Polar coordinates of x in the tip frame. `side` (+1 / -1: the crack side,
/// sign of phi) picks the branch of theta behind the tip (x1 < 0), so that a
/// point on the crack line gets the lip it belongs to; side 0 uses atan2.
struct Polar
{
  double r, theta, c, s; ///< r, theta, cos(theta), sin(theta)
  double x1, x2;         ///< local coordinates
};
Polar tip_polar(const TipFrame& f, std::array<double, 2> x, int side);

/// The four scalar branch functions sqrt(r) {sin(t/2), cos(t/2), sin(t/2)
/// sin(t), cos(t/2) sin(t)} at x: values F[4] and global gradients
/// dF[4][2].
void branch_functions(const TipFrame& f, std::array<double, 2> x, int side,
                      std::array<double, 4>& F, std::array<std::array<double, 2>, 4>& dF);

/// The 2D Williams displacement fields (mode I, mode II) without the factor
/// K / (2 mu sqrt(2 pi)): U[m][i] is global component i of mode m, dU[m][i][j]
/// = d U[m][i] / d x_j (global). kappa = 3 - 4 nu (plane strain).
///   mode I : sqrt(r) (cos(t/2) (kappa - cos t) e1 + sin(t/2) (kappa - cos t) e2)
///   mode II: sqrt(r) (sin(t/2) (kappa + 2 + cos t) e1 - cos(t/2) (kappa - 2 + cos t) e2)
void williams_displacement(const TipFrame& f, std::array<double, 2> x, int side, double kappa,
                           std::array<std::array<double, 2>, 2>& U,
                           std::array<std::array<std::array<double, 2>, 2>, 2>& dU);

} // namespace cracklip
