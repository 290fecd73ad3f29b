// annulus.geo: annulus with radii 0.3 and 1.0 centred at the origin.
// Mesh: gmsh annulus.geo -2 -format msh41 -o annulus.msh
SetFactory("OpenCASCADE");
Disk(1) = {0, 0, 0, 1.0};
Disk(2) = {0, 0, 0, 0.3};
BooleanDifference(3) = { Surface{1}; Delete; }{ Surface{2}; Delete; };
Mesh.MeshSizeMin = 0.025;
Mesh.MeshSizeMax = 0.025;
Mesh.Algorithm = 6; // Frontal-Delaunay
