//! The base of a machinist's vise, after the paper's Figure 15.
//!
//! A long base block with a T-slot along its top (concave end faces), a fixed
//! jaw and a sliding jaw with a tongue in the slot, serrated jaw plates, a
//! screw running through both jaws with a T-handle, and four mounting ears
//! with round bolt holes (each ear cap is two concave halves, since a
//! polygon cannot have a hole), hex nuts and bolts. About 320 polygons in
//! greys, a union of closed parts: parts touch with opposite faces or
//! interpenetrate (the screw and bolts), never share a face.

use super::parts::{cylinder, extrude, ngon, Frame, Part};
use super::{Scene, SceneBuilder};
use crate::geom::Rgb;
use glam::{DVec2, DVec3};

const CAST: Rgb = [150, 152, 156];
const MACHINED: Rgb = [196, 198, 202];
const STEEL: Rgb = [110, 112, 118];
const DARK: Rgb = [70, 72, 78];

/// Base length along x.
const L: f64 = 10.0;

fn pts(p: &[(f64, f64)]) -> Vec<DVec2> {
    p.iter().map(|&(x, y)| DVec2::new(x, y)).collect()
}

/// The base block: a T-slot profile in the (y, z) plane, extruded along x.
fn base() -> Part {
    let profile = pts(&[
        (-2.0, 0.0),
        (2.0, 0.0),
        (2.0, 1.5),
        (0.4, 1.5),
        (0.4, 1.1),
        (0.8, 1.1),
        (0.8, 0.6),
        (-0.8, 0.6),
        (-0.8, 1.1),
        (-0.4, 1.1),
        (-0.4, 1.5),
        (-2.0, 1.5),
    ]);
    let frame = Frame::new(DVec3::ZERO, DVec3::Y, DVec3::Z); // w = +x
    extrude(&[profile], 0.0, L, CAST, MACHINED).placed(&frame)
}

/// A jaw plate with a serrated face: profile in the (x, z) plane, teeth
/// pointing to `-dir` (dir = ±1), extruded along y over ±1.6.
fn jaw_plate(x_back: f64, dir: f64) -> Part {
    let (z0, z1, teeth) = (2.0, 3.8, 6);
    let depth = 0.2;
    let mut p = vec![(x_back, z0)];
    let step = (z1 - z0) / teeth as f64;
    for k in 0..teeth {
        let z = z0 + step * k as f64;
        p.push((x_back - dir * depth, z));
        p.push((x_back - dir * (depth + 0.08), z + step * 0.5));
    }
    p.push((x_back - dir * depth, z1));
    p.push((x_back, z1));
    let frame = Frame::new(DVec3::new(0.0, 1.6, 0.0), DVec3::X, DVec3::Z); // w = -y
    extrude(&[pts(&p)], 0.0, 3.2, STEEL, STEEL).placed(&frame)
}

/// The fixed jaw: a block with a slanted back on the base's far end.
fn fixed_jaw() -> Part {
    let profile = pts(&[(8.0, 1.5), (10.0, 1.5), (10.0, 3.0), (9.2, 4.0), (8.0, 4.0)]);
    let frame = Frame::new(DVec3::new(0.0, 1.8, 0.0), DVec3::X, DVec3::Z);
    extrude(&[profile], 0.0, 3.6, CAST, CAST).placed(&frame)
}

/// The sliding jaw: body on the base plus a T-tongue hanging in the slot
/// with clearance; profile in (y, z), extruded along x over [4, 6].
fn moving_jaw() -> Part {
    let profile = pts(&[
        (-0.75, 0.65),
        (0.75, 0.65),
        (0.75, 1.05),
        (0.35, 1.05),
        (0.35, 1.5),
        (1.8, 1.5),
        (1.8, 3.8),
        (-1.8, 3.8),
        (-1.8, 1.5),
        (-0.35, 1.5),
        (-0.35, 1.05),
        (-0.75, 1.05),
    ]);
    let frame = Frame::new(DVec3::new(4.0, 0.0, 0.0), DVec3::Y, DVec3::Z);
    extrude(&[profile], 0.0, 2.0, CAST, MACHINED).placed(&frame)
}

/// A mounting ear with a bolt hole, in local coordinates: attached along
/// x = 0, reaching out to x = a + b with a round end, hole of radius `r` at
/// (a, 0). The cap is cut along y = 0 into two concave halves that share
/// the cut's vertices exactly.
fn ear_pieces(a: f64, b: f64, r: f64) -> Vec<Vec<DVec2>> {
    let hole = 16;
    let arc = 4;
    let at = |c: DVec2, rad: f64, deg: f64| {
        let t = deg.to_radians();
        c + DVec2::new(t.cos(), t.sin()) * rad
    };
    let c = DVec2::new(a, 0.0);
    let half = |sign: f64| {
        // Upper half (sign = 1) counter-clockwise: along the cut, over the
        // hole (clockwise around it), along the cut, round the outer arc,
        // back along the top edge. The lower half mirrors it.
        let mut p = vec![DVec2::new(0.0, 0.0), DVec2::new(a - r, 0.0)];
        for k in 1..hole / 2 {
            let deg = 180.0 - 360.0 / hole as f64 * k as f64;
            p.push(at(c, r, sign * deg));
        }
        p.push(DVec2::new(a + r, 0.0));
        p.push(DVec2::new(a + b, 0.0));
        for k in 1..=arc {
            p.push(at(c, b, sign * 90.0 / arc as f64 * k as f64));
        }
        p.push(DVec2::new(0.0, sign * b));
        if sign < 0.0 {
            p.reverse();
        }
        // Make exact copies of the mirrored cut vertices (y = ±0 → 0).
        p.iter().map(|q| DVec2::new(q.x, q.y + 0.0)).collect()
    };
    vec![half(1.0), half(-1.0)]
}

/// One ear with its nut and bolt, at `x` on the side `side = ±1` (y).
fn ear(x: f64, side: f64) -> Vec<Part> {
    let (a, b, r) = (1.0, 0.6, 0.35);
    let (u, v) = (DVec3::Y * side, DVec3::X * -side); // w = +z
    let frame = Frame::new(DVec3::new(x, 2.0 * side, 0.0), u, v);
    let plate = extrude(&ear_pieces(a, b, r), 0.0, 0.4, CAST, MACHINED).placed(&frame);
    let centre = frame.apply(DVec3::new(a, 0.0, 0.0));
    let hex = ngon(DVec2::ZERO, 0.5, 6, 0.3);
    let nut_frame = Frame::new(centre, DVec3::X, DVec3::Y);
    let nut = extrude(&[hex], 0.4, 0.7, STEEL, STEEL).placed(&nut_frame);
    let bolt = cylinder(centre - DVec3::Z * 0.3, DVec3::Z * 1.3, 0.3, 8, DARK);
    vec![plate, nut, bolt]
}

/// The vise base, about 320 polygons, closed (a union of closed parts).
pub fn vise() -> Scene {
    let mut s = SceneBuilder::default();
    s.add(base());
    s.add(fixed_jaw());
    s.add(jaw_plate(8.0, 1.0));
    s.add(moving_jaw());
    s.add(jaw_plate(6.0, -1.0));
    // The screw runs from inside the sliding jaw out through the fixed jaw.
    let axis = DVec3::new(5.0, 0.0, 2.6);
    s.add(cylinder(axis, DVec3::X * 6.5, 0.3, 16, DARK));
    // T-handle through the screw's end, with round knobs.
    let bar = DVec3::new(11.2, -2.5, 2.6);
    s.add(cylinder(bar, DVec3::Y * 5.0, 0.15, 12, STEEL));
    for y in [-2.5, 2.5] {
        let knob = DVec3::new(11.2, y - 0.2, 2.6);
        s.add(cylinder(knob, DVec3::Y * 0.4, 0.3, 8, DARK));
    }
    for x in [2.0, 8.0] {
        for side in [1.0, -1.0] {
            s.add_all(ear(x, side));
        }
    }
    s.finish("vise", true)
}
