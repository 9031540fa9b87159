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
//! The firmware measures all three (on, off, compiled out) per effect; the
//! README has the figures.

use core::fmt;

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
}

/// A pipeline containing the effects with bits `BITS`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Pipeline<const BITS: u32>;

impl<const BITS: u32> Compiled for Pipeline<BITS> {
    const SET: Effects = Effects::from_bits(BITS);
}

/// Every stage compiled in: the default pipeline.
pub type AllEffects = Pipeline<0xff>;

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
}
