// square.geo: unit square [0,1]^2 (converted to square.obj by msh22_to_obj.py).
// Mesh: gmsh square.geo -2 -format msh22 -o square_tmp.msh
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {1, 1, 0};
Point(4) = {0, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Mesh.MeshSizeMin = 0.024;
Mesh.MeshSizeMax = 0.024;
Mesh.Algorithm = 6; // Frontal-Delaunay
