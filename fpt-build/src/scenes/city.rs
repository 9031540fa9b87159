//! The benchmark city: a 14 × 14 grid of lots on a ground slab.
//!
//! Each lot holds one of: a box (sometimes turned about the vertical, often
//! with a set-back tower on top), an L-shaped block (concave caps), a
//! polygonal tower, or a box with an annex that interpenetrates it and sinks
//! into the ground slab. Sizes are random but fixed (seeded), and continuous,
//! so that no two faces of different parts coincide. About 1,900 polygons,
//! closed (a union of closed parts).

use super::parts::{cuboid, extrude, ngon, oriented_box, Part, Rng};
use super::{Scene, SceneBuilder};
use crate::geom::Rgb;
use glam::{DVec2, DVec3};

const LOTS: usize = 14;
const PITCH: f64 = 1.4;
const GROUND: Rgb = [90, 92, 96];

/// A building colour: light facades of varied hue.
fn facade(rng: &mut Rng) -> Rgb {
    let base = rng.range(150.0, 230.0);
    let tint = |r: &mut Rng| (base + r.range(-25.0, 25.0)).clamp(0.0, 255.0) as u8;
    [tint(rng), tint(rng), tint(rng)]
}

/// The buildings of the lot whose centre is `c`.
fn lot(c: DVec2, rng: &mut Rng) -> Vec<Part> {
    let color = facade(rng);
    let kind = rng.range(0.0, 1.0);
    let height = rng.range(0.4, 3.0);
    if kind < 0.4 {
        // A box, turned by up to ±0.3 rad, with a set-back tower half the time.
        let turn = if rng.range(0.0, 1.0) < 0.5 {
            rng.range(-0.3, 0.3)
        } else {
            0.0
        };
        let (hx, hy) = (rng.range(0.2, 0.3), rng.range(0.2, 0.3));
        let (cos, sin) = (turn.cos(), turn.sin());
        let (ax, ay) = (DVec3::new(cos, sin, 0.0), DVec3::new(-sin, cos, 0.0));
        let centre = c.extend(height * 0.5);
        let mut parts = vec![oriented_box(
            centre,
            ax * hx,
            ay * hy,
            DVec3::Z * (height * 0.5),
            color,
        )];
        if rng.range(0.0, 1.0) < 0.5 {
            let th = rng.range(0.3, 1.5);
            let (sx, sy) = (rng.range(0.4, 0.8), rng.range(0.4, 0.8));
            let top = c.extend(height + th * 0.5);
            let tower = oriented_box(
                top,
                ax * (hx * sx),
                ay * (hy * sy),
                DVec3::Z * (th * 0.5),
                color,
            );
            parts.push(tower);
        }
        parts
    } else if kind < 0.6 {
        // An L-shaped block: a concave hexagon extruded.
        let (x0, x1) = (c.x - rng.range(0.3, 0.45), c.x + rng.range(0.3, 0.45));
        let (y0, y1) = (c.y - rng.range(0.3, 0.45), c.y + rng.range(0.3, 0.45));
        let xm = rng.range(x0 + 0.15, x1 - 0.15);
        let ym = rng.range(y0 + 0.15, y1 - 0.15);
        let l: Vec<DVec2> = [(x0, y0), (x1, y0), (x1, ym), (xm, ym), (xm, y1), (x0, y1)]
            .iter()
            .map(|&(x, y)| DVec2::new(x, y))
            .collect();
        vec![extrude(&[l], 0.0, height, color, color)]
    } else if kind < 0.75 {
        // A polygonal tower.
        let n = if rng.range(0.0, 1.0) < 0.5 { 6 } else { 8 };
        let r = rng.range(0.25, 0.42);
        let pts = ngon(c, r, n, rng.range(0.0, 1.0));
        vec![extrude(&[pts], 0.0, height * 1.3, color, color)]
    } else {
        // A box and an annex through its side, sunk into the ground slab.
        let lo = DVec3::new(c.x - rng.range(0.15, 0.4), c.y - rng.range(0.15, 0.4), 0.0);
        let hi = DVec3::new(
            c.x + rng.range(0.05, 0.2),
            c.y + rng.range(0.05, 0.2),
            height,
        );
        let annex_lo = DVec3::new(
            rng.range(lo.x + 0.05, hi.x - 0.05),
            rng.range(lo.y + 0.05, hi.y - 0.05),
            -0.05,
        );
        let annex_hi = DVec3::new(
            c.x + rng.range(0.25, 0.45),
            c.y + rng.range(0.25, 0.45),
            height * rng.range(0.3, 0.9),
        );
        let other = facade(rng);
        vec![cuboid(lo, hi, color), cuboid(annex_lo, annex_hi, other)]
    }
}

/// The benchmark city, about 1,900 polygons, closed.
pub fn bench_city() -> Scene {
    let mut rng = Rng(0xC17_5EED);
    let mut s = SceneBuilder::default();
    // Lot centres run from 0.2 to 18.4; buildings reach 0.45 beyond them.
    let far = (LOTS - 1) as f64 * PITCH + 0.8;
    s.add(cuboid(
        DVec3::new(-0.4, -0.4, -0.2),
        DVec3::new(far, far, 0.0),
        GROUND,
    ));
    for i in 0..LOTS {
        for j in 0..LOTS {
            let c = DVec2::new(i as f64 * PITCH + 0.2, j as f64 * PITCH + 0.2);
            s.add_all(lot(c, &mut rng));
        }
    }
    s.finish("bench_city", true)
}
