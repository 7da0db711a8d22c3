// SPDX-License-Identifier: GPL-3.0-or-later
// The right half (x >= 0) of a coated block: the block [0, 2] x [-1, 0]
// with a stiff coating of thickness t on its top. The coating and the
// substrate are two surfaces that share the curve y = -t (its nodes too):
// one body, two regions, two materials. signorini meshes it at size
// h / level, h the sizes of the points below.
t = 0.1;     // the coating's thickness
hc = 0.02;   // under the disc
hm = 0.1;    // mid-way
hf = 0.25;   // far from it
Point(1) = {0, 0, 0, hc};
Point(2) = {0.6, 0, 0, hc};
Point(3) = {2, 0, 0, hf};
Point(4) = {2, -t, 0, hf};
Point(5) = {0.6, -t, 0, hc};
Point(6) = {0, -t, 0, hc};
Point(7) = {2, -1, 0, hf};
Point(8) = {0, -1, 0, hm};
Line(1) = {1, 2};     // top, under the disc
Line(2) = {2, 3};     // top, beyond
Line(3) = {3, 4};     // the coating's right end
Line(4) = {4, 5};     // the interface (shared by both surfaces)
Line(5) = {5, 6};
Line(6) = {6, 1};     // the coating's cut x = 0
Line(7) = {4, 7};     // the substrate's right end
Line(8) = {7, 8};     // bottom
Line(9) = {8, 6};     // the substrate's cut x = 0
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {-5, -4, 7, 8, 9};
Plane Surface(2) = {2};
Physical Curve("top") = {1, 2};
Physical Curve("bottom") = {8};
Physical Curve("cut") = {6, 9};
Physical Surface("coating") = {1};
Physical Surface("substrate") = {2};
