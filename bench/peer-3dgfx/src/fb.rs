//! The framebuffer the peer draws into: a slice of RGB565 pixels behind the
//! `embedded-graphics` `DrawTarget` trait, written like the peer's own
//! `examples/integration_minimal.rs` (its recommended MCU integration):
//! per-pixel `draw_iter` with clipping, and a bulk `fill_solid`.

use core::convert::Infallible;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Dimensions, OriginDimensions, Size};
use embedded_graphics_core::pixelcolor::Rgb565;
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;

pub struct Framebuffer<'a> {
    pixels: &'a mut [Rgb565],
    width: usize,
    height: usize,
}

impl<'a> Framebuffer<'a> {
    pub fn new(pixels: &'a mut [Rgb565], width: usize, height: usize) -> Self {
        assert_eq!(pixels.len(), width * height);
        Framebuffer {
            pixels,
            width,
            height,
        }
    }

    /// Every pixel set to `color`.
    pub fn fill(&mut self, color: Rgb565) {
        self.pixels.fill(color);
    }

    /// The pixels, row-major from the top left.
    pub fn pixels(&self) -> &[Rgb565] {
        self.pixels
    }

    /// How many pixels differ from `background`.
    pub fn covered(&self, background: Rgb565) -> usize {
        self.pixels.iter().filter(|&&p| p != background).count()
    }
}

impl OriginDimensions for Framebuffer<'_> {
    fn size(&self) -> Size {
        Size::new(self.width as u32, self.height as u32)
    }
}

impl DrawTarget for Framebuffer<'_> {
    type Color = Rgb565;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        for Pixel(point, color) in pixels {
            // The rasterizer can hand out pixels just off the screen.
            if let (Ok(x), Ok(y)) = (usize::try_from(point.x), usize::try_from(point.y)) {
                if x < self.width && y < self.height {
                    self.pixels[y * self.width + x] = color;
                }
            }
        }
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, color: Self::Color) -> Result<(), Self::Error> {
        let area = area.intersection(&self.bounding_box());
        let Some(bottom_right) = area.bottom_right() else {
            return Ok(());
        };
        let (x0, x1) = (area.top_left.x as usize, bottom_right.x as usize);
        for y in area.top_left.y as usize..=bottom_right.y as usize {
            self.pixels[y * self.width + x0..=y * self.width + x1].fill(color);
        }
        Ok(())
    }
}
