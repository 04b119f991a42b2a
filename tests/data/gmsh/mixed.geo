// A tet block and a prism layer on top (extruded, recombined): a mixed-element mesh.
Point(1)={0,0,0,0.5}; Point(2)={1,0,0,0.5}; Point(3)={1,1,0,0.5}; Point(4)={0,1,0,0.5};
Line(1)={1,2}; Line(2)={2,3}; Line(3)={3,4}; Line(4)={4,1};
Curve Loop(1)={1,2,3,4}; Plane Surface(1)={1};
e1[] = Extrude{0,0,1}{ Surface{1}; };                            // tets
e2[] = Extrude{0,0,0.2}{ Surface{e1[0]}; Layers{2}; Recombine; }; // prisms
Physical Volume("bulk",1) = {e1[1]};
Physical Volume("layer",2) = {e2[1]};
