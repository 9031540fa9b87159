//! Scene effects: the renderer's optional stages, declared per scene.
//!
//! A scene pays only for what it uses. Each stage below is one bit of
//! [`Effects`]; a tree file carries its scene's set in the header's
//! `effects` field (written by `fpt build --effects LIST`, see
//! [`crate::format`]), and a caller may override it per frame
//! ([`crate::raster::Renderer::set_effects`]).
//!
//! | name | bit | stage | cost when on |
//! |---|---:|---|---|
//! | `culling` | 0 | the walk drops faces turned away from the viewer | saves work: without it a closed volume's back faces are drawn too, all of them first (see [`crate::order::Order::with_culling`]) |
//! | `two-sided` | 1 | a face seen from behind is lit as if it faced the viewer (its normal flipped) | one facing test per drawn face |
//! | `clipping` | 2 | polygons crossing the near plane or the guard band are clipped | only on polygons that cross; off, such polygons are dropped whole |
//! | `lighting` | 3 | flat Lambert shading from a directional light plus ambient | a dot product per drawn face |
//! | `depth-cue` | 4 | faces fade toward the fog colour with eye depth | a few multiplications per drawn face |
//! | `dither` | 5 | 4×4 ordered (Bayer) dithering to a `Gray8` panel's levels or to `BinaryColor` | per pixel: it is a sink ([`crate::raster::Dither`]), chosen by the caller |
//! | `outline` | 6 | the visible edges of each face drawn after its fill (hidden-line look); declared at build time, the tree marks every edge (feature edge, inner, or smooth: drawn as a silhouette only; see [`crate::format`]) | a line per outline edge of each drawn face, and its mask worked out per drawn face |
//! | `smooth` | 7 | Gouraud shading: a lit colour per polygon corner from its vertex normal (the tree's corner normal section, declared at build time, see [`crate::format`]), interpolated across the polygon ([`crate::raster::gouraud`]); needs `lighting`; a tree without normals is drawn flat | three corner colours and a colour step per pixel of each drawn face; bands walk the tree once per band |
//!
//! **Free when absent**, two ways:
//! * **Decided once per polygon or frame**: every stage tests a bit of the
//!   renderer's [`Effects`] value, never per pixel (dithering, the only
//!   per-pixel effect, is a different sink type, so a sink without it has
//!   no per-pixel test at all).
//! * **Compiled out**: the renderer's type names the stages it contains,
//!   [`crate::raster::Renderer`]`<P, E>` with `E:` [`Compiled`] (default
//!   [`AllEffects`]); the tests are `if E::SET.contains(..) && ..`, so in a
//!   pipeline built without a stage (`Pipeline<{ Effects::ALL.without(Effects::OUTLINE).bits() }>`)
//!   its code is not even in the binary.
//!
//! **Off is compiled out**: a frame whose effects leave out a switched
//! effect ([`Compiled::SWITCHED`], default [`DEFAULT_SWITCHED`]: on a
//! microcontroller with an FPU culling, lighting, and the [`EXTRAS`] depth
//! cueing, outlines and smooth shading as one; without one, and on hosted
//! targets, none; [`Switched`] switches them anywhere) is
//! drawn by the walk-and-fill compiled for [`Without`] that effect, whose
//! set is that of the pipeline built without it: off runs the very code of
//! compiled out, plus one test a frame (`for_frame`; which set a frame
//! picks: [`compiled_for`]). The price is code size: each switched effect
//! a pipeline compiles in doubles its copies of the walk-and-fill (a
//! pipeline of every effect holds eight per sink type and draw entry;
//! docs/effects.md).
//!
//! The firmware measures all three (on, off, compiled out) per effect; the
//! docs/effects.md has the figures.

use core::fmt;
use core::marker::PhantomData;

use crate::cpu::HAS_FPU;

/// A set of effects (see the module docs). Unknown bits are ignored.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Effects(u32);

impl Effects {
    /// No effect at all.
    pub const NONE: Effects = Effects(0);
    /// Back-face culling (closed volumes).
    pub const CULLING: Effects = Effects(1 << 0);
    /// Two-sided lighting (open volumes).
    pub const TWO_SIDED: Effects = Effects(1 << 1);
    /// Near-plane and guard-band clipping.
    pub const CLIPPING: Effects = Effects(1 << 2);
    /// Flat Lambert lighting.
    pub const LIGHTING: Effects = Effects(1 << 3);
    /// Depth cueing.
    pub const DEPTH_CUE: Effects = Effects(1 << 4);
    /// Ordered dithering (`Gray8`, `BinaryColor` targets).
    pub const DITHER: Effects = Effects(1 << 5);
    /// Hidden-line outlines.
    pub const OUTLINE: Effects = Effects(1 << 6);
    /// Gouraud (smooth) shading.
    pub const SMOOTH: Effects = Effects(1 << 7);
    /// Every effect.
    pub const ALL: Effects = Effects(0xff);

    /// Every effect with its name, in bit order.
    pub const NAMED: [(&'static str, Effects); 8] = [
        ("culling", Effects::CULLING),
        ("two-sided", Effects::TWO_SIDED),
        ("clipping", Effects::CLIPPING),
        ("lighting", Effects::LIGHTING),
        ("depth-cue", Effects::DEPTH_CUE),
        ("dither", Effects::DITHER),
        ("outline", Effects::OUTLINE),
        ("smooth", Effects::SMOOTH),
    ];

    /// The set with these bits (unknown bits dropped).
    pub const fn from_bits(bits: u32) -> Effects {
        Effects(bits & Effects::ALL.0)
    }

    /// The bits.
    pub const fn bits(self) -> u32 {
        self.0
    }

    /// Whether every effect of `o` is in `self`.
    pub const fn contains(self, o: Effects) -> bool {
        self.0 & o.0 == o.0
    }

    /// Both sets.
    pub const fn with(self, o: Effects) -> Effects {
        Effects(self.0 | o.0)
    }

    /// `self` without the effects of `o`.
    pub const fn without(self, o: Effects) -> Effects {
        Effects(self.0 & !o.0)
    }

    /// Effects in both sets.
    pub const fn and(self, o: Effects) -> Effects {
        Effects(self.0 & o.0)
    }

    /// The sensible default of a scene: culling for a closed volume,
    /// two-sided lighting for an open one, clipping and lighting on.
    pub const fn defaults(closed: bool) -> Effects {
        let side = if closed {
            Effects::CULLING
        } else {
            Effects::TWO_SIDED
        };
        side.with(Effects::CLIPPING).with(Effects::LIGHTING)
    }

    /// The effect called `name` (exactly one of the names in [`Effects::NAMED`]).
    pub fn by_name(name: &str) -> Option<Effects> {
        Effects::NAMED
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, e)| *e)
    }

    /// Parses a comma-separated list of names (spaces around a name are
    /// ignored), or `none`. An empty list, an empty item or an unknown name
    /// is an error carrying the offending item.
    pub fn parse(list: &str) -> Result<Effects, UnknownEffect<'_>> {
        let list = list.trim();
        if list == "none" {
            return Ok(Effects::NONE);
        }
        let mut set = Effects::NONE;
        for item in list.split(',') {
            let name = item.trim();
            set = set.with(Effects::by_name(name).ok_or(UnknownEffect(name))?);
        }
        Ok(set)
    }
}

/// A name that is not an effect (see [`Effects::parse`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UnknownEffect<'a>(pub &'a str);

impl fmt::Display for UnknownEffect<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "unknown effect `{}` (expected a comma-separated list of ",
            self.0
        )?;
        for (i, (n, _)) in Effects::NAMED.iter().enumerate() {
            let sep = if i == 0 { "" } else { ", " };
            write!(f, "{sep}{n}")?;
        }
        f.write_str(", or none)")
    }
}

impl fmt::Display for Effects {
    /// The names, comma-separated, in bit order; `none` for the empty set.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut first = true;
        for (n, e) in Effects::NAMED {
            if self.contains(e) {
                if !first {
                    f.write_str(",")?;
                }
                f.write_str(n)?;
                first = false;
            }
        }
        if first {
            f.write_str("none")?;
        }
        Ok(())
    }
}

impl fmt::Debug for Effects {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Effects({self})")
    }
}

/// The stages a pipeline type contains (see the module docs): an effect
/// outside [`Compiled::SET`] is compiled out, whatever the run-time flags.
pub trait Compiled {
    /// The compiled-in effects.
    const SET: Effects;
    /// The compiled-in effects that, when off for a frame, have the frame
    /// drawn by a copy of the walk-and-fill compiled without them (see
    /// "Off is compiled out" in the module docs): each one of `SET`, or
    /// [`EXTRAS`] as one, doubles the copies a pipeline holds. Default
    /// [`DEFAULT_SWITCHED`]; a pipeline type short of flash may switch fewer
    /// ([`Effects::NONE`]: one copy, and an effect that is off runs its
    /// flag tests), and [`Switched`] switches [`SWITCHED`] on any target.
    /// [`EXTRAS`] switch only when all are in it.
    const SWITCHED: Effects = DEFAULT_SWITCHED;
}

/// A pipeline containing the effects with bits `BITS`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Pipeline<const BITS: u32>;

impl<const BITS: u32> Compiled for Pipeline<BITS> {
    const SET: Effects = Effects::from_bits(BITS);
}

/// Every stage compiled in: the default pipeline.
pub type AllEffects = Pipeline<0xff>;

/// A pipeline containing the effects with bits `BITS` that switches
/// [`SWITCHED`] whatever the target: [`Pipeline`] with the switching a
/// microcontroller with an FPU gets by default, for hosted code that wants
/// it too (the tests that check that off draws what compiled out draws,
/// through the code a microcontroller runs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Switched<const BITS: u32>;

impl<const BITS: u32> Compiled for Switched<BITS> {
    const SET: Effects = Effects::from_bits(BITS);
    const SWITCHED: Effects = SWITCHED;
}

/// What a pipeline switches by default ([`Compiled::SWITCHED`]): on a
/// microcontroller (`target_os = "none"`) [`SWITCHED`]; on a hosted
/// target nothing. The host draws the same pictures either way (an effect
/// that is off draws what compiled out draws, tested); it only takes no
/// copies: the host simulator instantiates many pipelines, and with eight
/// copies of the walk-and-fill each its library took more than 16 CPU
/// minutes to compile (session 12), against about 3 without.
pub const DEFAULT_SWITCHED: Effects = if cfg!(target_os = "none") {
    SWITCHED
} else {
    Effects::NONE
};

/// The effects whose `off` runs a copy compiled without them, by default
/// ([`Compiled::SWITCHED`]): every effect whose off path is a test in the
/// walk's per-polygon code, where a pipeline that merely turns it off was
/// measured to cost up to 2.8 % more than the pipeline built without it
/// (session 11, `bench_city`; docs/effects.md). Culling and
/// lighting are switched one by one; depth cueing, outlines and smooth
/// shading together ([`EXTRAS`]). Two-sided lighting and clipping are
/// not (an untaken test each, within 0.4 % measured), nor dithering (a
/// sink type: off is already compiled out). On a core without an FPU none:
/// there the copy is about three times larger (software floating point)
/// and flash the tighter limit (eight copies overflowed the Cortex-M0
/// firmware's 256 KiB by 120 KB); a pipeline type may still switch some
/// ([`Compiled::SWITCHED`]).
pub const SWITCHED: Effects = if HAS_FPU {
    Effects::CULLING.with(Effects::LIGHTING).with(EXTRAS)
} else {
    Effects::NONE
};

/// The effects `for_frame` switches as one: depth cueing, outlines and
/// smooth shading are taken out of a frame's code when every one of them
/// that the pipeline compiles is off (the usual case: few scenes declare
/// any), so that they cost two copies of the walk-and-fill, not eight.
pub const EXTRAS: Effects = Effects::DEPTH_CUE
    .with(Effects::OUTLINE)
    .with(Effects::SMOOTH);

/// Pipeline `E` without the effects with bits `BITS`: what a frame of `E`
/// with those effects off is drawn by (`for_frame`). Its
/// [`Compiled::SET`] equals that of the [`Pipeline`] built without them,
/// so the two compile to the same walk-and-fill.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Without<E, const BITS: u32>(PhantomData<E>);

impl<E: Compiled, const BITS: u32> Compiled for Without<E, BITS> {
    const SET: Effects = E::SET.without(Effects::from_bits(BITS));
    const SWITCHED: Effects = E::SWITCHED;
}

/// Code generic over the pipeline it is compiled for: the frame's
/// walk-and-fill, handed to `for_frame`.
pub(crate) trait ForPipeline {
    /// What the code returns.
    type Output;
    /// Runs the code compiled for pipeline `X` (whose set is within the
    /// renderer's: every `X` that `for_frame` picks is).
    fn run<X: Compiled>(self) -> Self::Output;
}

/// Runs `code` compiled for pipeline `E` without every effect of
/// `E::SWITCHED` that the frame's effects `active` leave out (an
/// [`EXTRAS`] effect only with all the others of `E`'s extras): a frame
/// with such an effect off runs the very code of the pipeline built
/// without it, plus one test a frame per switched effect. A copy is made
/// only for the effects `E` compiles in and switches (the condition is a
/// constant, so the other arm is never instantiated).
#[inline(always)]
pub(crate) fn for_frame<E: Compiled, C: ForPipeline>(active: Effects, code: C) -> C::Output {
    // One step per effect, or group of effects switched as one ([`EXTRAS`]),
    // culling's first; each leaves its effects in the type or takes them
    // out, and hands over to the next.
    let code = step::<_, { EXTRAS.bits() }>(code, active);
    let code = step::<_, { Effects::DITHER.bits() }>(code, active);
    let code = step::<_, { Effects::LIGHTING.bits() }>(code, active);
    let code = step::<_, { Effects::CLIPPING.bits() }>(code, active);
    let code = step::<_, { Effects::TWO_SIDED.bits() }>(code, active);
    let code = step::<_, { Effects::CULLING.bits() }>(code, active);
    code.run::<E>()
}

/// The compiled set of the code that draws a frame of pipeline `E` whose
/// effects are `active` ([`crate::raster::Renderer::effects`]): `E`'s set
/// without the switched effects that are off ([`Compiled::SWITCHED`]). Two
/// pipelines with the same answer run the same code: with an effect off,
/// [`AllEffects`] runs, on a microcontroller, the code of the pipeline
/// built without it ([`Switched`] does so on any target).
///
/// ```
/// use fpt_nostd::effects::{compiled_for, Effects, Switched};
/// let fx = Effects::defaults(true).without(Effects::CULLING);
/// const NO_CULLING: u32 = Effects::ALL.without(Effects::CULLING).bits();
/// assert_eq!(compiled_for::<Switched<0xff>>(fx), compiled_for::<Switched<NO_CULLING>>(fx));
/// assert!(!compiled_for::<Switched<0xff>>(fx).contains(Effects::CULLING));
/// ```
pub fn compiled_for<E: Compiled>(active: Effects) -> Effects {
    /// Code that returns what it is compiled for.
    struct Set;
    impl ForPipeline for Set {
        type Output = Effects;
        fn run<X: Compiled>(self) -> Effects {
            X::SET
        }
    }
    for_frame::<E, _>(active.and(E::SET), Set)
}

/// One step of `for_frame`: the effects with bits `B`, switched as one
/// when the pipeline switches all of them.
struct Switch<C, const B: u32> {
    next: C,
    active: Effects,
}

/// [`Switch`] for effect bit `B` before `next`.
#[inline(always)]
fn step<C, const B: u32>(next: C, active: Effects) -> Switch<C, B> {
    Switch { next, active }
}

impl<C: ForPipeline, const B: u32> ForPipeline for Switch<C, B> {
    type Output = C::Output;

    #[inline(always)]
    fn run<X: Compiled>(self) -> C::Output {
        // Taken out when every effect of the step that the pipeline
        // compiles is off: the bits it does not compile are out already.
        let step = Effects::from_bits(B);
        if const {
            X::SWITCHED.contains(Effects::from_bits(B))
                && X::SET.and(Effects::from_bits(B)).bits() != 0
        } && self.active.and(X::SET).and(step) == Effects::NONE
        {
            self.next.run::<Without<X, B>>()
        } else {
            self.next.run::<X>()
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::string::ToString;

    #[test]
    fn names_round_trip_and_unknown_names_are_errors() {
        for (n, e) in Effects::NAMED {
            assert_eq!(Effects::parse(n), Ok(e));
            assert_eq!(e.to_string(), n);
        }
        let all = "culling,two-sided,clipping,lighting,depth-cue,dither,outline,smooth";
        assert_eq!(Effects::parse(all), Ok(Effects::ALL));
        assert_eq!(Effects::ALL.to_string(), all);
        assert_eq!(
            Effects::parse(" lighting , outline "),
            Ok(Effects::LIGHTING.with(Effects::OUTLINE))
        );
        assert_eq!(Effects::parse("none"), Ok(Effects::NONE));
        assert_eq!(Effects::NONE.to_string(), "none");
        assert_eq!(Effects::parse("lighting,fog"), Err(UnknownEffect("fog")));
        assert_eq!(Effects::parse(""), Err(UnknownEffect("")));
        assert_eq!(Effects::parse("lighting,"), Err(UnknownEffect("")));
        assert_eq!(Effects::parse("none,lighting"), Err(UnknownEffect("none")));
        assert!(UnknownEffect("fog").to_string().contains("depth-cue"));
    }

    #[test]
    fn defaults_and_set_operations() {
        assert_eq!(
            Effects::defaults(true).to_string(),
            "culling,clipping,lighting"
        );
        assert_eq!(
            Effects::defaults(false).to_string(),
            "two-sided,clipping,lighting"
        );
        assert_eq!(Effects::from_bits(0xffff_ffff), Effects::ALL);
        let e = Effects::ALL.without(Effects::DITHER);
        assert!(!e.contains(Effects::DITHER) && e.contains(Effects::OUTLINE));
        assert_eq!(<AllEffects as Compiled>::SET, Effects::ALL);
        assert_eq!(<Pipeline<8> as Compiled>::SET, Effects::LIGHTING);
    }

    /// The code `for_frame` runs, seen through what it is compiled for.
    struct Picked;

    impl ForPipeline for Picked {
        type Output = (Effects, &'static str);

        fn run<X: Compiled>(self) -> (Effects, &'static str) {
            (X::SET, core::any::type_name::<X>())
        }
    }

    /// The pipeline `for_frame` picks for a frame of `E` with `active`.
    fn picked<E: Compiled>(active: Effects) -> (Effects, &'static str) {
        for_frame::<E, _>(active, Picked)
    }

    #[test]
    fn an_effect_that_is_off_runs_the_pipeline_built_without_it() {
        let base = Effects::defaults(true); // culling, clipping, lighting
        let lean = Effects::ALL.without(EXTRAS);
        const NO_CULL: u32 = Effects::ALL.without(Effects::CULLING).bits();
        const NO_LIGHT: u32 = Effects::ALL.without(Effects::LIGHTING).bits();
        const NO_SMOOTH: u32 = Effects::ALL.without(Effects::SMOOTH).bits();
        // The scene's own effects: the extras (all off) taken out.
        let (set, name) = picked::<Switched<0xff>>(base);
        assert_eq!(set, lean);
        assert!(name.contains("Without"), "{name}");
        // All effects with culling off runs the set of the pipeline built
        // without culling, as that pipeline does; the same for lighting.
        for (off, bare) in [
            (Effects::CULLING, picked::<Switched<NO_CULL>> as fn(_) -> _),
            (Effects::LIGHTING, picked::<Switched<NO_LIGHT>>),
            (Effects::SMOOTH, picked::<Switched<NO_SMOOTH>>),
        ] {
            let fx = base.without(off);
            assert_eq!(picked::<Switched<0xff>>(fx).0, lean.without(off), "{off}");
            assert_eq!(bare(fx).0, lean.without(off), "{off}");
        }
        // Both off: both taken out.
        let none = Effects::CLIPPING;
        assert_eq!(
            picked::<Switched<0xff>>(none).0,
            Effects::ALL.without(SWITCHED)
        );
        // Every switched effect on: the pipeline itself, not a copy.
        let (set, name) = picked::<Switched<0xff>>(Effects::ALL);
        assert_eq!(set, Effects::ALL);
        assert!(!name.contains("Without"), "{name}");
        // One extra on keeps all three; unswitched effects stay compiled
        // in when off.
        let outline = base.with(Effects::OUTLINE).without(Effects::CLIPPING);
        assert_eq!(picked::<Switched<0xff>>(outline).0, Effects::ALL);
        // A pipeline without culling makes no copy for it: culling off (as
        // always there) picks the pipeline itself.
        let (set, name) = picked::<Switched<NO_CULL>>(Effects::ALL.without(Effects::CULLING));
        assert_eq!(set, Effects::ALL.without(Effects::CULLING));
        assert!(!name.contains("Without"), "{name}");
        // The default pipeline switches on microcontrollers only.
        let expect = if cfg!(target_os = "none") {
            lean
        } else {
            Effects::ALL
        };
        assert_eq!(picked::<AllEffects>(base).0, expect);
    }

    #[test]
    fn a_pipeline_may_switch_no_effect() {
        /// Every effect compiled in, none switched.
        struct Fixed;
        impl Compiled for Fixed {
            const SET: Effects = Effects::ALL;
            const SWITCHED: Effects = Effects::NONE;
        }
        assert_eq!(picked::<Fixed>(Effects::NONE).0, Effects::ALL);
        assert_eq!(<Without<Fixed, 1> as Compiled>::SWITCHED, Effects::NONE);
    }
}
