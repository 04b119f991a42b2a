// A block whose top face holds a round port: a surface group ("port") that is part of
// the block's boundary on a flat face, so its border is no crease; the rest of the
// boundary is in no group. For the tests of SurfacePatches: simplification keeps the
// port's border, and the group is found again on the simplified mesh.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 1};
Disk(10) = {1, 0.5, 1, 0.3};
BooleanFragments{ Volume{1}; Delete; }{ Surface{10}; Delete; }
Physical Volume("block", 1) = {1};
Physical Surface("port", 20) = Surface In BoundingBox{0.69, 0.19, 0.99, 1.31, 0.81, 1.01};
