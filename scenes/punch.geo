// SPDX-License-Identifier: GPL-3.0-or-later
// The right half (x >= 0) of a flat punch with rounded corners on a block:
// the punch [0, 0.5] x [0, 1] with its lower corner rounded at radius 0.1,
// the block [0, 2] x [-2, 0] under it. The two bodies touch along y = 0 and
// have their own nodes there (two surfaces, no shared curve). signorini
// meshes them at size h / level, h the sizes of the points below.
hf = 0.02;   // at the punch's corner
hb = 0.035;  // under the punch
hp = 0.1;    // the punch's top
hx = 0.4;    // far in the block
r = 0.1;
// punch
Point(1) = {0, 0, 0, hb};
Point(2) = {0.5 - r, 0, 0, hf};
Point(3) = {0.5 - r, r, 0, hf};    // the corner's centre
Point(4) = {0.5, r, 0, hf};
Point(5) = {0.5, 1, 0, hp};
Point(6) = {0, 1, 0, hp};
Line(1) = {1, 2};
Circle(2) = {2, 3, 4};
Line(3) = {4, 5};
Line(4) = {5, 6};
Line(5) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
// block
Point(11) = {0, 0, 0, hb};
Point(12) = {0.5, 0, 0, hf};
Point(13) = {2, 0, 0, hx};
Point(14) = {2, -2, 0, hx};
Point(15) = {0, -2, 0, hx};
Line(11) = {11, 12};
Line(12) = {12, 13};
Line(13) = {13, 14};
Line(14) = {14, 15};
Line(15) = {15, 11};
Curve Loop(2) = {11, 12, 13, 14, 15};
Plane Surface(2) = {2};
Physical Curve("punch_bottom") = {1, 2};
Physical Curve("punch_top") = {4};
Physical Curve("punch_axis") = {5};
Physical Curve("block_top") = {11, 12};
Physical Curve("block_bottom") = {14};
Physical Curve("block_axis") = {15};
Physical Surface("steel") = {1};
Physical Surface("aluminium") = {2};
