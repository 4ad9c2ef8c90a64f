// A plate with a through hole, as a solid (gmsh's OpenCASCADE kernel): the
// part of demos/scenes/corner_crack_hole.toml. Width 40 mm (x), length
// 80 mm (y, the load direction), thickness 5 mm (z from 0 to 5), a hole of
// radius 4 mm through the thickness at the origin. The crack is not in this
// file: the scene gives it (a quarter-elliptical corner crack at the hole's
// edge, where the bore meets the face z = 5), and cracklip refines the mesh
// along its front when it meshes the part.
//
// What cracklip needs from a solid .geo (see docs/scenes.md):
// - a named Physical Surface for every face that a scene file loads or
//   supports by tag (without any, every face N is tag "surface N");
// - optionally a Physical Volume (without one, every volume is the part).
// cracklip replaces the sizes of the file with its own (mesh.h, mesh.tip_h,
// mesh.crack_h).
SetFactory("OpenCASCADE");

W = 40; L = 80; t = 5; R = 4;
Box(1) = {-W / 2, -L / 2, 0, W, L, t};
Cylinder(2) = {0, 0, -1, 0, 0, t + 2, R};
// Turn the cylinder's seam (the line where its surface closes, a line of
// mesh nodes) away from the crack's plane y = 0.
Rotate {{0, 0, 1}, {0, 0, 0}, Pi / 4} { Volume{2}; }
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };

e = 1e-3;
Physical Surface("xmin") = Surface In BoundingBox{-W / 2 - e, -L / 2 - e, -e, -W / 2 + e, L / 2 + e, t + e};
Physical Surface("xmax") = Surface In BoundingBox{W / 2 - e, -L / 2 - e, -e, W / 2 + e, L / 2 + e, t + e};
Physical Surface("ymin") = Surface In BoundingBox{-W / 2 - e, -L / 2 - e, -e, W / 2 + e, -L / 2 + e, t + e};
Physical Surface("ymax") = Surface In BoundingBox{-W / 2 - e, L / 2 - e, -e, W / 2 + e, L / 2 + e, t + e};
Physical Surface("zmin") = Surface In BoundingBox{-W / 2 - e, -L / 2 - e, -e, W / 2 + e, L / 2 + e, e};
Physical Surface("zmax") = Surface In BoundingBox{-W / 2 - e, -L / 2 - e, t - e, W / 2 + e, L / 2 + e, t + e};
Physical Surface("hole") = Surface In BoundingBox{-R - e, -R - e, -e, R + e, R + e, t + e};
Physical Volume("plate") = {3};
