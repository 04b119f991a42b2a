// A shell around a spherical cavity of radius 3, and a bead of radius 0.1 in the
// cavity, 0.05 from its wall, meshed apart (two bodies). The cavity's wall is concave:
// coarsened with a tolerance above the bead's size, its chords could sweep past the
// whole bead, crossing none of its faces. For the simplifier's guard between bodies.
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, 5};
Sphere(2) = {0, 0, 0, 3};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Sphere(4) = {0, 0, 2.85, 0.1};
Physical Volume("shell", 1) = {3};
Physical Volume("bead", 2) = {4};
MeshSize{ PointsOf{ Volume{4}; } } = 0.05;
