//! Cross-stage tests of the scan conversion on plain screen polygons:
//! exact coverage, shared edges (no crack, no overdraw), concave polygons
//! against a point-in-polygon reference, fill rules, bounds and bands.

extern crate std;

use std::vec;
use std::vec::Vec;

use super::band::Band;
use super::edge::Edge;
use super::scan::{fill_polygon, FillRule, Paint, SpanBounds, SpanSink};
use super::transform::ScreenPt;

/// Deterministic PRNG for the randomized tests (SplitMix64).
pub(crate) struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in `lo..=hi`.
    pub fn range(&mut self, lo: i32, hi: i32) -> i32 {
        lo + (self.next() % ((hi - lo) as u64 + 1)) as i32
    }
    /// Uniform in `[lo, hi)`.
    pub fn float(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * ((self.next() >> 40) as f32 / (1u64 << 24) as f32)
    }
}

/// Counts writes per pixel and remembers the last id.
pub(crate) struct CountSink {
    pub w: i32,
    pub h: i32,
    pub y0: i32,
    pub count: Vec<u32>,
    pub id: Vec<u32>,
}

impl CountSink {
    pub fn new(w: i32, h: i32) -> Self {
        CountSink {
            w,
            h,
            y0: 0,
            count: vec![0; (w * h) as usize],
            id: vec![0; (w * h) as usize],
        }
    }
    pub fn at(&self, x: i32, y: i32) -> u32 {
        self.count[(y * self.w + x) as usize]
    }
}

impl SpanSink for CountSink {
    type Color = u32;
    fn color(&self, p: &Paint) -> u32 {
        p.id + 1
    }
    fn bounds(&self) -> SpanBounds {
        SpanBounds {
            x0: 0,
            y0: self.y0,
            x1: self.w,
            y1: self.y0 + self.h,
        }
    }
    fn span(&mut self, y: i32, x0: i32, x1: i32, c: u32) {
        let b = self.bounds();
        assert!(
            y >= b.y0 && y < b.y1 && b.x0 <= x0 && x0 < x1 && x1 <= b.x1,
            "span {y} {x0}..{x1}"
        );
        for x in x0..x1 {
            let k = ((y - self.y0) * self.w + x) as usize;
            self.count[k] += 1;
            self.id[k] = c;
        }
    }
}

/// Fills `pts` with enough scratch; panics on scratch errors (a bug here).
pub(crate) fn fill<K: SpanSink>(
    pts: &[ScreenPt],
    sub: u32,
    rule: FillRule,
    sink: &mut K,
    id: u32,
) -> usize {
    let mut edges = vec![Edge::default(); pts.len()];
    let mut active = vec![0u16; pts.len()];
    let all = SpanBounds {
        x0: i32::MIN,
        y0: i32::MIN,
        x1: i32::MAX,
        y1: i32::MAX,
    };
    let c = sink.color(&Paint {
        rgb: Default::default(),
        id,
    });
    fill_polygon(pts, sub, rule, &all, &mut edges, &mut active, c, sink)
        .unwrap_or_else(|e| panic!("fill failed: {e:?}"))
}

fn pt(x: i32, y: i32) -> ScreenPt {
    ScreenPt { x, y }
}

/// Point-in-polygon reference at the centre of pixel `(i, j)`, computed
/// exactly in doubled sub-pixel units. `None` when the centre lies exactly
/// on an edge (ownership there is the fill's top-left rule, not the
/// reference's business). Even-odd crossing count.
fn reference_inside(pts: &[ScreenPt], sub: u32, i: i32, j: i32) -> Option<bool> {
    let s = 1i128 << sub;
    let (px, py) = ((2 * i as i128 + 1) * s, (2 * j as i128 + 1) * s);
    let mut inside = false;
    for k in 0..pts.len() {
        let a = pts[k];
        let b = pts[(k + 1) % pts.len()];
        let (ax, ay, bx, by) = (
            2 * a.x as i128,
            2 * a.y as i128,
            2 * b.x as i128,
            2 * b.y as i128,
        );
        let cross = (bx - ax) * (py - ay) - (by - ay) * (px - ax);
        let within = px >= ax.min(bx) && px <= ax.max(bx) && py >= ay.min(by) && py <= ay.max(by);
        if cross == 0 && within {
            return None;
        }
        if (ay > py) != (by > py) {
            // x of the edge at py compared with px, sign-corrected for dy.
            let lhs = (px - ax) * (by - ay);
            let rhs = (py - ay) * (bx - ax);
            if (by > ay && lhs < rhs) || (by < ay && lhs > rhs) {
                inside = !inside;
            }
        }
    }
    Some(inside)
}

fn scaled(pts: &[(i32, i32)], sub: u32) -> Vec<ScreenPt> {
    pts.iter().map(|&(x, y)| pt(x << sub, y << sub)).collect()
}

#[test]
fn square_covers_exactly_the_expected_pixels() {
    for sub in [0u32, 2, 4, 8] {
        // Integer corners: pixels [2, 7) × [3, 9).
        let sq = scaled(&[(2, 3), (7, 3), (7, 9), (2, 9)], sub);
        // Half-pixel corners (2.5, 3.5)–(7.5, 9.5): centres on the left and
        // top edges are in, right and bottom out — the same pixel set.
        let h = if sub > 0 { 1 << (sub - 1) } else { 0 };
        let half: Vec<_> = sq.iter().map(|p| pt(p.x + h, p.y + h)).collect();
        for (poly, reversed) in [(&sq, false), (&half, false), (&sq, true)] {
            if sub == 0 && core::ptr::eq(poly, &half) {
                continue;
            }
            let mut poly = poly.clone();
            if reversed {
                poly.reverse();
            }
            let mut s = CountSink::new(12, 12);
            let spans = fill(&poly, sub, FillRule::NonZero, &mut s, 0);
            assert_eq!(spans, 6);
            for y in 0..12 {
                for x in 0..12 {
                    let want = (2..7).contains(&x) && (3..9).contains(&y);
                    assert_eq!(s.at(x, y), want as u32, "sub {sub} ({x},{y})");
                }
            }
        }
    }
}

/// A random simple quadrilateral a-b-c-d split along a-c into two
/// triangles on opposite sides of the diagonal.
fn random_split_quad(rng: &mut Rng, sub: u32, span: i32) -> Option<[ScreenPt; 4]> {
    let mut r = || {
        pt(
            rng.range(-4 << sub, span << sub),
            rng.range(-4 << sub, span << sub),
        )
    };
    let (a, b, c, d) = (r(), r(), r(), r());
    let side = |p: ScreenPt| {
        (c.x - a.x) as i64 * (p.y - a.y) as i64 - (c.y - a.y) as i64 * (p.x - a.x) as i64
    };
    (side(b).signum() * side(d).signum() < 0).then_some([a, b, c, d])
}

#[test]
fn triangles_sharing_an_edge_cover_their_union_exactly_once() {
    let mut rng = Rng(7);
    let mut tested = 0;
    for sub in [0u32, 2, 4, 6, 8] {
        for round in 0..800 {
            let Some([a, b, c, d]) = random_split_quad(&mut rng, sub, 40) else {
                continue;
            };
            tested += 1;
            // Vary traversal direction of each triangle independently.
            let mut t1 = vec![a, b, c];
            let mut t2 = vec![a, c, d];
            if round % 2 == 0 {
                t1.reverse();
            }
            if round % 3 == 0 {
                t2.reverse();
            }
            let rule = if round % 5 == 0 {
                FillRule::EvenOdd
            } else {
                FillRule::NonZero
            };
            let mut both = CountSink::new(40, 40);
            fill(&t1, sub, rule, &mut both, 1);
            fill(&t2, sub, rule, &mut both, 2);
            let mut union = CountSink::new(40, 40);
            fill(&[a, b, c, d], sub, rule, &mut union, 3);
            assert_eq!(both.count, union.count, "sub {sub} {a:?} {b:?} {c:?} {d:?}");
            assert!(both.count.iter().all(|&n| n <= 1));
        }
    }
    assert!(tested > 1000);
}

#[test]
fn jittered_mesh_covers_its_rectangle_exactly_once() {
    // A grid of cells split into triangles, interior vertices jittered:
    // many shared edges of every slope, union = the outer rectangle.
    let mut rng = Rng(99);
    for sub in [0u32, 3, 8] {
        let (nx, ny, cell) = (9, 7, 6 << sub);
        let mut grid = vec![vec![pt(0, 0); nx + 1]; ny + 1];
        for (j, row) in grid.iter_mut().enumerate() {
            for (i, p) in row.iter_mut().enumerate() {
                let interior = i > 0 && i < nx && j > 0 && j < ny;
                let jit = if interior { cell / 3 } else { 0 };
                *p = pt(
                    i as i32 * cell + rng.range(-jit, jit),
                    j as i32 * cell + rng.range(-jit, jit),
                );
            }
        }
        let mut s = CountSink::new(60, 50);
        for j in 0..ny {
            for i in 0..nx {
                let (p00, p10, p01, p11) = (
                    grid[j][i],
                    grid[j][i + 1],
                    grid[j + 1][i],
                    grid[j + 1][i + 1],
                );
                if (i + j) % 2 == 0 {
                    fill(&[p00, p10, p11], sub, FillRule::NonZero, &mut s, 0);
                    fill(&[p00, p11, p01], sub, FillRule::NonZero, &mut s, 1);
                } else {
                    fill(&[p00, p10, p01], sub, FillRule::NonZero, &mut s, 0);
                    fill(&[p10, p11, p01], sub, FillRule::NonZero, &mut s, 1);
                }
            }
        }
        for y in 0..50 {
            for x in 0..60 {
                let want = (x < nx as i32 * 6 && y < ny as i32 * 6) as u32;
                assert_eq!(s.at(x, y), want, "sub {sub} ({x},{y})");
            }
        }
    }
}

fn star(cx: i32, cy: i32, r_out: f32, r_in: f32, points: usize, sub: u32) -> Vec<ScreenPt> {
    (0..2 * points)
        .map(|k| {
            let a = k as f32 * core::f32::consts::PI / points as f32;
            let r = if k % 2 == 0 { r_out } else { r_in };
            let s = (1 << sub) as f32;
            pt(
                ((cx as f32 + r * libm::cosf(a)) * s) as i32,
                ((cy as f32 + r * libm::sinf(a)) * s) as i32,
            )
        })
        .collect()
}

fn check_against_reference(poly: &[ScreenPt], sub: u32, w: i32, h: i32) -> usize {
    let mut checked = 0;
    for rule in [FillRule::NonZero, FillRule::EvenOdd] {
        let mut s = CountSink::new(w, h);
        fill(poly, sub, rule, &mut s, 0);
        for y in 0..h {
            for x in 0..w {
                if let Some(inside) = reference_inside(poly, sub, x, y) {
                    assert_eq!(s.at(x, y), inside as u32, "sub {sub} ({x},{y}) {rule:?}");
                    checked += inside as usize;
                }
            }
        }
    }
    checked
}

#[test]
fn concave_polygons_match_point_in_polygon() {
    for sub in [0u32, 1, 4, 8] {
        let st = star(30, 25, 22.0, 8.0, 7, sub);
        assert!(check_against_reference(&st, sub, 64, 52) > 300);
        let u = scaled(
            &[
                (5, 5),
                (15, 5),
                (15, 30),
                (35, 30),
                (35, 5),
                (45, 5),
                (45, 40),
                (5, 40),
            ],
            sub,
        );
        assert!(check_against_reference(&u, sub, 50, 45) > 500);
        // Same U with fractional vertices.
        let mut uf = u.clone();
        for (k, p) in uf.iter_mut().enumerate() {
            p.x += (k as i32 * 37) % (1 << sub);
            p.y += (k as i32 * 11) % (1 << sub);
        }
        check_against_reference(&uf, sub, 50, 45);
    }
    // Random concave polygons (star-shaped around a centre, random radii).
    let mut rng = Rng(3);
    for _ in 0..60 {
        let sub = rng.range(0, 8) as u32;
        let n = rng.range(5, 20) as usize;
        let poly: Vec<_> = (0..n)
            .map(|k| {
                let a = k as f32 * 2.0 * core::f32::consts::PI / n as f32;
                let r = rng.float(3.0, 20.0) * (1 << sub) as f32;
                pt(
                    (20.0 * (1 << sub) as f32 + r * libm::cosf(a)) as i32,
                    (20.0 * (1 << sub) as f32 + r * libm::sinf(a)) as i32,
                )
            })
            .collect();
        check_against_reference(&poly, sub, 42, 42);
    }
}

#[test]
fn fill_rules_differ_on_a_self_intersecting_pentagram() {
    // {5/2} star: the centre pentagon has winding 2.
    let outer = star(20, 20, 15.0, 15.0, 5, 4);
    let pentagram: Vec<_> = (0..5).map(|k| outer[(4 * k) % 10]).collect();
    let mut nz = CountSink::new(40, 40);
    let mut eo = CountSink::new(40, 40);
    fill(&pentagram, 4, FillRule::NonZero, &mut nz, 0);
    fill(&pentagram, 4, FillRule::EvenOdd, &mut eo, 0);
    assert_eq!((nz.at(20, 20), eo.at(20, 20)), (1, 0));
    // Each tip is covered by both rules.
    assert_eq!((nz.at(30, 20), eo.at(30, 20)), (1, 1));
    assert!(nz.count.iter().all(|&c| c <= 1));
}

#[test]
fn bounds_and_bands_reproduce_the_full_fill() {
    let mut rng = Rng(42);
    let polys: Vec<Vec<ScreenPt>> = (0..40)
        .map(|_| {
            let n = rng.range(3, 9) as usize;
            (0..n)
                .map(|_| pt(rng.range(-200, 1200), rng.range(-200, 900)))
                .collect()
        })
        .collect();
    let (w, h) = (64, 48);
    let mut full = CountSink::new(w, h);
    for (k, p) in polys.iter().enumerate() {
        fill(p, 4, FillRule::NonZero, &mut full, k as u32);
    }
    for rows in [1, 5, 16, 48] {
        let mut y0 = 0;
        while y0 < h {
            let n = rows.min(h - y0);
            let mut band_buf = CountSink::new(w, rows);
            let mut band = Band::new(&mut band_buf, y0);
            for (k, p) in polys.iter().enumerate() {
                fill(p, 4, FillRule::NonZero, &mut band, k as u32);
            }
            let at = (y0 * w) as usize;
            assert_eq!(
                &band_buf.id[..(n * w) as usize],
                &full.id[at..at + (n * w) as usize],
                "rows {rows} y0 {y0}"
            );
            assert_eq!(
                &band_buf.count[..(n * w) as usize],
                &full.count[at..at + (n * w) as usize]
            );
            y0 += rows;
        }
    }
}

#[test]
fn spans_respect_an_offset_clip_rectangle() {
    let poly = star(20, 20, 30.0, 10.0, 5, 2);
    let mut full = CountSink::new(40, 40);
    fill(&poly, 2, FillRule::NonZero, &mut full, 0);
    let mut edges = [Edge::default(); 10];
    let mut active = [0u16; 10];
    let clip = SpanBounds {
        x0: 7,
        y0: 9,
        x1: 23,
        y1: 31,
    };
    let mut part = CountSink::new(40, 40);
    let r = fill_polygon(
        &poly,
        2,
        FillRule::NonZero,
        &clip,
        &mut edges,
        &mut active,
        1,
        &mut part,
    );
    assert!(r.is_ok_and(|n| n > 0));
    for y in 0..40 {
        for x in 0..40 {
            let inside = (7..23).contains(&x) && (9..31).contains(&y);
            assert_eq!(
                part.at(x, y),
                if inside { full.at(x, y) } else { 0 },
                "({x},{y})"
            );
        }
    }
    // Scratch too small is an error, not a panic.
    let mut small = [Edge::default(); 4];
    let r = fill_polygon(
        &poly,
        2,
        FillRule::NonZero,
        &clip,
        &mut small,
        &mut active,
        1,
        &mut part,
    );
    assert!(r.is_err());
}
