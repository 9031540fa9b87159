//! The accuracy plot: error against host time, one labelled point per
//! configuration, as a PNG.
//!
//! `plotters` draws the chart (frame, grid, points) into an RGB buffer; it
//! is built without font support (which would need system fonts), so the
//! text — title, tick values, point labels — is drawn into the same buffer
//! with `embedded-graphics` mono fonts. The PNG is written atomically by
//! [`crate::cli::render::save_png`].

use crate::cli::render::{save_png, Image};
use crate::cli::CliError;
use crate::cli_err;
use embedded_graphics::mono_font::ascii::FONT_6X10;
use embedded_graphics::mono_font::MonoTextStyle;
use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::{DrawTarget, OriginDimensions, Point, RgbColor, Size as EgSize};
use embedded_graphics::primitives::{Line, Primitive, PrimitiveStyle};
use embedded_graphics::text::{Alignment, Text};
use embedded_graphics::{Drawable, Pixel};
use plotters::prelude::*;
use std::path::Path;

/// Picture width in pixels.
pub const WIDTH: u32 = 1140;
/// Picture height in pixels.
pub const HEIGHT: u32 = 600;
const LEFT: u32 = 80;
/// Room for the table of exact values right of the chart.
const RIGHT: u32 = 280;
const TOP: u32 = 40;
const BOTTOM: u32 = 60;

/// One labelled point: x = relative host time, y = error fraction.
#[derive(Clone, Debug, PartialEq)]
pub struct PlotPoint {
    /// Label drawn beside the point.
    pub label: String,
    /// Host time relative to the default configuration.
    pub x: f64,
    /// Error (a fraction; drawn in percent).
    pub y: f64,
}

/// An RGB888 byte buffer as an `embedded-graphics` draw target.
struct Canvas<'a> {
    buf: &'a mut [u8],
    w: u32,
    h: u32,
}

impl OriginDimensions for Canvas<'_> {
    fn size(&self) -> EgSize {
        EgSize::new(self.w, self.h)
    }
}

impl DrawTarget for Canvas<'_> {
    type Color = Rgb888;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb888>>>(
        &mut self,
        it: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in it {
            if p.x < 0 || p.y < 0 || p.x as u32 >= self.w || p.y as u32 >= self.h {
                continue;
            }
            let at = (p.y as usize * self.w as usize + p.x as usize) * 3;
            if let Some(px) = self.buf.get_mut(at..at + 3) {
                px.copy_from_slice(&[c.r(), c.g(), c.b()]);
            }
        }
        Ok(())
    }
}

/// A screen rectangle: x, y, width, height.
type Rect = (i32, i32, i32, i32);

fn overlaps(a: Rect, b: Rect) -> bool {
    a.0 < b.0 + b.2 && b.0 < a.0 + a.2 && a.1 < b.1 + b.3 && b.1 < a.1 + a.3
}

fn text(canvas: &mut Canvas<'_>, s: &str, p: Point, a: Alignment, st: MonoTextStyle<'_, Rgb888>) {
    let _ = Text::with_alignment(s, p, st, a).draw(canvas);
}

/// `[lo, hi]` widened by 8 % (and made non-empty).
fn padded(lo: f64, hi: f64) -> (f64, f64) {
    let span = if hi > lo { hi - lo } else { hi.abs().max(1e-3) };
    (lo - 0.08 * span, hi + 0.08 * span)
}

/// Draws `points` (y as a fraction, shown in percent) with axis titles
/// `x_title` and `y_title` and writes the PNG to `path`.
pub fn plot(
    points: &[PlotPoint],
    title: &str,
    x_title: &str,
    y_title: &str,
    path: &Path,
) -> Result<(), CliError> {
    let finite: Vec<&PlotPoint> = points
        .iter()
        .filter(|p| p.x.is_finite() && p.y.is_finite())
        .collect();
    let fold = |f: fn(&PlotPoint) -> f64| {
        finite
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(f(p)), hi.max(f(p)))
            })
    };
    let (x_lo, x_hi) = fold(|p| p.x);
    let (y_lo, y_hi) = fold(|p| 100.0 * p.y);
    let (x0, x1) = if finite.is_empty() {
        (0.0, 1.0)
    } else {
        padded(x_lo, x_hi)
    };
    let (y0, y1) = if finite.is_empty() {
        (0.0, 1.0)
    } else {
        // Errors are never negative: the axis starts at 0.
        let (lo, hi) = padded(y_lo.min(0.0), y_hi);
        (lo.max(0.0), hi)
    };
    let mut buf = vec![255u8; (WIDTH * HEIGHT * 3) as usize];
    let mut ticks = Vec::new();
    let mut marks = Vec::new();
    {
        let root = BitMapBackend::with_buffer(&mut buf, (WIDTH, HEIGHT)).into_drawing_area();
        let area = root.margin(TOP, BOTTOM, LEFT, RIGHT);
        let mut chart = ChartBuilder::on(&area)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| cli_err!("plot: {e}"))?;
        let grey = RGBColor(220, 220, 220);
        for k in 0..=5 {
            let x = x0 + (x1 - x0) * f64::from(k) / 5.0;
            let y = y0 + (y1 - y0) * f64::from(k) / 5.0;
            chart
                .draw_series(LineSeries::new([(x, y0), (x, y1)], grey))
                .map_err(|e| cli_err!("plot: {e}"))?;
            chart
                .draw_series(LineSeries::new([(x0, y), (x1, y)], grey))
                .map_err(|e| cli_err!("plot: {e}"))?;
            ticks.push((chart.backend_coord(&(x, y0)), format!("{x:.2}"), true));
            ticks.push((chart.backend_coord(&(x0, y)), format!("{y:.3}%"), false));
        }
        chart
            .draw_series(LineSeries::new(
                [(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)],
                BLACK,
            ))
            .map_err(|e| cli_err!("plot: {e}"))?;
        chart
            .draw_series(
                finite
                    .iter()
                    .map(|p| Circle::new((p.x, 100.0 * p.y), 4, BLUE.filled())),
            )
            .map_err(|e| cli_err!("plot: {e}"))?;
        for p in &finite {
            marks.push((chart.backend_coord(&(p.x, 100.0 * p.y)), p.label.clone()));
        }
        root.present().map_err(|e| cli_err!("plot: {e}"))?;
    }
    let mut canvas = Canvas {
        buf: &mut buf,
        w: WIDTH,
        h: HEIGHT,
    };
    let style = MonoTextStyle::new(&FONT_6X10, Rgb888::BLACK);
    let label_style = MonoTextStyle::new(&FONT_6X10, Rgb888::new(0, 0, 160));
    text(
        &mut canvas,
        title,
        Point::new((WIDTH / 2) as i32, 12),
        Alignment::Center,
        style,
    );
    text(
        &mut canvas,
        x_title,
        Point::new(
            (LEFT + (WIDTH - LEFT - RIGHT) / 2) as i32,
            (HEIGHT - 15) as i32,
        ),
        Alignment::Center,
        style,
    );
    text(
        &mut canvas,
        y_title,
        Point::new(8, (TOP - 8) as i32),
        Alignment::Left,
        style,
    );
    for ((x, y), s, is_x) in &ticks {
        if *is_x {
            text(
                &mut canvas,
                s,
                Point::new(*x, y + 16),
                Alignment::Center,
                style,
            );
        } else {
            text(
                &mut canvas,
                s,
                Point::new(x - 6, y + 3),
                Alignment::Right,
                style,
            );
        }
    }
    // Labels beside their point; where that would cover another label or
    // point, the first free place further down (or, failing that, to the
    // left), tied to its point by a thin line.
    let dots: Vec<Rect> = marks
        .iter()
        .map(|((x, y), _)| (x - 5, y - 5, 10, 10))
        .collect();
    let mut placed: Vec<Rect> = Vec::new();
    let mut order: Vec<&((i32, i32), String)> = marks.iter().collect();
    order.sort_by_key(|((x, y), _)| (*y, *x));
    for ((x, y), s) in order {
        let width = 6 * s.len() as i32;
        // Inside the chart (off it are the ticks), clear of the others.
        let inside = |r: Rect| r.0 >= LEFT as i32 && r.1 + r.3 <= (HEIGHT - BOTTOM) as i32;
        let free = |r: Rect| inside(r) && !placed.iter().chain(&dots).any(|&o| overlaps(r, o));
        let candidates = (0..12)
            .map(|k| (x + 7, y + 3 + 10 * k))
            .chain((0..12).map(|k| (x - 7 - width, y + 3 + 10 * k)));
        let mut spot = (x + 7, y + 3);
        for c in candidates {
            if free((c.0, c.1 - 8, width, 10)) {
                spot = c;
                break;
            }
        }
        placed.push((spot.0, spot.1 - 8, width, 10));
        if (spot.1 - (y + 3)).abs() > 0 || spot.0 < *x {
            let end = if spot.0 < *x { spot.0 + width } else { spot.0 };
            let _ = Line::new(Point::new(*x, *y), Point::new(end, spot.1 - 3))
                .into_styled(PrimitiveStyle::with_stroke(Rgb888::new(150, 150, 200), 1))
                .draw(&mut canvas);
        }
        text(
            &mut canvas,
            s,
            Point::new(spot.0, spot.1),
            Alignment::Left,
            label_style,
        );
    }
    // The exact values, since labels of nearby points may be displaced.
    let tx = (WIDTH - RIGHT + 20) as i32;
    text(
        &mut canvas,
        &format!("{:<16}{:>8}{:>10}", "config", "time", "error %"),
        Point::new(tx, (TOP + 8) as i32),
        Alignment::Left,
        style,
    );
    for (k, p) in points.iter().enumerate() {
        let line = format!("{:<16}{:>8.3}{:>10.4}", p.label, p.x, 100.0 * p.y);
        let y = (TOP + 22) as i32 + 12 * k as i32;
        text(
            &mut canvas,
            &line,
            Point::new(tx, y),
            Alignment::Left,
            label_style,
        );
    }
    save_png(&Image::Rgb888(buf), WIDTH, HEIGHT, path)
}
