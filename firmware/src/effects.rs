//! `effect name=NAME on=N off=N bare=N` lines (feature `full`): the
//! instructions per frame of the benchmark scene with each effect on, off,
//! and through a pipeline compiled without it (see
//! [`fpt_frames::effects`] for the scene, view, targets and the
//! rule that `off` and `bare` draw the same pixels, which is checked here).

use cortex_m_semihosting::hprintln;

use fpt_frames::effects::{
    bare_pipeline, on_off, render_effect, Bare, EffectTarget, EFFECT_SCENE, EFFECT_VIEW, MONO_BYTES,
};
use fpt_frames::{FramePrecision, FrameRenderer, VIEWS};
use fpt_nostd::effects::{AllEffects, Compiled, Effects};
use fpt_nostd::raster::{Camera, Mat4, Renderer};
use fpt_nostd::reader::Tree;

use crate::clock::Clock;
use crate::fail::fail;
use crate::probe::TotalProbe;

/// One measured run: instructions and checksum.
#[inline(never)]
fn run<E: Compiled>(
    clock: &Clock,
    r: &mut FrameRenderer,
    tree: &Tree<'_>,
    effects: Effects,
    buf: &mut [u16],
    mono: bool,
) -> (u64, u32) {
    let camera = Camera::from_matrix(Mat4::IDENTITY, 1.0);
    let Some(mut renderer) =
        Renderer::<FramePrecision, E>::new(fpt_frames::WIDTH, fpt_frames::HEIGHT, &camera)
    else {
        fail(format_args!("effect renderer size"))
    };
    let view = &VIEWS[EFFECT_VIEW];
    let probe = TotalProbe::default();
    let target = if mono {
        // SAFETY: the bytes of `buf` (a `&mut [u16]` borrowed for this call
        // only) viewed as `u8`: same memory, alignment 1 ≤ 2, length twice
        // the words; `buf` is not used while `bytes` lives.
        let bytes: &mut [u8] = unsafe {
            core::slice::from_raw_parts_mut(buf.as_mut_ptr().cast::<u8>(), buf.len() * 2)
        };
        let Some(bytes) = bytes.get_mut(..MONO_BYTES) else {
            fail(format_args!("mono buffer"))
        };
        EffectTarget::Mono {
            buf: bytes,
            dither: effects.contains(Effects::DITHER),
        }
    } else {
        EffectTarget::Rgb565(buf)
    };
    let out = render_effect(
        &mut renderer,
        &mut r.scratch,
        tree,
        view,
        effects,
        target,
        &probe,
    );
    match out {
        Ok(crc) => (clock.instr(probe.ticks()), crc),
        Err(e) => fail(format_args!("effect run: {e}")),
    }
}

/// The `bare` run of effect `i` of [`Effects::NAMED`]: each needs its own
/// pipeline type, so one arm per effect.
fn bare(
    i: usize,
    clock: &Clock,
    r: &mut FrameRenderer,
    tree: &Tree<'_>,
    fx: Effects,
    buf: &mut [u16],
    mono: bool,
) -> (u64, u32) {
    const CULL: u32 = bare_pipeline(Effects::CULLING);
    const TWO: u32 = bare_pipeline(Effects::TWO_SIDED);
    const CLIP: u32 = bare_pipeline(Effects::CLIPPING);
    const LIGHT: u32 = bare_pipeline(Effects::LIGHTING);
    const CUE: u32 = bare_pipeline(Effects::DEPTH_CUE);
    const DITHER: u32 = bare_pipeline(Effects::DITHER);
    const OUTLINE: u32 = bare_pipeline(Effects::OUTLINE);
    const SMOOTH: u32 = bare_pipeline(Effects::SMOOTH);
    match i {
        0 => run::<Bare<CULL>>(clock, r, tree, fx, buf, mono),
        1 => run::<Bare<TWO>>(clock, r, tree, fx, buf, mono),
        2 => run::<Bare<CLIP>>(clock, r, tree, fx, buf, mono),
        3 => run::<Bare<LIGHT>>(clock, r, tree, fx, buf, mono),
        4 => run::<Bare<CUE>>(clock, r, tree, fx, buf, mono),
        5 => run::<Bare<DITHER>>(clock, r, tree, fx, buf, mono),
        6 => run::<Bare<OUTLINE>>(clock, r, tree, fx, buf, mono),
        _ => run::<Bare<SMOOTH>>(clock, r, tree, fx, buf, mono),
    }
}

/// Prints one `effect` line per effect; `false` if an `off` and a `bare`
/// run drew different pixels.
pub fn measure(
    clock: &Clock,
    r: &mut FrameRenderer,
    trees: &[(&str, &[u8])],
    buf: &mut [u16],
) -> bool {
    let Some(bytes) = trees.iter().find(|(n, _)| *n == EFFECT_SCENE).map(|t| t.1) else {
        fail(format_args!("no tree for {EFFECT_SCENE}"))
    };
    let tree = match Tree::from_bytes(bytes) {
        Ok(t) => t,
        Err(e) => fail(format_args!("{EFFECT_SCENE}: {e}")),
    };
    let base = Effects::from_bits(tree.effects());
    let mut ok = true;
    for (i, (name, e)) in Effects::NAMED.iter().enumerate() {
        let mono = *e == Effects::DITHER;
        let (on_fx, off_fx) = on_off(base, *e);
        let (on, _) = run::<AllEffects>(clock, r, &tree, on_fx, buf, mono);
        let (off, off_crc) = run::<AllEffects>(clock, r, &tree, off_fx, buf, mono);
        let (bare, bare_crc) = bare(i, clock, r, &tree, off_fx, buf, mono);
        hprintln!("effect name={} on={} off={} bare={}", name, on, off, bare);
        if off_crc != bare_crc {
            hprintln!(
                "error: effect {}: off drew crc {:08x}, bare {:08x}",
                name,
                off_crc,
                bare_crc
            );
            ok = false;
        }
    }
    ok
}
