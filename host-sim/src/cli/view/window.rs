//! The SDL2 window of `fpt view` (cargo feature `view`): draws the orbit
//! view into a simulator display, shows it and turns the keys into
//! [`Key`]s (see the parent module for what they do).

use super::super::render::{
    open_tree, orbit_camera, parse_size, read_tree, render_job, Format, Image, Job,
};
use super::super::turntable::MAX_SIDE;
use super::{Key, ViewArgs, ViewOrbit};
use crate::cli::{CliError, CliResult};
use crate::cli_err;
use embedded_graphics::geometry::{Point, Size};
use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::DrawTarget;
use embedded_graphics::Pixel;
use embedded_graphics_simulator::sdl2::Keycode;
use embedded_graphics_simulator::{
    OutputSettingsBuilder, SimulatorDisplay, SimulatorEvent, Window,
};

/// The [`Key`] of an SDL key code, if it has one.
fn key_of(code: Keycode) -> Option<Key> {
    Some(match code {
        Keycode::LEFT => Key::Left,
        Keycode::RIGHT => Key::Right,
        Keycode::UP => Key::Up,
        Keycode::DOWN => Key::Down,
        Keycode::PLUS | Keycode::EQUALS | Keycode::KP_PLUS => Key::ZoomIn,
        Keycode::MINUS | Keycode::KP_MINUS => Key::ZoomOut,
        Keycode::ESCAPE | Keycode::Q => Key::Quit,
        _ => return None,
    })
}

/// `fpt view` with the window.
pub fn run(a: &ViewArgs) -> CliResult {
    let (w, h) = parse_size(&a.size)?;
    if w > MAX_SIDE || h > MAX_SIDE {
        return Err(cli_err!(
            "--size: the window is at most {MAX_SIDE} pixels a side, got {w}x{h}"
        ));
    }
    let look = a.look.parse()?;
    let bytes = read_tree(&a.tree)?;
    let tree = open_tree(&bytes, &a.tree)?;
    let start = orbit_camera(&a.orbit, &tree, w, h)?;
    let mut orbit = ViewOrbit::of(&start).ok_or_else(|| cli_err!("no orbit camera"))?;

    let mut display = SimulatorDisplay::<Rgb888>::new(Size::new(w, h));
    let title = format!("fpt view {}", a.tree.display());
    let mut window = Window::new(&title, &OutputSettingsBuilder::new().build());
    let mut dirty = true;
    let mut updates = 0u32;
    loop {
        if dirty {
            let job = Job {
                w,
                h,
                camera: orbit.camera(&start),
                format: Format::Rgb888,
                band: None,
                look,
                ids: false,
                effects: None,
                gray_levels: None,
            };
            let Image::Rgb888(rgb) = render_job(&tree, &job, &a.look.precision)?.image else {
                return Err(cli_err!("the renderer returned no 24-bit picture"));
            };
            let pixels = rgb.chunks_exact(3).enumerate().map(|(i, c)| {
                let (x, y) = (i as u32 % w, i as u32 / w);
                Pixel(
                    Point::new(x as i32, y as i32),
                    Rgb888::new(c[0], c[1], c[2]),
                )
            });
            display.draw_iter(pixels).map_err(|e| cli_err!("{e:?}"))?;
            dirty = false;
        }
        update(&mut window, &display, updates == 0)?;
        updates += 1;
        if a.frames.is_some_and(|n| updates >= n) {
            return Ok(());
        }
        for event in window.events() {
            let key = match event {
                SimulatorEvent::Quit => Key::Quit,
                SimulatorEvent::KeyDown { keycode, .. } => match key_of(keycode) {
                    Some(k) => k,
                    None => continue,
                },
                _ => continue,
            };
            let (next, open) = orbit.apply(key);
            if !open {
                return Ok(());
            }
            dirty |= next != orbit;
            orbit = next;
        }
    }
}

/// Shows `display` in `window`. The first update opens the window, where
/// the simulator panics when SDL cannot (no display server): that one is
/// caught and reported as an error, with the panic's own message.
fn update(
    window: &mut Window,
    display: &SimulatorDisplay<Rgb888>,
    first: bool,
) -> Result<(), CliError> {
    if !first {
        window.update(display);
        return Ok(());
    }
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let opened = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| window.update(display)));
    std::panic::set_hook(hook);
    opened.map_err(|e| {
        let why = e
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default();
        cli_err!("cannot open the SDL window (is a display server running, DISPLAY set?): {why}")
    })
}
