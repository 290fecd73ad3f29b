// lshape.geo: L-shaped domain [0,1]^2 minus [0.5,1]^2.
// Mesh: gmsh lshape.geo -2 -format msh22 -o lshape.msh
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {1, 0.5, 0};
Point(4) = {0.5, 0.5, 0};
Point(5) = {0.5, 1, 0};
Point(6) = {0, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Mesh.MeshSizeMin = 0.022;
Mesh.MeshSizeMax = 0.022;
Mesh.Algorithm = 6; // Frontal-Delaunay
