// A block of one material (1) with two sheets inside it, for the surface groups that
// lie inside a material: "sheet" (100) is one sheet; "top_and_sheet" (300) is the
// block's top face and the other sheet; "bottom" (200) is the bottom face.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 1};
Rectangle(10) = {0.5, 0.25, 0.5, 1, 0.5};
Rectangle(11) = {0.5, 0.25, 0.25, 1, 0.5};
BooleanFragments{ Volume{1}; Delete; }{ Surface{10, 11}; Delete; }
Physical Volume(1) = {1};
Physical Surface("sheet", 100) = Surface In BoundingBox{0.49, 0.24, 0.49, 1.51, 0.76, 0.51};
Physical Surface("bottom", 200) = Surface In BoundingBox{-0.01, -0.01, -0.01, 2.01, 1.01, 0.01};
Physical Surface("top_and_sheet", 300) = {Surface In BoundingBox{-0.01, -0.01, 0.99, 2.01, 1.01, 1.01},
                                          Surface In BoundingBox{0.49, 0.24, 0.24, 1.51, 0.76, 0.26}};
