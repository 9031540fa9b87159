//! The double-buffered band loop against one buffer and a full frame, and
//! its side of the driver contract (one transfer at a time, buffers in
//! turns, errors stop the frame, nothing left in flight).

extern crate std;

use std::vec;
use std::vec::Vec;

use embedded_graphics::pixelcolor::Rgb565;

use super::*;
use crate::raster::{FloatLibm, Libm, Orbit, Rgb565BeFormat, Rgb565Framebuffer};
use crate::render::{memory_words, BandBuffer, CapacityError};

const W: u32 = 64;
/// Not a multiple of the band: the last band is short.
const H: u32 = 50;
const ROWS: u32 = 16;
const BG: Rgb565 = Rgb565::new(3, 7, 9);

type R = TreeRenderer<FloatLibm<4>, 64>;

fn vise() -> Tree<'static> {
    match Tree::from_bytes(include_bytes!("../../../../firmware/trees/vise.fpt")) {
        Ok(t) => t,
        Err(e) => panic!("{e:?}"),
    }
}

fn frame(tree: &Tree<'_>, yaw: f32) -> Frame {
    let orbit = Orbit::framing::<Libm>(tree.bounding_radius(), yaw, 0.4, 1.0, 1.0);
    Frame::relative(tree, &orbit.camera::<Libm>(W as f32 / H as f32))
}

fn renderer() -> R {
    match R::new(W, H) {
        Some(r) => r,
        None => panic!("renderer"),
    }
}

/// A link that keeps the band in flight and "sends" it in `finish`: its
/// pixels go into `image` at the band's rows. `fail_start`/`fail_finish`:
/// the call (counted from 0) that fails.
struct Link<'b> {
    in_flight: Option<(i32, Framebuffer<'b, Rgb565BeFormat>)>,
    image: Vec<u16>,
    rows: Vec<i32>,
    buffers: Vec<usize>,
    starts: usize,
    finishes: usize,
    fail_start: Option<usize>,
    fail_finish: Option<usize>,
}

impl Link<'_> {
    fn new() -> Self {
        Link {
            in_flight: None,
            image: vec![0; (W * H) as usize],
            rows: Vec::new(),
            buffers: Vec::new(),
            starts: 0,
            finishes: 0,
            fail_start: None,
            fail_finish: None,
        }
    }
}

impl<'b> BandTransfer<'b, Rgb565BeFormat> for Link<'b> {
    type Error = (&'static str, usize);

    fn start(&mut self, y: i32, band: Framebuffer<'b, Rgb565BeFormat>) -> Result<(), Self::Error> {
        assert!(self.in_flight.is_none(), "a second transfer started");
        let k = self.starts;
        self.starts += 1;
        if self.fail_start == Some(k) {
            return Err(("start", k));
        }
        self.rows.push(y);
        self.buffers.push(band.data().as_ptr() as usize);
        self.in_flight = Some((y, band));
        Ok(())
    }

    fn finish(&mut self) -> Result<Framebuffer<'b, Rgb565BeFormat>, Self::Error> {
        let k = self.finishes;
        self.finishes += 1;
        let Some((y, band)) = self.in_flight.take() else {
            panic!("finish without a transfer");
        };
        if self.fail_finish == Some(k) {
            return Err(("finish", k));
        }
        let at = y as usize * W as usize;
        let words = band.data();
        self.image[at..at + words.len()].copy_from_slice(words);
        Ok(band)
    }
}

/// The frame through one band buffer, big-endian words.
fn one_buffer(tree: &Tree<'_>, frame: &Frame, memory: &mut [u32]) -> Vec<u16> {
    let mut image = vec![0u16; (W * H) as usize];
    let mut buf = vec![0u16; (W * ROWS) as usize];
    let band = BandBuffer::<Rgb565BeFormat> {
        buf: &mut buf,
        rows: ROWS,
        background: BG,
    };
    let out = renderer().render_banded_in::<64, _>(tree, frame, band, memory, |y, fb| {
        let at = y as usize * W as usize;
        image[at..at + fb.data().len()].copy_from_slice(fb.data());
    });
    if let Err(e) = out {
        panic!("{e}");
    }
    image
}

fn double(
    tree: &Tree<'_>,
    frame: &Frame,
    memory: &mut [u32],
    link: &mut Link<'_>,
    back_words: usize,
) -> Result<RenderStats, BandError<(&'static str, usize)>> {
    let mut a = vec![0u16; (W * ROWS) as usize];
    let mut b = vec![0u16; back_words];
    // The link may not outlive the buffers: run on a fresh link and copy
    // its record back.
    let mut inner = Link::new();
    inner.fail_start = link.fail_start;
    inner.fail_finish = link.fail_finish;
    let mut bands = BandBuffers::<Rgb565BeFormat> {
        front: &mut a,
        back: &mut b,
        rows: ROWS,
        background: BG,
    };
    let out = renderer()
        .render_double_buffered_in::<64, _, _>(tree, frame, &mut bands, memory, &mut inner);
    assert!(inner.in_flight.is_none(), "a transfer left in flight");
    // Both buffers come back but for the band of a failed `start` or
    // `finish` (that one stays with the driver).
    let back = [bands.front.len(), bands.back.len()];
    let failed = link.fail_finish.is_some_and(|k| k < inner.finishes)
        || link.fail_start.is_some_and(|k| k < inner.starts);
    let lost = usize::from(failed);
    assert_eq!(back.iter().filter(|&&n| n == 0).count(), lost, "{back:?}");
    link.image = inner.image;
    link.rows = inner.rows;
    link.buffers = inner.buffers;
    link.starts = inner.starts;
    link.finishes = inner.finishes;
    out
}

#[test]
fn same_pixels_as_one_buffer_and_full_frame() {
    let tree = vise();
    let full_memory = memory_words(&tree);
    for yaw in [0.3f32, 2.2] {
        let frame = frame(&tree, yaw);
        // The full frame, native words, turned big-endian to compare.
        let mut full = vec![0u16; (W * H) as usize];
        let mut fb = match Rgb565Framebuffer::new(&mut full, W, H) {
            Ok(fb) => fb,
            Err(e) => panic!("{e}"),
        };
        fb.fill_all(BG);
        if let Err(e) = renderer().render::<64, _>(&tree, &frame, &mut fb) {
            panic!("{e}");
        }
        let full: Vec<u16> = full.iter().map(|w| w.to_be()).collect();
        // No memory (a walk a band), a little (a few walks), enough (one).
        for words in [0, full_memory / 3, full_memory] {
            let mut memory = vec![0u32; words];
            let single = one_buffer(&tree, &frame, &mut memory);
            let mut link = Link::new();
            let stats = match double(&tree, &frame, &mut memory, &mut link, (W * ROWS) as usize) {
                Ok(s) => s,
                Err(e) => panic!("{e}"),
            };
            assert_eq!(link.image, single, "yaw {yaw}, {words} words");
            assert_eq!(link.image, full, "yaw {yaw}, {words} words");
            assert!(link.image.iter().any(|&w| w != BG_BE), "nothing drawn");
            assert_eq!(link.rows, [0, 16, 32, 48]);
            assert_eq!((link.starts, link.finishes), (4, 4));
            assert!(stats.drawn > 0 && stats.skipped == 0);
            if words == full_memory {
                assert_eq!(stats.walks, 1);
            }
        }
    }
}

/// The background as the panel's big-endian word.
const BG_BE: u16 = {
    let raw = ((3u16) << 11) | (7 << 5) | 9;
    raw.to_be()
};

#[test]
fn buffers_alternate() {
    let tree = vise();
    let mut link = Link::new();
    if let Err(e) = double(
        &tree,
        &frame(&tree, 1.0),
        &mut [],
        &mut link,
        (W * ROWS) as usize,
    ) {
        panic!("{e}");
    }
    let b = &link.buffers;
    assert_eq!(b.len(), 4);
    assert_ne!(b[0], b[1]);
    assert_eq!(b[0], b[2]);
    assert_eq!(b[1], b[3]);
}

#[test]
fn a_failed_finish_stops_the_frame() {
    let tree = vise();
    let mut link = Link::new();
    // The second finish (band 1's, called before band 2 starts) fails.
    link.fail_finish = Some(1);
    let out = double(
        &tree,
        &frame(&tree, 1.0),
        &mut [],
        &mut link,
        (W * ROWS) as usize,
    );
    assert_eq!(out, Err(BandError::Display(("finish", 1))));
    assert_eq!(link.rows, [0, 16]);
    assert_eq!((link.starts, link.finishes), (2, 2));
}

#[test]
fn a_failed_start_stops_the_frame_and_finishes_nothing_more() {
    let tree = vise();
    let mut link = Link::new();
    link.fail_start = Some(2);
    let out = double(
        &tree,
        &frame(&tree, 1.0),
        &mut [],
        &mut link,
        (W * ROWS) as usize,
    );
    assert_eq!(out, Err(BandError::Display(("start", 2))));
    // Bands 0 and 1 started and finished; band 2's start failed.
    assert_eq!(link.rows, [0, 16]);
    assert_eq!((link.starts, link.finishes), (3, 2));
}

#[test]
fn refusals_send_nothing() {
    let tree = vise();
    let mut link = Link::new();
    let out = double(
        &tree,
        &frame(&tree, 1.0),
        &mut [],
        &mut link,
        (W * ROWS) as usize - 1,
    );
    assert_eq!(
        out,
        Err(BandError::Render(RenderError::Band(
            FramebufferError::BufferTooSmall
        )))
    );
    assert_eq!(link.starts, 0);
    // Too small a walk stack: the capacity error, before any band.
    let (mut a, mut b) = (
        vec![0u16; (W * ROWS) as usize],
        vec![0u16; (W * ROWS) as usize],
    );
    let mut bands = BandBuffers::<Rgb565BeFormat> {
        front: &mut a,
        back: &mut b,
        rows: ROWS,
        background: BG,
    };
    let mut inner = Link::new();
    let out = renderer().render_double_buffered_in::<4, _, _>(
        &tree,
        &frame(&tree, 1.0),
        &mut bands,
        &mut [],
        &mut inner,
    );
    assert!(matches!(
        out,
        Err(BandError::Render(RenderError::Capacity(
            CapacityError::WalkDepth { have: 4, .. }
        )))
    ));
    assert_eq!(inner.starts, 0);
}
