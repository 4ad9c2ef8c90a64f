// Brazilian disc of radius 50 mm (gmsh's built-in kernel): the rim in four
// arcs whose ends (top, bottom, left, right) are points, so that the
// diametral load points (0, +-50) and the supports (+-50, 0) are mesh nodes.
// A crack through the centre is a crack of the scene file.
R = 50;
lc = R / 12;
Point(1) = {0, 0, 0, lc};      // centre (a construction point)
Point(2) = {R, 0, 0, lc};
Point(3) = {0, R, 0, lc};
Point(4) = {-R, 0, 0, lc};
Point(5) = {0, -R, 0, lc};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("rim") = {1, 2, 3, 4};
Physical Surface("disc") = {1};
