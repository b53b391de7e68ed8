// The unit lid-driven cavity in gmsh Delaunay triangles of size h, one
// layer extruded in z (patches movingWall, fixedWalls, frontAndBack as in
// OpenFOAM's icoFoam cavity tutorial). h from the command line:
//   gmsh -3 -format msh2 -setnumber h 0.04125 cavityTriangles.geo -o cavity.msh
// (tools/cavityValidate.sh -mesh tri: h = 1.65 / n; test_solver_re1000.sh)
If (!Exists(h))
    h = 0.05;
EndIf
Point(1) = {0, 0, 0, h}; Point(2) = {1, 0, 0, h}; Point(3) = {1, 1, 0, h}; Point(4) = {0, 1, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
out[] = Extrude {0, 0, 0.1} { Surface{1}; Layers{1}; Recombine; };
// The patch types gmshToFoam cannot know, set by the scripts that mesh
// with this file (tests/integration/lib.sh mesh_from_geo, bench/cases.sh
// cavity_triangles, tools/cavityValidate.sh):
// foam-patch-type: movingWall wall
// foam-patch-type: fixedWalls wall
// foam-patch-type: frontAndBack empty
Physical Surface("frontAndBack") = {1, out[0]};
Physical Surface("movingWall") = {out[4]};
Physical Surface("fixedWalls") = {out[2], out[3], out[5]};
Physical Volume("fluid") = {out[1]};
