//! A two-storey house with a gable roof, after the paper's Figure 16.
//!
//! Walls are slabs with window and door openings. A polygon cannot have a
//! hole, so each wall face is cut along one horizontal line per row of
//! openings into bands: every band is a simple polygon, concave where the
//! openings notch it, and neighbouring bands share every vertex on their
//! common line (no T-junctions). Windows have glass panes with crossed bars
//! and sills; the front door has a knob; the roof is made of planks meeting
//! at a ridge; a hollow chimney pierces the roof; steps, a path, a lawn and
//! trees complete it. About 700 polygons in colour, a union of closed parts.

use super::parts::{cuboid, cylinder, extrude, pyramid, Frame, Part};
use super::{Scene, SceneBuilder};
use crate::geom::Rgb;
use glam::{DVec2, DVec3};

const WALL: Rgb = [236, 214, 168];
const REVEAL: Rgb = [214, 190, 146];
const ROOF: Rgb = [178, 52, 40];
const RIDGE: Rgb = [120, 34, 28];
const BRICK: Rgb = [150, 72, 50];
const DOOR: Rgb = [112, 62, 30];
const BRASS: Rgb = [222, 188, 60];
const GLASS: Rgb = [120, 172, 228];
const FRAME: Rgb = [246, 246, 246];
const SILL: Rgb = [228, 228, 222];
const STONE: Rgb = [128, 128, 128];
const STEP: Rgb = [168, 166, 160];
const PATH: Rgb = [192, 180, 158];
const LAWN: Rgb = [84, 160, 64];
const TRUNK: Rgb = [100, 70, 40];
const CROWN: Rgb = [40, 128, 52];

/// House width (x), depth (y), eaves height, ridge rise, wall thickness.
const W: f64 = 8.0;
const D: f64 = 6.0;
const H: f64 = 5.0;
const RISE: f64 = 2.0;
const T: f64 = 0.25;

/// A rectangular opening in wall coordinates (x along, y up); a door starts
/// at y = 0.
#[derive(Clone, Copy)]
struct Opening {
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
}

const fn op(x0: f64, x1: f64, y0: f64, y1: f64) -> Opening {
    Opening { x0, x1, y0, y1 }
}

/// The wall face of length `len` cut into simple pieces: horizontal bands
/// between `cuts` (each opening must cross exactly one cut), the last band
/// closed on top by `top` (points from x = len down to x = 0). A band is
/// split into several pieces where an opening crosses it from bottom to top.
fn wall_pieces(len: f64, top: &[DVec2], openings: &[Opening], cuts: &[f64]) -> Vec<Vec<DVec2>> {
    let mut pieces = Vec::new();
    let p = DVec2::new;
    for band in 0..=cuts.len() {
        let lo = if band == 0 { 0.0 } else { cuts[band - 1] };
        let last = band == cuts.len();
        let hi = if last { f64::NAN } else { cuts[band] };
        // No opening reaches the top of the wall, so none spans the last band.
        let spans = |o: &Opening| !last && o.y0 <= lo && o.y1 >= hi;
        let from_below = |o: &Opening| o.y0 <= lo && o.y1 > lo && !spans(o);
        let from_above = |o: &Opening| !last && o.y0 < hi && o.y1 >= hi && !spans(o);
        // Openings spanning the whole band split it into sub-bands.
        let mut blockers: Vec<&Opening> = openings.iter().filter(|o| spans(o)).collect();
        blockers.sort_by(|a, b| a.x0.total_cmp(&b.x0));
        let mut edges = vec![0.0];
        for b in &blockers {
            edges.push(b.x0);
            edges.push(b.x1);
        }
        edges.push(len);
        for sub in edges.chunks(2) {
            let (xa, xb) = (sub[0], sub[1]);
            let inside = |o: &&Opening| o.x0 > xa && o.x1 < xb;
            let mut below: Vec<&Opening> = openings.iter().filter(|o| from_below(o)).collect();
            below.retain(inside);
            below.sort_by(|a, b| a.x0.total_cmp(&b.x0));
            let mut above: Vec<&Opening> = openings.iter().filter(|o| from_above(o)).collect();
            above.retain(inside);
            above.sort_by(|a, b| b.x0.total_cmp(&a.x0));
            let mut poly = vec![p(xa, lo)];
            for o in below {
                poly.extend([p(o.x0, lo), p(o.x0, o.y1), p(o.x1, o.y1), p(o.x1, lo)]);
            }
            poly.push(p(xb, lo));
            if last {
                poly.extend_from_slice(top);
            } else {
                poly.push(p(xb, hi));
                for o in above {
                    poly.extend([p(o.x1, hi), p(o.x1, o.y0), p(o.x0, o.y0), p(o.x0, hi)]);
                }
                poly.push(p(xa, hi));
            }
            pieces.push(poly);
        }
    }
    pieces
}

/// A wall and its fittings. `frame` maps wall coordinates (x along, y up,
/// z from the outer face inwards) into the model.
fn wall(
    frame: &Frame,
    len: f64,
    top: &[DVec2],
    openings: &[Opening],
    cuts: &[f64],
    door: Option<usize>,
) -> Vec<Part> {
    let slab = extrude(&wall_pieces(len, top, openings, cuts), 0.0, T, WALL, REVEAL);
    let mut parts = vec![slab.placed(frame)];
    let local = |lo: DVec3, hi: DVec3, c: Rgb| cuboid(lo, hi, c).placed(frame);
    for (k, o) in openings.iter().enumerate() {
        if door == Some(k) {
            let door = local(
                DVec3::new(o.x0 + 0.05, 0.02, 0.1),
                DVec3::new(o.x1 - 0.05, o.y1 - 0.05, 0.15),
                DOOR,
            );
            let kx = o.x1 - 0.2;
            let knob = local(
                DVec3::new(kx - 0.05, 1.0, 0.02),
                DVec3::new(kx + 0.05, 1.1, 0.1),
                BRASS,
            );
            parts.extend([door, knob]);
            continue;
        }
        let (xm, ym) = ((o.x0 + o.x1) * 0.5, (o.y0 + o.y1) * 0.5);
        parts.push(local(
            DVec3::new(o.x0 + 0.05, o.y0 + 0.05, 0.1),
            DVec3::new(o.x1 - 0.05, o.y1 - 0.05, 0.14),
            GLASS,
        ));
        // Bars at different depths, so that their faces never coincide.
        parts.push(local(
            DVec3::new(xm - 0.03, o.y0 + 0.02, 0.06),
            DVec3::new(xm + 0.03, o.y1 - 0.02, 0.18),
            FRAME,
        ));
        parts.push(local(
            DVec3::new(o.x0 + 0.02, ym - 0.03, 0.05),
            DVec3::new(o.x1 - 0.02, ym + 0.03, 0.19),
            FRAME,
        ));
        parts.push(local(
            DVec3::new(o.x0 - 0.1, o.y0 - 0.09, -0.15),
            DVec3::new(o.x1 + 0.1, o.y0 - 0.01, 0.0),
            SILL,
        ));
    }
    parts
}

/// The frame of a wall whose outer face has outward normal `out` and whose
/// wall coordinate origin (outer face, ground, start) is at `origin`.
fn wall_frame(origin: DVec3, out: DVec3) -> Frame {
    let w = -out;
    let u = DVec3::Z.cross(w);
    Frame::new(origin, u, DVec3::Z)
}

/// The four walls: front and back span the full width, the gable walls fit
/// between them.
fn walls() -> Vec<Part> {
    let flat = |len: f64| vec![DVec2::new(len, H), DVec2::new(0.0, H)];
    let front_openings = [
        op(3.5, 4.5, 0.0, 2.2),
        op(1.0, 2.2, 0.9, 2.1),
        op(5.8, 7.0, 0.9, 2.1),
        op(1.0, 2.2, 3.0, 4.2),
        op(3.4, 4.6, 3.0, 4.2),
        op(5.8, 7.0, 3.0, 4.2),
    ];
    let mut parts = wall(
        &wall_frame(DVec3::new(W, 0.0, 0.0), -DVec3::Y),
        W,
        &flat(W),
        &front_openings,
        &[1.5, 3.6],
        Some(0),
    );
    let back_openings = [
        op(5.4, 6.3, 0.0, 2.1),
        op(1.2, 2.6, 1.0, 2.0),
        op(3.2, 4.4, 1.0, 2.0),
        op(1.2, 2.6, 3.1, 4.1),
        op(5.2, 6.6, 3.1, 4.1),
    ];
    parts.extend(wall(
        &wall_frame(DVec3::new(0.0, D, 0.0), DVec3::Y),
        W,
        &flat(W),
        &back_openings,
        &[1.5, 3.6],
        Some(0),
    ));
    // Gable walls: the top follows the roof plane through (y = 0, z = H)
    // and the ridge (y = D/2, z = H + RISE).
    let len = D - 2.0 * T;
    let roof_z = |y: f64| H + RISE * (y.min(D - y) / (D * 0.5));
    let gable = vec![
        DVec2::new(len, roof_z(D - T)),
        DVec2::new(len * 0.5, H + RISE),
        DVec2::new(0.0, roof_z(T)),
    ];
    let side_openings = [op(1.0, 2.0, 0.9, 2.1), op(3.3, 4.5, 3.0, 4.2)];
    parts.extend(wall(
        &wall_frame(DVec3::new(0.0, T, 0.0), -DVec3::X),
        len,
        &gable,
        &side_openings,
        &[1.5, 3.6],
        None,
    ));
    let other_side = [op(3.3, 4.5, 0.9, 2.1), op(1.0, 2.0, 3.0, 4.2)];
    parts.extend(wall(
        &wall_frame(DVec3::new(W, D - T, 0.0), DVec3::X),
        len,
        &gable,
        &other_side,
        &[1.5, 3.6],
        None,
    ));
    parts
}

/// Roof planks on both slopes (sunk 0.01 into the walls' tops), the ridge
/// cap and the chimney.
fn roof() -> Vec<Part> {
    let mut parts = Vec::new();
    let planks = 8;
    let thick = 0.1;
    for side in [-1.0, 1.0] {
        // The slopes' planks cross at the ridge: their ends must not lie in
        // one plane there.
        let half_x = W * 0.5 + 0.41 + 0.01 * side;
        // Down-slope direction and outward normal of this slope.
        let down = DVec3::new(0.0, side * (D * 0.5), -RISE).normalize();
        let normal = DVec3::new(0.0, side * RISE, D * 0.5).normalize();
        let ridge = DVec3::new(W * 0.5, D * 0.5, H + RISE) - normal * 0.01;
        let length = (D * 0.5 + 0.4) / down.y.abs();
        let width = length / planks as f64;
        for k in 0..planks {
            let c = ridge + down * (width * (k as f64 + 0.5)) + normal * (thick * 0.5);
            parts.push(super::parts::oriented_box(
                c,
                DVec3::X * half_x,
                down * (width * 0.5),
                normal * (thick * 0.5),
                ROOF,
            ));
        }
    }
    let top = DVec3::new(W * 0.5, D * 0.5, H + RISE + 0.07);
    parts.push(super::parts::oriented_box(
        top,
        DVec3::X * (W * 0.5 + 0.45),
        DVec3::Y * 0.14,
        DVec3::Z * 0.09,
        RIDGE,
    ));
    // A hollow chimney: a square ring cut into four trapezoids.
    let (o, i) = (0.4, 0.25);
    let sq = |r: f64| [(-r, -r), (r, -r), (r, r), (-r, r)].map(|(x, y)| DVec2::new(x, y));
    let (outer, inner) = (sq(o), sq(i));
    let ring: Vec<Vec<DVec2>> = (0..4)
        .map(|k| vec![outer[k], outer[(k + 1) % 4], inner[(k + 1) % 4], inner[k]])
        .collect();
    let frame = Frame::new(DVec3::new(5.9, 4.4, 0.0), DVec3::X, DVec3::Y);
    parts.push(extrude(&ring, H + 0.3, H + RISE + 1.0, BRICK, BRICK).placed(&frame));
    parts
}

/// Ground, foundation, steps, a path and trees.
fn grounds() -> Vec<Part> {
    let v = DVec3::new;
    let mut parts = vec![
        cuboid(v(-4.0, -3.0, -0.5), v(12.0, 9.0, -0.3), LAWN),
        cuboid(v(-0.2, -0.2, -0.3), v(W + 0.2, D + 0.2, 0.0), STONE),
        cuboid(v(3.3, -0.8, -0.3), v(4.7, -0.2, -0.2), STEP),
        cuboid(v(3.3, -0.5, -0.2), v(4.7, -0.2, -0.1), STEP),
    ];
    for k in 0..5 {
        let y = -1.0 - 0.4 * k as f64;
        parts.push(cuboid(v(3.6, y - 0.3, -0.3), v(4.4, y, -0.27), PATH));
    }
    for (x, y, s) in [(-2.0, -1.5, 1.0), (10.0, 2.0, 1.2), (9.5, 7.0, 0.8)] {
        parts.push(cylinder(
            v(x, y, -0.3),
            v(0.0, 0.0, 1.5 * s),
            0.15 * s,
            8,
            TRUNK,
        ));
        parts.push(pyramid(v(x, y, 1.0 * s), 0.8 * s, 10, 2.5 * s, CROWN));
    }
    parts
}

/// The house, about 700 polygons, closed (a union of closed parts).
pub fn house() -> Scene {
    let mut s = SceneBuilder::default();
    s.add_all(walls());
    s.add_all(roof());
    s.add_all(grounds());
    s.finish("house", true)
}
