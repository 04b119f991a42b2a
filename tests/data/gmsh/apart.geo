// A ball of radius 3 inside a shell from radius 3 + gap to 5, meshed apart: two
// bodies with no vertex in common. With gap 0.15 (apart.msh) they are 0.15 apart, and a
// tolerance above that would let collapses push one into the other; with gap 0
// (touch.msh) they meet on the sphere of radius 3, whose two meshes' chords cross each
// other by design. For the simplifier's guard between bodies.
SetFactory("OpenCASCADE");
DefineConstant[ gap = 0.15 ];
Sphere(1) = {0, 0, 0, 5};
Sphere(2) = {0, 0, 0, 3 + gap};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Sphere(4) = {0, 0, 0, 3};
Physical Volume("shell", 1) = {3};
Physical Volume("core", 2) = {4};
