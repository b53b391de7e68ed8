// umppmFoam test case: square channel [0,1]x[0,1] with a circular hole of
// radius 0.2 at the centre, as a 2-D OpenFOAM case (one layer of cells).
//
// Hybrid mesh: a structured ring of quadrilaterals (four transfinite,
// recombined quarter-annuli, r = 0.2 .. 0.32, radially graded) around the
// hole, unstructured triangles between the ring and the square. Extruded
// one layer in z (0 .. 0.1): quads become hexahedra, triangles prisms.
//
// Build (tests/integration/lib.sh, make_case):
//   gmsh -3 -format msh2 holeHybrid.geo -o holeHybrid.msh
//   gmshToFoam holeHybrid.msh
// then the patch types below are applied to constant/polyMesh/boundary
// (gmshToFoam makes every patch of type "patch"):
// foam-patch-type: frontAndBack empty
// foam-patch-type: walls wall
// foam-patch-type: hole wall

r1 = 0.2;     // hole radius
r2 = 0.32;    // outer radius of the quad ring
xc = 0.5;  yc = 0.5;
h  = 0.05;    // triangle size near the square
nArc = 11;    // nodes per quarter arc (10 quads)
nRad = 5;     // nodes across the ring (4 quads)
dz = 0.1;     // thickness

// square
Point(1) = {0, 0, 0, h};
Point(2) = {1, 0, 0, h};
Point(3) = {1, 1, 0, h};
Point(4) = {0, 1, 0, h};
Line(1) = {1, 2};   // bottom
Line(2) = {2, 3};   // right  (outlet)
Line(3) = {3, 4};   // top
Line(4) = {4, 1};   // left   (inlet)

// circles: centre, inner points 11-14, outer points 21-24 at 45, 135, 225, 315 deg
Point(10) = {xc, yc, 0, h};
c = Cos(Pi/4);
Point(11) = {xc + r1*c, yc + r1*c, 0, h};
Point(12) = {xc - r1*c, yc + r1*c, 0, h};
Point(13) = {xc - r1*c, yc - r1*c, 0, h};
Point(14) = {xc + r1*c, yc - r1*c, 0, h};
Point(21) = {xc + r2*c, yc + r2*c, 0, h};
Point(22) = {xc - r2*c, yc + r2*c, 0, h};
Point(23) = {xc - r2*c, yc - r2*c, 0, h};
Point(24) = {xc + r2*c, yc - r2*c, 0, h};

Circle(11) = {11, 10, 12};
Circle(12) = {12, 10, 13};
Circle(13) = {13, 10, 14};
Circle(14) = {14, 10, 11};
Circle(21) = {21, 10, 22};
Circle(22) = {22, 10, 23};
Circle(23) = {23, 10, 24};
Circle(24) = {24, 10, 21};
Line(31) = {11, 21};
Line(32) = {12, 22};
Line(33) = {13, 23};
Line(34) = {14, 24};

// quad ring: four quarter-annuli
Curve Loop(41) = {11, 32, -21, -31};
Curve Loop(42) = {12, 33, -22, -32};
Curve Loop(43) = {13, 34, -23, -33};
Curve Loop(44) = {14, 31, -24, -34};
Plane Surface(41) = {41};
Plane Surface(42) = {42};
Plane Surface(43) = {43};
Plane Surface(44) = {44};
Transfinite Curve {11, 12, 13, 14, 21, 22, 23, 24} = nArc;
Transfinite Curve {31, 32, 33, 34} = nRad Using Progression 1.15;
Transfinite Surface {41, 42, 43, 44};
Recombine Surface {41, 42, 43, 44};

// triangles between the ring and the square
Curve Loop(50) = {1, 2, 3, 4};
Curve Loop(51) = {21, 22, 23, 24};
Plane Surface(50) = {50, 51};

Extrude {0, 0, dz} {
    Surface{41, 42, 43, 44, 50}; Layers{1}; Recombine;
}

// patches, found by position (e = tolerance)
e = 1e-6;
Physical Surface("inlet")  = Surface In BoundingBox{-e, -e, -e,  e, 1+e, dz+e};
Physical Surface("outlet") = Surface In BoundingBox{1-e, -e, -e, 1+e, 1+e, dz+e};
Physical Surface("walls")  = {Surface In BoundingBox{-e, -e, -e, 1+e, e, dz+e},
                              Surface In BoundingBox{-e, 1-e, -e, 1+e, 1+e, dz+e}};
Physical Surface("hole")   = Surface In BoundingBox{xc-r1-e, yc-r1-e, -e, xc+r1+e, yc+r1+e, dz+e};
Physical Surface("frontAndBack") = {Surface In BoundingBox{-e, -e, -e, 1+e, 1+e, e},
                                    Surface In BoundingBox{-e, -e, dz-e, 1+e, 1+e, dz+e}};
Physical Volume("fluid") = Volume{:};
