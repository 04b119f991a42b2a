// The coax of coax.geo with a further physical volume holding both conductors: the
// inner conductor and the shield are each in two physical groups.
Include "coax.geo";
Physical Volume("conductors", 100) = {Physical Volume{1}, Physical Volume{4}};
