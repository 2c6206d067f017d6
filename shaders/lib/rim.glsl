// What the rim normals' two passes share (rim_edge_rows.frag, rim_normals.frag; docs/liquid.md, "Rim normals").

// How far from a silhouette, in pixels, a front normal is bent: the outer pixels of a round body, where the
// smoothed depth faces the camera too much (13 degrees in the outer 2 px of the light benchmark's ball, 1 degree
// at 4 to 8 px).
const int kRimReach = 8;
// A row's offset where no uncovered pixel lies within kRimReach.
const float kNoEdge = 1e4;
