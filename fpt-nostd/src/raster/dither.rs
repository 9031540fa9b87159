//! Ordered dithering for grey and monochrome panels (the `dither` effect).
//!
//! [`Dither`] is a [`SpanSink`] over a `Gray8` or `BinaryColor`
//! framebuffer (or one band of it). A polygon's colour becomes its luma
//! (embedded-graphics' `Rgb888 → Gray8` conversion, the one the plain
//! framebuffer uses); each pixel then gets one of the panel's `levels`
//! grey levels (2 for `BinaryColor`; for `Gray8`, e.g. 16 for a 4-bit
//! SSD1327-class OLED), chosen with the 4×4 Bayer threshold of its frame
//! position:
//!
//! ```text
//! level = (luma · (levels − 1) + t(x, y)) / 255,   t = 16 · bayer[y mod 4][x mod 4] + 8
//! ```
//!
//! (`t` runs over 8, 24, …, 248: plain rounding would be `t = 127` on every
//! pixel, which [`Dither::rounding`] does, to compare). The pattern is fixed
//! to frame coordinates, so bands ([`Dither::band`]) give the full frame's
//! pixels exactly. Pixels of one span that share a threshold column get the
//! same level, so a span is filled as at most four runs per distinct level
//! pattern, and a span whose four levels agree (flat colours on a panel
//! level) is one fill.
//!
//! This is the only per-pixel effect; choosing this sink *is* turning it
//! on, so a scene without it has no per-pixel test anywhere.

use embedded_graphics::pixelcolor::{BinaryColor, Gray8, GrayColor};

use super::framebuffer::{BinaryFormat, Framebuffer, Gray8Format, PixelFormat};
use super::scan::{Paint, SpanBounds, SpanSink};

/// The 4×4 Bayer matrix (values 0..16).
const BAYER: [[u8; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];

/// Pixel formats a [`Dither`] sink can write.
pub trait DitherFormat: PixelFormat {
    /// Most levels the format can show.
    const MAX_LEVELS: u16;
    /// The colour of level `level` out of `levels`.
    fn level_color(level: u16, levels: u16) -> Self::Color;
}

impl DitherFormat for Gray8Format {
    const MAX_LEVELS: u16 = 256;
    fn level_color(level: u16, levels: u16) -> Gray8 {
        let top = u32::from(levels.max(2) - 1);
        Gray8::new(((u32::from(level) * 255 + top / 2) / top).min(255) as u8)
    }
}

impl DitherFormat for BinaryFormat {
    const MAX_LEVELS: u16 = 2;
    fn level_color(level: u16, _: u16) -> BinaryColor {
        if level > 0 {
            BinaryColor::On
        } else {
            BinaryColor::Off
        }
    }
}

/// A dithering sink over a framebuffer (see the module docs).
pub struct Dither<'f, 'a, F: DitherFormat> {
    fb: &'f mut Framebuffer<'a, F>,
    y0: i32,
    levels: u16,
    ordered: bool,
}

impl<'f, 'a, F: DitherFormat> Dither<'f, 'a, F> {
    /// Ordered dithering to `levels` levels (clamped to `2..=F::MAX_LEVELS`)
    /// into the whole frame `fb`.
    pub fn new(fb: &'f mut Framebuffer<'a, F>, levels: u16) -> Self {
        Self::band(fb, 0, levels)
    }

    /// Like [`Dither::new`] into a band: `fb`'s row 0 is frame row `y0`.
    pub fn band(fb: &'f mut Framebuffer<'a, F>, y0: i32, levels: u16) -> Self {
        Dither {
            fb,
            y0,
            levels: levels.clamp(2, F::MAX_LEVELS),
            ordered: true,
        }
    }

    /// The same quantisation with plain rounding instead of the pattern
    /// (what the panel shows without the effect).
    pub fn rounding(mut self) -> Self {
        self.ordered = false;
        self
    }

    /// The level of luma `l` at frame pixel `(x, y)`.
    #[inline]
    fn level(&self, l: u8, x: i32, y: i32) -> u16 {
        let t = if self.ordered {
            let row = BAYER[(y & 3) as usize];
            u32::from(row[(x & 3) as usize]) * 16 + 8
        } else {
            127
        };
        ((u32::from(l) * u32::from(self.levels - 1) + t) / 255) as u16
    }
}

impl<F: DitherFormat> core::fmt::Debug for Dither<'_, '_, F> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Dither")
            .field("y0", &self.y0)
            .field("levels", &self.levels)
            .field("ordered", &self.ordered)
            .finish_non_exhaustive()
    }
}

impl<F: DitherFormat> SpanSink for Dither<'_, '_, F> {
    type Color = u8;
    const NEEDS_ID: bool = false;

    fn color(&self, paint: &Paint) -> u8 {
        Gray8::from(paint.rgb).luma()
    }

    fn bounds(&self) -> SpanBounds {
        let mut b = SpanBounds::of_size(self.fb.width(), self.fb.height());
        b.y0 = b.y0.saturating_add(self.y0);
        b.y1 = b.y1.saturating_add(self.y0);
        b
    }

    fn span(&mut self, y: i32, x0: i32, x1: i32, l: u8) {
        let local = y.wrapping_sub(self.y0);
        let lv = [0, 1, 2, 3].map(|k| self.level(l, x0.wrapping_add(k), y));
        if lv.iter().all(|&v| v == lv[0]) {
            let c = F::level_color(lv[0], self.levels);
            self.fb.fill_span(local, x0, x1, c);
            return;
        }
        // Four interleaved columns: pixel x has the level of (x − x0) mod 4.
        let mut x = x0;
        while x < x1 {
            let c = F::level_color(lv[(x.wrapping_sub(x0) & 3) as usize], self.levels);
            self.fb.fill_span(local, x, x.saturating_add(1), c);
            x += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use embedded_graphics::pixelcolor::Rgb888;
    use std::vec;

    fn paint(g: u8) -> Paint {
        Paint {
            rgb: Rgb888::new(g, g, g),
            id: 0,
        }
    }

    /// The pattern, per pixel, from the formula in the module docs.
    fn want(l: u8, x: i32, y: i32, levels: u32) -> u32 {
        let t = u32::from(BAYER[(y & 3) as usize][(x & 3) as usize]) * 16 + 8;
        (u32::from(l) * (levels - 1) + t) / 255
    }

    #[test]
    fn binary_spans_match_the_per_pixel_formula_and_average_the_grey() {
        for g in [0u8, 1, 60, 127, 128, 200, 254, 255] {
            let mut buf = vec![0u8; 8 * 13];
            let mut fb = Framebuffer::<BinaryFormat>::new(&mut buf, 64, 13).unwrap();
            let mut d = Dither::new(&mut fb, 2);
            let c = d.color(&paint(g));
            for y in 0..13 {
                d.span(y, y, 64 - 2 * y, c);
            }
            for y in 0..13 {
                for x in 0..64 {
                    let px = fb.pixel(x as u32, y as u32).unwrap();
                    let inside = x >= y && x < 64 - 2 * y;
                    let expect = inside && want(g, x, y, 2) == 1;
                    assert_eq!(px.is_on(), expect, "grey {g} at {x},{y}");
                }
            }
        }
        // Over a 4×4 tile the lit fraction is the grey level to 1/16.
        let mut buf = vec![0u8; 4];
        let mut fb = Framebuffer::<BinaryFormat>::new(&mut buf, 8, 4).unwrap();
        let mut d = Dither::new(&mut fb, 2);
        for y in 0..4 {
            d.span(y, 0, 4, 100);
        }
        let lit = (0..4)
            .flat_map(|y| (0..4).map(move |x| (x, y)))
            .filter(|&(x, y)| fb.pixel(x, y).unwrap().is_on())
            .count();
        assert_eq!(lit, (100 * 16 + 127) / 255);
    }

    #[test]
    fn gray_levels_and_bands_agree_with_the_full_frame() {
        let draw = |fb: &mut Framebuffer<'_, Gray8Format>, y0: i32, rows: i32| {
            let mut d = Dither::band(fb, y0, 16);
            for y in y0..y0 + rows {
                d.span(y, 3, 29, 77);
            }
        };
        let mut full = vec![0u8; 32 * 12];
        let mut fb = Framebuffer::<Gray8Format>::new(&mut full, 32, 12).unwrap();
        draw(&mut fb, 0, 12);
        let mut banded = vec![];
        for y0 in (0..12).step_by(5) {
            let rows = 5.min(12 - y0);
            let mut b = vec![0u8; 32 * rows as usize];
            let mut fb = Framebuffer::<Gray8Format>::new(&mut b, 32, rows as u32).unwrap();
            draw(&mut fb, y0, rows);
            banded.extend(b);
        }
        assert_eq!(full, banded);
        for y in 0..12 {
            for x in 3..29 {
                let lv = want(77, x, y, 16);
                assert_eq!(u32::from(full[(y * 32 + x) as usize]), (lv * 255 + 7) / 15);
            }
        }
        // Rounding: one level everywhere (77 · 15 / 255 = 4.53 → 5).
        let mut b = vec![0u8; 8];
        let mut fb = Framebuffer::<Gray8Format>::new(&mut b, 8, 1).unwrap();
        let mut d = Dither::new(&mut fb, 16).rounding();
        d.span(0, 0, 8, 77);
        assert!(b
            .iter()
            .all(|&v| v == Gray8Format::level_color(5, 16).luma()));
    }
}
