//! Framebuffers over caller-supplied storage, for `Rgb565`, `Rgb888`,
//! `Gray8` and packed `BinaryColor`.
//!
//! A [`Framebuffer<F>`] is a `width × height` image in a borrowed slice of
//! [`PixelFormat::Word`]s, rows stored top to bottom with
//! [`PixelFormat::words_per_row`] words each:
//! * [`Rgb565Format`]: one `u16` per pixel, the `Rgb565` storage value
//!   (native endianness; byte-swap when sending to a big-endian panel).
//! * [`Rgb888Format`]: three `u8` per pixel, in `r, g, b` order.
//! * [`Gray8Format`]: one `u8` per pixel (luma).
//! * [`BinaryFormat`]: one bit per pixel, 8 pixels per byte, the leftmost
//!   pixel in the most significant bit, each row padded to whole bytes;
//!   1 = `BinaryColor::On`.
//!
//! Each implements `DrawTarget` + `OriginDimensions` (with `fill_solid` and
//! `clear` overridden to fill whole row slices) and [`SpanSink`] (spans go
//! straight to the row fill: the rasterizer's fast path). Colours arrive as
//! `Rgb888` from shading and are converted once per polygon with
//! embedded-graphics' own `From` conversions (luma for grey, luma ≥ 128 for
//! binary), so the fast path and a generic `DrawTarget` agree exactly.

use core::convert::Infallible;
use core::marker::PhantomData;

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::{OriginDimensions, Point, Size};
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::{
    BinaryColor, Gray8, GrayColor, IntoStorage, PixelColor, Rgb565, Rgb888, RgbColor,
};
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::Pixel;

use super::scan::{rgb_word, word_rgb, Paint, SpanBounds, SpanSink};
use super::transform::MAX_DIM;
use crate::cpu::HAS_DIV;

/// How pixels of one colour type are laid out in words.
pub trait PixelFormat {
    /// The embedded-graphics colour type.
    type Color: PixelColor + From<Rgb888>;
    /// The storage word (plain data, so that bands of it can be lent
    /// for any lifetime).
    type Word: Copy + 'static;
    /// Words per row for `width` pixels.
    fn words_per_row(width: u32) -> usize;
    /// Sets pixels `x0..x1` of `row` (callers guarantee `x0 ≤ x1 ≤ width`).
    fn fill_row(row: &mut [Self::Word], x0: usize, x1: usize, c: Self::Color);
    /// Reads pixel `x` of `row`.
    fn get(row: &[Self::Word], x: usize) -> Self::Color;
    /// Sets every pixel of `rows`, whole rows of `width` pixels (the
    /// default fills row by row; formats without padding may do better).
    fn fill_rows(rows: &mut [Self::Word], width: u32, c: Self::Color) {
        let stride = Self::words_per_row(width).max(1);
        for row in rows.chunks_mut(stride) {
            Self::fill_row(row, 0, width as usize, c);
        }
    }
    /// A colour as a word of at most 24 bits, when the format's colours
    /// fit one (`None`, the default, when they do not): what a
    /// framebuffer's [`SpanSink::keep_color`] keeps for a polygon carried
    /// between bands, so that it is not converted from its rgb again.
    /// [`PixelFormat::word_color`] of it is the colour again.
    #[inline(always)]
    fn color_word(c: Self::Color) -> Option<u32> {
        let _ = c;
        None
    }
    /// The colour of a word of [`PixelFormat::color_word`] (`None` for a
    /// format whose colours it does not keep).
    #[inline(always)]
    fn word_color(w: u32) -> Option<Self::Color> {
        let _ = w;
        None
    }
}

/// A `Rgb565` as a word: its 16 bits ([`PixelFormat::color_word`] of both
/// `Rgb565` formats, whose pixels differ only in byte order).
#[inline(always)]
fn rgb565_word(c: Rgb565) -> u32 {
    u32::from(c.into_storage())
}

/// The `Rgb565` of [`rgb565_word`]'s word `w`.
#[inline(always)]
fn word_rgb565(w: u32) -> Rgb565 {
    Rgb565::from(RawU16::new(w as u16))
}

/// `Rgb565`, one `u16` per pixel.
#[derive(Clone, Copy, Debug, Default)]
pub struct Rgb565Format;
/// `Rgb565` in a display panel's byte order: one `u16` per pixel whose
/// two bytes in memory are big-endian (high byte first), whatever the
/// CPU's order, which is what MIPI-DCS panels (ST7789, ILI9341, ...) take
/// on their SPI bus: [`Framebuffer::panel_bytes`] goes to the display as
/// it is, with no per-pixel swap.
#[derive(Clone, Copy, Debug, Default)]
pub struct Rgb565BeFormat;
/// `Rgb888`, three bytes per pixel.
#[derive(Clone, Copy, Debug, Default)]
pub struct Rgb888Format;
/// `Gray8`, one byte per pixel.
#[derive(Clone, Copy, Debug, Default)]
pub struct Gray8Format;
/// `BinaryColor`, one bit per pixel, MSB first, rows padded to bytes.
#[derive(Clone, Copy, Debug, Default)]
pub struct BinaryFormat;

impl PixelFormat for Rgb565Format {
    type Color = Rgb565;
    type Word = u16;
    fn words_per_row(width: u32) -> usize {
        width as usize
    }
    fn fill_row(row: &mut [u16], x0: usize, x1: usize, c: Rgb565) {
        if let Some(s) = row.get_mut(x0..x1) {
            s.fill(c.into_storage());
        }
    }
    /// The whole buffer is pixels (no padding): two a store on its
    /// word-aligned middle, as a 32-bit core writes a word as fast as a
    /// halfword. (Spans keep the plain loop: most are short, and the split
    /// costs more than it saves there.)
    fn fill_rows(rows: &mut [u16], _width: u32, c: Rgb565) {
        let v = c.into_storage();
        let (head, body, tail) = bytemuck::pod_align_to_mut::<u16, u32>(rows);
        head.fill(v);
        // Blocks of 16 words, each a copy of one constant block: stores
        // of several registers at once (the plain word loop stored 4 words
        // in 6 instructions).
        let w = u32::from(v) * 0x0001_0001;
        let mut blocks = body.chunks_exact_mut(16);
        for b in &mut blocks {
            b.copy_from_slice(&[w; 16]);
        }
        blocks.into_remainder().fill(w);
        tail.fill(v);
    }
    #[inline(always)]
    fn color_word(c: Rgb565) -> Option<u32> {
        Some(rgb565_word(c))
    }
    #[inline(always)]
    fn word_color(w: u32) -> Option<Rgb565> {
        Some(word_rgb565(w))
    }
    fn get(row: &[u16], x: usize) -> Rgb565 {
        Rgb565::from(RawU16::new(row.get(x).copied().unwrap_or(0)))
    }
}

impl PixelFormat for Rgb565BeFormat {
    type Color = Rgb565;
    type Word = u16;
    fn words_per_row(width: u32) -> usize {
        width as usize
    }
    fn fill_row(row: &mut [u16], x0: usize, x1: usize, c: Rgb565) {
        if let Some(s) = row.get_mut(x0..x1) {
            s.fill(c.into_storage().to_be());
        }
    }
    #[inline(always)]
    fn color_word(c: Rgb565) -> Option<u32> {
        Some(rgb565_word(c))
    }
    #[inline(always)]
    fn word_color(w: u32) -> Option<Rgb565> {
        Some(word_rgb565(w))
    }
    fn get(row: &[u16], x: usize) -> Rgb565 {
        Rgb565::from(RawU16::new(u16::from_be(row.get(x).copied().unwrap_or(0))))
    }
}

impl<'a> Framebuffer<'a, Rgb565BeFormat> {
    /// The pixels as bytes in the panel's order: row-major, two bytes a
    /// pixel, high byte first (what a MIPI-DCS `RAMWR` takes).
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::Rgb565;
    /// use fpt_nostd::raster::{Framebuffer, Rgb565BeFormat};
    /// let mut buf = [0u16; 2];
    /// let mut fb = Framebuffer::<Rgb565BeFormat>::new(&mut buf, 2, 1).unwrap();
    /// fb.fill_all(Rgb565::new(31, 0, 1)); // 0xf801
    /// assert_eq!(fb.panel_bytes(), &[0xf8, 0x01, 0xf8, 0x01]);
    /// ```
    pub fn panel_bytes(&self) -> &[u8] {
        bytemuck::cast_slice(self.data())
    }
}

impl PixelFormat for Rgb888Format {
    type Color = Rgb888;
    type Word = u8;
    fn words_per_row(width: u32) -> usize {
        3 * width as usize
    }
    fn fill_row(row: &mut [u8], x0: usize, x1: usize, c: Rgb888) {
        if let Some(s) = row.get_mut(3 * x0..3 * x1) {
            for px in s.chunks_exact_mut(3) {
                px.copy_from_slice(&[c.r(), c.g(), c.b()]);
            }
        }
    }
    fn get(row: &[u8], x: usize) -> Rgb888 {
        match row.get(3 * x..3 * x + 3) {
            Some(p) => Rgb888::new(p[0], p[1], p[2]),
            None => Rgb888::BLACK,
        }
    }
}

impl PixelFormat for Gray8Format {
    type Color = Gray8;
    type Word = u8;
    fn words_per_row(width: u32) -> usize {
        width as usize
    }
    fn fill_row(row: &mut [u8], x0: usize, x1: usize, c: Gray8) {
        if let Some(s) = row.get_mut(x0..x1) {
            s.fill(c.luma());
        }
    }
    fn get(row: &[u8], x: usize) -> Gray8 {
        Gray8::new(row.get(x).copied().unwrap_or(0))
    }
}

impl PixelFormat for BinaryFormat {
    type Color = BinaryColor;
    type Word = u8;
    fn words_per_row(width: u32) -> usize {
        (width as usize).div_ceil(8)
    }
    fn fill_row(row: &mut [u8], x0: usize, x1: usize, c: BinaryColor) {
        if x0 >= x1 || x1.div_ceil(8) > row.len() {
            return;
        }
        let on = c.is_on();
        let apply = |b: &mut u8, mask: u8| {
            if on {
                *b |= mask
            } else {
                *b &= !mask
            }
        };
        let (b0, b1) = (x0 / 8, (x1 - 1) / 8);
        // Bits of byte b0 from x0 on, of byte b1 up to x1 (MSB = leftmost).
        let head = 0xFFu8 >> (x0 % 8);
        let tail = 0xFFu8 << (7 - (x1 - 1) % 8);
        if b0 == b1 {
            apply(&mut row[b0], head & tail);
        } else {
            apply(&mut row[b0], head);
            row[b0 + 1..b1].fill(if on { 0xFF } else { 0 });
            apply(&mut row[b1], tail);
        }
    }
    fn get(row: &[u8], x: usize) -> BinaryColor {
        let bit = row.get(x / 8).map_or(0, |b| (b >> (7 - x % 8)) & 1);
        BinaryColor::from(bit != 0)
    }
}

/// Why a framebuffer could not be created.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FramebufferError {
    /// A side is zero or larger than [`MAX_DIM`].
    BadSize,
    /// The storage slice is shorter than `height × words_per_row(width)`.
    BufferTooSmall,
}

impl core::fmt::Display for FramebufferError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            FramebufferError::BadSize => {
                write!(f, "a side is zero or larger than {MAX_DIM} pixels")
            }
            FramebufferError::BufferTooSmall => f.write_str("the pixel storage is too small"),
        }
    }
}

/// An image of `F`-format pixels in borrowed storage (see module docs).
#[derive(Debug)]
pub struct Framebuffer<'a, F: PixelFormat> {
    buf: &'a mut [F::Word],
    width: u32,
    height: u32,
    stride: usize,
    _f: PhantomData<F>,
}

/// `Rgb565` framebuffer over `&mut [u16]`.
pub type Rgb565Framebuffer<'a> = Framebuffer<'a, Rgb565Format>;
/// `Rgb888` framebuffer over `&mut [u8]`.
pub type Rgb888Framebuffer<'a> = Framebuffer<'a, Rgb888Format>;
/// `Gray8` framebuffer over `&mut [u8]`.
pub type Gray8Framebuffer<'a> = Framebuffer<'a, Gray8Format>;
/// Packed `BinaryColor` framebuffer over `&mut [u8]`.
pub type BinaryFramebuffer<'a> = Framebuffer<'a, BinaryFormat>;

impl<'a, F: PixelFormat> Framebuffer<'a, F> {
    /// Words of storage needed for `width × height`.
    pub fn required_len(width: u32, height: u32) -> usize {
        F::words_per_row(width) * height as usize
    }

    /// Wraps `buf` as a `width × height` image (extra storage is unused).
    pub fn new(buf: &'a mut [F::Word], width: u32, height: u32) -> Result<Self, FramebufferError> {
        if !(1..=MAX_DIM).contains(&width) || !(1..=MAX_DIM).contains(&height) {
            return Err(FramebufferError::BadSize);
        }
        let stride = F::words_per_row(width);
        if buf.len() < stride * height as usize {
            return Err(FramebufferError::BufferTooSmall);
        }
        Ok(Framebuffer {
            buf,
            width,
            height,
            stride,
            _f: PhantomData,
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The storage of row `y` (`None` outside the image).
    pub fn row(&self, y: u32) -> Option<&[F::Word]> {
        let s = y as usize * self.stride;
        (y < self.height).then(|| &self.buf[s..s + self.stride])
    }

    /// The whole storage in use (`height` rows).
    pub fn data(&self) -> &[F::Word] {
        &self.buf[..self.stride * self.height as usize]
    }

    /// The whole storage the framebuffer was made over (all of it, not
    /// only the `height` rows in use), given back: what a band loop that
    /// lends a band to a display driver gets back to draw the next one in.
    ///
    /// ```
    /// use fpt_nostd::raster::Rgb565Framebuffer;
    /// let mut buf = [0u16; 8];
    /// let fb = Rgb565Framebuffer::new(&mut buf, 2, 3).unwrap();
    /// assert_eq!(fb.data().len(), 6);
    /// assert_eq!(fb.into_storage().len(), 8);
    /// ```
    pub fn into_storage(self) -> &'a mut [F::Word] {
        self.buf
    }

    /// The colour at `(x, y)`, `None` outside the image.
    pub fn pixel(&self, x: u32, y: u32) -> Option<F::Color> {
        if x >= self.width {
            return None;
        }
        self.row(y).map(|r| F::get(r, x as usize))
    }

    /// Fills `x0..x1` of row `y`, clipped to the image.
    pub fn fill_span(&mut self, y: i32, x0: i32, x1: i32, c: F::Color) {
        // One unsigned comparison is both `y ≥ 0` and `y < height`.
        if y as u32 >= self.height {
            return;
        }
        let x0 = x0.max(0) as usize;
        let x1 = x1.min(self.width as i32);
        if x1 <= x0 as i32 {
            return;
        }
        let s = y as usize * self.stride;
        F::fill_row(&mut self.buf[s..s + self.stride], x0, x1 as usize, c);
    }

    /// Fills the whole image.
    pub fn fill_all(&mut self, c: F::Color) {
        let n = self.stride * self.height as usize;
        if let Some(rows) = self.buf.get_mut(..n) {
            F::fill_rows(rows, self.width, c);
        }
    }
}

impl<F: PixelFormat> OriginDimensions for Framebuffer<'_, F> {
    fn size(&self) -> Size {
        Size::new(self.width, self.height)
    }
}

impl<F: PixelFormat> DrawTarget for Framebuffer<'_, F> {
    type Color = F::Color;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<F::Color>>,
    {
        for Pixel(Point { x, y }, c) in pixels {
            self.fill_span(y, x, x.saturating_add(1), c);
        }
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, color: F::Color) -> Result<(), Infallible> {
        let a = area.intersection(&Rectangle::new(Point::zero(), self.size()));
        if a.is_zero_sized() {
            return Ok(());
        }
        let (x0, x1) = (a.top_left.x, a.top_left.x + a.size.width as i32);
        for y in a.rows() {
            self.fill_span(y, x0, x1, color);
        }
        Ok(())
    }

    fn clear(&mut self, color: F::Color) -> Result<(), Infallible> {
        self.fill_all(color);
        Ok(())
    }
}

impl<F: PixelFormat> SpanSink for Framebuffer<'_, F> {
    type Color = F::Color;
    const NEEDS_ID: bool = false;
    fn color(&self, paint: &Paint) -> F::Color {
        F::Color::from(paint.rgb)
    }
    #[inline(always)]
    fn keep_color(&self, color: F::Color, paint: &Paint) -> u32 {
        F::color_word(color).unwrap_or_else(|| rgb_word(paint.rgb))
    }
    #[inline(always)]
    fn kept_color(&self, word: u32) -> F::Color {
        F::word_color(word).unwrap_or_else(|| F::Color::from(word_rgb(word)))
    }
    fn bounds(&self) -> SpanBounds {
        SpanBounds::of_size(self.width, self.height)
    }
    fn span(&mut self, y: i32, x0: i32, x1: i32, c: F::Color) {
        self.fill_span(y, x0, x1, c);
    }
    /// Steps a row slice down the image instead of computing and checking
    /// each row's place ([`Framebuffer::fill_span`]). The spans of a run
    /// that starts outside the image, of rows past its bottom, and spans
    /// not within its columns (the fill never sends any of these) are
    /// counted but dropped, not clipped. (Painting the rows of a run that
    /// starts above the image made the fill's code dearer: +3.6 % on a
    /// `bench_city` frame, Cortex-M4F.)
    #[inline(always)]
    fn span_rows<I: Iterator<Item = (i32, i32)>>(
        &mut self,
        y: i32,
        spans: I,
        c: F::Color,
    ) -> usize {
        let stride = self.stride.max(1);
        let from = if (y as u32) < self.height {
            y as usize * stride
        } else {
            self.buf.len()
        };
        let end = self.buf.len().min(stride * self.height as usize);
        let rows = self.buf.get_mut(from..end).unwrap_or_default();
        if HAS_DIV {
            paint_rows::<F>(rows.chunks_exact_mut(stride), spans, c)
        } else {
            paint_rows::<F>(Rows { rest: rows, stride }, spans, c)
        }
    }
}

/// [`Framebuffer`]'s `span_rows` loop: span `k` on the `k`-th row of
/// `rows` (counted, and dropped when the rows ran out).
#[inline(always)]
fn paint_rows<'r, F: PixelFormat>(
    mut rows: impl Iterator<Item = &'r mut [F::Word]>,
    spans: impl Iterator<Item = (i32, i32)>,
    c: F::Color,
) -> usize
where
    F::Word: 'r,
{
    let mut n = 0;
    for (x0, x1) in spans {
        let row = rows.next();
        if x0 < x1 {
            n += 1;
            if let Some(row) = row {
                // A negative `x0` becomes a huge index: no pixel.
                F::fill_row(row, x0 as usize, x1 as usize, c);
            }
        }
    }
    n
}

/// The rows `chunks_exact_mut(stride)` gives, without its set-up's
/// `len % stride`: on a core without a divider ([`HAS_DIV`]) that is a
/// call of about 70 instructions for every run of rows (on a Cortex-M4
/// the division is one instruction, and the iterator below made the band
/// frames' row loops 0.1–0.4 % dearer, so it keeps `chunks_exact_mut`).
struct Rows<'r, W> {
    rest: &'r mut [W],
    stride: usize,
}

impl<'r, W> Iterator for Rows<'r, W> {
    type Item = &'r mut [W];
    #[inline(always)]
    fn next(&mut self) -> Option<&'r mut [W]> {
        let (row, tail) = core::mem::take(&mut self.rest).split_at_mut_checked(self.stride)?;
        self.rest = tail;
        Some(row)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// The division-free rows are `chunks_exact_mut`'s, ragged ends and
    /// empty buffers included.
    #[test]
    fn rows_are_chunks_exact() {
        for len in 0..40usize {
            for stride in 1..12usize {
                let mut a: std::vec::Vec<u16> = (0..len as u16).collect();
                let mut b = a.clone();
                let want: std::vec::Vec<std::vec::Vec<u16>> =
                    a.chunks_exact_mut(stride).map(|r| r.to_vec()).collect();
                let got: std::vec::Vec<std::vec::Vec<u16>> = Rows {
                    rest: &mut b[..],
                    stride,
                }
                .map(|r| r.to_vec())
                .collect();
                assert_eq!(got, want, "{len} {stride}");
            }
        }
    }
    use embedded_graphics::primitives::{Primitive, PrimitiveStyle, Triangle};
    use embedded_graphics::Drawable;
    use std::vec;

    /// The colour word a framebuffer keeps for a polygon carried between
    /// bands gives back the colour its paint converts to, for every
    /// format (its own word for `Rgb565`, the rgb for the others).
    fn check_kept_color<F: PixelFormat>(width: u32, init: F::Word)
    where
        F::Color: PartialEq + core::fmt::Debug,
    {
        let mut buf = vec![init; F::words_per_row(width)];
        let fb = Framebuffer::<F>::new(&mut buf, width, 1).unwrap();
        for k in 0..4096u32 {
            let rgb = Rgb888::new(
                (k * 37) as u8,
                ((k * 101) >> 3) as u8,
                ((k * 13) >> 4) as u8,
            );
            let paint = Paint { rgb, id: 0 };
            let color = fb.color(&paint);
            let word = fb.keep_color(color, &paint);
            assert!(word < 1 << 24);
            assert_eq!(fb.kept_color(word), color);
        }
    }

    #[test]
    fn kept_colors_round_trip() {
        check_kept_color::<Rgb565Format>(3, 0);
        check_kept_color::<Rgb565BeFormat>(3, 0);
        check_kept_color::<Rgb888Format>(3, 0);
        check_kept_color::<Gray8Format>(3, 0);
        check_kept_color::<BinaryFormat>(9, 0);
    }

    /// Row fill against a per-pixel reference for every x0/x1 pair.
    fn check_format<F: PixelFormat>(width: u32, colors: [F::Color; 2], init: F::Word)
    where
        F::Color: PartialEq + core::fmt::Debug,
    {
        let n = F::words_per_row(width);
        for x0 in 0..=width as usize {
            for x1 in x0..=width as usize {
                let mut row = vec![init; n];
                F::fill_row(&mut row, 0, width as usize, colors[0]);
                F::fill_row(&mut row, x0, x1, colors[1]);
                for x in 0..width as usize {
                    let want = if (x0..x1).contains(&x) {
                        colors[1]
                    } else {
                        colors[0]
                    };
                    assert_eq!(F::get(&row, x), want, "x0={x0} x1={x1} x={x}");
                }
            }
        }
    }

    /// A framebuffer's `span_rows` (a row slice stepped down the image)
    /// paints and counts what `span` once a row does, with the band's
    /// offset too, and consumes every span even for rows outside; a run
    /// that starts above the image is counted and dropped whole.
    #[test]
    fn span_rows_equal_span_per_row() {
        use super::super::band::Band;
        let (w, h) = (9u32, 6u32);
        let runs: [(i32, &[(i32, i32)]); 4] = [
            (0, &[(0, 9), (3, 3), (2, 7), (8, 9)]),
            (2, &[(1, 4), (5, 2), (0, 1)]),
            (4, &[(4, 6), (0, 9), (7, 8)]), // the last row is outside
            (-1, &[(0, 3), (2, 5)]),        // starts above: dropped whole
        ];
        for y0 in [0, 3] {
            let mut a = vec![0u16; (w * h) as usize];
            let mut b = a.clone();
            let mut fa = Rgb565Framebuffer::new(&mut a, w, h).unwrap();
            let mut fb = Rgb565Framebuffer::new(&mut b, w, h).unwrap();
            let c = Rgb565::new(31, 0, 7);
            for (y, spans) in runs {
                let mut used = 0;
                let mut band = Band::new(&mut fa, y0);
                let n = band.span_rows(
                    y + y0,
                    spans.iter().map(|&s| {
                        used += 1;
                        s
                    }),
                    c,
                );
                assert_eq!(used, spans.len());
                let mut want = 0;
                for (k, &(x0, x1)) in spans.iter().enumerate() {
                    if x0 < x1 {
                        if y >= 0 {
                            fb.span(y + k as i32, x0, x1, c);
                        }
                        want += 1;
                    }
                }
                assert_eq!(n, want);
            }
            assert_eq!(fa.data(), fb.data());
        }
    }

    #[test]
    fn row_fills_match_per_pixel_reference() {
        check_format::<Rgb565Format>(13, [Rgb565::new(1, 2, 3), Rgb565::new(31, 0, 17)], 0);
        check_format::<Rgb888Format>(7, [Rgb888::new(1, 2, 3), Rgb888::new(200, 0, 9)], 0);
        check_format::<Gray8Format>(9, [Gray8::new(5), Gray8::new(250)], 0);
        for w in [1, 7, 8, 9, 17, 24] {
            check_format::<BinaryFormat>(w, [BinaryColor::Off, BinaryColor::On], 0);
            check_format::<BinaryFormat>(w, [BinaryColor::On, BinaryColor::Off], 0xFF);
        }
    }

    /// `fill_all` (the word-wide path for RGB565) against span-by-span
    /// fills, on storage starting at both halfword alignments, with spare
    /// words after the image that must stay untouched.
    #[test]
    fn fill_all_equals_row_fills_at_any_alignment() {
        fn check<F: PixelFormat>(width: u32, height: u32, init: F::Word, c: F::Color)
        where
            F::Word: PartialEq + core::fmt::Debug,
        {
            let n = Framebuffer::<F>::required_len(width, height);
            for skip in 0..2 {
                let mut fast = vec![init; n + 5];
                let mut slow = fast.clone();
                Framebuffer::<F>::new(&mut fast[skip..], width, height)
                    .unwrap_or_else(|e| panic!("{e:?}"))
                    .fill_all(c);
                let mut fb = Framebuffer::<F>::new(&mut slow[skip..], width, height)
                    .unwrap_or_else(|e| panic!("{e:?}"));
                for y in 0..height as i32 {
                    fb.fill_span(y, 0, width as i32, c);
                }
                assert_eq!(fast, slow, "{width}x{height} from word {skip}");
            }
        }
        for (w, h) in [(1, 1), (2, 1), (3, 2), (13, 3), (240, 2), (240, 9)] {
            check::<Rgb565Format>(w, h, 0x5a5a, Rgb565::new(31, 7, 9));
            check::<Gray8Format>(w, h, 3, Gray8::new(200));
            check::<BinaryFormat>(w, h, 0x55, BinaryColor::On);
            check::<Rgb888Format>(w, h, 1, Rgb888::new(9, 8, 7));
        }
    }

    #[test]
    fn binary_layout_is_msb_first_with_padded_rows() {
        let mut buf = [0u8; 4];
        let mut fb = BinaryFramebuffer::new(&mut buf, 10, 2).unwrap_or_else(|e| panic!("{e:?}"));
        fb.fill_span(0, 0, 1, BinaryColor::On);
        fb.fill_span(1, 8, 10, BinaryColor::On);
        assert_eq!(fb.data(), &[0x80, 0x00, 0x00, 0xC0]);
    }

    #[test]
    fn constructor_checks() {
        let mut small = [0u16; 10];
        assert_eq!(
            Rgb565Framebuffer::new(&mut small, 4, 3).err(),
            Some(FramebufferError::BufferTooSmall)
        );
        assert_eq!(
            Rgb565Framebuffer::new(&mut small, 0, 3).err(),
            Some(FramebufferError::BadSize)
        );
        assert_eq!(Rgb888Framebuffer::required_len(4, 3), 36);
        assert_eq!(BinaryFramebuffer::required_len(9, 3), 6);
    }

    /// A generic DrawTarget with only `draw_iter` (every default method).
    struct Plain(std::vec::Vec<Option<Gray8>>, u32, u32);
    impl OriginDimensions for Plain {
        fn size(&self) -> Size {
            Size::new(self.1, self.2)
        }
    }
    impl DrawTarget for Plain {
        type Color = Gray8;
        type Error = Infallible;
        fn draw_iter<I: IntoIterator<Item = Pixel<Gray8>>>(
            &mut self,
            it: I,
        ) -> Result<(), Infallible> {
            for Pixel(p, c) in it {
                if p.x >= 0 && p.y >= 0 && (p.x as u32) < self.1 && (p.y as u32) < self.2 {
                    self.0[(p.y as u32 * self.1 + p.x as u32) as usize] = Some(c);
                }
            }
            Ok(())
        }
    }

    #[test]
    fn overridden_fill_solid_equals_default_draw_iter() {
        let (w, h) = (23u32, 17u32);
        let mut buf = vec![0u8; (w * h) as usize];
        let mut fb = Gray8Framebuffer::new(&mut buf, w, h).unwrap_or_else(|e| panic!("{e:?}"));
        let mut plain = Plain(vec![Some(Gray8::new(0)); (w * h) as usize], w, h);
        let rects = [
            ((-5, -3), (10, 8)),
            ((4, 5), (30, 2)),
            ((20, 15), (9, 9)),
            ((3, 3), (0, 5)),
        ];
        for (k, ((x, y), (rw, rh))) in rects.into_iter().enumerate() {
            let r = Rectangle::new(Point::new(x, y), Size::new(rw, rh));
            let c = Gray8::new(40 * k as u8 + 30);
            let _ = fb.fill_solid(&r, c);
            let _ = plain.fill_solid(&r, c);
        }
        let tri = Triangle::new(Point::new(-3, 2), Point::new(20, 8), Point::new(6, 30))
            .into_styled(PrimitiveStyle::with_fill(Gray8::new(255)));
        let _ = tri.draw(&mut fb);
        let _ = tri.draw(&mut plain);
        for y in 0..h {
            for x in 0..w {
                assert_eq!(fb.pixel(x, y), plain.0[(y * w + x) as usize], "({x},{y})");
            }
        }
    }
}
