// Compact tension specimen C(T), ASTM E399 proportions, as a plane section
// (gmsh's built-in kernel). W = 50 mm from the load line (x = 0) to the
// back face; front face at x = -0.25 W; height 1.2 W; pin holes of
// diameter 0.25 W at y = +-0.275 W. The notch and the fatigue crack are a
// crack of the scene file (X-FEM), not a slot in this geometry.
//
// What cracklip needs from a .geo (see docs/guide.md):
// - a Physical Surface: the part (gmsh saves only physical groups' elements
//   once any group is defined);
// - a named Physical Curve for every boundary that a scene file loads or
//   supports by tag;
// - a Point wherever a point force or a point support acts: here the load
//   points at the top of the upper hole and the bottom of the lower one
//   (where a pin bears), and the supports on the back face. cracklip embeds
//   a scene's points itself when it meshes the geometry; a .msh meshed
//   elsewhere must already have a node there.
// The characteristic lengths below are ignored by cracklip, which sets the
// sizes from the scene (mesh.h, mesh.tip_h, mesh.refine); gmsh's own
// `gmsh ct_specimen.geo -2` uses them.

W = 50;
lc = W / 20;
x0 = -0.25 * W;   // front face
H = 0.6 * W;      // half height
R = 0.125 * W;    // pin hole radius
yc = 0.275 * W;   // pin hole centres

Point(1) = {x0, -H, 0, lc};
Point(2) = {W, -H, 0, lc};
Point(3) = {W, 0, 0, lc};      // support: u_x = u_y = 0
Point(4) = {W, H, 0, lc};      // support: u_x = 0
Point(5) = {x0, H, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 1};

// Upper pin hole: its top point (0, yc + R) is the load point.
Point(10) = {0, yc, 0, lc};    // centre (a construction point)
Point(11) = {0, yc + R, 0, lc};
Point(12) = {-R, yc, 0, lc};
Point(13) = {0, yc - R, 0, lc};
Point(14) = {R, yc, 0, lc};
Circle(11) = {11, 10, 12};
Circle(12) = {12, 10, 13};
Circle(13) = {13, 10, 14};
Circle(14) = {14, 10, 11};

// Lower pin hole: its bottom point (0, -yc - R) is the load point.
Point(20) = {0, -yc, 0, lc};
Point(21) = {0, -yc + R, 0, lc};
Point(22) = {-R, -yc, 0, lc};
Point(23) = {0, -yc - R, 0, lc};
Point(24) = {R, -yc, 0, lc};
Circle(21) = {21, 20, 22};
Circle(22) = {22, 20, 23};
Circle(23) = {23, 20, 24};
Circle(24) = {24, 20, 21};

Curve Loop(1) = {1, 2, 3, 4, 5};
Curve Loop(2) = {11, 12, 13, 14};
Curve Loop(3) = {21, 22, 23, 24};
Plane Surface(1) = {1, 2, 3};

Physical Curve("bottom") = {1};
Physical Curve("back") = {2, 3};
Physical Curve("top") = {4};
Physical Curve("front") = {5};
Physical Curve("pin_top") = {11, 12, 13, 14};
Physical Curve("pin_bottom") = {21, 22, 23, 24};
Physical Surface("specimen") = {1};
