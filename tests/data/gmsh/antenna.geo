// A patch antenna: a thin copper patch (0.2 thick) on a substrate over a ground plane
// (0.2 thick), joined to it by a feed pin through the substrate, in a box of air. Thin
// layers whose tets are flat (many below the default stretch threshold), junction
// curves where patch, pin and substrate meet, and a pin whose ends are interfaces.
SetFactory("OpenCASCADE");
Box(1) = {-15,-15,-8, 30,30,16};        // air
Box(2) = {-8,-8,-0.8, 16,16,1.6};       // substrate
Box(3) = {-4,-3,0.8, 8,6,0.2};          // patch
Cylinder(4) = {-1.5,0,-0.8, 0,0,1.6, 0.4};  // feed pin
Box(5) = {-8,-8,-1.0, 16,16,0.2};       // ground plane
BooleanFragments{ Volume{1}; Delete; }{ Volume{2,3,4,5}; Delete; }
Physical Volume("air", 1) = {6};
Physical Volume("substrate", 2) = {7};
Physical Volume("patch", 3) = {3};
Physical Volume("feed", 4) = {4};
Physical Volume("ground", 5) = {5};
