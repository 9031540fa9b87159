//! The peer side by side: `embedded-3dgfx` 0.7.2 (z-buffer rasterizer, from
//! crates.io) drawing the standard orbit of `socket.off` under QEMU, measured
//! the way our firmware measures feudal (SysTick calibrated to instructions
//! under `-icount shift=0`, stack painting, linker symbols for the statics).
//!
//! One line per run:
//!
//! ```text
//! peer cpu=m4f size=WxH frames=N instr_median=… instr_min=… instr_max=… ram_static=… stack_peak=… …
//! ```
//!
//! The frame (what `instr` counts): camera and light for the frame, clearing
//! the framebuffer to the background, then the peer's `record` (transform,
//! back-face cull, flat Lambert shading, one command per visible triangle,
//! plus a z-buffer clear) and `execute` (z-buffer clear, z-buffered scan
//! conversion, pixel writes through `DrawTarget`). With `PEER_CHUNK` the
//! mesh is recorded and executed in slices of that many triangles, so that
//! a small command buffer suffices (the M0's 16 KiB); the z-buffer is then
//! cleared by the first slice only.
//!
//! The size, frames and chunk are fixed at build time (`build.rs`);
//! `run.sh` builds and runs every configuration.
#![no_std]
#![no_main]

// The firmware's own clock calibration, failure report and stack
// measurement, so that both sides are measured alike.
#[path = "../../../firmware/src/clock.rs"]
mod clock;
#[path = "../../../firmware/src/fail.rs"]
mod fail;
mod fb;
mod model;
#[path = "../../../firmware/src/stack.rs"]
mod stack;

mod config {
    include!(concat!(env!("OUT_DIR"), "/config.rs"));
}

use core::f32::consts::PI;

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use embedded_3dgfx::prelude::{
    CommandBuffer, FrameCtx, Geometry, K3dMesh, K3dengine, RenderMode, ZDepth,
};
use embedded_graphics_core::pixelcolor::{IntoStorage, Rgb565};
use nalgebra::{Point3, Vector3};

use config::{CHUNK, CMD_CAP, CPU, FRAMES, NF, RADIUS, SIZE};
use fail::fail;

/// The standard orbit (as `fpt_frames::orbit`): vertical field of
/// view, eye distance in bounding radii, pitch.
const FOV_DEGREES: f32 = 60.0;
const DISTANCE: f32 = 2.1;
const PITCH_DEGREES: f32 = 25.0;
/// Background, RGB565 (2, 4, 6).
const BACKGROUND: Rgb565 = Rgb565::new(2, 4, 6);
/// Pixels of the display.
const PIXELS: usize = SIZE * SIZE;

#[entry]
fn main() -> ! {
    // cortex-m-rt turns these `static mut`s into `&'static mut` references
    // handed to `main` alone: the big buffers live in `.bss` (counted by
    // `ram_static`, not on the stack) without any `unsafe` here.
    static mut FRAMEBUFFER: [Rgb565; PIXELS] = [Rgb565::new(0, 0, 0); PIXELS];
    static mut ZBUFFER: [ZDepth; PIXELS] = [0; PIXELS];
    static mut COMMANDS: CommandBuffer<CMD_CAP> = CommandBuffer::new();
    static mut INSTR: [u32; FRAMES] = [0; FRAMES];

    stack::paint();
    let clock = clock::Clock::take_and_start();
    hprintln!(
        "calib loop_instr={} ticks={} instr_per_1000_ticks={}",
        clock.cal_instr,
        clock.cal_ticks,
        clock.instr_per_kilotick()
    );
    stack::paint();

    let mut fb = fb::Framebuffer::new(FRAMEBUFFER, SIZE, SIZE);
    let mut engine = K3dengine::new(SIZE as u16, SIZE as u16);
    engine.camera.set_fovy(FOV_DEGREES * PI / 180.0);
    // Near and far bracket the model (w from 1.1 to 3.1 radii): the peer
    // drops a whole triangle with a vertex outside them, and its integer
    // depth `ndc.z·(far − near) + near` must stay ≥ 0 over the model
    // (far ≤ 2·near at the nearest point), which near = 0.8 R ensures.
    engine.camera.set_near_far(0.8 * RADIUS, 3.2 * RADIUS);
    engine.camera.set_target(Point3::origin());

    // One mesh whose geometry is pointed at each slice of triangles in turn
    // (a `K3dMesh` per slice would cost RAM the M0 does not have).
    let geometry = |k: usize| {
        let end = (k + CHUNK).min(NF);
        Geometry {
            normals: &model::NORMALS[k..end],
            ..Geometry::new(&model::VERTICES, &model::FACES[k..end])
        }
    };
    let mut mesh = K3dMesh::new(geometry(0));

    let mut covered_min = usize::MAX;
    let mut commands_max = 0;
    let mut crc = Crc32::new();
    for (i, instr) in INSTR.iter_mut().enumerate() {
        let t0 = clock::now();
        let light = set_camera(&mut engine, i);
        // The peer's flat Lambert mode: colour · (max(n·l, 0) + 0.1), one
        // colour per triangle. It negates the z of the direction given.
        mesh.set_render_mode(RenderMode::SolidLightDir(Vector3::new(
            light[0], light[1], -light[2],
        )));
        // `record` does not clear the colour buffer; the frame includes it.
        fb.fill(BACKGROUND);
        let mut k = 0;
        while k < NF {
            engine.set_depth_clear_enabled(k == 0);
            mesh.geometry = geometry(k);
            if let Err(e) = engine.record(core::iter::once(&mesh), COMMANDS, None) {
                fail(format_args!("record: {e:?}"))
            }
            commands_max = commands_max.max(COMMANDS.len());
            let mut frame = FrameCtx {
                zbuffer: &mut ZBUFFER[..],
                width: SIZE,
                height: SIZE,
            };
            if let Err(e) = engine.execute(&mut fb, &mut frame, COMMANDS, None) {
                fail(format_args!("execute: {e:?}"))
            }
            k += CHUNK;
        }
        let t1 = clock::now();
        *instr = u32::try_from(clock.instr(t1 - t0)).unwrap_or(u32::MAX);
        // Not timed: a check that the model is drawn, and a checksum of
        // every frame (same as our frames': CRC-32 of little-endian RGB565).
        covered_min = covered_min.min(fb.covered(BACKGROUND));
        fb.pixels().iter().for_each(|p| crc.update(p));
        if config::DUMP && i == 0 {
            dump(fb.pixels());
        }
    }

    let stack_peak = stack::peak();
    if stack::overflowed() {
        fail(format_args!(
            "stack overflow: the stack reached the statics ({} bytes of room)",
            stack::room()
        ))
    }
    INSTR.sort_unstable();
    hprintln!(
        "peer cpu={} size={}x{} frames={} instr_median={} instr_min={} instr_max={} \
         ram_static={} stack_peak={} fb={} zbuf={} cmdbuf={} chunk={} commands_max={} \
         covered_min={} crc={:08x}",
        CPU,
        SIZE,
        SIZE,
        FRAMES,
        median(INSTR),
        INSTR[0],
        INSTR[FRAMES - 1],
        stack::static_ram(),
        stack_peak,
        core::mem::size_of_val(FRAMEBUFFER),
        core::mem::size_of_val(ZBUFFER),
        core::mem::size_of_val(COMMANDS),
        CHUNK,
        commands_max,
        covered_min,
        crc.finish(),
    );
    debug::exit(debug::EXIT_SUCCESS);
    loop {
        cortex_m::asm::wfi();
    }
}

/// Places the camera for frame `i` of the orbit and returns the key light
/// (world space, unit): our renderer's `Frame::key_light`, toward the eye,
/// raised 0.6 toward the top of the screen and moved 0.4 to its left.
fn set_camera(engine: &mut K3dengine, i: usize) -> [f32; 3] {
    let yaw = 2.0 * PI * (i as f32 / FRAMES as f32);
    let pitch = PITCH_DEGREES * PI / 180.0;
    let (sy, cy) = (libm::sinf(yaw), libm::cosf(yaw));
    let (sp, cp) = (libm::sinf(pitch), libm::cosf(pitch));
    let toward = Vector3::new(cp * sy, sp, cp * cy);
    engine
        .camera
        .set_position(Point3::from(toward * (DISTANCE * RADIUS)));
    // Screen axes in world space: right = up_world × back, up = back × right.
    let right = Vector3::y().cross(&toward).normalize();
    let up = toward.cross(&right);
    let l = (toward + up * 0.6 - right * 0.4).normalize();
    [l.x, l.y, l.z]
}

/// Prints `pixels` as `dump` lines of hex RGB565 words, 16 pixels a line,
/// row-major (a small buffer: at the largest sizes the stack has little room).
fn dump(pixels: &[Rgb565]) {
    for run in pixels.chunks(16) {
        let mut line = [0u8; 4 * 16];
        for (k, p) in run.iter().enumerate() {
            for (j, nib) in [12, 8, 4, 0].into_iter().enumerate() {
                line[4 * k + j] = b"0123456789abcdef"[usize::from((p.into_storage() >> nib) & 15)];
            }
        }
        hprintln!(
            "dump {}",
            core::str::from_utf8(&line[..4 * run.len()]).unwrap_or("")
        );
    }
}

fn median(sorted: &[u32]) -> u32 {
    let n = sorted.len();
    if n % 2 == 1 {
        sorted[n / 2]
    } else {
        ((u64::from(sorted[n / 2 - 1]) + u64::from(sorted[n / 2])) / 2) as u32
    }
}

/// CRC-32 (IEEE, as zlib) of RGB565 words stored little-endian.
struct Crc32(u32);

impl Crc32 {
    fn new() -> Crc32 {
        Crc32(!0)
    }

    fn update(&mut self, p: &Rgb565) {
        let v = p.into_storage();
        for b in v.to_le_bytes() {
            self.0 ^= u32::from(b);
            for _ in 0..8 {
                self.0 = (self.0 >> 1) ^ (0xEDB8_8320 & (self.0 & 1).wrapping_neg());
            }
        }
    }

    fn finish(&self) -> u32 {
        !self.0
    }
}
