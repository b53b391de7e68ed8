// The unit lid-driven cavity in gmsh triangles graded toward the walls:
// size 0.014 at the walls growing linearly with the distance to 0.045 at
// 0.25 from them (3 588 cells with Debian bookworm's gmsh 4.8.4), one layer extruded in z
// (patches movingWall, fixedWalls, frontAndBack as in OpenFOAM's icoFoam
// cavity tutorial):
//   gmsh -3 -format msh2 cavityTrianglesGraded.geo -o cavity.msh
// (bench/trianglesRe1000.sh; README "Triangles at icoFoam's step, more meshes")
Point(1) = {0, 0, 0, 0.045}; Point(2) = {1, 0, 0, 0.045}; Point(3) = {1, 1, 0, 0.045}; Point(4) = {0, 1, 0, 0.045};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Field[1] = Distance;
Field[1].CurvesList = {1, 2, 3, 4};
Field[1].NumPointsPerCurve = 200;
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = 0.014;
Field[2].SizeMax = 0.045;
Field[2].DistMin = 0;
Field[2].DistMax = 0.25;
Background Field = 2;
Mesh.CharacteristicLengthExtendFromBoundary = 0;
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
