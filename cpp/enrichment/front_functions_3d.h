// Crack-front enrichment functions in 3D and their gradients (layer a).
//
// Near the front a point has local coordinates (x1, x2) in the plane normal
// to the front (x1 along the propagation direction e1, x2 along the crack
// normal e2, towards the phi > 0, "+", side), polar (r, theta), theta in
// (-pi, pi], the lips at theta = +pi (+ side) and -pi (- side), and the
// directions e1, e2, e3 = e1 x e2 of the local frame. The fields are those of
// williams_local.h (plane-strain modes I and II in (e1, e2), the anti-plane
// mode III along e3, the four branch functions).
//
// Two sources of local coordinates:
//   - a front point's frame (FrontFrame): x1 = (x - origin) . e1, x2 =
//     (x - origin) . e2, constant directions: the exact fields of a straight
//     front (the auxiliary fields of the interaction integral);
//   - the level sets (the enrichment): x1 = psi, x2 = phi (signed distances
//     to the front within the crack's surface and to the surface, P1
//     interpolated, so their gradients are constant on a cell), the
//     directions interpolated from nodal frames: a continuous function whose
//     gradient below is exact (including the directions' variation).
// Either way the caller fills LocalCoordinates and the functions below do
// the rest.
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

/// Local coordinates of a point and their derivatives: x1, x2 with their
/// global gradients g1, g2; the directions e[k] (k = 0, 1, 2: e1, e2, e3)
/// and their gradients de[k][i][j] = d e[k]_i / d x_j (zero for a fixed
/// frame).
struct LocalCoordinates
{
  double x1, x2;
  Point3 g1, g2;
  std::array<Point3, 3> e;
  std::array<std::array<Point3, 3>, 3> de;
};

/// The local coordinates of x in a front point's frame (fixed directions).
LocalCoordinates frame_coordinates(const FrontFrame& f, const Point3& x);

/// Polar angle of local coordinates: atan2(x2, x1); side (+1 / -1: the
/// crack side, sign of phi) picks the branch behind the front (x1 < 0), so
/// that a point on the crack's plane gets the lip it belongs to (+pi on the +
/// side); side 0 uses atan2 alone.
double front_angle(double x1, double x2, int side);

/// The same angle continued across the plane x2 = 0 behind the front instead
/// of mirrored: a point of the + side (side +1) with x1 < 0 and x2 < 0 gets
/// 2 pi + atan2(x2, x1) (just above pi), one of the - side with x2 > 0 gets
/// atan2 - 2 pi. Where the coordinates are a curved surface's (the
/// auxiliary fields of a curved crack, interaction_integral_3d.h) a point of
/// the real + lip may lie a little below x2 = 0; the continued angle keeps
/// the field analytic in the material of its side, as its gradient assumes.
/// Equal to front_angle wherever the side agrees with the sign of x2.
double continued_front_angle(double x1, double x2, int side);

/// The Williams displacement fields of modes I, II, III (williams_local.h,
/// without K / (2 mu sqrt(2 pi))): U[m] global vector of mode m and
/// dU[m][i][j] = d U[m]_i / d x_j (global). kappa = 3 - 4 nu (the front is
/// in plane strain). At r = 0 the gradients are set to 0.
void front_vector_functions(const LocalCoordinates& lc, int side, double kappa, std::array<Point3, 3>& U,
                            std::array<std::array<Point3, 3>, 3>& dU);

/// The four scalar branch functions sqrt(r) {sin(t/2), cos(t/2),
/// sin(t/2) sin t, cos(t/2) sin t}: values F and global gradients dF.
void front_branch_functions(const LocalCoordinates& lc, int side, std::array<double, 4>& F,
                            std::array<Point3, 4>& dF);

/// The same in a front point's frame (the straight-front fields).
void front_vector_functions(const FrontFrame& f, const Point3& x, int side, double kappa,
                            std::array<Point3, 3>& U, std::array<std::array<Point3, 3>, 3>& dU);
void front_branch_functions(const FrontFrame& f, const Point3& x, int side, std::array<double, 4>& F,
                            std::array<Point3, 4>& dF);

} // namespace cracklip
