//! Planar polygons, planes and the one tolerance used to classify and split.
//!
//! Contract: every classification of a point against a plane in the builder
//! goes through [`Plane::side_of`] with the model's [`Tolerance`]; splitting
//! uses the very same test, so a vertex within tolerance of a plane is "on" it
//! for both, and a split passes through it without moving it. Planes are
//! computed with Newell's method over all vertices, never from three of them.

use glam::DVec3;

/// Relative tolerance: distances below `REL_EPS × model diagonal` count as 0.
pub const REL_EPS: f64 = 1e-7;

/// The classification tolerance of one model, an absolute distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance(pub f64);

impl Tolerance {
    /// The tolerance for a model whose bounding box has diagonal `diag`.
    pub fn for_diagonal(diag: f64) -> Self {
        let d = if diag.is_finite() && diag > 0.0 {
            diag
        } else {
            1.0
        };
        Tolerance(REL_EPS * d)
    }
}

/// A plane `normal · x + d = 0` with a unit normal; the front side is `> 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// Unit normal.
    pub normal: DVec3,
    /// Offset.
    pub d: f64,
}

/// Where a point lies against a plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PointSide {
    /// Strictly in front (beyond tolerance).
    Front,
    /// Strictly behind (beyond tolerance).
    Back,
    /// Within tolerance of the plane.
    On,
}

/// The one-way relation of a polygon P against the plane of Q.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Relation {
    /// P in front of Q (`P <| Q`).
    Front,
    /// P behind Q (`P >| Q`).
    Back,
    /// P cut by Q's plane.
    Cut,
    /// P lies in Q's plane.
    Coplanar,
}

impl Plane {
    /// Newell's plane through `verts`, or `None` when their area is (near) zero.
    pub fn newell(verts: &[DVec3]) -> Option<Plane> {
        if verts.len() < 3 {
            return None;
        }
        // Centre first: Newell's sums are then free of the cancellation that
        // large absolute coordinates would otherwise cause.
        let c = centroid(verts);
        let mut n = DVec3::ZERO;
        for i in 0..verts.len() {
            let a = verts[i] - c;
            let b = verts[(i + 1) % verts.len()] - c;
            n.x += (a.y - b.y) * (a.z + b.z);
            n.y += (a.z - b.z) * (a.x + b.x);
            n.z += (a.x - b.x) * (a.y + b.y);
        }
        let len = n.length();
        if !(len.is_finite() && len > 0.0) {
            return None;
        }
        let normal = n / len;
        Some(Plane {
            normal,
            d: -normal.dot(c),
        })
    }

    /// Signed distance of `p` (positive in front).
    #[inline]
    pub fn distance(&self, p: DVec3) -> f64 {
        self.normal.dot(p) + self.d
    }

    /// The side of `p`, with tolerance.
    #[inline]
    pub fn side_of(&self, p: DVec3, tol: Tolerance) -> PointSide {
        let s = self.distance(p);
        if s > tol.0 {
            PointSide::Front
        } else if s < -tol.0 {
            PointSide::Back
        } else {
            PointSide::On
        }
    }

    /// The one-way relation of the polygon with vertices `verts` to this plane.
    pub fn relation(&self, verts: &[DVec3], tol: Tolerance) -> Relation {
        let (mut front, mut back) = (false, false);
        for &v in verts {
            match self.side_of(v, tol) {
                PointSide::Front => front = true,
                PointSide::Back => back = true,
                PointSide::On => {}
            }
            if front && back {
                return Relation::Cut;
            }
        }
        match (front, back) {
            (true, false) => Relation::Front,
            (false, true) => Relation::Back,
            _ => Relation::Coplanar,
        }
    }

    /// The same plane facing the other way.
    pub fn flipped(&self) -> Plane {
        Plane {
            normal: -self.normal,
            d: -self.d,
        }
    }

    /// The orthogonal projection of `p` onto the plane.
    pub fn project(&self, p: DVec3) -> DVec3 {
        p - self.normal * self.distance(p)
    }
}

/// A vertex's identity by bit pattern (−0 taken as +0): the key with which
/// vertices at the very same position are one vertex (the serializer's
/// encoding merges exactly such vertices, so seams and merges use it too).
pub(crate) fn vertex_key(v: DVec3) -> [u64; 3] {
    v.to_array().map(|c| (c + 0.0).to_bits())
}

/// Mean of the vertices.
pub fn centroid(verts: &[DVec3]) -> DVec3 {
    let sum: DVec3 = verts.iter().copied().sum();
    sum / verts.len().max(1) as f64
}

/// Area of a planar polygon (Newell's vector area), always ≥ 0.
pub fn area(verts: &[DVec3]) -> f64 {
    if verts.len() < 3 {
        return 0.0;
    }
    let c = centroid(verts);
    let mut n = DVec3::ZERO;
    for i in 0..verts.len() {
        let a = verts[i] - c;
        let b = verts[(i + 1) % verts.len()] - c;
        n += a.cross(b);
    }
    0.5 * n.length()
}

/// An RGB colour for a face.
pub type Rgb = [u8; 3];

/// The neutral grey of faces that have no colour of their own.
pub const DEFAULT_COLOR: Rgb = [200, 200, 200];

/// A planar polygon (convex or concave, simple) with the plane it lies in.
///
/// The plane is computed once, from the source face, and kept by every piece
/// split from it: pieces of one face stay exactly coplanar for the builder.
#[derive(Clone, Debug, PartialEq)]
pub struct Polygon {
    /// Vertices in counter-clockwise order seen from the front side.
    pub verts: Vec<DVec3>,
    /// The plane; its normal points out of the solid.
    pub plane: Plane,
    /// Index of the face in the input file it came from (from 0).
    pub source: u32,
    /// Colour of the face.
    pub color: Rgb,
    /// Vertex normals from the mesh file (OBJ `vn`, PLY `nx ny nz`), one
    /// per vertex of `verts` (unit, on the front side); `None` when the
    /// file gave the face none, and the serializer computes them with the
    /// crease angle (`crate::normals`). Pieces of a split and vertices
    /// the seam repair inserts get theirs from [`Polygon::normals_at`].
    pub normals: Option<Vec<DVec3>>,
}

impl Polygon {
    /// A polygon with its Newell plane, or `None` for a degenerate one.
    pub fn new(verts: Vec<DVec3>, source: u32, color: Rgb) -> Option<Polygon> {
        let plane = Plane::newell(&verts)?;
        Some(Polygon {
            verts,
            plane,
            source,
            color,
            normals: None,
        })
    }

    /// The file normals at points `at` of this polygon (its vertices, or
    /// points on its edges such as a split's crossings), from its own
    /// [`Polygon::normals`]; `None` when it has none.
    ///
    /// A point equal to a vertex (bit for bit) takes that vertex's normal;
    /// any other point takes the normalized linear interpolation of the
    /// normals at the ends of the edge nearest to it, at its projection on
    /// that edge (clamped to the edge): the normal Gouraud shading of the
    /// unsplit polygon would show along that edge. A point moved by the
    /// seam weld (a tolerance away from a vertex) so keeps about that
    /// vertex's normal.
    pub fn normals_at(&self, at: &[DVec3]) -> Option<Vec<DVec3>> {
        let normals = self.normals.as_ref()?;
        let n = self.verts.len().min(normals.len());
        if n == 0 {
            return None;
        }
        let key = |v: DVec3| v.to_array().map(f64::to_bits);
        let exact: std::collections::HashMap<[u64; 3], usize> = self.verts[..n]
            .iter()
            .enumerate()
            .rev()
            .map(|(i, &v)| (key(v), i))
            .collect();
        let along = |q: DVec3| -> DVec3 {
            let mut best = (f64::INFINITY, normals[0]);
            for k in 0..n {
                let (a, b) = (self.verts[k], self.verts[(k + 1) % n]);
                let ab = b - a;
                let len2 = ab.length_squared();
                let t = if len2 > 0.0 {
                    ((q - a).dot(ab) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let d = (a + ab * t).distance_squared(q);
                if d < best.0 {
                    let (na, nb) = (normals[k], normals[(k + 1) % n]);
                    best = (d, (na + (nb - na) * t).try_normalize().unwrap_or(na));
                }
            }
            best.1
        };
        Some(
            at.iter()
                .map(|&q| match exact.get(&key(q)) {
                    Some(&i) => normals[i],
                    None => along(q),
                })
                .collect(),
        )
    }
}

/// Axis-aligned bounds of a set of polygons: `(min, max)`.
pub fn bounds(polys: &[Polygon]) -> (DVec3, DVec3) {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for p in polys {
        for &v in &p.verts {
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn newell_of_ccw_square_points_up() {
        let sq = [
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(1.0, 0.0, 1.0),
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(0.0, 1.0, 1.0),
        ];
        let p = Plane::newell(&sq).unwrap();
        assert!((p.normal - DVec3::Z).length() < 1e-12);
        assert!((p.d + 1.0).abs() < 1e-12);
        assert!((area(&sq) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn collinear_points_have_no_plane() {
        let line = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        assert!(Plane::newell(&line).is_none());
    }

    #[test]
    fn relation_respects_tolerance() {
        let p = Plane {
            normal: DVec3::Z,
            d: 0.0,
        };
        let tol = Tolerance(1e-6);
        let tri = [DVec3::new(0.0, 0.0, 1e-7), DVec3::X, DVec3::Y];
        assert_eq!(p.relation(&tri, tol), Relation::Coplanar);
        let tri = [
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::X,
            DVec3::new(0.0, 1.0, -1e-7),
        ];
        assert_eq!(p.relation(&tri, tol), Relation::Front);
        let tri = [
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::X,
            DVec3::new(0.0, 1.0, -1.0),
        ];
        assert_eq!(p.relation(&tri, tol), Relation::Cut);
    }
}
