// Crack-front enrichment functions in 3D and their gradients (layer a).
//
// Each point near the front is described in the frame of a point of the
// front: origin on the front, e1 the propagation direction (in the crack's
// plane, normal to the front, away from the crack), e2 the crack normal
// (towards the phi > 0, "+", side), e3 = e1 x e2 along the front. In the
// plane (e1, e2) the polar coordinates are (r, theta), theta in (-pi, pi],
// the lips at theta = +pi (+ side) and -pi (- side). The fields are those of
// williams_local.h (plane-strain modes I and II in (e1, e2), the anti-plane
// mode III along e3, the four branch functions), rotated into the global
// frame. Gradients hold the frame fixed: the O(r x curvature) terms of a
// curved front are dropped, as code_aster does (coor_cyl, lcourb = false);
// the shift by nodal values in the enrichment keeps them consistent.
#pragma once

#include <array>

namespace cracklip
{

using Point3 = std::array<double, 3>;

/// The frame of a front point: origin on the front and the orthonormal,
/// right-handed e1 (propagation), e2 (crack normal, + side), e3 = e1 x e2.
struct FrontFrame
{
  Point3 origin;
  Point3 e1, e2, e3;
};

/// Coordinates of a point in a front frame: local (x1, x2, x3), polar
/// (r, theta) in the (e1, e2) plane, cos and sin theta.
struct FrontPolar
{
  double x1, x2, x3;
  double r, theta, c, s;
};

/// side (+1 / -1: the crack side, sign of phi) picks the branch of theta
/// behind the front (x1 < 0), so that a point on the crack's plane gets the
/// lip it belongs to (+pi on the + side); side 0 uses atan2.
FrontPolar front_polar(const FrontFrame& f, const Point3& x, int side);

/// The Williams displacement fields of modes I, II, III (williams_local.h,
/// without K / (2 mu sqrt(2 pi))): U[m] global vector of mode m and
/// dU[m][i][j] = d U[m]_i / d x_j (global). kappa = 3 - 4 nu (the front is
/// in plane strain). At r = 0 the gradients are set to 0.
void front_vector_functions(const FrontFrame& f, const Point3& x, int side, double kappa,
                            std::array<Point3, 3>& U, std::array<std::array<Point3, 3>, 3>& dU);

/// The four scalar branch functions sqrt(r) {sin(t/2), cos(t/2),
/// sin(t/2) sin t, cos(t/2) sin t}: values F and global gradients dF.
void front_branch_functions(const FrontFrame& f, const Point3& x, int side, std::array<double, 4>& F,
                            std::array<Point3, 4>& dF);

} // namespace cracklip
