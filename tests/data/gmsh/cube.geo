// A unit cube of one physical volume, for meshes of higher order.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Physical Volume("cube", 1) = {1};
