//! What `fpt render` simulates of a display, only when asked.
//!
//! The framebuffer format (`--format`) is the panel's storage: the default
//! `rgb888` keeps the renderer's exact colours, `rgb565` quantises to 16-bit
//! colour, `gray8` to grey (to `--gray-levels N` levels
//! when given: a 4-bit OLED has 16), `mono` to one bit per pixel, by a
//! threshold, or by ordered dithering when the scene's `dither` effect is on
//! (see `fpt_nostd::raster::dither`). `--display` then chooses how the PNG
//! shows those pixels: `plain` one image pixel per display pixel as stored,
//! or the look of a panel through `embedded-graphics-simulator`'s output
//! settings (its `BinaryColorTheme` colours, which map the pixel's luma
//! between the panel's off and on colours, and enlarged pixels with a gap
//! between them). The panel looks make sense for `mono` and `gray8`.

use super::CliError;
use crate::cli_err;
use embedded_graphics_simulator::{BinaryColorTheme, OutputSettings, OutputSettingsBuilder};

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

    /// The simulator's output settings for this look.
    pub fn settings(self) -> OutputSettings {
        let theme = match self {
            Panel::Plain => return OutputSettingsBuilder::new().build(),
            Panel::OledBlue => BinaryColorTheme::OledBlue,
            Panel::OledWhite => BinaryColorTheme::OledWhite,
            Panel::LcdGreen => BinaryColorTheme::LcdGreen,
            Panel::LcdWhite => BinaryColorTheme::LcdWhite,
            Panel::LcdBlue => BinaryColorTheme::LcdBlue,
        };
        OutputSettingsBuilder::new()
            .theme(theme)
            .scale(PANEL_SCALE)
            .pixel_spacing(1)
            .build()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_parses_and_unknown_ones_are_errors() {
        for n in PANELS {
            assert!(Panel::parse(n).is_ok(), "{n}");
        }
        assert_eq!(Panel::parse("plain").unwrap(), Panel::Plain);
        assert!(Panel::parse("crt").is_err());
    }
}
