// Two unit cubes of one material touching at one vertex only: one material, two
// regions, and a non-manifold boundary vertex.
SetFactory("OpenCASCADE");
Box(1) = {0,0,0, 1,1,1};
Box(2) = {1,1,1, 1,1,1};
v() = BooleanFragments{ Volume{1,2}; Delete; }{};
Physical Volume(1) = {v(0), v(1)};
Mesh.CharacteristicLengthMax = 0.25;
