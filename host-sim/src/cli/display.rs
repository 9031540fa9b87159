//! What `fpt render` simulates of a display, only when asked.
//!
//! The framebuffer format (`--format`) is the panel's storage: the default
//! `rgb888` keeps the renderer's exact colours, `rgb565` quantises to 16-bit
//! colour, `gray8` to grey (to `--gray-levels N` levels
//! when given: a 4-bit OLED has 16), `mono` to one bit per pixel, by a
//! threshold, or by ordered dithering when the scene's `dither` effect is on
//! (see `fpt_nostd::raster::dither`). `--display` then chooses how the PNG
//! shows those pixels: `plain` one image pixel per display pixel as stored,
//! or the look of a panel: every display pixel drawn [`PANEL_SCALE`] image
//! pixels wide with a one-pixel gap, its stored level (the luma of its
//! colour) mapped linearly between the panel's off colour (level 0, also
//! the gaps) and its on colour (full level). The off and on colours are
//! those of `embedded-graphics-simulator`'s `BinaryColorTheme` of the same
//! name, but the mapping is ours: the simulator's themes are for binary
//! displays and turn every non-black pixel fully on, which would show a
//! 4-level grey picture in 2 colours. The panel looks make sense for `mono`
//! and `gray8`.

use super::CliError;
use crate::cli_err;
use embedded_graphics::geometry::{Point, Size};
use embedded_graphics::pixelcolor::{PixelColor, Rgb888, RgbColor};
use embedded_graphics::prelude::{OriginDimensions, Primitive};
use embedded_graphics::primitives::{PrimitiveStyle, Rectangle};
use embedded_graphics::Drawable;
use embedded_graphics_simulator::{OutputImage, OutputSettings, SimulatorDisplay};

/// The names `--display` accepts.
pub const PANELS: [&str; 6] = [
    "plain",
    "oled-blue",
    "oled-white",
    "lcd-green",
    "lcd-white",
    "lcd-blue",
];

/// How a picture is shown (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Panel {
    /// Pixels as stored, one image pixel each.
    #[default]
    Plain,
    /// Light blue on dark blue (SSD1306-style OLED).
    OledBlue,
    /// White on black OLED.
    OledWhite,
    /// Dark grey on green reflective LCD.
    LcdGreen,
    /// Dark grey on white LCD.
    LcdWhite,
    /// Blue-white on blue LCD.
    LcdBlue,
}

/// Display pixels are drawn this many image pixels wide for a panel look.
pub const PANEL_SCALE: u32 = 3;

impl Panel {
    /// Parses a `--display` name (one of [`PANELS`]).
    pub fn parse(s: &str) -> Result<Panel, CliError> {
        Ok(match s {
            "plain" => Panel::Plain,
            "oled-blue" => Panel::OledBlue,
            "oled-white" => Panel::OledWhite,
            "lcd-green" => Panel::LcdGreen,
            "lcd-white" => Panel::LcdWhite,
            "lcd-blue" => Panel::LcdBlue,
            _ => {
                return Err(cli_err!(
                    "unknown display '{s}' (expected one of {})",
                    PANELS.join(", ")
                ))
            }
        })
    }

    /// The panel's off and on colours, `None` for [`Panel::Plain`] (the
    /// colours of the simulator's `BinaryColorTheme` of the same name).
    pub fn colors(self) -> Option<(Rgb888, Rgb888)> {
        let rgb = Rgb888::new;
        match self {
            Panel::Plain => None,
            Panel::OledBlue => Some((rgb(0, 20, 40), rgb(0, 210, 255))),
            Panel::OledWhite => Some((rgb(20, 20, 20), Rgb888::WHITE)),
            Panel::LcdGreen => Some((rgb(120, 185, 50), rgb(32, 32, 32))),
            Panel::LcdWhite => Some((rgb(245, 245, 245), rgb(32, 32, 32))),
            Panel::LcdBlue => Some((rgb(70, 80, 230), rgb(230, 230, 255))),
        }
    }

    /// The picture held by `display` as this panel shows it, as an image to
    /// save (see the module docs): the stored pixels themselves for
    /// [`Panel::Plain`].
    pub fn output<C>(self, display: &SimulatorDisplay<C>) -> OutputImage<Rgb888>
    where
        C: PixelColor + Into<Rgb888>,
    {
        let Some((off, on)) = self.colors() else {
            return display.to_rgb_output_image(&OutputSettings::default());
        };
        let size = display.size();
        let pitch = PANEL_SCALE + 1;
        let out_size = Size::new(
            (size.width * pitch).saturating_sub(1),
            (size.height * pitch).saturating_sub(1),
        );
        let mut out = SimulatorDisplay::<Rgb888>::with_default_color(out_size, off);
        for y in 0..size.height {
            for x in 0..size.width {
                let stored: Rgb888 = display.get_pixel(Point::new(x as i32, y as i32)).into();
                let color = between(off, on, luma(stored));
                let corner = Point::new((x * pitch) as i32, (y * pitch) as i32);
                // Drawing into a simulator display cannot fail.
                let _ = Rectangle::new(corner, Size::new_equal(PANEL_SCALE))
                    .into_styled(PrimitiveStyle::with_fill(color))
                    .draw(&mut out);
            }
        }
        out.to_rgb_output_image(&OutputSettings::default())
    }
}

/// The level of a stored colour, 0..=255: the grey itself for a grey (the
/// `gray8` and `mono` formats), else its Rec. 601 luma.
pub fn luma(c: Rgb888) -> u8 {
    let l = (299 * u32::from(c.r()) + 587 * u32::from(c.g()) + 114 * u32::from(c.b()) + 500) / 1000;
    l.min(255) as u8
}

/// The colour `level / 255` of the way from `off` to `on`, per channel,
/// rounded.
pub fn between(off: Rgb888, on: Rgb888, level: u8) -> Rgb888 {
    let t = f64::from(level) / 255.0;
    let mix = |a: u8, b: u8| (f64::from(a) + (f64::from(b) - f64::from(a)) * t).round() as u8;
    Rgb888::new(
        mix(off.r(), on.r()),
        mix(off.g(), on.g()),
        mix(off.b(), on.b()),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::prelude::DrawTarget;

    #[test]
    fn every_name_parses_and_unknown_ones_are_errors() {
        for n in PANELS {
            assert!(Panel::parse(n).is_ok(), "{n}");
        }
        assert_eq!(Panel::parse("plain").unwrap(), Panel::Plain);
        assert!(Panel::parse("crt").is_err());
    }

    #[test]
    fn levels_map_between_off_and_on() {
        for n in PANELS {
            let p = Panel::parse(n).unwrap();
            let Some((off, on)) = p.colors() else {
                assert_eq!(p, Panel::Plain);
                continue;
            };
            assert_eq!(between(off, on, 0), off, "{n}");
            assert_eq!(between(off, on, 255), on, "{n}");
            // Four grey levels stay four colours, in order between the two.
            let four: Vec<Rgb888> = [0u8, 85, 170, 255]
                .iter()
                .map(|&l| between(off, on, luma(Rgb888::new(l, l, l))))
                .collect();
            for w in four.windows(2) {
                assert_ne!(w[0], w[1], "{n}");
                let d = |c: Rgb888| (i32::from(c.g()) - i32::from(off.g())).abs();
                assert!(d(w[0]) <= d(w[1]), "{n}: {four:?}");
            }
        }
        assert_eq!(luma(Rgb888::new(77, 77, 77)), 77);
        assert_eq!(luma(Rgb888::WHITE), 255);
    }

    #[test]
    fn panel_output_has_gaps_in_the_off_colour_and_one_colour_per_level() {
        let mut d = SimulatorDisplay::<Rgb888>::with_default_color(Size::new(4, 1), Rgb888::BLACK);
        for (x, l) in [0u8, 85, 170, 255].into_iter().enumerate() {
            let _ = d.draw_iter([embedded_graphics::Pixel(
                Point::new(x as i32, 0),
                Rgb888::new(l, l, l),
            )]);
        }
        let (off, on) = Panel::LcdWhite.colors().unwrap();
        let img = Panel::LcdWhite.output(&d);
        assert_eq!(img.size(), Size::new(4 * 4 - 1, 3));
        let buf = img.as_image_buffer();
        let at = |x: u32, y: u32| {
            let p = buf.get_pixel(x, y).0;
            Rgb888::new(p[0], p[1], p[2])
        };
        assert_eq!(at(0, 0), off);
        assert_eq!(at(3, 1), off, "gap");
        assert_eq!(at(14, 2), on);
        let blocks: Vec<Rgb888> = (0..4).map(|k| at(4 * k + 1, 1)).collect();
        let mut distinct = blocks.clone();
        distinct.dedup();
        assert_eq!(distinct.len(), 4, "{blocks:?}");
        let plain = Panel::Plain.output(&d);
        assert_eq!(plain.size(), Size::new(4, 1));
    }
}
