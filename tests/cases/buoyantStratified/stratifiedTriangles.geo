// umppmFoam test mesh: the stratified box of tests/cases/buoyantStratified
// ([0,1]^2, hot wall x = 0, cold wall x = 1, adiabatic walls y = 0 and
// y = 1; one layer of thickness 0.1 in z) as unstructured triangles
// (gmsh Delaunay, edge ~0.06: 688 triangles with gmsh 4.8.4), extruded to
// prisms. test_buoyant.sh part 2 replaces the blockMesh mesh by it:
//   gmsh -3 -format msh2 stratifiedTriangles.geo -o stratifiedTriangles.msh
//   gmshToFoam stratifiedTriangles.msh
// then the patch types below are applied to constant/polyMesh/boundary:
// foam-patch-type: frontAndBack empty
// foam-patch-type: hot wall
// foam-patch-type: cold wall
// foam-patch-type: adiabatic wall

lc = 0.06;
Point(1) = {0, 0, 0, lc};
Point(2) = {1, 0, 0, lc};
Point(3) = {1, 1, 0, lc};
Point(4) = {0, 1, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
out[] = Extrude {0, 0, 0.1} { Surface{1}; Layers{1}; Recombine; };
// out[0]: top surface, out[1]: volume, out[2..5]: the sides of lines 1..4
Physical Surface("frontAndBack") = {1, out[0]};
Physical Surface("hot") = {out[5]};
Physical Surface("cold") = {out[3]};
Physical Surface("adiabatic") = {out[2], out[4]};
Physical Volume("fluid") = {out[1]};
