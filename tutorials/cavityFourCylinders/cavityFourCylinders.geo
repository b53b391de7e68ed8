// umppmFoam tutorial: lid-driven flow in a complex cavity, Ng, Sheu &
// Hwang (2016) section 4.2.3, Fig. 22: the unit square with four circular
// cylinders A, B, C, D centred at (1/3, 1/3), (2/3, 1/3), (1/3, 2/3),
// (2/3, 2/3); the lid y = 1 moves at (1 0 0), Re = 1000. 2-D OpenFOAM case
// (one layer of cells in z).
//
// The cylinders' radius is not stated in the paper (the figure is not
// measured here): R = 0.1 m is our choice. It leaves gaps of 0.133 m
// between neighbouring cylinders and 0.233 m to the walls; the lines
// x = 0.5 and y = 0.5 pass through the gaps.
//
// Hybrid mesh: a structured ring of quadrilaterals around each cylinder
// (four transfinite, recombined quarter-annuli, r = R .. R + 1.2 lc, 2 cells
// graded 1.2 away from the cylinder), unstructured triangles (gmsh
// Delaunay, edge 1.5 lc) everywhere else. Extruded one layer in z (0 ..
// dz): quads become hexahedra, triangles prisms.
//
// lc = the average cell size l_avg = sqrt(area / N_m) (fluid area
// 1 - 4 pi R^2 = 0.8743 m^2), selectable on the command line:
//   gmsh -3 -format msh2 -setnumber lc 0.02 cavityFourCylinders.geo -o cavityFourCylinders.msh
//   gmshToFoam cavityFourCylinders.msh
// then the patch types below are applied to constant/polyMesh/boundary
// (gmshToFoam makes every patch of type "patch"):
// foam-patch-type: frontAndBack empty
// foam-patch-type: movingWall wall
// foam-patch-type: fixedWalls wall
// foam-patch-type: cylinders wall
//
// Cells N_m (gmsh 4.8.4; quads + triangles; l_avg = sqrt(0.8743/N_m)):
//   lc 0.04 ->  526 (96 + 430),   l_avg 0.0408
//   lc 0.02 -> 2270 (192 + 2078), l_avg 0.0196  (the paper's l_avg 0.02)
//   lc 0.01 -> 8730 (352 + 8378), l_avg 0.0100

DefineConstant[ lc = {0.02, Name "lc"} ];

R   = 0.1;            // cylinder radius: not stated in the paper, our choice
lcT = 1.5*lc;         // triangle edge length (l_avg ~ lc, counts below)
tr  = 1.2*lc;         // thickness of the quad ring around each cylinder
r2  = R + tr;
nArc = Ceil(0.5*Pi*R/lcT) + 1;         // nodes per quarter arc
nRad = 3;             // nodes across the ring (2 quads)
dz  = 0.01;           // thickness in z
lcRing = 0.5*Pi*r2/(nArc - 1);         // arc spacing at the ring edge

// the square: bottom 1, right 2, top (the lid) 3, left 4

Point(1) = {0, 0, 0, lcT};
Point(2) = {1, 0, 0, lcT};
Point(3) = {1, 1, 0, lcT};
Point(4) = {0, 1, 0, lcT};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};

// cylinders A, B, C, D: centre b, arc points b+1..b+4 (45, 135, 225, 315
// deg), ring edge b+11..b+14, arcs b+1.., b+11.., radial lines b+21..,
// quarter-annuli b+31..b+34, ring edge loop b+40
xs[] = {1/3, 2/3, 1/3, 2/3};
ys[] = {1/3, 1/3, 2/3, 2/3};
cq = Cos(Pi/4);
rings[] = {};
holes[] = {};
cyl[] = {};
For k In {0:3}
  b = 100*(k + 1);
  xc = xs[k]; yc = ys[k];
  Point(b) = {xc, yc, 0, lcT};
  Point(b + 1) = {xc + R*cq, yc + R*cq, 0, lcRing};
  Point(b + 2) = {xc - R*cq, yc + R*cq, 0, lcRing};
  Point(b + 3) = {xc - R*cq, yc - R*cq, 0, lcRing};
  Point(b + 4) = {xc + R*cq, yc - R*cq, 0, lcRing};
  Point(b + 11) = {xc + r2*cq, yc + r2*cq, 0, lcRing};
  Point(b + 12) = {xc - r2*cq, yc + r2*cq, 0, lcRing};
  Point(b + 13) = {xc - r2*cq, yc - r2*cq, 0, lcRing};
  Point(b + 14) = {xc + r2*cq, yc - r2*cq, 0, lcRing};
  Circle(b + 1) = {b + 1, b, b + 2};
  Circle(b + 2) = {b + 2, b, b + 3};
  Circle(b + 3) = {b + 3, b, b + 4};
  Circle(b + 4) = {b + 4, b, b + 1};
  Circle(b + 11) = {b + 11, b, b + 12};
  Circle(b + 12) = {b + 12, b, b + 13};
  Circle(b + 13) = {b + 13, b, b + 14};
  Circle(b + 14) = {b + 14, b, b + 11};
  Line(b + 21) = {b + 1, b + 11};
  Line(b + 22) = {b + 2, b + 12};
  Line(b + 23) = {b + 3, b + 13};
  Line(b + 24) = {b + 4, b + 14};
  Curve Loop(b + 31) = {b + 1, b + 22, -(b + 11), -(b + 21)};
  Curve Loop(b + 32) = {b + 2, b + 23, -(b + 12), -(b + 22)};
  Curve Loop(b + 33) = {b + 3, b + 24, -(b + 13), -(b + 23)};
  Curve Loop(b + 34) = {b + 4, b + 21, -(b + 14), -(b + 24)};
  Plane Surface(b + 31) = {b + 31};
  Plane Surface(b + 32) = {b + 32};
  Plane Surface(b + 33) = {b + 33};
  Plane Surface(b + 34) = {b + 34};
  Transfinite Curve {b + 1, b + 2, b + 3, b + 4, b + 11, b + 12, b + 13, b + 14} = nArc;
  Transfinite Curve {b + 21, b + 22, b + 23, b + 24} = nRad Using Progression 1.2;
  Transfinite Surface {b + 31, b + 32, b + 33, b + 34};
  Recombine Surface {b + 31, b + 32, b + 33, b + 34};
  Curve Loop(b + 40) = {b + 11, b + 12, b + 13, b + 14};
  holes[] += {b + 40};
  rings[] += {b + 31, b + 32, b + 33, b + 34};
EndFor

// triangles between the rings and the square
Curve Loop(10) = {1, 2, 3, 4};
Plane Surface(10) = {10, holes[]};

// Extrude returns, per surface: top, volume, then the side surfaces in the
// order of the surface's curves (for a ring quarter: the cylinder arc first).
fluid[] = {};
front[] = {};
cylinders[] = {};
For i In {0:#rings[] - 1}
  q[] = Extrude {0, 0, dz} { Surface{rings[i]}; Layers{1}; Recombine; };
  fluid[] += {q[1]};
  front[] += {q[0]};
  cylinders[] += {q[2]};
EndFor
t[] = Extrude {0, 0, dz} { Surface{10}; Layers{1}; Recombine; };

Physical Surface("movingWall") = {t[4]};
Physical Surface("fixedWalls") = {t[2], t[3], t[5]};
Physical Surface("cylinders") = {cylinders[]};
Physical Surface("frontAndBack") = {10, rings[], t[0], front[]};
Physical Volume("fluid") = {fluid[], t[1]};
