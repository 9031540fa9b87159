//! The walk's loads of a polygon's points through the frame's vertex
//! cache (indexed or tagged), and the cache's fill before a walk whose
//! camera is proven: the [`Renderer`] methods the cached pipeline
//! (`render::cached`) calls for every polygon. Split out of
//! `renderer.rs`, whose module docs state the pipeline.

use super::super::clip::{ClipNum, ClipVert};
use super::super::precision::Precision;
use super::super::proof::VertexBound;
use super::super::transform::{ScreenPt, VertexPath};
use super::super::vcache::{pack_fitting, pack_tagged, unpack, Slot, VertexCache};
use super::{Renderer, Scalar, Scratch};
use crate::effects::Compiled;
use crate::reader::{Tree, VertexIndices};

/// Polygon `i`'s vertex indices into `active`, as [`Renderer::load_cached`]
/// leaves them (each below 2^16: a polygon recorded by them has every
/// vertex cached), for the band walk, which loads without them
/// ([`Renderer::load_cached_bare`]). Out of line and cold: only a polygon
/// whose own index does not fit 16 bits takes it.
#[cold]
#[inline(never)]
pub(crate) fn vertex_indices(tree: &Tree<'_>, i: u32, active: &mut [u16]) {
    for (dst, v) in active.iter_mut().zip(tree.polygon_vertex_indices(i)) {
        *dst = v as u16;
    }
}

impl<P: Precision, E: Compiled> Renderer<P, E> {
    /// Loads a polygon's screen points through `cache` into
    /// `scratch.screen[..n]` and its vertex indices into
    /// `scratch.active[..n]`; a vertex not cached yet is transformed with
    /// `xform` (given its index) and projected, once a frame; a vertex
    /// beyond an indexed cache's capacity is transformed and projected here
    /// without being kept. Returns `n` and whether every vertex is cached
    /// for the rest of the frame (so that the indices stand for the points).
    /// A tagged cache has no indexed slots, so here every vertex is beyond
    /// it: the walk loads through [`Renderer::load_tagged`] instead (and
    /// never by index: a later polygon may take a tagged entry over).
    /// `None` when the polygon
    /// must take the per-polygon path instead: a vertex is [`Slot::Slow`]
    /// (outside a clip plane, not finite or far off screen), or the polygon
    /// has more than `N` vertices. Every path gives the same points (see
    /// [`super::vcache`]).
    #[inline]
    pub(crate) fn load_cached<const N: usize>(
        &self,
        scratch: &mut Scratch<P, N>,
        cache: &mut VertexCache<'_>,
        indices: impl Iterator<Item = u32>,
        xform: impl Fn(u32) -> Option<ClipVert<Scalar<P>>>,
    ) -> Option<(usize, bool)> {
        let project = |v: u32| {
            xform(v)
                .filter(|c| <Scalar<P> as ClipNum>::inside(c, self.near))
                .and_then(|c| P::Path::project_inside(&c, &self.viewport))
        };
        let cap = cache.indexed_len();
        let mut n = 0;
        let mut all = true;
        for v in indices {
            let p = if v as usize >= cap {
                all = false;
                project(v)?
            } else {
                match cache.get_indexed(v) {
                    Slot::Point(p) => p,
                    Slot::Slow => return None,
                    Slot::Unset => cache.insert_indexed(v, project(v))?,
                }
            };
            *scratch.screen.get_mut(n)? = p;
            // Cached vertices have indices below the cache's capacity, at
            // most 2^16 (`render::cached`); the others are not read back.
            *scratch.active.get_mut(n)? = v as u16;
            n += 1;
        }
        Some((n, all))
    }

    /// [`Renderer::load_cached`] without the vertex indices: nothing but
    /// the band walk's record of a polygon by its vertices' indices reads
    /// them (`render::cached::bands`, for a polygon whose own index does
    /// not fit 16 bits, which reads them from the tree instead), and the
    /// fill takes `active` as scratch. Measured (session 19, firmware band
    /// set, every checksum equal): bench_city −37.5 to −42.7 k
    /// instructions a view, house −20.8 to −25.1 k, vise −10.6 to −11.0 k,
    /// mostly the band walk's registers (in line, as here; through a
    /// generic `load_cached` with or without the indices it gained 3 k,
    /// and the full frame, which keeps its own copy above for that
    /// reason, then cost 10 k more).
    ///
    /// A miss takes the vertex `decode` reads by index to the screen
    /// with `point` (transform, clip test and projection in one,
    /// [`Renderer::model_point`]: the finiteness and clip tests shared, as
    /// a tagged cache's misses do), handed this renderer rather than a
    /// closure's reference to it, as in [`Renderer::load_tagged`]
    /// (measured: bench_city bands 9 k cheaper a view).
    #[inline(always)]
    pub(crate) fn load_cached_bare<T, const N: usize>(
        &self,
        scratch: &mut Scratch<P, N>,
        cache: &mut VertexCache<'_>,
        indices: impl Iterator<Item = u32>,
        (decode, point): (impl Fn(u32) -> T, impl Fn(&Self, T) -> Option<ScreenPt>),
    ) -> Option<(usize, bool)> {
        let project = |v: u32| point(self, decode(v));
        let cap = cache.indexed_len();
        let mut n = 0;
        let mut all = true;
        for v in indices {
            let p = if v as usize >= cap {
                all = false;
                project(v)?
            } else {
                match cache.get_indexed(v) {
                    Slot::Point(p) => p,
                    Slot::Slow => return None,
                    Slot::Unset => cache.insert_indexed(v, project(v))?,
                }
            };
            *scratch.screen.get_mut(n)? = p;
            n += 1;
        }
        Some((n, all))
    }

    /// [`Renderer::load_cached`] through a tagged cache: every vertex goes
    /// through it, and none is reported cached for the rest of the frame
    /// (a later polygon may take its entry over), so `scratch.active` is
    /// not written. `point` gives a vertex's screen point from what
    /// `decode` reads of it by index (transform, clip test and projection:
    /// [`Renderer::model_point`]), `None` when it must take the per-polygon
    /// path; it is handed this renderer, not a closure's copy of a
    /// reference to it, so that the compiler sees that the cache's stores
    /// leave the frame's constants alone (the viewport's scales were
    /// computed again at every miss). Out of line: the
    /// walk-and-fill function that inlines `load_cached` keeps the indexed
    /// loop's code (and register allocation) nearly as it was, plus one
    /// test a polygon (docs/cortex-m4.md, "What a frame is made of",
    /// session 13: the placements measured).
    #[inline(never)]
    pub(crate) fn load_tagged<T, const N: usize>(
        &self,
        scratch: &mut Scratch<P, N>,
        cache: &mut VertexCache<'_>,
        indices: VertexIndices<'_>,
        how: (
            impl Fn(u32) -> T + Copy,
            impl Fn(&Self, T) -> Option<ScreenPt> + Copy,
        ),
    ) -> Option<usize> {
        let mut get = |v: u32| {
            cache
                .tagged_word(v, |v| self.tagged_miss(v, how))
                .map(unpack)
        };
        // Two-byte indices (every tree below 2^16 vertices): their count
        // known first, one loop over them and the points without a width
        // test or a count a vertex.
        if let Some(bytes) = indices.narrow() {
            let n = bytes.len() / 2;
            let dst = scratch.screen.get_mut(..n)?;
            for (d, b) in dst.iter_mut().zip(bytes.chunks_exact(2)) {
                *d = get(u32::from(u16::from_le_bytes([b[0], b[1]])))?;
            }
            return Some(n);
        }
        let mut n = 0;
        for v in indices {
            *scratch.screen.get_mut(n)? = get(v)?;
            n += 1;
        }
        Some(n)
    }

    /// A tagged cache's miss: vertex `v`'s point packed into its word
    /// (`vcache::pack_tagged`), `None` when it takes the per-polygon path. Out of
    /// line: the lookup loop keeps its few values in registers, and the
    /// miss its own (measured: the miss in line kept the matrix in
    /// registers but spilled the loop's values, 3 k instructions dearer
    /// on `bench_city` view 0).
    #[inline(never)]
    fn tagged_miss<T>(
        &self,
        v: u32,
        (decode, point): (impl Fn(u32) -> T, impl Fn(&Self, T) -> Option<ScreenPt>),
    ) -> Option<u32> {
        let p = point(self, decode(v))?;
        // Proven once per viewport where the path allows (the float path
        // at the firmware's sizes): then the word without the test.
        if P::Path::points_fit_i16(&self.viewport) {
            Some(pack_fitting(p))
        } else {
            pack_tagged(p)
        }
    }

    /// The screen point of model point `x` as a cache miss computes it
    /// (`VertexPath::project_model`).
    #[inline(always)]
    pub(crate) fn model_point(&self, x: [f32; 3]) -> Option<ScreenPt> {
        P::Path::project_model(&self.matrix, self.near, x, &self.viewport)
    }

    /// [`Renderer::model_point`] of a q16 tree's raw vertex (`frac`
    /// fraction bits): the transform, the clip test and the projection.
    #[inline(always)]
    pub(crate) fn raw_point(&self, x: [i32; 3], frac: u32) -> Option<ScreenPt> {
        P::Path::transform_q(&self.matrix, x, frac)
            .filter(|c| <Scalar<P> as ClipNum>::inside(c, self.near))
            .and_then(|c| P::Path::project_inside(&c, &self.viewport))
    }

    /// Whether this frame's camera lets every model point within `bound`
    /// skip the per-vertex checks (`VertexPath::prove`, once a frame):
    /// then [`Renderer::prefill`] may stand for the walk's transforms.
    pub(crate) fn prove(&self, bound: &VertexBound) -> bool {
        P::Path::prove(&self.matrix, self.near, bound)
    }

    /// Fills `cache` with the screen point of every vertex it holds (the
    /// first `count` at most, `model` giving each by index), transformed
    /// and projected without the per-vertex checks
    /// (`VertexPath::project_proven`), for a frame where
    /// [`Renderer::prove`] holds for every vertex `model` gives. The same
    /// points [`Renderer::load_cached`] finds, found before the walk and
    /// outside it: the walk then finds every cached vertex there, and its
    /// own code (and register allocation) is that of any other frame.
    #[inline(never)]
    pub(crate) fn prefill(
        &self,
        cache: &mut VertexCache<'_>,
        count: usize,
        model: impl Fn(u32) -> [f32; 3],
    ) {
        let (m, near, vp) = (&self.matrix, self.near, &self.viewport);
        let n = cache.capacity().min(count).min(u32::MAX as usize) as u32;
        // Only for an indexed cache (`render::cached::prefill`).
        for v in 0..n {
            let _ = cache.insert_indexed(v, P::Path::project_proven(m, near, model(v), vp));
        }
    }
}
