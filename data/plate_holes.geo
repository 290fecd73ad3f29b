// plate_holes.geo: 4 x 2 plate with rounded corners (radius 0.3), two circular
// holes (radius 0.35 at x = -1 and x = 1, y = -0.1), a small elliptical hole
// and a semicircular notch (radius 0.3) in the top edge. Finer mesh near the holes.
// Mesh: gmsh plate_holes.geo -2 -format msh41 -o plate_holes.msh
SetFactory("OpenCASCADE");
Rectangle(1) = {-2, -1, 0, 4, 2, 0.3};
Disk(2) = {-1, -0.1, 0, 0.35};
Disk(3) = {1, -0.1, 0, 0.35};
Disk(4) = {0, 1, 0, 0.3};
Disk(5) = {0, -0.45, 0, 0.25, 0.12};
BooleanDifference(10) = { Surface{1}; Delete; }{ Surface{2, 3, 4, 5}; Delete; };
Mesh.MeshSizeMin = 0.012;
Mesh.MeshSizeMax = 0.024;
Mesh.MeshSizeFromCurvature = 24; // elements per 2*pi radians on curved edges
Mesh.Algorithm = 6; // Frontal-Delaunay
