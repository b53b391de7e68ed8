// umppmFoam tutorial: flow in a complex channel with two inlets, one outlet
// and four semi-circular grooves; Ng, Sheu & Hwang (2016) section 4.3.2,
// Figs. 28-30. 2-D OpenFOAM case (one layer of cells).
//
// The paper gives W = 1.0 m (primary channel), Ws = 0.5 m (secondary
// channel), the inflow speeds and "four semi-circular grooves in the middle
// section"; the other dimensions are not given in the text, so this
// geometry is our choice (all lengths in m, origin at the left end of the
// primary inlet):
//
//   primary channel     0 < x < W = 1.0,  0 < y < Lp = 7.0
//                       inlet  "inlet"     y = 0    (U = (0 1.456 0))
//                       outlet "outlet"    y = Lp   (p = 0)
//   secondary channel   -Ls < x < 0, ys < y < ys + Ws, Ls = 1.0, ys = 1.0,
//                       Ws = 0.5, joining the left wall of the primary one;
//                       inlet "inletSecondary" x = -Ls (U = (2.912 0 0))
//   grooves             four half-discs of radius R = 0.35 protruding from
//                       the walls, alternately left (x = 0) and right (x = 1),
//                       centres (0, 2.6), (1, 3.4), (0, 4.2), (1, 5.0):
//                       pitch 0.8, gap between a disc and the opposite wall
//                       W - R = 0.65
//
//              outlet (p = 0)
//          y=7 +-----------+
//              |           |
//              |        _  |
//          y=5 |       ( | |  groove 4 (right)
//              |   _     | |
//        y=4.2 |  | )      |  groove 3 (left)
//              |        _  |
//        y=3.4 |       ( | |  groove 2 (right)
//              |   _     | |
//        y=2.6 |  | )      |  groove 1 (left)
//              |           |
//    +---------+           |
//  ->| y=1..1.5            |  secondary channel, Ws = 0.5, 2.912 m/s
//    +---------+           |
//   x=-1       |           |
//          y=0 +-----------+
//             x=0   ^     x=1
//                 inlet, W = 1, 1.456 m/s
//
// Flow rates (per m depth): 1.456 (primary) + 1.456 (secondary) = 2.912 m^2/s
// through the channel above the junction (mean speed 2.912 m/s).
//
// Triangles everywhere (Frontal-Delaunay), one layer extruded in z (prisms).
// lc = target cell size in m (default 0.05 = the paper's l_avg), about the
// square root of the mean cell area (triangle edges 1.52 lc, an equilateral
// triangle's area being lc^2), as in the other tutorials:
//   gmsh -3 -format msh2 -setnumber lc 0.05 groovedChannel.geo -o groovedChannel.msh
//   gmshToFoam groovedChannel.msh
// then the patch types below are applied to constant/polyMesh/boundary
// (gmshToFoam makes every patch of type "patch"):
// foam-patch-type: frontAndBack empty
// foam-patch-type: walls wall
//
// Cells (gmsh 4.8.4): lc 0.15 -> 405, 0.1 -> 807, 0.07 -> 1702,
// 0.05 -> 3085 (default), 0.035 -> 6007, 0.025 -> 11491.

DefineConstant[ lc = {0.05, Name "lc"} ];

W  = 1.0;             // primary channel width
Lp = 7.0;             // primary channel length (inlet y = 0 to outlet y = Lp)
Ws = 0.5;             // secondary channel width
Ls = 1.0;             // secondary channel length
ys = 1.0;             // lower wall of the secondary channel
R  = 0.35;            // groove (half-disc) radius
yg1 = 2.6;            // groove centres: left, right, left, right
yg2 = 3.4;
yg3 = 4.2;
yg4 = 5.0;
dz = 0.1;             // thickness in z
lcT = lc*Sqrt(4/Sqrt(3));              // triangle edge: triangle area = lc^2

// boundary, counter-clockwise from the primary inlet's left end
Point(1)  = {0, 0, 0, lcT};
Point(2)  = {W, 0, 0, lcT};
// right wall, groove 2 (centre 21)
Point(20) = {W, yg2 - R, 0, lcT};
Point(21) = {W, yg2, 0, lcT};
Point(22) = {W - R, yg2, 0, lcT};
Point(23) = {W, yg2 + R, 0, lcT};
// right wall, groove 4 (centre 41)
Point(40) = {W, yg4 - R, 0, lcT};
Point(41) = {W, yg4, 0, lcT};
Point(42) = {W - R, yg4, 0, lcT};
Point(43) = {W, yg4 + R, 0, lcT};
Point(3)  = {W, Lp, 0, lcT};
Point(4)  = {0, Lp, 0, lcT};
// left wall, groove 3 (centre 31)
Point(30) = {0, yg3 + R, 0, lcT};
Point(31) = {0, yg3, 0, lcT};
Point(32) = {R, yg3, 0, lcT};
Point(33) = {0, yg3 - R, 0, lcT};
// left wall, groove 1 (centre 11)
Point(10) = {0, yg1 + R, 0, lcT};
Point(11) = {0, yg1, 0, lcT};
Point(12) = {R, yg1, 0, lcT};
Point(13) = {0, yg1 - R, 0, lcT};
// secondary channel
Point(5)  = {0, ys + Ws, 0, lcT};
Point(6)  = {-Ls, ys + Ws, 0, lcT};
Point(7)  = {-Ls, ys, 0, lcT};
Point(8)  = {0, ys, 0, lcT};

Line(1)    = {1, 2};              // inlet
Line(2)    = {2, 20};
Circle(3)  = {20, 21, 22};
Circle(4)  = {22, 21, 23};
Line(5)    = {23, 40};
Circle(6)  = {40, 41, 42};
Circle(7)  = {42, 41, 43};
Line(8)    = {43, 3};
Line(9)    = {3, 4};              // outlet
Line(10)   = {4, 30};
Circle(11) = {30, 31, 32};
Circle(12) = {32, 31, 33};
Line(13)   = {33, 10};
Circle(14) = {10, 11, 12};
Circle(15) = {12, 11, 13};
Line(16)   = {13, 5};
Line(17)   = {5, 6};
Line(18)   = {6, 7};              // inletSecondary
Line(19)   = {7, 8};
Line(20)   = {8, 1};

Curve Loop(1) = {1:20};
Plane Surface(1) = {1};
Mesh.Algorithm = 6;               // Frontal-Delaunay triangles

// Extrude returns: top, volume, then the side surfaces in the order of the
// surface's curves (1 ... 20).
e[] = Extrude {0, 0, dz} { Surface{1}; Layers{1}; Recombine; };

Physical Surface("inlet") = {e[2]};
Physical Surface("outlet") = {e[10]};
Physical Surface("inletSecondary") = {e[19]};
Physical Surface("walls") = {e[{3:9}], e[{11:18}], e[{20:21}]};
Physical Surface("frontAndBack") = {1, e[0]};
Physical Volume("fluid") = {e[1]};
