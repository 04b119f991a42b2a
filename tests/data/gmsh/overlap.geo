// Two boxes (materials 1 and 2) with overlapping surface groups, as Gmsh users make
// them: "all outer" is the whole outer boundary, "x0" one face of it (each of its
// surfaces is in both groups). For the tests of SurfacePatches: both are kept, a
// triangle going to the smaller group.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {1, 0, 0, 1, 1, 1};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
Physical Volume("left", 1) = {1};
Physical Volume("right", 2) = {2};
Physical Surface("all outer", 30) = CombinedBoundary{ Volume{1, 2}; };
Physical Surface("x0", 31) = Surface In BoundingBox{-0.01, -0.01, -0.01, 0.01, 1.01, 1.01};
