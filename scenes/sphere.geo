// SPDX-License-Identifier: GPL-3.0-or-later
// An eighth of an elastic ball of radius R (centre (0, 0, R)): the part
// x >= 0, y >= 0, z <= R, meshed finer towards the contact at the origin.
// signorini meshes it at size h / level, h the sizes below.
SetFactory("OpenCASCADE");
R = 8;
Sphere(1) = {0, 0, R, R, -Pi/2, 0, Pi/2};

// the size: 0.25 at the contact, growing with the distance from it
Field[1] = MathEval;
Field[1].F = "0.25 + 0.25 * Sqrt(x^2 + y^2 + z^2)";
Background Field = 1;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.MeshSizeExtendFromBoundary = 0;

e = 1e-6;
top() = Surface In BoundingBox{-e, -e, R - e, R + e, R + e, R + e};
symx() = Surface In BoundingBox{-e, -e, -e, e, R + e, R + e};
symy() = Surface In BoundingBox{-e, -e, -e, R + e, e, R + e};
ball() = Surface{:};
ball() -= {top(), symx(), symy()};
Physical Surface("top") = top();
Physical Surface("symx") = symx();
Physical Surface("symy") = symy();
Physical Surface("surface") = ball();
Physical Volume("ball") = {1};
