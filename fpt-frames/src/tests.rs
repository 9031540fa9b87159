//! Tests of the shared frame code on a small hand-made tree; the real
//! scenes are checked against the firmware in `tests/tests/all/firmware_crc.rs`.

extern crate std;

use core::cell::Cell;
use std::vec;
use std::vec::Vec;

use embedded_graphics::pixelcolor::IntoStorage;

use super::*;
use fpt_nostd::format::{crc32, FLAG_CLOSED};
use fpt_nostd::render::draw_frame;
use fpt_nostd::render::FaceIds;
use fpt_nostd::test_util::two_floors;

fn tree(bytes: &[u8]) -> Tree<'_> {
    match Tree::from_bytes(bytes) {
        Ok(t) => t,
        Err(e) => panic!("{e:?}"),
    }
}

fn renderer() -> FrameRenderer {
    match FrameRenderer::new(WIDTH, HEIGHT) {
        Some(r) => r,
        None => panic!("renderer"),
    }
}

fn full(t: &Tree<'_>, v: &ViewSpec, probe: &impl Probe) -> (Vec<u16>, Rendered) {
    let mut buf = vec![0u16; FRAME_WORDS];
    match render_full(&mut renderer(), t, v, &mut buf, &mut [], probe) {
        Ok(out) => (buf, out),
        Err(e) => panic!("{e}"),
    }
}

/// The two squares of `two_floors`, open, and the same marked closed.
fn floors(closed: bool) -> Vec<u8> {
    let mut r = two_floors();
    // Coloured, so that the lighting shows (the helper leaves them black).
    for (p, c) in r.polys.iter_mut().zip([[200, 120, 40], [60, 160, 220]]) {
        p.3 = c;
    }
    if closed {
        r.flags |= FLAG_CLOSED;
    }
    r.bytes()
}

#[test]
fn pixel_crc_is_the_crc_of_little_endian_words_in_any_pieces() {
    let words: Vec<u16> = (0..77u32)
        .map(|i| (i.wrapping_mul(2_654_435_761) >> 7) as u16)
        .collect();
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
    let mut whole = PixelCrc::new();
    whole.update(&words);
    let mut pieces = PixelCrc::new();
    for part in [&words[..1], &words[1..17], &words[17..50], &words[50..]] {
        pieces.update(part);
    }
    let want = crc32(&bytes);
    assert_eq!(whole.finish(), want);
    assert_eq!(pieces.finish(), want);
    let mut one = PixelCrc::new();
    one.update(&[0x1234]);
    assert_eq!(one.finish(), crc32(&[0x34, 0x12]));
    assert_eq!(PixelCrc::new().finish(), 0);
}

#[test]
fn frame_line_round_trips_and_ignores_extra_fields() {
    let l = FrameLine {
        scene: "bench_city",
        view: 3,
        crc: 0x00ab_cdef,
    };
    let s = std::format!("{l}");
    assert_eq!(s, "frame scene=bench_city view=3 crc=00abcdef");
    assert_eq!(FrameLine::parse(&s), Some(l));
    let long = std::format!("{s} instr=123 post=1 xform=2 fill=3");
    assert_eq!(FrameLine::parse(&long), Some(l));
    for bad in [
        "",
        "stack_peak=100",
        "frame scene=x view=1",
        "frame scene=x view=a crc=00000000",
        "frame scene=x view=1 crc=123",
        "frame scene= view=1 crc=00000000",
        "frame view=1 scene=x crc=00000000",
        "frames scene=x view=1 crc=00000000",
        "frame scene=x view=1 crc=0000000g",
    ] {
        assert_eq!(FrameLine::parse(bad), None, "{bad}");
    }
}

/// A view from below the squares (every one of [`VIEWS`] looks from above).
const BELOW: ViewSpec = ViewSpec {
    yaw: 0.3,
    pitch: -0.6,
    distance: 2.0,
    fov: 0.9,
};

#[test]
fn full_frame_equals_draw_frame_and_bands_equal_full() {
    for closed in [false, true] {
        let bytes = floors(closed);
        let t = tree(&bytes);
        let mut drew_something = false;
        for v in VIEWS.iter().chain([&BELOW]) {
            let (ours, out) = full(&t, v, &NoProbe);
            // The same frame through render::draw_frame.
            let mut r = renderer();
            let frame = v.frame(&t);
            r.renderer
                .set_light(Light::new(frame.key_light(), AMBIENT, DIFFUSE));
            let mut theirs = vec![0u16; FRAME_WORDS];
            let mut fb = match Rgb565Framebuffer::new(&mut theirs, WIDTH, HEIGHT) {
                Ok(fb) => fb,
                Err(e) => panic!("{e:?}"),
            };
            fb.fill_all(BACKGROUND);
            let stats = draw_frame::<_, WALK_DEPTH, MAX_VERTS, _, _>(
                &t,
                &frame,
                &mut r.renderer,
                &mut r.scratch,
                FaceIds::Source,
                &mut fb,
            );
            assert_eq!(stats, Ok(out.stats));
            assert!(ours == theirs, "closed={closed} view={v:?}");
            let mut crc = PixelCrc::new();
            crc.update(&ours);
            assert_eq!(crc.finish(), out.crc);
            let bg = BACKGROUND.into_storage();
            drew_something |= ours.iter().any(|&p| p != bg);

            // Bands and a vertex cache, with any amount of memory: the same
            // picture and counters.
            let need = fpt_nostd::render::memory_words(&t);
            // Walks, memory and spans (a band boundary may cut a run) differ.
            let counts = |s: RenderStats| (s.drawn, s.invisible, s.skipped, s.clipped);
            for words in [0, 1, 5, 12, 20, need] {
                let mut memory = vec![0u32; words];
                let mut band = vec![0u16; BAND_WORDS];
                match render_banded(&mut renderer(), &t, v, &mut band, &mut memory, &NoProbe) {
                    Ok(b) => assert_eq!(
                        (b.crc, counts(b.stats)),
                        (out.crc, counts(out.stats)),
                        "closed={closed} view={v:?} words={words}"
                    ),
                    Err(e) => panic!("{e}"),
                }
                let mut buf = vec![0u16; FRAME_WORDS];
                match render_full(&mut renderer(), &t, v, &mut buf, &mut memory, &NoProbe) {
                    Ok(b) => assert_eq!((b.crc, counts(b.stats)), (out.crc, counts(out.stats))),
                    Err(e) => panic!("{e}"),
                }
            }
        }
        assert!(drew_something);
    }
}

#[test]
fn closed_and_open_trees_differ_where_back_faces_show() {
    // The squares face +z, which Z_UP turns to "up": seen from below,
    // the open tree draws their back sides, the closed one culls them.
    let below = BELOW;
    let (open, closed) = (floors(false), floors(true));
    let bg = BACKGROUND.into_storage();
    let (a, _) = full(&tree(&open), &below, &NoProbe);
    let (b, _) = full(&tree(&closed), &below, &NoProbe);
    assert!(a.iter().any(|&p| p != bg));
    assert!(b.iter().all(|&p| p == bg));
    // From above (every one of VIEWS) both draw the same.
    let (c, _) = full(&tree(&open), &VIEWS[0], &NoProbe);
    let (d, _) = full(&tree(&closed), &VIEWS[0], &NoProbe);
    assert!(c.iter().any(|&p| p != bg) && c == d);
}

/// Counts the hooks and checks that they nest.
#[derive(Default)]
struct Counting {
    running: Cell<bool>,
    starts: Cell<u32>,
    enters: [Cell<u32>; 3],
    bad: Cell<bool>,
}

impl Probe for Counting {
    fn start(&self, _phase: Phase) {
        self.bad.set(self.bad.get() | self.running.get());
        self.running.set(true);
        self.starts.set(self.starts.get() + 1);
    }
    fn enter(&self, phase: Phase) {
        self.bad.set(self.bad.get() | !self.running.get());
        let c = &self.enters[phase as usize];
        c.set(c.get() + 1);
    }
    fn stop(&self) {
        self.bad.set(self.bad.get() | !self.running.get());
        self.running.set(false);
    }
}

#[test]
fn probe_hooks_mark_every_polygon_and_nest() {
    let bytes = floors(false);
    let t = tree(&bytes);
    let p = Counting::default();
    let (_, out) = full(&t, &VIEWS[0], &p);
    let s = out.stats;
    let polys = s.drawn + s.invisible + s.skipped;
    assert_eq!(polys, 2);
    assert!(!p.bad.get() && !p.running.get());
    assert_eq!(p.starts.get(), 1);
    // Post: once at the walk's start and after each polygon; Xform: once
    // per polygon; Fill: the clear, plus each polygon that reached the
    // sink.
    assert_eq!(p.enters[Phase::Post as usize].get(), 1 + polys);
    assert_eq!(p.enters[Phase::Xform as usize].get(), polys);
    assert_eq!(p.enters[Phase::Fill as usize].get(), 1 + s.drawn);

    // Bands with enough memory: one walk (Xform once at the start and
    // once per polygon), and the probe stopped while each band is handed
    // out.
    let q = Counting::default();
    let mut band = vec![0u16; BAND_WORDS];
    let mut memory = vec![0u32; fpt_nostd::render::memory_words(&t)];
    if let Err(e) = render_banded(&mut renderer(), &t, &VIEWS[0], &mut band, &mut memory, &q) {
        panic!("{e}");
    }
    let bands = HEIGHT.div_ceil(BAND_ROWS);
    assert!(!q.bad.get() && !q.running.get());
    assert_eq!(q.starts.get(), 1 + bands);
    assert_eq!(q.enters[Phase::Xform as usize].get(), 1 + polys);
}

#[test]
fn small_buffers_are_errors() {
    let bytes = floors(false);
    let t = tree(&bytes);
    let mut small = vec![0u16; FRAME_WORDS - 1];
    let r = render_full(
        &mut renderer(),
        &t,
        &VIEWS[0],
        &mut small,
        &mut [],
        &NoProbe,
    );
    assert_eq!(
        r.err(),
        Some(FrameError::Buffer(FramebufferError::BufferTooSmall))
    );
    let mut band = vec![0u16; BAND_WORDS - 1];
    let p = Counting::default();
    let r = render_banded(&mut renderer(), &t, &VIEWS[0], &mut band, &mut [], &p);
    assert_eq!(
        r.err(),
        Some(FrameError::Buffer(FramebufferError::BufferTooSmall))
    );
    assert!(!p.running.get());
}
