// SPDX-License-Identifier: GPL-3.0-or-later
// Half of a ring (x >= 0) of outer radius 1 and inner radius 0.8, centre
// at the origin, between two plates y = -1 and y = 1. The outer arc is cut
// at +-45 degrees so that the two contact boundaries share no node.
// signorini meshes it at size h / level, h the sizes of the points below.
ro = 1; ri = 0.8;
h = 0.08; hc = 0.03;   // hc near the plates
c = Cos(Pi / 4);
Point(1) = {0, 0, 0, h};
Point(2) = {0, -ro, 0, hc};
Point(3) = {ro * c, -ro * c, 0, h};
Point(4) = {ro * c, ro * c, 0, h};
Point(5) = {0, ro, 0, hc};
Point(6) = {0, -ri, 0, hc};
Point(7) = {ri, 0, 0, h};
Point(8) = {0, ri, 0, hc};
Circle(1) = {2, 1, 3};    // outer, bottom eighth
Circle(2) = {3, 1, 4};    // outer, the side
Circle(3) = {4, 1, 5};    // outer, top eighth
Line(4) = {5, 8};         // the cut at the top
Circle(5) = {8, 1, 7};    // inner, top quarter (turning back)
Circle(6) = {7, 1, 6};    // inner, bottom quarter
Line(7) = {6, 2};         // the cut at the bottom
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7};
Plane Surface(1) = {1};
Physical Curve("outer_bottom") = {1};
Physical Curve("outer_side") = {2};
Physical Curve("outer_top") = {3};
Physical Curve("inner") = {5, 6};
Physical Curve("cut") = {4, 7};
Physical Surface("ring") = {1};
