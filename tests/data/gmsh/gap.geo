// A ball of radius 5 with a spherical gap 0.15 wide at radius 3, bridged by a
// cylinder along z (so one piece). The gap's two walls are both outer boundary: a
// coarse enough simplification with a tolerance above the gap would push one through
// the other (the chords of the concave outer wall cut into the gap). For the tests of
// the simplifier's guard against a boundary that crosses itself.
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, 5};
Sphere(2) = {0, 0, 0, 3.15};
Sphere(3) = {0, 0, 0, 3};
BooleanDifference(4) = { Volume{2}; Delete; }{ Volume{3}; Delete; };
Cylinder(5) = {0, 0, -6, 0, 0, 12, 1};
BooleanDifference(6) = { Volume{4}; Delete; }{ Volume{5}; Delete; };
BooleanDifference(7) = { Volume{1}; Delete; }{ Volume{6}; Delete; };
Physical Volume("part", 1) = {7};
