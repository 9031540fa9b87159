extern crate std;

use std::vec;

use embedded_graphics::pixelcolor::Rgb888;

use super::{widest, Smooth, SmoothSink};
use crate::raster::edge::Edge;
use crate::raster::scan::{fill_polygon, FillRule, SpanBounds, SpanSink};
use crate::raster::transform::ScreenPt;
use crate::raster::Rgb888Framebuffer;

const W: u32 = 40;
const H: u32 = 30;
const SUB: u32 = 4;

fn pts(p: &[(i32, i32)]) -> vec::Vec<ScreenPt> {
    p.iter().map(|&(x, y)| ScreenPt { x, y }).collect()
}

/// Fills `poly` into a fresh frame through `sink_of` (flat colour `flat`,
/// or the smooth plane through its widest triangle with `rgb`).
fn draw(poly: &[ScreenPt], flat: Option<Rgb888>, rgb: [Rgb888; 3]) -> vec::Vec<u8> {
    let mut buf = vec![0u8; (3 * W * H) as usize];
    let mut fb = Rgb888Framebuffer::new(&mut buf, W, H).unwrap();
    let mut edges = [Edge::ZERO; 8];
    let mut active = [0u16; 8];
    let clip = SpanBounds::of_size(W, H);
    match flat {
        Some(c) => {
            let color = fb.color(&crate::raster::Paint { rgb: c, id: 0 });
            fill_polygon(
                poly,
                SUB,
                FillRule::NonZero,
                &clip,
                &mut edges,
                &mut active,
                color,
                &mut fb,
            )
            .unwrap();
        }
        None => {
            let (k, _) = widest(poly).unwrap();
            let s = Smooth::new(k.map(|i| poly[i]), rgb, SUB);
            let mut sink = SmoothSink::new(&s, 0, &mut fb);
            fill_polygon(
                poly,
                SUB,
                FillRule::NonZero,
                &clip,
                &mut edges,
                &mut active,
                (),
                &mut sink,
            )
            .unwrap();
        }
    }
    buf
}

#[test]
fn equal_corner_colours_draw_the_flat_fill() {
    let polys = [
        pts(&[(17, 9), (600, 40), (300, 450)]),
        pts(&[(5, 5), (630, 5), (630, 470), (5, 470)]),
        // Concave, with a corner far outside the frame.
        pts(&[(20, 20), (900, 30), (200, 150), (400, 470), (-300, 200)]),
        // A sliver.
        pts(&[(10, 10), (620, 300), (11, 12)]),
    ];
    for c in [
        Rgb888::new(200, 100, 7),
        Rgb888::new(0, 0, 0),
        Rgb888::new(255, 255, 255),
    ] {
        for p in &polys {
            assert_eq!(draw(p, None, [c; 3]), draw(p, Some(c), [c; 3]), "{p:?}");
        }
    }
}

#[test]
fn corners_get_their_colours_and_spans_interpolate_between() {
    let tri = pts(&[(8, 8), (632, 8), (8, 472)]);
    let (red, green, blue) = (
        Rgb888::new(255, 0, 0),
        Rgb888::new(0, 255, 0),
        Rgb888::new(0, 0, 255),
    );
    let buf = draw(&tri, None, [red, green, blue]);
    let px = |x: usize, y: usize| {
        let i = 3 * (y * W as usize + x);
        [buf[i], buf[i + 1], buf[i + 2]]
    };
    // Near each corner, its colour dominates.
    assert!(px(1, 1)[0] > 230, "{:?}", px(1, 1));
    assert!(px(37, 1)[1] > 230, "{:?}", px(37, 1));
    assert!(px(1, 27)[2] > 230, "{:?}", px(1, 27));
    // Along row 1 red falls and green grows, and the channels add up to
    // the full level (an affine blend).
    for x in 1..38 {
        let (a, b) = (px(x - 1, 1), px(x, 1));
        assert!(b[0] <= a[0] && b[1] >= a[1], "x {x}: {a:?} {b:?}");
        let sum: u32 = b.iter().map(|&c| u32::from(c)).sum();
        assert!((253..=257).contains(&sum), "x {x}: {b:?}");
    }
    // Exactly: pixel (19, 1) has its centre at x = 19.5 (312 sixteenths);
    // green is 255 · (312 − 8) / 624 = 124.2 whatever the row.
    assert_eq!(px(19, 1)[1], 124);
}

#[test]
fn the_widest_fan_triangle_is_chosen() {
    let quad = pts(&[(0, 0), (10, 0), (100, 100), (0, 10)]);
    let (k, area) = widest(&quad).unwrap();
    assert_eq!(k, [0, 1, 2]);
    assert_eq!(area, 1000);
    assert_eq!(widest(&quad[..2]), None);
    // A degenerate plane draws the mean colour.
    let line = [
        ScreenPt { x: 0, y: 0 },
        ScreenPt { x: 16, y: 16 },
        ScreenPt { x: 32, y: 32 },
    ];
    let c = [
        Rgb888::new(0, 0, 0),
        Rgb888::new(90, 90, 90),
        Rgb888::new(30, 30, 30),
    ];
    let s = Smooth::new(line, c, SUB);
    assert_eq!(s.gx, [0; 3]);
    assert_eq!(s.c[0] >> 16, 40);
}
