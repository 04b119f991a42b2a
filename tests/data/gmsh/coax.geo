// Coaxial cable segment, mm: inner conductor a=1, two dielectric layers (eps 2 to r=2, eps 4 to b=3.5),
// outer conductor shield 3.5..4, length L=10 along z.
SetFactory("OpenCASCADE");
L = 4;
Cylinder(1) = {0,0,0, 0,0,L, 1.0};
Cylinder(2) = {0,0,0, 0,0,L, 2.0};
Cylinder(3) = {0,0,0, 0,0,L, 3.5};
Cylinder(4) = {0,0,0, 0,0,L, 4.0};
BooleanFragments{ Volume{4}; Delete; }{ Volume{1,2,3}; Delete; }
Physical Volume("inner_conductor", 1) = Volume In BoundingBox{-1.01,-1.01,-0.01, 1.01,1.01,L+0.01};
v2() = Volume In BoundingBox{-2.01,-2.01,-0.01, 2.01,2.01,L+0.01};
v3() = Volume In BoundingBox{-3.51,-3.51,-0.01, 3.51,3.51,L+0.01};
v4() = Volume{:};
v4() -= v3();
v3() -= v2();
v2() -= Volume In BoundingBox{-1.01,-1.01,-0.01, 1.01,1.01,L+0.01};
Physical Volume("dielectric_inner", 2) = {v2()};
Physical Volume("dielectric_outer", 3) = {v3()};
Physical Volume("shield", 4) = {v4()};
Physical Surface("ends", 20) = Surface In BoundingBox{-5,-5,-0.01, 5,5,0.01};
Physical Surface("ends", 20) += Surface In BoundingBox{-5,-5,L-0.01, 5,5,L+0.01};
ends() = Surface In BoundingBox{-5,-5,-0.01, 5,5,0.01};
ends() += Surface In BoundingBox{-5,-5,L-0.01, 5,5,L+0.01};
jk() = CombinedBoundary{ Volume{:}; };
jk() -= ends();
Physical Surface("jacket", 21) = {jk()};
