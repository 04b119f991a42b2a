// Two unit cubes of different materials touching along one edge only: the outer
// boundary is non-manifold along that edge.
SetFactory("OpenCASCADE");
Box(1) = {0,0,0, 1,1,1};
Box(2) = {1,1,0, 1,1,1};
v() = BooleanFragments{ Volume{1,2}; Delete; }{};
Physical Volume(1) = {v(0)};
Physical Volume(2) = {v(1)};
Mesh.CharacteristicLengthMax = 0.25;
