//! What a frame is made of: the counts a cost model multiplies (polygons
//! the walk hands out, their vertices, spans and pixels painted), for the
//! same frames the firmware measures. Host-side analysis (`fpt frames
//! --work`); the firmware never calls it.

use core::cell::Cell;
use core::fmt;

use embedded_graphics::pixelcolor::Rgb565;

use super::{draw_tree, setup, FrameError, FrameRenderer, Probe, ViewSpec, HEIGHT, WIDTH};
use fpt_nostd::raster::{Paint, SpanBounds, SpanSink};
use fpt_nostd::reader::{PolygonRef, Tree};

/// The work of one frame ([`frame_work`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Work {
    /// Polygons the walk hands out (after back-face culling).
    pub polygons: u32,
    /// Their vertices, as stored (what the transform decodes).
    pub vertices: u64,
    /// Polygons drawn (not invisible or skipped; see `RenderStats`).
    pub drawn: u32,
    /// Spans painted (at most one per row of a convex polygon).
    pub spans: u64,
    /// Pixels painted, overdraw included (not the clear).
    pub pixels: u64,
}

impl fmt::Display for Work {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "polygons={} vertices={} drawn={} spans={} pixels={}",
            self.polygons, self.vertices, self.drawn, self.spans, self.pixels
        )
    }
}

/// Counts the pixels of the spans it is given and stores nothing.
struct Tally {
    pixels: u64,
}

impl SpanSink for Tally {
    type Color = Rgb565;
    fn color(&self, paint: &Paint) -> Rgb565 {
        paint.rgb.into()
    }
    fn bounds(&self) -> SpanBounds {
        SpanBounds::of_size(WIDTH, HEIGHT)
    }
    fn span(&mut self, _y: i32, x0: i32, x1: i32, _c: Rgb565) {
        self.pixels += u64::from(x1.saturating_sub(x0).max(0).unsigned_abs());
    }
}

/// Counts the polygons handed to the renderer and their vertices.
#[derive(Default)]
struct Handed {
    polygons: Cell<u32>,
    vertices: Cell<u64>,
}

impl Probe for Handed {
    fn polygon(&self, p: &PolygonRef<'_>) {
        self.polygons.set(self.polygons.get() + 1);
        self.vertices
            .set(self.vertices.get() + p.vertex_count() as u64);
    }
}

/// The work of view `view` of `tree`, drawn as [`super::render_full`]
/// draws it (same walk, renderer and effects), into a sink that only
/// counts.
pub fn frame_work(
    r: &mut FrameRenderer,
    tree: &Tree<'_>,
    view: &ViewSpec,
) -> Result<Work, FrameError> {
    let frame = setup(r, tree, view);
    let mut sink = Tally { pixels: 0 };
    let handed = Handed::default();
    let stats = draw_tree(r, tree, &frame, &mut [], &mut sink, &handed)?;
    Ok(Work {
        polygons: handed.polygons.get(),
        vertices: handed.vertices.get(),
        drawn: stats.drawn,
        spans: stats.spans,
        pixels: sink.pixels,
    })
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::{render_full, NoProbe, BACKGROUND, FRAME_WORDS, VIEWS};
    use super::*;
    use embedded_graphics::pixelcolor::IntoStorage;
    use fpt_nostd::test_util::two_floors;

    /// The counts agree with the renderer's own counters and with the
    /// picture: two stacked squares, so the walk hands out at most two
    /// polygons of four vertices, and the pixels painted (overdraw
    /// included) are at least the pixels that differ from the background.
    #[test]
    fn counts_agree_with_the_frame() {
        let mut raw = two_floors();
        for (p, c) in raw.polys.iter_mut().zip([[200, 120, 40], [60, 160, 220]]) {
            p.3 = c;
        }
        let bytes = raw.bytes();
        let tree = Tree::from_bytes(&bytes).unwrap_or_else(|e| panic!("{e}"));
        let mut r = FrameRenderer::new(WIDTH, HEIGHT).unwrap_or_else(|| panic!("renderer"));
        let mut buf = std::vec![0u16; FRAME_WORDS];
        let bg = BACKGROUND.into_storage();
        let mut seen = 0;
        for v in &VIEWS {
            let w = frame_work(&mut r, &tree, v).unwrap_or_else(|e| panic!("{e:?}"));
            let full = render_full(&mut r, &tree, v, &mut buf, &mut [], &NoProbe)
                .unwrap_or_else(|e| panic!("{e:?}"));
            assert_eq!((w.drawn, w.spans), (full.stats.drawn, full.stats.spans));
            assert!(w.polygons <= 2 && w.drawn <= w.polygons, "{w}");
            assert_eq!(w.vertices, 4 * u64::from(w.polygons), "{w}");
            let painted = buf.iter().filter(|&&p| p != bg).count() as u64;
            assert!(w.pixels >= painted, "{w} {painted}");
            assert!(w.spans <= u64::from(HEIGHT) * u64::from(w.drawn), "{w}");
            seen += w.pixels;
        }
        assert!(seen > 0);
    }
}
