//! A frame's set-up for the draw loops of `render::cached`: the working
//! memory's vertex cache, the renderer's camera and how vertices reach it
//! ([`Source`]), the decoder the walk reads them with, and the cache's
//! fill before the walk where the camera is proven. Split out of
//! `render/cached.rs`.

use super::super::slivers;
use super::super::{walk_effects, Frame, WalkFx};
use super::MAX_CACHED;
use crate::effects::{Compiled, Effects};
use crate::format::VertexFormat;
use crate::raster::int_path::q16_camera;
use crate::raster::transform::VertexPath;
use crate::raster::vcache::VertexCache;
use crate::raster::{Camera, Precision, Renderer};
use crate::reader::{Tree, VertexDecoder};

/// The vertex cache over the first words of `memory`, cleared: one slot
/// per vertex of `tree`, at most [`MAX_CACHED`] and `limit`; none when
/// `cache` is false. When `tagged` and those words cannot hold every
/// vertex, a tagged cache over them instead ([`VertexCache::tagged`]: a
/// vertex shared by polygons drawn close together is still transformed
/// once; for a full frame, which records nothing for later). Returns it
/// and the words left.
pub(super) fn take_cache<'m>(
    memory: &'m mut [u32],
    tree: &Tree<'_>,
    (cache, tagged): (bool, bool),
    limit: usize,
) -> (VertexCache<'m>, &'m mut [u32]) {
    let want = if cache {
        tree.vertex_count() as usize
    } else {
        0
    };
    let slots = want.min(MAX_CACHED).min(limit).min(memory.len());
    let (c, rest) = memory.split_at_mut(slots);
    let mut c = if tagged && slots < want {
        VertexCache::tagged(c)
    } else {
        VertexCache::new(c)
    };
    c.clear();
    (c, rest)
}

/// In a frame whose camera is proven to keep every vertex of `tree`
/// inside the clip planes and the viewport ([`crate::raster::proof`]),
/// fills the cleared `cache` before the walk ([`Renderer::prefill`]): each
/// cached vertex is transformed without the per-vertex checks, in a loop
/// of its own; the walk then finds them all cached (the same points). Not
/// with raw q16 vertices (paths for cores without an FPU, which prove
/// nothing) nor depth cueing (no cache).
pub(super) fn prefill<P: Precision, E: Compiled>(
    r: &Renderer<P, E>,
    tree: &Tree<'_>,
    source: Source,
    cache: &mut VertexCache<'_>,
) {
    let s = match source.arm::<P>() {
        Arm::Decoded(s) => s,
        Arm::Raw(_) => return,
    };
    let proven = || match source {
        // Proven before the per-axis fold ([`begin_frame`]).
        Source::FoldedQ16 { proven } => proven,
        _ => r.prove(&tree.vertex_bound().scaled(source.scale())),
    };
    // A tagged cache holds only some vertices: nothing to fill ahead.
    if cache.capacity() == 0 || cache.is_tagged() || !proven() {
        return;
    }
    let dec = walk_decoder::<P>(tree, source);
    let count = tree.vertex_count() as usize;
    match (s, source) {
        (Some(s), _) => r.prefill(cache, count, |v| dec.get(v as usize).map(|c| c * s)),
        // The stored values read inline (the walk's `get` calls out for
        // them): a q16 tree's proven frame then costs an `f32` tree's.
        (None, Source::FoldedQ16 { .. }) => {
            r.prefill(cache, count, |v| dec.get_q16_as_stored(v as usize));
        }
        (None, _) => r.prefill(cache, count, |v| dec.get(v as usize)),
    }
}

/// How vertices reach the transform.
#[derive(Clone, Copy, Debug)]
pub(super) enum Source {
    /// Decoded to `f32` and multiplied by the frame's vertex scale (the
    /// renderer has the frame's camera).
    Scaled(f32),
    /// A q16 tree's `i16` values as stored, with this many fraction bits
    /// (the renderer has the frame's camera with the per-axis scale
    /// folded in: `VertexPath::RAW_Q16_FRAC`).
    Q16(u32),
    /// Decoded to `f32` as stored: the frame's vertex scale is folded into
    /// the renderer's matrix ([`folded_camera`]; the float path only).
    Folded,
    /// A q16 tree's `i16` values as stored, converted to `f32`: the frame's
    /// vertex scale and the per-axis scale are folded into the renderer's
    /// matrix ([`q16_folded_camera`]; the float path only). `proven`: the
    /// frame's proof ([`Renderer::prove`]) holds, found before the
    /// per-axis fold (the tree's vertex bound is of decoded vertices).
    FoldedQ16 { proven: bool },
}

/// The arm of a walk's load a [`Source`] takes for path `P`
/// ([`Source::arm`]).
#[derive(Clone, Copy, Debug)]
pub(super) enum Arm {
    /// Raw q16 values with this many fraction bits.
    Raw(u32),
    /// Decoded to `f32`, then multiplied by this scale (`None`: folded
    /// into the matrix).
    Decoded(Option<f32>),
}

impl Source {
    /// Which arm a walk of path `P` takes. `Q16` is only ever made for a path
    /// that takes raw values (`VertexPath::RAW_Q16_FRAC`, [`begin_frame`]),
    /// so for the others (the float path) the raw arm is dead code the
    /// compiler drops: the walk-and-fill function then holds one copy of
    /// the load, prepare and per-polygon pipeline, not two.
    /// The same for `Folded`, made only for a path that folds the scale
    /// (`VertexPath::FOLDS_SCALE`).
    /// A path that folds the scale has one arm (`Decoded(None)`): when the
    /// fold is not exact, its decoder scales instead ([`walk_decoder`]).
    #[inline(always)]
    pub(super) fn arm<P: Precision>(self) -> Arm {
        match self {
            Source::Q16(frac) if <P::Path as VertexPath>::RAW_Q16_FRAC.is_some() => Arm::Raw(frac),
            _ if <P::Path as VertexPath>::FOLDS_SCALE => Arm::Decoded(None),
            Source::Scaled(s) => Arm::Decoded(Some(s)),
            // Never made for such a path: an arm it has anyway.
            Source::Folded | Source::FoldedQ16 { .. } | Source::Q16(_) => Arm::Decoded(Some(1.0)),
        }
    }

    /// The scale the tree's vertices are multiplied by before the
    /// renderer's matrix (1 when folded into it, or raw).
    pub(super) fn scale(self) -> f32 {
        match self {
            Source::Scaled(s) => s,
            Source::Folded | Source::FoldedQ16 { .. } | Source::Q16(_) => 1.0,
        }
    }
}

/// The vertex decoder of a walk of `tree` from `source`: the tree's, or for
/// a path that folds the scale (whose walk multiplies nothing) in a frame
/// where folding is not exact, one that scales every vertex itself
/// ([`VertexDecoder::scaled`], the cold decode: such frames are of trees
/// whose radius reaches 2^14 or of a scale that is no power of two); for
/// a q16 tree whose per-axis scale is folded, one that reads the values
/// as stored ([`VertexDecoder::q16_as_stored`]).
pub(super) fn walk_decoder<'t, P: Precision>(tree: &Tree<'t>, source: Source) -> VertexDecoder<'t> {
    match source {
        Source::Scaled(s) if <P::Path as VertexPath>::FOLDS_SCALE => {
            tree.vertex_decoder().scaled(s)
        }
        Source::FoldedQ16 { .. } => tree.vertex_decoder().q16_as_stored(),
        _ => tree.vertex_decoder(),
    }
}

/// Starts a frame of the code compiled for pipeline `X` (`active`: the
/// effects [`Renderer::begin_tree`] settled, see [`frame_effects`]): zeroes
/// the counters, says what the walk needs of the effects
/// ([`walk_effects`], once a frame for every walk of it), sets the
/// renderer's camera for `frame` and says how vertices reach it: raw q16
/// values when the tree stores them and the path prefers them; and how a
/// face toward the viewer winds when the culling walk of a closed tree
/// draws slivers first (asked for with `Renderer::set_slivers`; 0: no
/// sliver pass, [`slivers`]).
pub(super) fn begin_frame<P: Precision, E: Compiled, X: Compiled>(
    r: &mut Renderer<P, E>,
    tree: &Tree<'_>,
    frame: &Frame,
    active: Effects,
) -> (Source, WalkFx, i32) {
    r.reset_stats();
    let fx = walk_effects::<X>(tree, active);
    let turn = if r.slivers() && fx.cull && tree.is_closed() {
        slivers::front_turn(frame)
    } else {
        0
    };
    let source = match <P::Path as VertexPath>::RAW_Q16_FRAC {
        Some(frac) if tree.vertex_format() == VertexFormat::Q16 => {
            let cam = q16_camera(&frame.camera, frame.vertex_scale, tree.half_extent(), frac);
            r.set_camera(&cam);
            Source::Q16(frac)
        }
        _ => match folded_camera::<P>(tree, frame) {
            Some(cam) => folded_source(r, tree, &cam),
            None => {
                r.set_camera(&frame.camera);
                Source::Scaled(frame.vertex_scale)
            }
        },
    };
    (source, fx, turn)
}

/// The camera of `frame` with its vertex scale `s` folded into the first
/// three columns of the matrix, for a path whose transform allows it
/// (`VertexPath::FOLDS_SCALE`): when `s` is a power of two `≥ 1` and every
/// scaled entry, and every coordinate of `tree` scaled (its
/// [`Tree::vertex_bound`]), stays finite, both scalings are exact, so
/// `(m·s)·x` is the very product `m·(x·s)` (each rounded once): the same
/// points, three multiplications fewer a transformed vertex. `None`
/// otherwise (the vertices are scaled as decoded).
fn folded_camera<P: Precision>(tree: &Tree<'_>, frame: &Frame) -> Option<Camera> {
    let s = frame.vertex_scale;
    // A normal power of two (no mantissa bits) of at least 1.
    let pow2 = s.to_bits() & 0x007f_ffff == 0 && s >= 1.0 && s.is_finite();
    if !<P::Path as VertexPath>::FOLDS_SCALE || !pow2 {
        return None;
    }
    if !tree.vertex_bound().abs.iter().all(|a| (a * s).is_finite()) {
        return None;
    }
    let mut cam = frame.camera;
    for row in &mut cam.matrix.0 {
        for c in row.iter_mut().take(3) {
            *c *= s;
        }
    }
    cam.matrix
        .0
        .iter()
        .flatten()
        .all(|c| c.is_finite())
        .then_some(cam)
}

/// Sets the renderer's camera to `cam` (a [`folded_camera`]), for a q16
/// tree with the per-axis scale folded in as well when that is exact
/// enough ([`q16_folded_camera`]), and says how vertices reach it. Out of
/// line: inlined into the walk-and-fill function it made the default
/// trees' frames dearer (its register allocation), once a frame.
#[inline(never)]
fn folded_source<P: Precision, E: Compiled>(
    r: &mut Renderer<P, E>,
    tree: &Tree<'_>,
    cam: &Camera,
) -> Source {
    r.set_camera(cam);
    match q16_folded_camera(tree, cam) {
        Some(q) => {
            let proven = r.prove(&tree.vertex_bound());
            r.set_camera(&q);
            Source::FoldedQ16 { proven }
        }
        None => Source::Folded,
    }
}

/// For a q16 tree, `cam` (a [`folded_camera`]) with column `j` of the
/// matrix also multiplied by the tree's per-axis scale `c_j`
/// ([`VertexDecoder::q16_scale`]), so that the stored values converted to
/// `f32` (exact) stand for the decoded vertices: `fl(m·c)·q` in place of
/// `m·fl(q·c)`, each product rounded once either way, a cache miss's cold
/// decode (a call and six multiplications) less. The points differ from
/// the decoded ones' by that rounding. A proof for `cam` and the tree's
/// bound (of decoded vertices) holds for the folded matrix and the stored
/// values: against a decoded vertex each product errs by `2u` more than
/// the transform's own rounding, within the proof's allowance
/// ([`crate::raster::proof`]: `2^-21·S` for the products, 8 times below its
/// margin). `None` for another format, or when a folded entry is not
/// normal or zero (the relative rounding above would not hold).
fn q16_folded_camera(tree: &Tree<'_>, cam: &Camera) -> Option<Camera> {
    if tree.vertex_format() != VertexFormat::Q16 {
        return None;
    }
    let c = tree.vertex_decoder().q16_scale();
    let mut q = *cam;
    for row in &mut q.matrix.0 {
        for (e, c) in row.iter_mut().zip(c) {
            *e *= c;
        }
    }
    q.matrix
        .0
        .iter()
        .flatten()
        .all(|e| e.is_normal() || *e == 0.0)
        .then_some(q)
}

#[cfg(test)]
mod tests {
    extern crate std;

    use super::*;
    use crate::raster::precision::{FloatLibm, Libm};
    use crate::raster::transform::FloatPath;
    use crate::raster::Orbit;
    use crate::test_util::two_floors;

    /// Where the fold is taken, an unscaled vertex through the folded
    /// matrix is the very clip point of the scaled vertex through the
    /// frame's (both scalings exact), and a frame whose scale is below 1
    /// keeps its matrix (its decoder scales instead).
    #[test]
    fn folded_matrix_transforms_as_the_scaled_vertices() {
        let bytes = two_floors().bytes();
        let t = Tree::from_bytes(&bytes).unwrap_or_else(|e| panic!("{e:?}"));
        let dec = t.vertex_decoder();
        for (yaw, pitch) in [(0.3f32, 0.2f32), (2.5, -1.1), (-1.0, 0.7)] {
            let o = Orbit::new([0.0; 3], yaw, pitch, 5.0, 0.9);
            let frame = Frame::relative(&t, &o.camera::<Libm>(1.2));
            let s = frame.vertex_scale;
            assert!(s >= 1.0, "{s}");
            let cam = folded_camera::<FloatLibm<4>>(&t, &frame)
                .unwrap_or_else(|| panic!("no fold at scale {s}"));
            for v in 0..t.vertex_count() as usize {
                let x = dec.get(v);
                let a = FloatPath::<Libm>::transform(&cam.matrix, x);
                let b = FloatPath::<Libm>::transform(&frame.camera.matrix, x.map(|c| c * s));
                assert_eq!(a, b, "vertex {v}");
            }
            let half = Frame {
                vertex_scale: 0.5,
                ..frame
            };
            assert!(folded_camera::<FloatLibm<4>>(&t, &half).is_none());
            let odd = Frame {
                vertex_scale: 3.0,
                ..frame
            };
            assert!(folded_camera::<FloatLibm<4>>(&t, &odd).is_none());
        }
    }

    /// A q16 tree's values as stored through the matrix with the per-axis
    /// scale folded in land where the decoded vertices do through the
    /// frame's (within the products' rounding), the stored values are read
    /// exactly, and an `f32` tree takes no per-axis fold.
    #[test]
    fn q16_folded_matrix_transforms_as_the_decoded_vertices() {
        let f32_bytes = two_floors().bytes();
        let t = Tree::from_bytes(&f32_bytes).unwrap_or_else(|e| panic!("{e:?}"));
        let mut r = two_floors();
        let (f32_dec, n) = (t.vertex_decoder(), t.vertex_count() as usize);
        r.format = VertexFormat::Q16;
        r.half_extent = [1.5, 1.25, 1.0];
        r.vertex_bytes.clear();
        for v in 0..n {
            for (c, h) in f32_dec.get(v).into_iter().zip(r.half_extent) {
                let q = (c / h * 32767.0).round() as i16;
                r.vertex_bytes.extend_from_slice(&q.to_le_bytes());
            }
        }
        let bytes = r.bytes();
        let q16 = Tree::from_bytes(&bytes).unwrap_or_else(|e| panic!("{e:?}"));
        let (dec, raw) = (q16.vertex_decoder(), q16.vertex_decoder().q16_as_stored());
        for v in 0..n {
            assert_eq!(raw.get(v), dec.raw_q16(v).map(|c| c as f32), "vertex {v}");
            assert_eq!(raw.get_q16_as_stored(v), raw.get(v));
            assert_eq!(t.vertex_decoder().q16_as_stored().get(v), f32_dec.get(v));
        }
        for (yaw, pitch) in [(0.3f32, 0.2f32), (2.5, -1.1), (-1.0, 0.7)] {
            let o = Orbit::new([0.0; 3], yaw, pitch, 5.0, 0.9);
            let frame = Frame::relative(&q16, &o.camera::<Libm>(1.2));
            let cam = folded_camera::<FloatLibm<4>>(&q16, &frame)
                .unwrap_or_else(|| panic!("no fold at scale {}", frame.vertex_scale));
            assert!(q16_folded_camera(&t, &cam).is_none());
            let q = q16_folded_camera(&q16, &cam).unwrap_or_else(|| panic!("no q16 fold"));
            for v in 0..n {
                let a = FloatPath::<Libm>::transform(&q.matrix, raw.get(v));
                let b = FloatPath::<Libm>::transform(&cam.matrix, dec.get(v));
                let (Some(a), Some(b)) = (a, b) else {
                    panic!("vertex {v}: {a:?} {b:?}");
                };
                let big = b.x.abs().max(b.y.abs()).max(b.w.abs());
                for (x, y) in [(a.x, b.x), (a.y, b.y), (a.w, b.w)] {
                    assert!((x - y).abs() <= big * 1e-6, "vertex {v}: {x} {y}");
                }
            }
        }
    }
}
