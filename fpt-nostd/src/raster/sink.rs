//! Span sinks besides the framebuffers: any embedded-graphics `DrawTarget`,
//! and an id buffer.
//!
//! * [`DrawTargetSink`] sends each span as a one-row `fill_solid`, so the
//!   rasterizer can draw straight to a display driver. The first error
//!   stops further drawing and is kept for [`DrawTargetSink::finish`].
//! * [`IdBuffer`] stores `id + 1` per pixel (0 = nothing drawn) over a
//!   caller-supplied `&mut [u32]`: which polygon is visible where, for
//!   tests and picking.

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::{Point, Size};
use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::primitives::Rectangle;

use super::scan::{Paint, SpanBounds, SpanSink};
use super::transform::MAX_DIM;

/// Adapts any `DrawTarget` whose colour converts from `Rgb888`.
#[derive(Debug)]
pub struct DrawTargetSink<'a, D: DrawTarget> {
    target: &'a mut D,
    error: Option<D::Error>,
}

impl<'a, D: DrawTarget> DrawTargetSink<'a, D>
where
    D::Color: From<Rgb888>,
{
    /// Wraps `target`.
    pub fn new(target: &'a mut D) -> Self {
        DrawTargetSink {
            target,
            error: None,
        }
    }

    /// The first drawing error, if any.
    pub fn finish(self) -> Result<(), D::Error> {
        match self.error {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }
}

impl<D: DrawTarget> SpanSink for DrawTargetSink<'_, D>
where
    D::Color: From<Rgb888>,
{
    type Color = D::Color;
    fn color(&self, paint: &Paint) -> D::Color {
        D::Color::from(paint.rgb)
    }
    fn bounds(&self) -> SpanBounds {
        let b = self.target.bounding_box();
        let c = |v: u32| v.min(i32::MAX as u32) as i32;
        SpanBounds {
            x0: b.top_left.x,
            y0: b.top_left.y,
            x1: b.top_left.x.saturating_add(c(b.size.width)),
            y1: b.top_left.y.saturating_add(c(b.size.height)),
        }
    }
    fn span(&mut self, y: i32, x0: i32, x1: i32, color: D::Color) {
        if self.error.is_some() || x1 <= x0 {
            return;
        }
        let r = Rectangle::new(Point::new(x0, y), Size::new((x1 - x0) as u32, 1));
        if let Err(e) = self.target.fill_solid(&r, color) {
            self.error = Some(e);
        }
    }
}

/// Why an id buffer could not be created.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IdBufferError {
    /// A side is zero or above [`MAX_DIM`], or the slice is too short.
    BadSize,
}

impl core::fmt::Display for IdBufferError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            IdBufferError::BadSize => write!(
                f,
                "a side is zero or larger than {MAX_DIM} pixels, or the storage is too small"
            ),
        }
    }
}

/// One `u32` per pixel holding `id + 1` of the last polygon drawn there
/// (ids saturate at `u32::MAX − 1`).
#[derive(Debug)]
pub struct IdBuffer<'a> {
    buf: &'a mut [u32],
    width: u32,
    height: u32,
}

impl<'a> IdBuffer<'a> {
    /// Wraps `buf` (at least `width × height` entries), row-major.
    pub fn new(buf: &'a mut [u32], width: u32, height: u32) -> Result<Self, IdBufferError> {
        let ok = (1..=MAX_DIM).contains(&width)
            && (1..=MAX_DIM).contains(&height)
            && buf.len() >= width as usize * height as usize;
        if !ok {
            return Err(IdBufferError::BadSize);
        }
        Ok(IdBuffer { buf, width, height })
    }

    /// `id + 1` at `(x, y)`, 0 if nothing was drawn; `None` outside.
    pub fn get(&self, x: u32, y: u32) -> Option<u32> {
        (x < self.width && y < self.height).then(|| self.buf[(y * self.width + x) as usize])
    }

    /// Sets every pixel to 0.
    pub fn clear(&mut self) {
        self.buf.fill(0);
    }

    /// The pixels, row-major.
    pub fn data(&self) -> &[u32] {
        &self.buf[..(self.width * self.height) as usize]
    }
}

impl SpanSink for IdBuffer<'_> {
    type Color = u32;
    fn color(&self, paint: &Paint) -> u32 {
        paint.id.saturating_add(1)
    }
    fn bounds(&self) -> SpanBounds {
        SpanBounds::of_size(self.width, self.height)
    }
    fn span(&mut self, y: i32, x0: i32, x1: i32, color: u32) {
        if y < 0 || y >= self.height as i32 {
            return;
        }
        let (x0, x1) = (x0.max(0), x1.min(self.width as i32));
        if x0 < x1 {
            let s = y as usize * self.width as usize;
            self.buf[s + x0 as usize..s + x1 as usize].fill(color);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::mock_display::MockDisplay;
    use embedded_graphics::pixelcolor::BinaryColor;

    #[test]
    fn draw_target_sink_clips_to_target_and_reports_bounds() {
        let mut d: MockDisplay<BinaryColor> = MockDisplay::new();
        let mut s = DrawTargetSink::new(&mut d);
        assert_eq!(
            s.bounds(),
            SpanBounds {
                x0: 0,
                y0: 0,
                x1: 64,
                y1: 64
            }
        );
        let c = s.color(&Paint {
            rgb: Rgb888::new(255, 255, 255),
            id: 0,
        });
        s.span(3, 2, 5, c);
        assert!(s.finish().is_ok());
        let on = |x, y| d.get_pixel(Point::new(x, y)) == Some(BinaryColor::On);
        assert!(on(2, 3) && on(4, 3) && !on(5, 3) && !on(1, 3));
    }

    #[test]
    fn id_buffer_stores_id_plus_one() {
        let mut buf = [0u32; 12];
        let mut ids = match IdBuffer::new(&mut buf, 4, 3) {
            Ok(b) => b,
            Err(e) => panic!("{e:?}"),
        };
        let c = ids.color(&Paint {
            rgb: Rgb888::new(0, 0, 0),
            id: 7,
        });
        ids.span(1, -3, 2, c);
        ids.span(5, 0, 4, c); // outside: ignored
        assert_eq!(ids.data(), &[0, 0, 0, 0, 8, 8, 0, 0, 0, 0, 0, 0]);
        assert_eq!(ids.get(4, 0), None);
        assert!(IdBuffer::new(&mut [0u32; 5], 2, 3).is_err());
    }
}
