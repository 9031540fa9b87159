//! A faceted torus of any size: the scaling benchmark of the builders.
//!
//! Every facet is an isosceles trapezoid (symmetric about the meridian half
//! way between its two meridians), hence exactly planar; the inner half of
//! the surface is saddle-shaped, so facets hide each other in cycles and the
//! builders must split. Its size is `major × minor` quads.

use super::parts::Part;
use super::{Scene, SceneBuilder};
use glam::DVec3;

/// A closed torus of `major × minor` planar quads (radii 3 and 1).
pub fn torus(major: usize, minor: usize) -> Scene {
    let (major, minor) = (major.max(3), minor.max(3));
    let (big, small) = (3.0, 1.0);
    let mut part = Part::default();
    let tau = std::f64::consts::TAU;
    for i in 0..major {
        let u = tau * i as f64 / major as f64;
        for j in 0..minor {
            let v = tau * j as f64 / minor as f64;
            let r = big + small * v.cos();
            part.vert(DVec3::new(r * u.cos(), r * u.sin(), small * v.sin()));
        }
    }
    let at = |i: usize, j: usize| (i % major) * minor + (j % minor);
    for i in 0..major {
        for j in 0..minor {
            // Shade bands so that pictures show the facets.
            let g = 150 + 60 * ((i + j) % 2) as u8;
            part.face(
                vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)],
                [g, g, 230],
            );
        }
    }
    let mut b = SceneBuilder::default();
    b.add(part);
    b.finish(&format!("torus_{}", major * minor), true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Tolerance;

    #[test]
    fn torus_is_closed_planar_and_outward() {
        let t = torus(24, 12);
        assert_eq!(t.polygons.len(), 288);
        assert!(super::super::closed_defects(&t.polygons, 5).is_empty());
        let tol = Tolerance(1e-12);
        for p in &t.polygons {
            assert!(p
                .verts
                .iter()
                .all(|&v| p.plane.side_of(v, tol) == crate::geom::PointSide::On));
            // Outward: the normal points away from the tube's centre line.
            let c = crate::geom::centroid(&p.verts);
            let axis = DVec3::new(c.x, c.y, 0.0).normalize() * 3.0;
            assert!(p.plane.normal.dot(c - axis) > 0.0);
        }
    }
}
