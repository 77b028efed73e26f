6 8 3
# A non-manifold "book": three pages (faces) share the spine 0-1; vertex 5 hangs
# off page 2 by a free edge (2-5) that belongs to no face. Records may come in any
# order: a face and an edge appear before some of the vertices they use.
v 0 0 0 0.1
v 0 0 1 0.2
v 1 0 0 0.3
f 0 1 2
e 0 1
e 0 2
v 0 1 0 0.4
v -1 0 0 0.5
v 2 0 0 0.6
e 1 2
f 0 1 3
f 0 1 4
e 0 3
e 1 3
e 0 4
e 1 4
e 2 5
