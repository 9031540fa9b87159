//! Small scenes that each stress one thing a builder or a walk can get wrong.

use super::parts::{cuboid, cylinder, extrude, oriented_box, pyramid, Frame, Part};
use super::{Scene, SceneBuilder};
use crate::geom::Rgb;
use glam::{DQuat, DVec2, DVec3};
use std::f64::consts::TAU;

const PALETTE: [Rgb; 8] = [
    [220, 60, 50],
    [60, 170, 70],
    [60, 100, 220],
    [230, 190, 40],
    [170, 70, 200],
    [40, 190, 190],
    [240, 130, 40],
    [150, 150, 150],
];

/// `n` thin boards in a pinwheel: board k runs along angle 2πk/n, offset
/// sideways by `s`, and rises with `slope` along its length, so that each
/// board lies on the next one where they cross: a cycle of overlaps that no
/// ordering of whole boards can draw; a split is needed.
fn pinwheel(centre: DVec3, n: usize, s: f64, half_len: f64, first_color: usize) -> Vec<Part> {
    let (slope, half_w, half_t) = (0.15, 0.1, 0.025);
    (0..n)
        .map(|k| {
            let th = TAU * k as f64 / n as f64;
            let d = DVec3::new(th.cos(), th.sin(), 0.0);
            let side = DVec3::new(-th.sin(), th.cos(), 0.0);
            let a = (d + DVec3::Z * slope) * half_len;
            let b = side * half_w;
            let e = a.cross(b).normalize() * half_t;
            let color = PALETTE[(first_color + k) % PALETTE.len()];
            oriented_box(centre + side * s, a, b, e, color)
        })
        .collect()
}

/// Three boards in cyclic overlap, and four more in another cycle.
pub fn cyclic_boards() -> Scene {
    let mut s = SceneBuilder::default();
    s.add_all(pinwheel(DVec3::ZERO, 3, 0.5, 1.4, 0));
    s.add_all(pinwheel(DVec3::new(3.5, 0.5, 0.4), 4, 0.5, 1.0, 3));
    s.finish("cyclic_boards", true)
}

/// Boxes through boxes: a three-armed jack of bars with distinct cross
/// sections, three boxes turned at odd angles through it, and a pyramid
/// piercing one of them.
pub fn interpenetrating_boxes() -> Scene {
    let mut s = SceneBuilder::default();
    let (x, y, z) = (DVec3::X, DVec3::Y, DVec3::Z);
    s.add(oriented_box(
        DVec3::ZERO,
        x * 1.5,
        y * 0.25,
        z * 0.3,
        PALETTE[0],
    ));
    s.add(oriented_box(
        DVec3::ZERO,
        x * 0.275,
        y * 1.5,
        z * 0.225,
        PALETTE[1],
    ));
    s.add(oriented_box(
        DVec3::ZERO,
        x * 0.2,
        y * 0.325,
        z * 1.5,
        PALETTE[2],
    ));
    let turned = [
        (
            DVec3::new(0.6, 0.3, 0.2),
            DVec3::new(1.0, 2.0, 0.5),
            0.7,
            DVec3::new(0.5, 0.3, 0.4),
        ),
        (
            DVec3::new(-0.5, -0.4, 0.3),
            DVec3::new(-1.0, 0.5, 1.5),
            1.1,
            DVec3::new(0.6, 0.2, 0.35),
        ),
        (
            DVec3::new(0.1, -0.6, -0.5),
            DVec3::new(0.3, -1.0, 0.2),
            2.0,
            DVec3::new(0.3, 0.7, 0.25),
        ),
    ];
    for (k, (c, axis, angle, half)) in turned.into_iter().enumerate() {
        let q = DQuat::from_axis_angle(axis.normalize(), angle);
        s.add(oriented_box(
            c,
            q * x * half.x,
            q * y * half.y,
            q * z * half.z,
            PALETTE[3 + k],
        ));
    }
    s.add(pyramid(
        DVec3::new(-0.6, 0.5, -0.8),
        0.45,
        3,
        1.6,
        PALETTE[6],
    ));
    s.finish("interpenetrating_boxes", true)
}

/// A gear outline: `teeth` teeth between radii `root` and `tip`, a concave
/// simple polygon of 4 × teeth vertices, counter-clockwise.
fn gear_outline(c: DVec2, teeth: usize, root: f64, tip: f64, phase: f64) -> Vec<DVec2> {
    let pitch = TAU / teeth as f64;
    let (root_half, tip_half) = (pitch * 0.26, pitch * 0.15);
    let at = |r: f64, a: f64| c + DVec2::new(a.cos(), a.sin()) * r;
    (0..teeth)
        .flat_map(|k| {
            let a = phase + pitch * k as f64;
            [
                at(root, a - root_half),
                at(tip, a - tip_half),
                at(tip, a + tip_half),
                at(root, a + root_half),
            ]
        })
        .collect()
}

/// Extruded gears: each cap is one concave planar n-gon (up to 64 vertices).
/// Two gears side by side, a third stacked over the first, with axles.
pub fn gear() -> Scene {
    let mut s = SceneBuilder::default();
    let flat = Frame::new(DVec3::ZERO, DVec3::X, DVec3::Y);
    let g = |c: DVec2, n: usize, root: f64, tip: f64, z0: f64, z1: f64, col: usize| {
        let o = gear_outline(c, n, root, tip, 0.1 * col as f64);
        extrude(&[o], z0, z1, PALETTE[col], PALETTE[(col + 4) % 8]).placed(&flat)
    };
    s.add(g(DVec2::ZERO, 16, 1.0, 1.25, 0.0, 0.5, 0));
    s.add(g(DVec2::new(2.2, 0.0), 10, 0.6, 0.85, 0.0, 0.5, 2));
    s.add(g(DVec2::new(0.8, 0.5), 12, 0.5, 0.7, 0.7, 1.0, 3));
    s.add(cylinder(
        DVec3::new(0.0, 0.0, -0.3),
        DVec3::Z * 1.5,
        0.15,
        12,
        PALETTE[7],
    ));
    s.add(cylinder(
        DVec3::new(2.2, 0.0, -0.3),
        DVec3::Z * 1.1,
        0.12,
        10,
        PALETTE[7],
    ));
    s.add(cylinder(
        DVec3::new(0.8, 0.5, 0.6),
        DVec3::Z * 0.7,
        0.1,
        8,
        PALETTE[7],
    ));
    s.finish("gear", true)
}

/// A 4 × 4 × 4 grid of separate cubes.
pub fn cube_grid() -> Scene {
    let mut s = SceneBuilder::default();
    for i in 0..4 {
        for j in 0..4 {
            for k in 0..4 {
                let lo = DVec3::new(i as f64, j as f64, k as f64);
                let color = [60 + 50 * i as u8, 60 + 50 * j as u8, 60 + 50 * k as u8];
                s.add(cuboid(lo, lo + DVec3::splat(0.6), color));
            }
        }
    }
    s.finish("cube_grid", true)
}

/// A hexahedron over a quadrilateral footprint (counter-clockwise) with
/// planar bottom and top given as height functions linear in (x, y).
fn slab(
    foot: [DVec2; 4],
    bottom: impl Fn(DVec2) -> f64,
    top: impl Fn(DVec2) -> f64,
    c: Rgb,
) -> Part {
    let mut p = Part::default();
    let b: Vec<usize> = foot.iter().map(|&q| p.vert(q.extend(bottom(q)))).collect();
    let t: Vec<usize> = foot.iter().map(|&q| p.vert(q.extend(top(q)))).collect();
    p.face(t.clone(), c);
    p.face(b.iter().rev().copied().collect(), c);
    for i in 0..4 {
        let j = (i + 1) % 4;
        p.face(vec![b[i], b[j], t[j], t[i]], c);
    }
    p
}

/// Six plates 2e-3 thick stacked with gaps of 1e-5 (about 6e-6 of the model
/// size), each turned and shifted a little; their tops and some bottoms are
/// tilted by about 1.5e-6 rad, which leaves at least 4e-6 between plates.
pub fn near_coplanar_stack() -> Scene {
    let mut s = SceneBuilder::default();
    let (thick, gap) = (2e-3, 1e-5);
    for (k, &color) in PALETTE.iter().enumerate().take(6) {
        let kf = k as f64;
        let turn = 0.03 * kf;
        let shift = DVec2::new(0.04 * kf, 0.025 * kf);
        let foot: [DVec2; 4] = [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]
            .map(|(x, y)| DVec2::from_angle(turn).rotate(DVec2::new(x, y)) + shift);
        let base = kf * (thick + gap);
        let (ta, tb) = (
            1.5e-6 * (kf - 2.5).signum(),
            -1.2e-6 * (kf % 2.0 - 0.5).signum(),
        );
        let bottom_tilt = if k % 3 == 1 { 1.1e-6 } else { 0.0 };
        let bottom = move |q: DVec2| base + bottom_tilt * (q.x - q.y) * 0.5;
        let top = move |q: DVec2| base + thick + ta * q.x + tb * q.y;
        s.add(slab(foot, bottom, top, color));
    }
    s.finish("near_coplanar_stack", true)
}

/// Very thin, long parts (aspect about 1e4): crossed blades 1e-4 thick,
/// needles 1e-4 square, flat wedges whose top meets the base at 1e-4 rad
/// and standing prisms over sliver triangles, all on a base block.
pub fn slivers() -> Scene {
    let mut s = SceneBuilder::default();
    let thin = 1e-4;
    s.add(cuboid(
        DVec3::new(-0.6, -0.6, -0.1),
        DVec3::new(0.6, 0.6, 0.0),
        PALETTE[7],
    ));
    for k in 0..4 {
        let a = TAU / 8.0 * k as f64 + 0.05;
        let d = DVec3::new(a.cos(), a.sin(), 0.0);
        let side = DVec3::new(-a.sin(), a.cos(), 0.0);
        let kf = k as f64;
        let c = DVec3::new(0.0, 0.0, 0.2 + 0.005 * kf);
        s.add(oriented_box(
            c,
            d * 0.5,
            DVec3::Z * (0.15 + 0.01 * kf),
            side * (thin * 0.5),
            PALETTE[k],
        ));
        let needle_c = DVec3::new(0.1 * kf - 0.15, -0.1, 0.03 + 0.07 * kf);
        let nd = DVec3::new((a + 1.0).cos(), (a + 1.0).sin(), 0.1);
        let nside = nd.cross(DVec3::Z).normalize();
        let nup = nside.cross(nd).normalize();
        s.add(oriented_box(
            needle_c,
            nd * 0.5,
            nside * (thin * 0.5),
            nup * (thin * 0.5),
            PALETTE[k + 4],
        ));
    }
    for k in 0..3 {
        let kf = k as f64;
        // A flat wedge lying on the base: triangle in (x, z), extruded along y.
        let tri = vec![
            DVec2::new(-0.5, 0.0),
            DVec2::new(0.5, 0.0),
            DVec2::new(0.1 * kf, thin),
        ];
        let frame = Frame::new(DVec3::new(0.0, -0.5 + 0.3 * kf, 0.0), DVec3::X, DVec3::Z);
        s.add(extrude(&[tri], 0.0, 0.15, PALETTE[k + 1], PALETTE[k + 1]).placed(&frame));
        // A standing prism over a sliver triangle in (x, y).
        let tri = vec![
            DVec2::new(-0.55, 0.45 - 0.1 * kf),
            DVec2::new(0.45, 0.5 - 0.1 * kf),
            DVec2::new(-0.05, 0.475 - 0.1 * kf + thin),
        ];
        s.add(extrude(
            &[tri],
            0.0,
            0.3 + 0.05 * kf,
            PALETTE[k + 4],
            PALETTE[k + 4],
        ));
    }
    s.finish("slivers", true)
}

/// An open scene: a wavy sheet of 12 × 12 planar quads (z = f(x) + g(y)
/// makes every grid quad planar), an open box through it, two lone quads
/// standing through it and a floating triangle. Single-sided faces, seen
/// from both sides.
pub fn open_sheet() -> Scene {
    let mut s = SceneBuilder::default();
    let n = 12;
    let mut sheet = Part::default();
    let coord = |i: usize| -2.0 + 4.0 * i as f64 / n as f64;
    let mut grid = vec![vec![0usize; n + 1]; n + 1];
    for (i, row) in grid.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            let (x, y) = (coord(i), coord(j));
            let z = 0.25 * (1.3 * x).sin() + 0.2 * (1.7 * y).cos();
            *v = sheet.vert(DVec3::new(x, y, z));
        }
    }
    for i in 0..n {
        for j in 0..n {
            let color = [(40 + 16 * i) as u8, (60 + 14 * j) as u8, 180];
            let f = vec![
                grid[i][j],
                grid[i + 1][j],
                grid[i + 1][j + 1],
                grid[i][j + 1],
            ];
            sheet.face(f, color);
        }
    }
    s.add(sheet);
    let mut open_box = cuboid(
        DVec3::new(-0.5, -0.5, -0.6),
        DVec3::new(0.5, 0.4, 0.45),
        PALETTE[0],
    );
    open_box.faces.remove(0); // the lid (the first cap) is left off
    s.add(open_box);
    let mut lone = Part::default();
    let q = [
        (1.2, -1.0, -0.5),
        (1.2, 1.0, -0.5),
        (1.2, 1.0, 0.7),
        (1.2, -1.0, 0.7),
    ];
    let ids = q.map(|(x, y, z)| lone.vert(DVec3::new(x, y, z)));
    lone.face(ids.to_vec(), PALETTE[3]);
    let q = [
        (-1.5, -1.2, -0.4),
        (-0.6, -1.6, -0.4),
        (-0.7, -1.7, 0.8),
        (-1.6, -1.3, 0.8),
    ];
    let ids = q.map(|(x, y, z)| lone.vert(DVec3::new(x, y, z)));
    lone.face(ids.to_vec(), PALETTE[4]);
    let t = [(0.3, 0.9, 0.9), (1.1, 1.4, 1.0), (0.4, 1.6, 0.7)];
    let ids = t.map(|(x, y, z)| lone.vert(DVec3::new(x, y, z)));
    lone.face(ids.to_vec(), PALETTE[5]);
    s.add(lone);
    s.finish("open_sheet", false)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pinwheel_boards_overlap_cyclically() {
        // Board k+1 must be above board k where their centre lines cross.
        for (n, s, half) in [(3, 0.5, 1.4), (4, 0.5, 1.0)] {
            let parts = pinwheel(DVec3::ZERO, n, s, half, 0);
            assert_eq!(parts.len(), n);
            for k in 0..n {
                let line = |k: usize| {
                    let th = TAU * k as f64 / n as f64;
                    let d = DVec2::new(th.cos(), th.sin());
                    (DVec2::new(-th.sin(), th.cos()) * s, d)
                };
                let ((p0, d0), (p1, d1)) = (line(k), line((k + 1) % n));
                // Solve p0 + t d0 = p1 + u d1.
                let det = d0.perp_dot(d1);
                let t = (p1 - p0).perp_dot(d1) / det;
                let u = (p1 - p0).perp_dot(d0) / det;
                assert!(t.abs() < half && u.abs() < half);
                assert!(
                    u - t > 0.5,
                    "board {} not above board {k}: t {t} u {u}",
                    k + 1
                );
            }
        }
    }

    #[test]
    fn gear_caps_are_single_concave_polygons() {
        let scene = gear();
        let caps: Vec<_> = scene
            .polygons
            .iter()
            .filter(|p| p.verts.len() == 64)
            .collect();
        assert_eq!(caps.len(), 2);
        for c in caps {
            assert!(c.plane.normal.z.abs() > 0.999_999);
        }
    }
}
