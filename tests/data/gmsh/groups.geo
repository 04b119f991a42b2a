// Two boxes side by side (materials 1 and 2). Surface groups: all of box 1's outer
// boundary (= boundary_1), the interface (= interface_1_2), and one face of box 2
// (part of boundary_2), for the tests of SurfacePatches.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {1, 0, 0, 1, 1, 1};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
Physical Volume(1) = {1};
Physical Volume(2) = {2};
left() = Boundary{ Volume{1}; };
right() = Boundary{ Volume{2}; };
shared() = Surface In BoundingBox{0.99, -0.01, -0.01, 1.01, 1.01, 1.01};
left() -= shared();
Physical Surface("outer_left", 100) = {left()};
Physical Surface("membrane", 200) = {shared()};
Physical Surface("right_end", 300) = Surface In BoundingBox{1.99, -0.01, -0.01, 2.01, 1.01, 1.01};
