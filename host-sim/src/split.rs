//! Splitting a planar polygon, convex or concave, by a plane.
