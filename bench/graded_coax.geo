// A graded three-material mesh for benchmarks (not bundled: Gmsh makes it in about a
// minute). A 40-wide box of air around an iron cylinder (radius 8, length 30) holding
// a copper sphere (radius 4); the element size grows from h0 at the centre as
// h0 + k r^2. The defaults give 1.92M tets; h0 0.04, k 0.002 give 15.1M (ten minutes).
//   gmsh -3 bench/graded_coax.geo -o graded.msh [-setnumber h0 0.04 -setnumber k 0.002]
SetFactory("OpenCASCADE");
DefineConstant[ h0 = 0.08, k = 0.004 ];
Box(1) = {-20,-20,-20, 40,40,40};
Cylinder(2) = {0,0,-15, 0,0,30, 8};
Sphere(3) = {0,0,0, 4};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2,3}; Delete; }
Physical Volume("air") = {4};
Physical Volume("iron") = {5};
Physical Volume("copper") = {3};
Field[1] = MathEval;
Field[1].F = Sprintf("%g + %g*(x*x+y*y+z*z)", h0, k);
Background Field = 1;
Mesh.CharacteristicLengthExtendFromBoundary = 0;
Mesh.CharacteristicLengthFromPoints = 0;
