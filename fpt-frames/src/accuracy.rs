//! The accuracy study's configurations on the MCU: the cost half of
//! `fpt bench-accuracy`'s rows (its `mcu_instr` and `m0_instr` columns),
//! measured by the firmware's `accuracy` binary and checked against the
//! host bit for bit.
//!
//! * **Configurations**: [`CONFIGS`], the rows of `fpt bench-accuracy`,
//!   each one arithmetic ([`fpt_nostd::raster::Precision`]) and, for
//!   `vertex-q16`/`vertex-q32`, the benchmark tree stored in that encoding
//!   ([`vertex_format`]). `trig-*` build the orbit camera with the
//!   configuration's own trigonometry; the others with `libm`. `int` is
//!   the integer vertex path ([`fpt_nostd::raster::int_path`]) on the `f32`
//!   tree; `int-q16` the same path on the q16 tree with its vertices
//!   drawn as stored (`VertexPath::RAW_Q16_FRAC`: no decoding to `f32`), the
//!   configuration of a core without an FPU.
//! * **Frames**: [`ACCURACY_SCENE`] from every view of [`super::VIEWS`],
//!   240×240 RGB565, cleared to [`super::BACKGROUND`], key light, the
//!   tree's declared effects, drawn into a whole frame ([`Full`]) or band
//!   by band ([`Bands`]: the same checksum). [`AccuracyLine`] is the line
//!   both sides print (the firmware appends `instr=N`).
//! * Each configuration renders with its own [`Renderer`] and [`Scratch`]
//!   on the stack (at most 106 bytes a vertex, [`ACCURACY_VERTS`]), so
//!   nothing stays allocated between configurations.
//! * **Flash**: [`render_config_in`] compiles only a set of
//!   [`Arithmetic`]s; [`one_arithmetic_builds`] are the builds that carry
//!   every configuration one arithmetic and one tree at a time (the
//!   Cortex-M0's 256 KiB).

use core::fmt;

use super::{clear, FrameError, PixelCrc, Probe, ViewSpec, AMBIENT, DIFFUSE, Z_UP};
use super::{Phase, BACKGROUND, HEIGHT, WALK_DEPTH, WIDTH};
use fpt_nostd::effects::AllEffects;
use fpt_nostd::format::VertexFormat;
use fpt_nostd::raster::{
    FixedMicromath, FixedPrecision, FloatLibm, FloatMicromath, FramebufferError, IntPrecision,
    Libm, Light, MathFns, Precision, Renderer, Rgb565Format, Rgb565Framebuffer, Scratch,
};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{BandBuffer, FaceIds, Frame, TreeRenderer};

/// The scene of the measurement.
pub const ACCURACY_SCENE: &str = "bench_city";

/// The study's vertex capacity: what [`ACCURACY_SCENE`]'s trees need (16
/// since the builder's coplanar merge and splitting fixes of sessions
/// 21–23; 38 before: their headers, `fpt info`), not the frame set's
/// [`super::MAX_VERTS`]. Why no more: each configuration's renderer and
/// scratch (up to 106 bytes a vertex) are on the stack, beside the
/// Cortex-M4's whole 115 KiB frame in its 128 KiB of RAM, and beside the
/// working memory in the Cortex-M0's 16 KiB, where every byte of scratch
/// is a byte less of memory (40 vertices left it 512 words, 16 leave it
/// 1,100). A tree that needs more is refused (`FrameError::Capacity`),
/// never drawn wrong.
pub const ACCURACY_VERTS: usize = 16;

/// Every configuration, in `fpt bench-accuracy`'s row order: its name,
/// the encoding of the tree it draws, and its [`Arithmetic`]. The one
/// list [`CONFIGS`], [`vertex_format`] and [`arithmetic`] read.
const TABLE: [(&str, VertexFormat, Arithmetic); 15] = {
    use Arithmetic as A;
    use VertexFormat::{F32, Q16, Q32};
    [
        ("vertex-f32", F32, A::Fixed4),
        ("vertex-q16", Q16, A::Fixed4),
        ("vertex-q32", Q32, A::Fixed4),
        ("fixed", F32, A::Fixed4),
        ("f32-libm", F32, A::FloatLibm),
        ("f32-micromath", F32, A::FloatMicromath),
        ("subpx-0", F32, A::Fixed0),
        ("subpx-2", F32, A::Fixed2),
        ("subpx-4", F32, A::Fixed4),
        ("subpx-6", F32, A::Fixed6),
        ("subpx-8", F32, A::Fixed8),
        ("trig-libm", F32, A::Fixed4),
        ("trig-micromath", F32, A::FixedMicromath),
        ("int", F32, A::Int),
        ("int-q16", Q16, A::Int),
    ]
};

/// The configurations, in `fpt bench-accuracy`'s row order.
pub const CONFIGS: [&str; 15] = {
    let mut names = [""; 15];
    let mut i = 0;
    while i < TABLE.len() {
        names[i] = TABLE[i].0;
        i += 1;
    }
    names
};

/// The entry of [`TABLE`] named `name`.
const fn entry(name: &str) -> Option<(VertexFormat, Arithmetic)> {
    let mut i = 0;
    while i < TABLE.len() {
        if same(TABLE[i].0, name) {
            return Some((TABLE[i].1, TABLE[i].2));
        }
        i += 1;
    }
    None
}

/// The vertex encoding of the tree configuration `name` draws (`f32` for
/// an unknown name).
pub fn vertex_format(name: &str) -> VertexFormat {
    entry(name).map_or(VertexFormat::F32, |e| e.0)
}

/// Where a configuration's frame is drawn: [`Full`] or [`Bands`]. A
/// trait, not an enum, so that a firmware compiles only the drawing it
/// uses (each is a walk-and-fill per configuration's arithmetic).
pub trait Target {
    /// Draws `frame` of `tree` with `r` (its light set); returns the
    /// checksum and leaves `probe` stopped.
    fn draw<P: Precision, Pr: Probe>(
        self,
        r: &mut TreeRenderer<P, ACCURACY_VERTS, AllEffects>,
        tree: &Tree<'_>,
        frame: &Frame,
        probe: &Pr,
    ) -> Result<u32, FrameError>;
}

/// A whole frame in one buffer of at least [`super::FRAME_WORDS`] words
/// (the Cortex-M4F's column).
#[derive(Debug)]
pub struct Full<'a>(pub &'a mut [u16]);

/// Band by band through `buf` (at least [`super::WIDTH`] × `rows` words),
/// with `memory` words of working memory (any length, the picture is the
/// same: [`TreeRenderer::render_banded_in`]): what a core with 16 KiB of
/// RAM does (the Cortex-M0's column). The bands are checksummed top to
/// bottom, so the checksum is the full frame's.
#[derive(Debug)]
pub struct Bands<'a> {
    /// The band buffer.
    pub buf: &'a mut [u16],
    /// Rows per band.
    pub rows: u32,
    /// The frame's working memory.
    pub memory: &'a mut [u32],
}

impl Target for Full<'_> {
    fn draw<P: Precision, Pr: Probe>(
        self,
        r: &mut TreeRenderer<P, ACCURACY_VERTS, AllEffects>,
        tree: &Tree<'_>,
        frame: &Frame,
        probe: &Pr,
    ) -> Result<u32, FrameError> {
        // A failure ends the measurement as well.
        let mut fb = Rgb565Framebuffer::new(self.0, WIDTH, HEIGHT).inspect_err(|_| probe.stop())?;
        clear(&mut fb);
        // A q16 tree with the integer path is drawn as stored (see
        // `VertexPath::RAW_Q16_FRAC`).
        let drawn = r.render::<WALK_DEPTH, _>(tree, frame, &mut fb);
        probe.stop();
        drawn?;
        let mut crc = PixelCrc::new();
        crc.update(fb.data());
        Ok(crc.finish())
    }
}

impl Target for Bands<'_> {
    fn draw<P: Precision, Pr: Probe>(
        self,
        r: &mut TreeRenderer<P, ACCURACY_VERTS, AllEffects>,
        tree: &Tree<'_>,
        frame: &Frame,
        probe: &Pr,
    ) -> Result<u32, FrameError> {
        let band = BandBuffer::<Rgb565Format> {
            buf: self.buf,
            rows: self.rows,
            background: BACKGROUND,
        };
        let mut crc = PixelCrc::new();
        // The probe is stopped while each band is checksummed.
        let drawn = r.render_banded_probed::<WALK_DEPTH, _, _>(
            tree,
            frame,
            band,
            self.memory,
            probe,
            |_, fb| {
                crc.update(fb.data());
                true
            },
        );
        probe.stop();
        drawn?;
        Ok(crc.finish())
    }
}

/// Draws view `view` of `tree` (in the configuration's
/// [`vertex_format`]) with configuration `name` into `target`; returns
/// the checksum ([`PixelCrc`]). `probe` sees one start (before the camera
/// set-up) and one stop (before the checksum of a full frame; in bands it
/// is also stopped while each band is checksummed).
pub fn render_config<Tg: Target, Pr: Probe>(
    name: &str,
    tree: &Tree<'_>,
    view: &ViewSpec,
    target: Tg,
    probe: &Pr,
) -> Result<u32, FrameError> {
    render_config_in::<ALL_ARITHMETICS, Tg, Pr>(name, tree, view, target, probe)
}

/// The arithmetic a configuration draws with (its vertex path, sub-pixel
/// bits and trigonometry): one walk-and-fill in a firmware's flash each.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u32)]
pub enum Arithmetic {
    /// 16.16 fixed point, 0 sub-pixel bits.
    Fixed0,
    /// 16.16 fixed point, 2 sub-pixel bits.
    Fixed2,
    /// 16.16 fixed point, 4 sub-pixel bits (the default).
    Fixed4,
    /// 16.16 fixed point, 6 sub-pixel bits.
    Fixed6,
    /// 16.16 fixed point, 8 sub-pixel bits.
    Fixed8,
    /// Fixed point with `micromath` trigonometry for the camera too.
    FixedMicromath,
    /// `f32` with `libm`.
    FloatLibm,
    /// `f32` with `micromath`.
    FloatMicromath,
    /// The integer vertex path.
    Int,
}

/// Every [`Arithmetic`], as a set (bit `a as u32` for each `a`).
pub const ALL_ARITHMETICS: u32 = (1 << 9) - 1;

/// `a == b` in a `const fn`.
const fn same(a: &str, b: &str) -> bool {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}

/// The arithmetic of configuration `name` (`None` for an unknown name).
pub const fn arithmetic(name: &str) -> Option<Arithmetic> {
    match entry(name) {
        Some(e) => Some(e.1),
        None => None,
    }
}

/// The set of the arithmetics of `names` (for [`render_config_in`]);
/// fails to compile (in a `const`) on an unknown name.
pub const fn arithmetics(names: &[&str]) -> u32 {
    let mut set = 0;
    let mut i = 0;
    while i < names.len() {
        match arithmetic(names[i]) {
            Some(a) => set |= 1 << a as u32,
            None => panic!("not an accuracy configuration"),
        }
        i += 1;
    }
    set
}

/// The builds that carry every configuration when a firmware's flash
/// holds one tree and one arithmetic (the Cortex-M0's 256 KiB: a
/// `bench_city` tree is 103–121 KiB, an arithmetic's walk-and-fill and
/// the code they share about 130 KiB there): each distinct pair of a tree
/// encoding ([`vertex_format`]) and an [`Arithmetic`], in [`CONFIGS`]
/// order (the configurations of a pair: [`in_build`]).
pub fn one_arithmetic_builds() -> impl Iterator<Item = (VertexFormat, Arithmetic)> {
    let key = |c: &&str| (vertex_format(c), arithmetic(c));
    CONFIGS.iter().enumerate().filter_map(move |(i, c)| {
        let k = key(c);
        let first = !CONFIGS[..i].iter().any(|d| key(d) == k);
        match (first, k) {
            (true, (f, Some(a))) => Some((f, a)),
            _ => None,
        }
    })
}

/// The configurations of the build of [`one_arithmetic_builds`] that
/// draws trees stored as `format` with arithmetic `a`.
pub fn in_build(format: VertexFormat, a: Arithmetic) -> impl Iterator<Item = &'static str> {
    CONFIGS
        .into_iter()
        .filter(move |c| vertex_format(c) == format && arithmetic(c) == Some(a))
}

/// [`render_config`] with only the arithmetics of `SET` compiled in
/// ([`arithmetics`]): a configuration outside it is
/// [`FrameError::UnknownConfig`]. What lets a firmware with 256 KiB of
/// flash carry a tree and the code of a few configurations (each
/// arithmetic is a walk-and-fill of its own).
pub fn render_config_in<const SET: u32, Tg: Target, Pr: Probe>(
    name: &str,
    tree: &Tree<'_>,
    view: &ViewSpec,
    target: Tg,
    probe: &Pr,
) -> Result<u32, FrameError> {
    use Arithmetic as A;
    // (`int-q16` gets the q16 tree: `vertex_format`; the integer path
    // draws it as stored. `trig-*` differ from `fixed` in the camera's
    // trigonometry only.)
    let f = Frame1 { tree, view };
    // Each arm's guard is a constant: an arithmetic outside `SET` is
    // never compiled.
    let on = |a: A| SET & (1 << a as u32) != 0;
    match arithmetic(name).ok_or(FrameError::UnknownConfig)? {
        A::Fixed0 if on(A::Fixed0) => {
            render_with::<FixedPrecision<0>, Libm, Tg, Pr>(f, target, probe)
        }
        A::Fixed2 if on(A::Fixed2) => {
            render_with::<FixedPrecision<2>, Libm, Tg, Pr>(f, target, probe)
        }
        A::Fixed4 if on(A::Fixed4) => {
            render_with::<FixedPrecision<4>, Libm, Tg, Pr>(f, target, probe)
        }
        A::Fixed6 if on(A::Fixed6) => {
            render_with::<FixedPrecision<6>, Libm, Tg, Pr>(f, target, probe)
        }
        A::Fixed8 if on(A::Fixed8) => {
            render_with::<FixedPrecision<8>, Libm, Tg, Pr>(f, target, probe)
        }
        A::FixedMicromath if on(A::FixedMicromath) => {
            render_with::<FixedMicromath<4>, <FixedMicromath<4> as Precision>::Math, Tg, Pr>(
                f, target, probe,
            )
        }
        A::FloatLibm if on(A::FloatLibm) => {
            render_with::<FloatLibm<4>, Libm, Tg, Pr>(f, target, probe)
        }
        A::FloatMicromath if on(A::FloatMicromath) => {
            render_with::<FloatMicromath<4>, Libm, Tg, Pr>(f, target, probe)
        }
        A::Int if on(A::Int) => render_with::<IntPrecision<4>, Libm, Tg, Pr>(f, target, probe),
        _ => Err(FrameError::UnknownConfig),
    }
}

/// What one frame of the study draws: a view of a tree.
#[derive(Clone, Copy)]
struct Frame1<'t, 'b, 'v> {
    tree: &'t Tree<'b>,
    view: &'v ViewSpec,
}

/// One frame with arithmetic `P` and orbit trigonometry `T`.
#[inline(never)]
fn render_with<P: Precision, T: MathFns, Tg: Target, Pr: Probe>(
    f: Frame1<'_, '_, '_>,
    target: Tg,
    probe: &Pr,
) -> Result<u32, FrameError> {
    let Frame1 { tree, view } = f;
    // `Renderer::sized` refuses only a side that is 0 or too large: the
    // frame's size, reported as such.
    let Some(renderer) = Renderer::<P, AllEffects>::sized(WIDTH, HEIGHT) else {
        return Err(FrameError::Buffer(FramebufferError::BadSize));
    };
    // The scratch (4 KiB with fixed point) built in place, not returned
    // in an `Option` and moved (`TreeRenderer::new`): on the Cortex-M0 the
    // move doubled this frame to 9.2 KiB of its 16 KiB.
    let mut r = TreeRenderer::<P, ACCURACY_VERTS, AllEffects> {
        renderer,
        scratch: Scratch::new(),
        ids: FaceIds::Source,
    };
    probe.start(Phase::Xform);
    let aspect = WIDTH as f32 / HEIGHT as f32;
    let camera = view.orbit(tree).camera::<T>(aspect).with_model(&Z_UP);
    let frame = Frame::relative(tree, &camera);
    r.renderer
        .set_light(Light::new(frame.key_light(), AMBIENT, DIFFUSE));
    target.draw(&mut r, tree, &frame, probe)
}

/// `accuracy config=NAME view=K crc=XXXXXXXX`: one configuration's frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AccuracyLine<'a> {
    /// The configuration.
    pub config: &'a str,
    /// The view.
    pub view: u32,
    /// The frame's checksum.
    pub crc: u32,
}

impl fmt::Display for AccuracyLine<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "accuracy config={} view={} crc={:08x}",
            self.config, self.view, self.crc
        )
    }
}

impl<'a> AccuracyLine<'a> {
    /// Parses the start of a line (trailing fields, such as the firmware's
    /// `instr=N`, are ignored); `None` if it is not one.
    pub fn parse(line: &'a str) -> Option<AccuracyLine<'a>> {
        let (config, view, crc) = super::parse_checksum_line(line, "accuracy", "config=")?;
        Some(AccuracyLine { config, view, crc })
    }

    /// The `instr=N` field of a firmware line, if any.
    pub fn instr(line: &str) -> Option<u64> {
        line.split_ascii_whitespace()
            .find_map(|t| t.strip_prefix("instr="))
            .and_then(|v| v.parse().ok())
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::string::ToString;

    #[test]
    fn lines_round_trip_and_carry_the_firmware_cost() {
        let l = AccuracyLine {
            config: "subpx-2",
            view: 3,
            crc: 0xdead_beef,
        };
        let text = l.to_string() + " instr=1234";
        assert_eq!(AccuracyLine::parse(&text), Some(l));
        assert_eq!(AccuracyLine::instr(&text), Some(1234));
        assert_eq!(
            AccuracyLine::parse("frame scene=x view=0 crc=00000000"),
            None
        );
        assert_eq!(AccuracyLine::parse("accuracy config=x view=0 crc=0"), None);
    }

    #[test]
    fn the_one_arithmetic_builds_cover_every_configuration_once() {
        let mut n = 0;
        for (f, a) in one_arithmetic_builds() {
            for c in in_build(f, a) {
                assert!(CONFIGS.contains(&c));
                n += 1;
            }
        }
        assert_eq!(n, CONFIGS.len());
        assert_eq!(one_arithmetic_builds().count(), 12);
        assert_eq!(arithmetics(&["fixed", "subpx-4", "int"]), 1 << 2 | 1 << 8);
        assert_eq!(arithmetic("nope"), None);
    }

    #[test]
    fn every_configuration_is_known_and_others_are_not() {
        let mut buf = [0u16; 4];
        let bytes = fpt_nostd::test_util::Raw::empty().bytes();
        let tree = Tree::from_bytes(&bytes).unwrap_or_else(|e| panic!("{e:?}"));
        let view = &super::super::VIEWS[0];
        for c in CONFIGS {
            // The buffer is too small: every known name gets that far.
            let r = render_config(c, &tree, view, Full(&mut buf), &super::super::NoProbe);
            assert!(matches!(r, Err(FrameError::Buffer(_))), "{c}: {r:?}");
        }
        let r = render_config("nope", &tree, view, Full(&mut buf), &super::super::NoProbe);
        assert_eq!(r, Err(FrameError::UnknownConfig));
    }
}
