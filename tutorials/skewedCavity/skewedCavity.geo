// umppmFoam tutorial: lid-driven flow in a skewed cavity (Erturk & Dursun
// 2007), Ng, Sheu & Hwang (2016) section 4.2.2, Fig. 16. All four sides
// L = 1 m, skew angle 15 deg; vertices O = (0, 0), (1, 0), (1 + cos 15,
// sin 15), (cos 15, sin 15). Edges: A bottom, B right, C top (the lid,
// moving at (1 0 0)), D left. 2-D OpenFOAM case (one layer of cells in z).
//
// Hybrid mesh:
// * quadrilateral wall layers: along each edge a transfinite, recombined
//   strip of 2 quads across (total thickness d = 1.6 lc, graded 1.2 away
//   from the wall) and edge length ~1.6 lc along the wall; at the two obtuse
//   corners (165 deg) neighbouring strips meet on the corner bisector;
// * triangles (gmsh Delaunay, edge ~1.6 lc) inside the strips and in the
//   two acute 15 deg corners, where the strips stop at the foot of the inner
//   corner point (a corner quad would be a sliver).
// Extruded one layer in z (0 .. dz): quads become hexahedra, triangles
// prisms.
//
// lc = the average cell size l_avg = sqrt(area / N_m) of the paper (area =
// sin 15 = 0.2588 m^2), selectable on the command line:
//   gmsh -3 -format msh2 -setnumber lc 0.01 skewedCavity.geo -o skewedCavity.msh
//   gmshToFoam skewedCavity.msh
// then the patch types below are applied to constant/polyMesh/boundary
// (gmshToFoam makes every patch of type "patch"):
// foam-patch-type: frontAndBack empty
// foam-patch-type: movingWall wall
// foam-patch-type: fixedWalls wall
//
// Cells N_m (gmsh 4.8.4; quads + triangles; l_avg = sqrt(0.2588/N_m)), the
// paper's N_m in brackets:
//   lc 0.04   ->   202 (72 + 130),     l_avg 0.0358  [157]
//   lc 0.02   ->   628 (192 + 436),    l_avg 0.0203  [589, Fig. 16(b)]
//   lc 0.01   ->  2410 (440 + 1970),   l_avg 0.0104  [2549]
//   lc 0.005  ->  9586 (944 + 8642),   l_avg 0.0052  [9920]
//   lc 0.0025 -> 37686 (1944 + 35742), l_avg 0.0026  [39395]

DefineConstant[ lc = {0.02, Name "lc"} ];

th = 15*Pi/180;       // skew angle
c = Cos(th);
s = Sin(th);
lcT = 1.6*lc;         // triangle edge and quad length along the walls
d = lcT;              // thickness of the quad layers
nL = 2;               // quads across a layer
e = d*(1 + c)/s;      // acute corner to the foot of its inner corner point
o = d*(1 - c)/s;      // obtuse corner: x offset of its inner corner point
nA = Ceil((1 - e)/lcT) + 1;            // nodes along a strip
dz = 0.01;            // thickness in z

// corners P1 (O, acute), P2 (obtuse), P3 (acute), P4 (obtuse)
Point(1) = {0, 0, 0, lcT};
Point(2) = {1, 0, 0, lcT};
Point(3) = {1 + c, s, 0, lcT};
Point(4) = {c, s, 0, lcT};
// inner corners I1..I4: the walls offset by d into the cavity
Point(11) = {e, d, 0, lcT};
Point(12) = {1 - o, d, 0, lcT};
Point(13) = {1 + c - e, s - d, 0, lcT};
Point(14) = {c + o, s - d, 0, lcT};
// feet of I1 and I3 on the walls: where the strips end at the acute corners
Point(21) = {e, 0, 0, lcT};                 // I1 on A
Point(22) = {e*c, e*s, 0, lcT};             // I1 on D
Point(23) = {1 + c - e, s, 0, lcT};         // I3 on C
Point(24) = {1 + c - e*c, s - e*s, 0, lcT}; // I3 on B

// walls: A = 1, 2; B = 3, 4; C (lid) = 5, 6; D = 7, 8
Line(1) = {1, 21};  Line(2) = {21, 2};
Line(3) = {2, 24};  Line(4) = {24, 3};
Line(5) = {3, 23};  Line(6) = {23, 4};
Line(7) = {4, 22};  Line(8) = {22, 1};
// across the strips, from the wall inwards (the grading starts at the wall)
Line(11) = {21, 11}; Line(12) = {2, 12}; Line(13) = {24, 13};
Line(14) = {23, 13}; Line(15) = {4, 14}; Line(16) = {22, 11};
// inner edges of the strips
Line(21) = {11, 12}; Line(22) = {12, 13}; Line(23) = {13, 14}; Line(24) = {14, 11};

// quad strips along A, B, C, D (the wall curve first)
Curve Loop(31) = {2, 12, -21, -11};   Plane Surface(31) = {31};
Curve Loop(32) = {3, 13, -22, -12};   Plane Surface(32) = {32};
Curve Loop(33) = {6, 15, -23, -14};   Plane Surface(33) = {33};
Curve Loop(34) = {7, 16, -24, -15};   Plane Surface(34) = {34};
// triangles: the acute corners at O (walls A, D) and P3 (walls C, B), the core
Curve Loop(35) = {1, 11, -16, 8};     Plane Surface(35) = {35};
Curve Loop(36) = {5, 14, -13, 4};     Plane Surface(36) = {36};
Curve Loop(37) = {21, 22, 23, 24};    Plane Surface(37) = {37};

Transfinite Curve {2, 3, 6, 7, 21, 22, 23, 24} = nA;
Transfinite Curve {11, 12, 13, 14, 15, 16} = nL + 1 Using Progression 1.2;
Transfinite Surface {31, 32, 33, 34};
Recombine Surface {31, 32, 33, 34};

// Extrude returns, per surface: top, volume, then the side surfaces in the
// order of the surface's curves.
b[] = Extrude {0, 0, dz} { Surface{31}; Layers{1}; Recombine; };
r[] = Extrude {0, 0, dz} { Surface{32}; Layers{1}; Recombine; };
t[] = Extrude {0, 0, dz} { Surface{33}; Layers{1}; Recombine; };
l[] = Extrude {0, 0, dz} { Surface{34}; Layers{1}; Recombine; };
k1[] = Extrude {0, 0, dz} { Surface{35}; Layers{1}; Recombine; };
k3[] = Extrude {0, 0, dz} { Surface{36}; Layers{1}; Recombine; };
m[] = Extrude {0, 0, dz} { Surface{37}; Layers{1}; Recombine; };

Physical Surface("movingWall") = {t[2], k3[2]};
Physical Surface("fixedWalls") = {b[2], r[2], l[2], k1[2], k1[5], k3[5]};
Physical Surface("frontAndBack") = {31, 32, 33, 34, 35, 36, 37,
                                    b[0], r[0], t[0], l[0], k1[0], k3[0], m[0]};
Physical Volume("fluid") = {b[1], r[1], t[1], l[1], k1[1], k3[1], m[1]};
