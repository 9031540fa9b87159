//! Band rendering: a frame drawn in horizontal bands through one small
//! buffer.
//!
//! A [`Band`] makes a buffer of `W × N` pixels (any [`SpanSink`], typically
//! a [`super::framebuffer::Framebuffer`] of N rows) stand for frame rows
//! `[y0, y0 + N)`: its bounds are the buffer's bounds moved down by `y0`,
//! and a span on frame row `y` is written to buffer row `y − y0`. The
//! renderer restricts edges to the band's rows, so drawing the whole scene
//! once per band and sending each band to the display gives exactly the
//! pixels of a full-frame render (the scan conversion is exact and starts
//! each edge at the band's first row by direct computation, not by
//! stepping from the top, so no rounding differs between bands).
//!
//! `Band` is also a `DrawTarget` (when the buffer is one) in frame
//! coordinates, so embedded-graphics overlays (text, markers) can be drawn
//! into the same bands.
//!
//! The usual way to draw bands is
//! [`crate::render::TreeRenderer::render_banded_in`]: it walks the tree
//! once a frame into a display list in memory the caller gives, and
//! replays it into each band (see `render::cached` for what less memory
//! costs). A band buffer of 16 rows of a 240-pixel RGB565 panel:
//!
//! ```
//! use fpt_nostd::raster::{FloatLibm, Rgb565Format};
//! use fpt_nostd::reader::Tree;
//! use fpt_nostd::render::{memory_words, BandBuffer, Frame, RenderError, TreeRenderer};
//! use embedded_graphics::pixelcolor::Rgb565;
//!
//! /// Draws one frame; `send` gets each band's first row and its pixels.
//! fn frame(
//!     r: &mut TreeRenderer<FloatLibm<4>, 40>,
//!     tree: &Tree<'_>,
//!     frame: &Frame,
//!     band: &mut [u16; 240 * 16],
//!     memory: &mut [u32],
//!     mut send: impl FnMut(i32, &[u16]),
//! ) -> Result<(), RenderError> {
//!     let band = BandBuffer::<Rgb565Format> {
//!         buf: band,
//!         rows: 16,
//!         background: Rgb565::new(2, 4, 6),
//!     };
//!     // 64-walk depth; `memory_words(tree)` words make it one walk.
//!     r.render_banded_in::<64, _>(tree, frame, band, memory, |y0, fb| send(y0, fb.data()))?;
//!     Ok(())
//! }
//! # let _ = memory_words;
//! ```

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::{Dimensions, Point};
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::Pixel;

use super::scan::{Paint, SpanBounds, SpanSink};

/// A band buffer placed at frame row `y0` (see module docs).
#[derive(Debug)]
pub struct Band<'a, T> {
    inner: &'a mut T,
    y0: i32,
}

impl<'a, T> Band<'a, T> {
    /// `inner`'s row 0 stands for frame row `y0`.
    pub fn new(inner: &'a mut T, y0: i32) -> Self {
        Band { inner, y0 }
    }

    /// The frame row of the buffer's first row.
    pub fn y0(&self) -> i32 {
        self.y0
    }

    /// The underlying buffer.
    pub fn inner(&mut self) -> &mut T {
        self.inner
    }
}

/// First rows of the bands covering `frame_height` rows, `band_rows` at a
/// time (`band_rows = 0` is treated as 1).
pub fn band_starts(frame_height: u32, band_rows: u32) -> impl Iterator<Item = i32> {
    let h = frame_height.min(i32::MAX as u32) as i32;
    (0..h).step_by(band_rows.clamp(1, i32::MAX as u32) as usize)
}

impl<T: SpanSink> SpanSink for Band<'_, T> {
    type Color = T::Color;
    const NEEDS_ID: bool = T::NEEDS_ID;
    fn color(&self, paint: &Paint) -> T::Color {
        self.inner.color(paint)
    }
    #[inline(always)]
    fn keep_color(&self, color: T::Color, paint: &Paint) -> u32 {
        self.inner.keep_color(color, paint)
    }
    #[inline(always)]
    fn kept_color(&self, word: u32) -> T::Color {
        self.inner.kept_color(word)
    }
    fn bounds(&self) -> SpanBounds {
        let b = self.inner.bounds();
        SpanBounds {
            y0: b.y0.saturating_add(self.y0),
            y1: b.y1.saturating_add(self.y0),
            ..b
        }
    }
    /// Frame row `y` is the buffer's row `y − y0`. Rows outside the band
    /// are the buffer's own out-of-bounds rows, which a sink ignores (the
    /// fill never sends them: it clips to [`SpanSink::bounds`]); testing
    /// them here again cost a bounds computation per span.
    #[inline]
    fn span(&mut self, y: i32, x0: i32, x1: i32, color: T::Color) {
        self.inner.span(y.wrapping_sub(self.y0), x0, x1, color);
    }
    /// The buffer's rows from `y − y0` on.
    #[inline(always)]
    fn span_rows<I: Iterator<Item = (i32, i32)>>(
        &mut self,
        y: i32,
        spans: I,
        color: T::Color,
    ) -> usize {
        self.inner.span_rows(y.wrapping_sub(self.y0), spans, color)
    }
}

impl<T: DrawTarget> Dimensions for Band<'_, T> {
    fn bounding_box(&self) -> Rectangle {
        let b = self.inner.bounding_box();
        Rectangle::new(b.top_left + Point::new(0, self.y0), b.size)
    }
}

impl<T: DrawTarget> DrawTarget for Band<'_, T> {
    type Color = T::Color;
    type Error = T::Error;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), T::Error>
    where
        I: IntoIterator<Item = Pixel<T::Color>>,
    {
        let off = Point::new(0, self.y0);
        self.inner
            .draw_iter(pixels.into_iter().map(|Pixel(p, c)| Pixel(p - off, c)))
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), T::Error>
    where
        I: IntoIterator<Item = T::Color>,
    {
        let a = Rectangle::new(area.top_left - Point::new(0, self.y0), area.size);
        self.inner.fill_contiguous(&a, colors)
    }

    fn fill_solid(&mut self, area: &Rectangle, color: T::Color) -> Result<(), T::Error> {
        let a = Rectangle::new(area.top_left - Point::new(0, self.y0), area.size);
        self.inner.fill_solid(&a, color)
    }

    fn clear(&mut self, color: T::Color) -> Result<(), T::Error> {
        self.inner.clear(color)
    }
}

#[cfg(test)]
mod tests {
    use super::super::framebuffer::Gray8Framebuffer;
    use super::*;
    use embedded_graphics::geometry::Size;
    use embedded_graphics::pixelcolor::{Gray8, GrayColor};

    #[test]
    fn band_starts_cover_the_frame() {
        let v: [i32; 4] = [0, 16, 32, 48];
        assert!(band_starts(50, 16).eq(v));
        assert_eq!(band_starts(5, 0).count(), 5);
        assert_eq!(band_starts(0, 8).count(), 0);
    }

    #[test]
    fn spans_and_draw_target_are_offset_and_clipped() {
        let mut buf = [0u8; 8 * 4];
        let mut fb = match Gray8Framebuffer::new(&mut buf, 8, 4) {
            Ok(f) => f,
            Err(e) => panic!("{e:?}"),
        };
        let mut band = Band::new(&mut fb, 10);
        assert_eq!(
            band.bounds(),
            SpanBounds {
                x0: 0,
                y0: 10,
                x1: 8,
                y1: 14
            }
        );
        band.span(11, 1, 3, Gray8::new(9));
        band.span(9, 0, 8, Gray8::new(9)); // above the band: ignored
        band.span(14, 0, 8, Gray8::new(9)); // below: ignored
        let r = Rectangle::new(Point::new(6, 12), Size::new(5, 5));
        let _ = band.fill_solid(&r, Gray8::new(7));
        let _ = band.draw_iter([Pixel(Point::new(0, 13), Gray8::new(3))]);
        let px = |x, y| fb.pixel(x, y).map(|c| c.luma());
        assert_eq!(
            (px(0, 1), px(1, 1), px(2, 1), px(3, 1)),
            (Some(0), Some(9), Some(9), Some(0))
        );
        assert_eq!(
            (px(6, 2), px(7, 3), px(5, 2), px(6, 1)),
            (Some(7), Some(7), Some(0), Some(0))
        );
        assert_eq!(px(0, 3), Some(3));
        assert_eq!(fb.data().iter().filter(|&&v| v != 0).count(), 2 + 4 + 1);
    }
}
