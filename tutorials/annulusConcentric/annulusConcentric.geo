// umppmFoam tutorial: natural convection in the annulus between two
// concentric circular cylinders, hot inner R1 = 0.02 m, cold outer
// R2 = 0.052 m, centre at the origin; Ng, Sheu & Hwang (2016). 2-D OpenFOAM
// case (one layer of cells).
//
// Hybrid mesh: a structured ring of quadrilaterals at each wall (four
// transfinite, recombined quarter-annuli each, 1.2 lc thick, 3 cells graded
// towards the wall), unstructured triangles between the two rings. Extruded
// one layer in z (0 .. dz): quads become hexahedra, triangles prisms.
//
// lc = target cell size in m (default 0.002), about the square root of the
// mean cell area (the triangles and the arcs get edges of 1.52 lc, the area
// of an equilateral triangle being lc^2), selectable on the command line:
//   gmsh -3 -format msh2 -setnumber lc 0.003 annulusConcentric.geo -o annulusConcentric.msh
//   gmshToFoam annulusConcentric.msh
// then the patch types below are applied to constant/polyMesh/boundary
// (gmshToFoam makes every patch of type "patch"):
// foam-patch-type: frontAndBack empty
// foam-patch-type: inner wall
// foam-patch-type: outer wall
//
// Cells (gmsh 4.8.4): lc 0.004 -> 640, 0.003 -> 976, 0.002 -> 2092 (the
// paper's mesh at l_avg = 2 mm has 1916).

DefineConstant[ lc = {0.002, Name "lc"} ];

R1 = 0.02;            // inner cylinder radius
R2 = 0.052;           // outer cylinder radius
lcT = lc*Sqrt(4/Sqrt(3));              // triangle edge: triangle area = lc^2
tr = 1.2*lc;          // thickness of each quad ring
ra = R1 + tr;         // outer edge of the inner ring
rb = R2 - tr;         // inner edge of the outer ring
n1 = Ceil(0.5*Pi*R1/lcT) + 1;          // nodes per quarter arc, inner ring
n2 = Ceil(0.5*Pi*R2/lcT) + 1;          // nodes per quarter arc, outer ring
nRad = 4;             // nodes across a ring (3 quads)
dz = 0.01;            // thickness in z
lca = 0.5*Pi*ra/(n1 - 1);              // arc spacing at the inner ring edge
lcb = 0.5*Pi*rb/(n2 - 1);              // arc spacing at the outer ring edge

Point(10) = {0, 0, 0, lc};
c = Cos(Pi/4);
// points at 45, 135, 225, 315 deg on r = R1 (11-14), ra (21-24), rb (31-34), R2 (41-44)
For k In {0:3}
    s1 = (k == 0 || k == 3) ? 1 : -1;  // sign of x
    s2 = (k < 2) ? 1 : -1;             // sign of y
    Point(11 + k) = {s1*R1*c, s2*R1*c, 0, lca};
    Point(21 + k) = {s1*ra*c, s2*ra*c, 0, lca};
    Point(31 + k) = {s1*rb*c, s2*rb*c, 0, lcb};
    Point(41 + k) = {s1*R2*c, s2*R2*c, 0, lcb};
EndFor

// arcs (counter-clockwise), quarter k from point k to point k+1
For k In {0:3}
    k1 = (k + 1) % 4;
    Circle(11 + k) = {11 + k, 10, 11 + k1};
    Circle(21 + k) = {21 + k, 10, 21 + k1};
    Circle(31 + k) = {31 + k, 10, 31 + k1};
    Circle(41 + k) = {41 + k, 10, 41 + k1};
    Line(51 + k) = {11 + k, 21 + k};   // inner ring, from the wall outwards
    Line(61 + k) = {41 + k, 31 + k};   // outer ring, from the wall inwards
EndFor

// quad rings
For k In {0:3}
    k1 = (k + 1) % 4;
    Curve Loop(71 + k) = {11 + k, 51 + k1, -(21 + k), -(51 + k)};
    Plane Surface(71 + k) = {71 + k};
    Curve Loop(81 + k) = {41 + k, 61 + k1, -(31 + k), -(61 + k)};
    Plane Surface(81 + k) = {81 + k};
EndFor
Transfinite Curve {11:14, 21:24} = n1;
Transfinite Curve {31:34, 41:44} = n2;
Transfinite Curve {51:54, 61:64} = nRad Using Progression 1.2;
Transfinite Surface {71:74, 81:84};
Recombine Surface {71:74, 81:84};

// triangles between the rings
Curve Loop(90) = {31, 32, 33, 34};
Curve Loop(91) = {21, 22, 23, 24};
Plane Surface(90) = {90, 91};

// Extrude returns, per surface: top, volume, then the side surfaces in the
// order of the surface's curves (the wall arc first for the rings).
inner[] = {}; outer[] = {}; tops[] = {}; vols[] = {};
For k In {0:3}
    q[] = Extrude {0, 0, dz} { Surface{71 + k}; Layers{1}; Recombine; };
    inner[] += q[2]; tops[] += q[0]; vols[] += q[1];
    q[] = Extrude {0, 0, dz} { Surface{81 + k}; Layers{1}; Recombine; };
    outer[] += q[2]; tops[] += q[0]; vols[] += q[1];
EndFor
t[] = Extrude {0, 0, dz} { Surface{90}; Layers{1}; Recombine; };
tops[] += t[0]; vols[] += t[1];

Physical Surface("inner") = inner[];
Physical Surface("outer") = outer[];
Physical Surface("frontAndBack") = {71:74, 81:84, 90, tops[]};
Physical Volume("fluid") = vols[];
