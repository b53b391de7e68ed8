// umppmFoam tutorial: natural convection between a cold outer square
// (side L = 0.1 m, centred at the origin) and a hot inner circular cylinder
// (radius R = 0.02 m, centre at the origin); Ng, Sheu & Hwang (2016),
// section 4.4.1. 2-D OpenFOAM case (one layer of cells).
//
// Hybrid mesh: a structured ring of quadrilaterals (four transfinite,
// recombined quarter-annuli, r = R .. R + 1.2 lc, 3 cells graded towards
// the cylinder) around the cylinder, unstructured triangles between the
// ring and the square. Extruded one layer in z (0 .. dz): quads become
// hexahedra, triangles prisms.
//
// lc = target cell size in m (default 0.0044), about the square root of the
// mean cell area (the triangles and the arcs get edges of 1.52 lc, the area
// of an equilateral triangle being lc^2), selectable on the command line:
//   gmsh -3 -format msh2 -setnumber lc 0.0022 annulusSquareCylinder.geo -o annulusSquareCylinder.msh
//   gmshToFoam annulusSquareCylinder.msh
// then the patch types below are applied to constant/polyMesh/boundary
// (gmshToFoam makes every patch of type "patch"):
// foam-patch-type: frontAndBack empty
// foam-patch-type: inner wall
// foam-patch-type: outer wall
//
// Cells (gmsh 4.8.4): lc 0.005 -> 408, 0.0044 -> 460 (the paper's coarsest
// mesh has 479), 0.004 -> 612, 0.003 -> 968, 0.0022 -> 1870, 0.002 -> 2254.

DefineConstant[ lc = {0.0044, Name "lc"} ];

R  = 0.02;            // cylinder radius
h  = 0.05;            // half side of the square
lcT = lc*Sqrt(4/Sqrt(3));              // triangle edge: triangle area = lc^2
tr = 1.2*lc;          // thickness of the quad ring
r2 = R + tr;          // outer radius of the quad ring
nArc = Ceil(0.5*Pi*R/lcT) + 1;         // nodes per quarter arc
nRad = 4;             // nodes across the ring (3 quads)
dz = 0.01;            // thickness in z
lcRing = 0.5*Pi*r2/(nArc - 1);         // arc spacing at the ring edge

// square
Point(1) = {-h, -h, 0, lcT};
Point(2) = { h, -h, 0, lcT};
Point(3) = { h,  h, 0, lcT};
Point(4) = {-h,  h, 0, lcT};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};

// circles: centre, inner points 11-14, outer points 21-24 at 45, 135, 225, 315 deg
Point(10) = {0, 0, 0, lc};
c = Cos(Pi/4);
Point(11) = { R*c,  R*c, 0, lcRing};
Point(12) = {-R*c,  R*c, 0, lcRing};
Point(13) = {-R*c, -R*c, 0, lcRing};
Point(14) = { R*c, -R*c, 0, lcRing};
Point(21) = { r2*c,  r2*c, 0, lcRing};
Point(22) = {-r2*c,  r2*c, 0, lcRing};
Point(23) = {-r2*c, -r2*c, 0, lcRing};
Point(24) = { r2*c, -r2*c, 0, lcRing};

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
Transfinite Curve {31, 32, 33, 34} = nRad Using Progression 1.2;
Transfinite Surface {41, 42, 43, 44};
Recombine Surface {41, 42, 43, 44};

// triangles between the ring and the square
Curve Loop(50) = {1, 2, 3, 4};
Curve Loop(51) = {21, 22, 23, 24};
Plane Surface(50) = {50, 51};

// Extrude returns, per surface: top, volume, then the side surfaces in the
// order of the surface's curves.
q1[] = Extrude {0, 0, dz} { Surface{41}; Layers{1}; Recombine; };
q2[] = Extrude {0, 0, dz} { Surface{42}; Layers{1}; Recombine; };
q3[] = Extrude {0, 0, dz} { Surface{43}; Layers{1}; Recombine; };
q4[] = Extrude {0, 0, dz} { Surface{44}; Layers{1}; Recombine; };
t[]  = Extrude {0, 0, dz} { Surface{50}; Layers{1}; Recombine; };

// patches: side surfaces of curves 11-14 (cylinder) and 1-4 (square)
Physical Surface("outer") = {t[2], t[3], t[4], t[5]};
Physical Surface("inner") = {q1[2], q2[2], q3[2], q4[2]};
Physical Surface("frontAndBack") = {41, 42, 43, 44, 50,
                                    q1[0], q2[0], q3[0], q4[0], t[0]};
Physical Volume("fluid") = {q1[1], q2[1], q3[1], q4[1], t[1]};
