//! Checks of the scenes' contract: closed parts, outward faces, planar simple
//! polygons, no coinciding faces, sizes.

use super::*;
use crate::geom::bounds;
use glam::DVec2;

fn diag(polys: &[Polygon]) -> f64 {
    let (lo, hi) = bounds(polys);
    (hi - lo).length()
}

/// The polygon in 2D, dropping the axis its normal is largest along.
fn flat(p: &Polygon) -> Vec<DVec2> {
    let n = p.plane.normal.abs();
    let drop = if n.x >= n.y && n.x >= n.z {
        0
    } else if n.y >= n.z {
        1
    } else {
        2
    };
    p.verts
        .iter()
        .map(|v| match drop {
            0 => DVec2::new(v.y, v.z),
            1 => DVec2::new(v.z, v.x),
            _ => DVec2::new(v.x, v.y),
        })
        .collect()
}

fn inside(poly: &[DVec2], q: DVec2) -> bool {
    let mut r = false;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        if (a.y > q.y) != (b.y > q.y) && q.x < a.x + (q.y - a.y) * (b.x - a.x) / (b.y - a.y) {
            r = !r;
        }
    }
    r
}

fn seg_dist(q: DVec2, a: DVec2, b: DVec2) -> f64 {
    let d = b - a;
    let t = ((q - a).dot(d) / d.length_squared()).clamp(0.0, 1.0);
    (q - a - d * t).length()
}

fn outline_dist(poly: &[DVec2], q: DVec2) -> f64 {
    (0..poly.len())
        .map(|i| seg_dist(q, poly[i], poly[(i + 1) % poly.len()]))
        .fold(f64::INFINITY, f64::min)
}

/// Whether segments ab and cd share a point.
fn segments_meet(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    let o = |p: DVec2, q: DVec2, r: DVec2| (q - p).perp_dot(r - p);
    let (d1, d2, d3, d4) = (o(c, d, a), o(c, d, b), o(a, b, c), o(a, b, d));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    let on = |p: DVec2, q: DVec2, r: DVec2| {
        o(p, q, r) == 0.0
            && r.x >= p.x.min(q.x)
            && r.x <= p.x.max(q.x)
            && r.y >= p.y.min(q.y)
            && r.y <= p.y.max(q.y)
    };
    on(c, d, a) || on(c, d, b) || on(a, b, c) || on(a, b, d)
}

/// Why the polygon is not simple, if it is not.
fn simplicity_problem(p: &Polygon) -> Option<String> {
    let f = flat(p);
    let n = f.len();
    for i in 0..n {
        let (a, b, c) = (f[i], f[(i + 1) % n], f[(i + 2) % n]);
        if a == b {
            return Some(format!("repeated vertex {i}"));
        }
        if (b - a).perp_dot(c - b) == 0.0 && (b - a).dot(c - b) < 0.0 {
            return Some(format!("edge {i} folds back"));
        }
        for j in i + 2..n {
            if (j + 1) % n == i {
                continue;
            }
            if segments_meet(a, b, f[j], f[(j + 1) % n]) {
                return Some(format!("edges {i} and {j} meet"));
            }
        }
    }
    None
}

fn is_concave(p: &Polygon) -> bool {
    let f = flat(p);
    let n = f.len();
    let turns: Vec<f64> = (0..n)
        .map(|i| (f[(i + 1) % n] - f[i]).perp_dot(f[(i + 2) % n] - f[(i + 1) % n]))
        .collect();
    turns.iter().any(|&t| t > 0.0) && turns.iter().any(|&t| t < 0.0)
}

/// Samples (on a 24 × 24 grid over the common bounds) strictly inside both
/// coplanar polygons.
fn overlap_samples(a: &Polygon, b: &Polygon, eps: f64) -> usize {
    let (fa, fb) = (flat(a), flat(b));
    let bb = |f: &[DVec2]| {
        f.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(l, h), &p| (l.min(p), h.max(p)),
        )
    };
    let ((la, ha), (lb, hb)) = (bb(&fa), bb(&fb));
    let (lo, hi) = (la.max(lb), ha.min(hb));
    if lo.x >= hi.x || lo.y >= hi.y {
        return 0;
    }
    let mut count = 0;
    for i in 0..24 {
        for j in 0..24 {
            let q = lo + (hi - lo) * DVec2::new((i as f64 + 0.5) / 24.0, (j as f64 + 0.5) / 24.0);
            if inside(&fa, q)
                && inside(&fb, q)
                && outline_dist(&fa, q) > eps
                && outline_dist(&fb, q) > eps
            {
                count += 1;
            }
        }
    }
    count
}

#[test]
fn scenes_have_the_promised_sizes_and_numbering() {
    let scenes = all();
    let count = |name: &str| {
        scenes
            .iter()
            .find(|s| s.name == name)
            .map(|s| s.polygons.len())
    };
    let vise = count("vise").unwrap();
    assert!((280..=360).contains(&vise), "vise {vise}");
    let house = count("house").unwrap();
    assert!((600..=800).contains(&house), "house {house}");
    let city = count("bench_city").unwrap();
    assert!((1500..=2600).contains(&city), "city {city}");
    for s in &scenes {
        println!(
            "{:24} {:5} polygons, {:4} parts, closed {}",
            s.name,
            s.polygons.len(),
            s.parts.len(),
            s.closed
        );
        for (i, p) in s.polygons.iter().enumerate() {
            assert_eq!(p.source as usize, i, "{}", s.name);
        }
        let covered: usize = s.parts.iter().map(|r| r.len()).sum();
        assert_eq!(covered, s.polygons.len(), "{}", s.name);
    }
    assert_eq!(count("house_tiny"), Some(house));
    assert_eq!(count("vise_huge"), Some(vise));
}

#[test]
fn closed_scenes_are_unions_of_closed_outward_parts() {
    for s in all() {
        if !s.closed {
            // The open scene really is open.
            assert!(!closed_defects(&s.polygons, 1).is_empty(), "{}", s.name);
            continue;
        }
        for (k, r) in s.parts.iter().enumerate() {
            let part = &s.polygons[r.clone()];
            let defects = closed_defects(part, 5);
            assert!(defects.is_empty(), "{} part {k}: {defects:#?}", s.name);
            // Outward faces enclose a positive volume.
            let origin = part[0].verts[0];
            let volume: f64 = part
                .iter()
                .map(|p| -crate::geom::area(&p.verts) * p.plane.distance(origin) / 3.0)
                .sum();
            assert!(volume > 0.0, "{} part {k}: volume {volume}", s.name);
        }
    }
}

#[test]
fn polygons_are_planar_and_simple() {
    for s in all() {
        let tol = 1e-12 * diag(&s.polygons).max(1e-300) * 1e3;
        for (i, p) in s.polygons.iter().enumerate() {
            for v in &p.verts {
                let d = p.plane.distance(*v).abs();
                assert!(d <= tol, "{} polygon {i}: vertex off plane by {d}", s.name);
            }
            if let Some(why) = simplicity_problem(p) {
                panic!("{} polygon {i} is not simple: {why}", s.name);
            }
        }
    }
}

#[test]
fn paper_objects_have_concave_faces() {
    let concave = |s: &Scene| s.polygons.iter().filter(|p| is_concave(p)).count();
    assert!(
        concave(&vise()) >= 8,
        "T-slot ends, jaw ends, plates, ear halves"
    );
    assert!(concave(&house()) >= 16, "wall bands with notches");
    assert!(concave(&gear()) == 6);
}

#[test]
fn no_two_faces_coincide() {
    // Coplanar faces that overlap would be z-fights: the same facing for a
    // closed scene (opposite facing faces are culled), any facing for an
    // open one.
    for s in all() {
        let d = diag(&s.polygons);
        let eps = 1e-9 * d;
        let polys = &s.polygons;
        for i in 0..polys.len() {
            for j in i + 1..polys.len() {
                let (a, b) = (&polys[i].plane, &polys[j].plane);
                let dot = a.normal.dot(b.normal);
                let same = dot > 1.0 - 1e-12 && (a.d - b.d).abs() < eps;
                let opposite = dot < -1.0 + 1e-12 && (a.d + b.d).abs() < eps;
                if !(same || (opposite && !s.closed)) {
                    continue;
                }
                let n = overlap_samples(&polys[i], &polys[j], eps);
                assert!(
                    n == 0,
                    "{}: polygons {i} and {j} coincide ({n} samples)",
                    s.name
                );
            }
        }
    }
}

#[test]
fn scenes_are_deterministic_and_scaling_keeps_them_closed() {
    assert_eq!(house().polygons, house().polygons);
    assert_eq!(bench_city().polygons, bench_city().polygons);
    let base = cyclic_boards();
    let s = scaled(&base, 1e3, DVec3::splat(1e5));
    for r in &s.parts {
        assert!(closed_defects(&s.polygons[r.clone()], 1).is_empty());
    }
    let p = base.polygons[3].verts[1] * 1e3 + DVec3::splat(1e5);
    assert_eq!(s.polygons[3].verts[1], p);
    assert!((s.polygons[3].plane.normal - base.polygons[3].plane.normal).length() < 1e-9);
}

#[test]
fn defects_are_found() {
    let mut s = cube_grid();
    s.polygons.truncate(6);
    assert!(closed_defects(&s.polygons, 10).is_empty());
    s.polygons[2].verts.reverse();
    assert!(!closed_defects(&s.polygons, 10).is_empty());
    s.polygons.truncate(5);
    assert_eq!(closed_defects(&cube_grid().polygons[..5], 100).len(), 4);
}
