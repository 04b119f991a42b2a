// A 2x2x2 checkerboard of unit cubes: material 1 where i+j+k is even, 2 where odd.
// Each material is four cubes that touch each other only along edges and at the
// centre vertex: four regions per material, joined by non-manifold edges and vertices.
SetFactory("OpenCASCADE");
n = 0;
For i In {0:1}
For j In {0:1}
For k In {0:1}
  n += 1;
  Box(n) = {i,j,k, 1,1,1};
EndFor
EndFor
EndFor
v() = BooleanFragments{ Volume{1:8}; Delete; }{};
Physical Volume(1) = {1,4,6,7};
Physical Volume(2) = {2,3,5,8};
Mesh.CharacteristicLengthMax = 0.25;
