//! A toy robot in six materials, the demo's coloured model: written out as
//! an OBJ file with a material (`.mtl`) file by [`crate::mesh::write_obj_mtl`]
//! and read back through the mesh import, so its colours come from the
//! files' `usemtl` and `Kd` as a user's model's would.
//!
//! z is up; the robot stands on z = 0, about 3 × 2 × 6 units. Parts
//! interpenetrate (legs into the feet and the body, the head onto the neck)
//! but no two faces of the same orientation overlap in one plane.

use super::parts::{cuboid, cylinder, pyramid};
use super::{Scene, SceneBuilder};
use crate::geom::Rgb;
use glam::DVec3;

const RED: Rgb = [200, 40, 35];
const BLUE: Rgb = [40, 90, 190];
const STEEL: Rgb = [165, 170, 180];
const DARK: Rgb = [60, 62, 70];
const YELLOW: Rgb = [240, 190, 30];
const CYAN: Rgb = [60, 210, 230];

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

/// The toy robot (closed parts, six colours).
pub fn robot() -> Scene {
    let mut s = SceneBuilder::default();
    for side in [-1.0, 1.0] {
        let x = 0.55 * side;
        // Foot, leg (into the foot and the body), arm and hand.
        s.add(cuboid(v(x - 0.45, -0.7, 0.0), v(x + 0.45, 0.6, 0.4), DARK));
        s.add(cuboid(v(x - 0.3, -0.25, 0.3), v(x + 0.3, 0.25, 2.3), BLUE));
        let ax = 1.42 * side;
        s.add(cuboid(
            v(ax - 0.25, -0.3, 2.2),
            v(ax + 0.25, 0.3, 4.1),
            BLUE,
        ));
        s.add(cuboid(
            v(ax - 0.3, -0.35, 1.75),
            v(ax + 0.3, 0.35, 2.3),
            STEEL,
        ));
        // Eye, sticking out of the head's front.
        s.add(cuboid(
            v(0.3 * side - 0.15, -0.72, 5.05),
            v(0.3 * side + 0.15, -0.55, 5.3),
            CYAN,
        ));
    }
    // Body, with a panel standing out of its front, on the legs.
    s.add(cuboid(v(-1.2, -0.55, 2.1), v(1.2, 0.55, 4.3), RED));
    s.add(cuboid(v(-0.6, -0.7, 2.7), v(0.6, -0.45, 3.7), YELLOW));
    // Neck, head, antenna with a pointed tip.
    s.add(cylinder(v(0.0, 0.0, 4.2), DVec3::Z * 0.5, 0.3, 12, STEEL));
    s.add(cuboid(v(-0.75, -0.6, 4.6), v(0.75, 0.6, 5.7), STEEL));
    s.add(cylinder(v(0.0, 0.0, 5.6), DVec3::Z * 0.6, 0.06, 6, DARK));
    s.add(pyramid(v(0.0, 0.0, 6.1), 0.18, 8, 0.35, RED));
    s.finish("robot", true)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn robot_parts_are_closed_and_use_six_colours() {
        let r = robot();
        assert!(r.closed);
        let defects = super::super::closed_defects(&r.polygons, 5);
        assert!(defects.is_empty(), "{defects:?}");
        let mut colours: Vec<Rgb> = r.polygons.iter().map(|p| p.color).collect();
        colours.sort_unstable();
        colours.dedup();
        assert_eq!(colours.len(), 6);
    }
}
