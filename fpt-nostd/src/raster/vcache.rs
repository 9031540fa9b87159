//! A per-frame cache of projected vertices, in storage the caller supplies.
//!
//! A tree stores each vertex once and its polygons refer to it by index;
//! a mesh vertex is shared by about six triangles, so transforming each
//! polygon's own corners (what [`super::Renderer::draw_polygon`] does)
//! transforms every visible vertex several times a frame. A
//! [`VertexCache`] keeps one 32-bit slot per vertex index: the vertex's
//! screen point once it has been transformed and projected this frame, so
//! the next polygon that uses it reads it back.
//!
//! # Contract
//!
//! * Storage: `&mut [u32]`, any length, 0 included. Two layouts:
//!   - **indexed** ([`VertexCache::new`]): one word per vertex index
//!     `0..len`; vertices with an index at or beyond the slice's length
//!     are simply not cached (they are transformed per polygon, as without
//!     a cache). Used when the storage holds every vertex of the tree.
//!   - **tagged** ([`VertexCache::tagged`]): for a tree with more vertices
//!     than words, a direct-mapped cache of `2^k` entries of two words
//!     (the vertex index as the tag, then the slot), the largest power of
//!     two that fits; vertex `v` lives in entry `v mod 2^k`, and a vertex
//!     that maps to an occupied entry evicts it. The walk visits a
//!     building's faces close together, so most reuse is caught: on
//!     `bench_city` 256 entries (512 words) take a frame from 6,679 vertex
//!     transforms to about 3,400, against 3,097 distinct vertices.
//!     An evicted vertex is simply transformed again (the same point), so
//!     a point read from a tagged entry is only good until the next
//!     insertion: a caller must copy it out at once, and never record a
//!     vertex by index for later ([`VertexCache::is_tagged`]).
//! * A slot holds either nothing yet ([`Slot::Unset`]), a screen point
//!   packed as two `i16` ([`Slot::Point`]), or a note that the vertex must
//!   take the per-polygon path ([`Slot::Slow`]): it lies outside a clip
//!   plane (its polygons need clipping, which needs clip coordinates), its
//!   transform was not finite, or its screen point does not fit 16 bits
//!   (far into the guard band of a large viewport). A tagged entry holds
//!   only points: such a vertex is not recorded there (its polygons take
//!   the per-polygon path each time), so that a hit is one comparison of
//!   the tag and no test of the word.
//! * Projection is a pure function of the clip vertex, and the clip vertex
//!   a pure function of the vertex and the frame's matrix, so a point read
//!   from the cache is bit-identical to the one the per-polygon path
//!   computes: pictures do not depend on whether, or how much, memory is
//!   given, nor on the layout.
//! * [`VertexCache::clear`] must be called when the camera changes (once
//!   a frame); it writes every slot.
//!
//! ```
//! use fpt_nostd::raster::vcache::{Slot, VertexCache};
//! use fpt_nostd::raster::ScreenPt;
//! let mut words = [0u32; 4];
//! let mut cache = VertexCache::new(&mut words);
//! cache.clear();
//! assert_eq!(cache.get(2), Slot::Unset);
//! cache.set(2, Some(ScreenPt { x: -5, y: 700 }));
//! assert_eq!(cache.get(2), Slot::Point(ScreenPt { x: -5, y: 700 }));
//! cache.set(3, None);
//! assert_eq!(cache.get(3), Slot::Slow);
//! assert_eq!(cache.get(9), Slot::Slow); // beyond the storage: not cached
//!
//! // Tagged: 2 entries (4 words); vertices 1 and 3 share entry 1.
//! let mut words = [0u32; 5];
//! let mut cache = VertexCache::tagged(&mut words);
//! cache.clear();
//! assert_eq!((cache.capacity(), cache.words()), (2, 4));
//! cache.set(3, Some(ScreenPt { x: 1, y: 2 }));
//! assert_eq!(cache.get(3), Slot::Point(ScreenPt { x: 1, y: 2 }));
//! assert_eq!(cache.get(1), Slot::Unset);
//! cache.set(1, Some(ScreenPt { x: 5, y: 6 }));
//! assert_eq!((cache.get(1), cache.get(3)), (Slot::Point(ScreenPt { x: 5, y: 6 }), Slot::Unset));
//! cache.set(3, None); // not cacheable: not recorded, nothing evicted
//! assert_eq!((cache.get(1), cache.get(3)), (Slot::Point(ScreenPt { x: 5, y: 6 }), Slot::Unset));
//! ```

use super::transform::ScreenPt;

/// Nothing stored yet: `(x, y) = (−2^15, −2^15)`, never a packed point
/// (packed coordinates are within ±(2^15 − 1)).
const UNSET: u32 = 0x8000_8000;
/// Per-polygon path: `y = −2^15` with another `x`.
const SLOW: u32 = 0x8000_8001;

/// What the cache knows of a vertex this frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Slot {
    /// Not transformed yet this frame.
    Unset,
    /// Transformed and projected; inside every clip plane.
    Point(ScreenPt),
    /// Not cacheable (see the module docs): use the per-polygon path.
    Slow,
}

/// An empty tagged entry: no vertex index is `u32::MAX` (a tree has at
/// most `u32::MAX` vertices, numbered from 0).
const NO_TAG: u32 = u32::MAX;

/// One slot per vertex index, or tagged entries (see the module docs).
#[derive(Debug)]
pub struct VertexCache<'m> {
    /// Indexed layout: the slot of vertex `v` is `slots[v]`. Tagged: the
    /// tag and the slot of the vertices `v` with `v & (n − 1) == i` (`n` entries) at
    /// `slots[2i]` and `slots[2i + 1]`.
    slots: &'m mut [u32],
    /// Whether the layout is tagged.
    tagged: bool,
}

impl<'m> VertexCache<'m> {
    /// An indexed cache over `slots` (one word per vertex index
    /// `0..slots.len()`). Call [`VertexCache::clear`] before the first
    /// frame.
    pub const fn new(slots: &'m mut [u32]) -> Self {
        VertexCache {
            slots,
            tagged: false,
        }
    }

    /// A tagged cache over `words`: the largest power of two of two-word
    /// entries that fits (the words beyond are unused; fewer than two
    /// words: a cache of capacity 0). For a tree with more vertices than
    /// words. Call [`VertexCache::clear`] before the first frame.
    pub fn tagged(words: &'m mut [u32]) -> Self {
        let pairs = words.len() / 2;
        if pairs == 0 {
            return VertexCache::new(&mut []);
        }
        // The largest power of two not above `pairs`.
        let n = 1usize << (usize::BITS - 1 - pairs.leading_zeros());
        let (used, _) = words.split_at_mut(2 * n);
        VertexCache {
            slots: used,
            tagged: true,
        }
    }

    /// Whether the layout is tagged ([`VertexCache::tagged`]): a point
    /// found may be evicted by the next insertion, so vertices must not be
    /// recorded by index for a later read.
    #[inline]
    pub fn is_tagged(&self) -> bool {
        self.tagged
    }

    /// Vertices it can hold at once (slots, or tagged entries).
    pub fn capacity(&self) -> usize {
        if self.tagged {
            self.slots.len() / 2
        } else {
            self.slots.len()
        }
    }

    /// Vertices with a slot of their own (indices `0..indexed_len()`): the
    /// capacity of an indexed cache, 0 for a tagged one.
    #[inline]
    pub(crate) fn indexed_len(&self) -> usize {
        if self.tagged {
            0
        } else {
            self.slots.len()
        }
    }

    /// The indexed layout's slots (`slots[v]` is vertex `v`'s word, a
    /// point [`unpack`]s from it once [`VertexCache::get`] gave
    /// [`Slot::Point`]); empty for a tagged cache. For a reader that knows
    /// every vertex it reads was cached as a point (the band replay's
    /// records by polygon): no layout test nor sentinel test a vertex.
    #[inline]
    pub(crate) fn indexed_slots(&self) -> &[u32] {
        if self.tagged {
            &[]
        } else {
            self.slots
        }
    }

    /// Words of the storage it uses.
    pub fn words(&self) -> usize {
        self.slots.len()
    }

    /// Forgets every vertex (a new frame or camera).
    pub fn clear(&mut self) {
        if self.tagged {
            for e in self.slots.chunks_exact_mut(2) {
                e.copy_from_slice(&[NO_TAG, UNSET]);
            }
        } else {
            self.slots.fill(UNSET);
        }
    }

    /// The slot of vertex `v`: indexed, [`Slot::Slow`] beyond the
    /// capacity; tagged, [`Slot::Unset`] when its entry holds another
    /// vertex (never [`Slot::Slow`] but with no entry at all). `v` is
    /// below `u32::MAX` (no tree has a vertex of that index: they are
    /// numbered from 0 and counted in a `u32`), the tag of an empty entry.
    #[inline]
    pub fn get(&self, v: u32) -> Slot {
        if self.is_tagged() {
            self.get_tagged(v)
        } else {
            self.get_indexed(v)
        }
    }

    /// [`VertexCache::get`] of the indexed layout (for callers that
    /// branch on the layout once, not per vertex).
    #[inline]
    pub(crate) fn get_indexed(&self, v: u32) -> Slot {
        slot_of(self.slots.get(v as usize).copied())
    }

    /// The tagged layout's entry of vertex `v`: entry `v & (n − 1)` of
    /// the `n` two-word entries (a power of two; `None` when there are
    /// none). The mask is taken from the entries' own count, so the
    /// compiler sees that the entry is in bounds whenever `n > 0`: one
    /// test a frame, hoisted out of the lookup loops, not one a vertex.
    #[inline(always)]
    fn entry_mut(&mut self, v: u32) -> Option<&mut [u32; 2]> {
        let entries = self.slots.as_chunks_mut::<2>().0;
        let i = (v as usize) & entries.len().wrapping_sub(1);
        entries.get_mut(i)
    }

    /// [`VertexCache::get`] of the tagged layout.
    #[inline]
    fn get_tagged(&self, v: u32) -> Slot {
        let entries = self.slots.as_chunks::<2>().0;
        match entries.get((v as usize) & entries.len().wrapping_sub(1)) {
            Some(&[tag, w]) if tag == v => Slot::Point(unpack(w)),
            Some(_) => Slot::Unset,
            None => Slot::Slow,
        }
    }

    /// The packed point of vertex `v` from a tagged cache: the entry's
    /// word when it holds `v`, else `word(v)` (the point [`pack_tagged`]),
    /// recorded, evicting the entry's vertex. `None` (not recorded, the
    /// entry left as it was) when `word` gives none (no point, or one that
    /// does not fit 16 bits) or the cache has no entry: the vertex takes
    /// the per-polygon path. A tagged entry never holds [`Slot::Slow`], so
    /// a hit is one comparison of the tag.
    #[inline(always)]
    pub(crate) fn tagged_word(
        &mut self,
        v: u32,
        word: impl FnOnce(u32) -> Option<u32>,
    ) -> Option<u32> {
        let [tag, slot] = self.entry_mut(v)?;
        if *tag == v {
            return Some(*slot);
        }
        let w = word(v)?;
        *tag = v;
        *slot = w;
        Some(w)
    }

    /// Records vertex `v`'s screen point (`None`: not cacheable). A point
    /// that does not fit 16 bits is recorded as [`Slot::Slow`]; `v` beyond
    /// an indexed cache's capacity is ignored.
    #[inline]
    pub fn set(&mut self, v: u32, p: Option<ScreenPt>) {
        let _ = self.insert(v, p);
    }

    /// [`VertexCache::set`], returning the point when the slot now holds
    /// it (`None`: the vertex takes the per-polygon path).
    #[inline]
    pub fn insert(&mut self, v: u32, p: Option<ScreenPt>) -> Option<ScreenPt> {
        if self.is_tagged() {
            self.insert_tagged(v, p)
        } else {
            self.insert_indexed(v, p)
        }
    }

    /// [`VertexCache::insert`] of the indexed layout.
    #[inline]
    pub(crate) fn insert_indexed(&mut self, v: u32, p: Option<ScreenPt>) -> Option<ScreenPt> {
        store(self.slots.get_mut(v as usize)?, p)
    }

    /// [`VertexCache::insert`] of the tagged layout: `v` takes its entry
    /// over from whatever vertex held it when `p` is a point that fits 16
    /// bits; otherwise nothing is recorded (as [`VertexCache::tagged_word`]
    /// does).
    #[inline]
    fn insert_tagged(&mut self, v: u32, p: Option<ScreenPt>) -> Option<ScreenPt> {
        let [tag, slot] = self.entry_mut(v)?;
        let w = pack_tagged(p?)?;
        *tag = v;
        *slot = w;
        p
    }
}

/// The [`Slot`] a stored word stands for (`None`: beyond the storage).
#[inline]
fn slot_of(word: Option<u32>) -> Slot {
    match word {
        None | Some(SLOW) => Slot::Slow,
        Some(UNSET) => Slot::Unset,
        Some(w) => Slot::Point(unpack(w)),
    }
}

/// Stores `p` into `slot` (as [`Slot::Slow`] when it is `None` or does
/// not fit 16 bits); returns it when stored as a point.
#[inline]
fn store(slot: &mut u32, p: Option<ScreenPt>) -> Option<ScreenPt> {
    match p.and_then(pack) {
        Some(w) => {
            *slot = w;
            p
        }
        None => {
            *slot = SLOW;
            None
        }
    }
}

/// `p` as two `i16` (x low, y high), or `None` when a coordinate is
/// outside ±(2^15 − 1).
#[inline]
pub(crate) fn pack(p: ScreenPt) -> Option<u32> {
    const LIM: i32 = i16::MAX as i32;
    let ok = (-LIM..=LIM).contains(&p.x) && (-LIM..=LIM).contains(&p.y);
    ok.then_some((p.x as u16 as u32) | ((p.y as u16 as u32) << 16))
}

/// [`pack`] for a tagged entry, which holds no sentinel (a hit is its
/// tag): any `i16` pair, `−2^15` included; a sign extension and a
/// comparison a coordinate.
#[inline]
pub(crate) fn pack_tagged(p: ScreenPt) -> Option<u32> {
    let fits = |c: i32| i32::from(c as i16) == c;
    (fits(p.x) && fits(p.y)).then_some(pack_fitting(p))
}

/// [`pack_tagged`] of a point already known to fit `i16` on both axes
/// (`VertexPath::points_fit_i16`): the same word, without the test.
#[inline]
pub(crate) fn pack_fitting(p: ScreenPt) -> u32 {
    (p.x as u16 as u32) | ((p.y as u16 as u32) << 16)
}

/// The inverse of [`pack`] and [`pack_tagged`].
#[inline]
pub(crate) fn unpack(w: u32) -> ScreenPt {
    ScreenPt {
        x: i32::from(w as u16 as i16),
        y: i32::from((w >> 16) as u16 as i16),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `Viewport::float_points_fit_i16` holds only where the float path's
    /// extreme points (the NDC clamp's `±4.5` on both axes) pack with the
    /// test, so `tagged_miss` may leave it out there.
    #[test]
    fn float_points_fit_i16_where_claimed() {
        use super::super::precision::Libm;
        use super::super::transform::{FloatPath, VertexPath, Viewport};
        assert!(Viewport::new(11915, 1, 0).unwrap().float_points_fit_i16());
        assert!(!Viewport::new(11916, 1, 0).unwrap().float_points_fit_i16());
        assert!(Viewport::new(240, 240, 4).unwrap().float_points_fit_i16());
        for (side, sub) in [(11915, 0), (5957, 1), (240, 4), (186, 6), (46, 8), (1, 0)] {
            let vp = Viewport::new(side, side, sub).unwrap();
            assert!(vp.float_points_fit_i16());
            for (x, y) in [(-1e9, -1e9), (1e9, 1e9), (-1e9, 1e9), (1e9, -1e9)] {
                let c = crate::raster::clip::ClipVert { x, y, w: 1.0 };
                let p = FloatPath::<Libm>::project_clipped(&c, &vp).unwrap();
                assert_eq!(pack_tagged(p), Some(pack_fitting(p)), "{side} {sub} {p:?}");
            }
        }
    }

    #[test]
    fn pack_round_trips_and_rejects_the_sentinels() {
        for (x, y) in [(0, 0), (-1, 1), (32767, -32767), (-32767, 32767), (5, -9)] {
            let p = ScreenPt { x, y };
            let w = pack(p);
            assert_eq!(w.map(unpack), Some(p));
            assert!(w != Some(UNSET) && w != Some(SLOW));
        }
        for (x, y) in [(-32768, 0), (0, -32768), (40000, 0), (0, i32::MIN)] {
            assert_eq!(pack(ScreenPt { x, y }), None);
        }
    }

    #[test]
    fn out_of_range_points_and_indices_are_slow() {
        let mut w = [0u32; 2];
        let mut c = VertexCache::new(&mut w);
        c.clear();
        c.set(0, Some(ScreenPt { x: 1 << 20, y: 0 }));
        assert_eq!(c.get(0), Slot::Slow);
        c.set(7, Some(ScreenPt { x: 1, y: 1 }));
        assert_eq!(c.get(7), Slot::Slow);
        assert_eq!(c.get(1), Slot::Unset);
        let mut none: [u32; 0] = [];
        let c = VertexCache::new(&mut none);
        assert_eq!((c.capacity(), c.get(0)), (0, Slot::Slow));
    }

    #[test]
    fn tagged_layout_uses_a_power_of_two_of_pairs() {
        for (len, cap) in [
            (0, 0),
            (1, 0),
            (2, 1),
            (3, 1),
            (4, 2),
            (7, 2),
            (8, 4),
            (900, 256),
        ] {
            let mut w = [7u32; 900];
            let mut c = VertexCache::tagged(&mut w[..len]);
            c.clear();
            assert_eq!((c.capacity(), c.words()), (cap, 2 * cap), "{len} words");
            assert_eq!(c.is_tagged(), cap > 0, "{len} words");
            // Every vertex misses after a clear, whatever the old words.
            for v in [0, 1, 5, 1000, u32::MAX - 1] {
                let want = if cap > 0 { Slot::Unset } else { Slot::Slow };
                assert_eq!(c.get(v), want, "{len} words, vertex {v}");
            }
        }
        // The words beyond the entries are left alone.
        let mut w = [5u32; 7];
        VertexCache::tagged(&mut w).clear();
        assert_eq!(w[4..], [5, 5, 5]);
        assert!(w[..4] != [5, 5, 5, 5]);
    }

    #[test]
    fn tagged_hits_misses_and_evictions() {
        let mut w = [0u32; 8];
        let mut c = VertexCache::tagged(&mut w);
        c.clear();
        let p = |x| Some(ScreenPt { x, y: -x });
        // Vertices 1, 5, 9 share entry 1 of 4; 2 has its own.
        assert_eq!(c.insert(1, p(10)), p(10));
        assert_eq!(c.insert(2, p(20)), p(20));
        assert_eq!(c.get(1), Slot::Point(ScreenPt { x: 10, y: -10 }));
        assert_eq!(c.get(5), Slot::Unset);
        assert_eq!(c.insert(5, p(50)), p(50));
        assert_eq!(
            (c.get(1), c.get(5)),
            (Slot::Unset, Slot::Point(ScreenPt { x: 50, y: -50 }))
        );
        // A vertex that must take the per-polygon path is not recorded
        // (nor evicts), nor is a point beyond 16 bits.
        assert_eq!(c.insert(9, None), None);
        assert_eq!(
            (c.get(9), c.get(5)),
            (Slot::Unset, Slot::Point(ScreenPt { x: 50, y: -50 }))
        );
        assert_eq!(c.insert(1, p(1 << 16)), None);
        assert_eq!(c.get(1), Slot::Unset);
        assert_eq!(c.get(5), Slot::Point(ScreenPt { x: 50, y: -50 }));
        // A hit does not compute the point again.
        let w = pack(ScreenPt { x: 50, y: -50 });
        assert_eq!(c.tagged_word(5, |_| unreachable!()), w);
        // A tagged entry holds no sentinel: −2^15 is a coordinate there.
        let low = ScreenPt {
            x: -32768,
            y: 32767,
        };
        assert_eq!(c.insert(13, Some(low)), Some(low));
        assert_eq!(c.get(13), Slot::Point(low));
        assert_eq!(pack_tagged(ScreenPt { x: 0, y: -32769 }), None);
        assert_eq!(c.get(2), Slot::Point(ScreenPt { x: 20, y: -20 }));
        // The tag is the whole index: a vertex 2^32 apart cannot exist, but
        // one a multiple of the entries apart never reads another's point.
        for v in (2..1000).step_by(4) {
            assert!(v == 2 || c.get(v) == Slot::Unset, "vertex {v}");
        }
        // A new frame forgets everything.
        c.clear();
        assert!((0..16).all(|v| c.get(v) == Slot::Unset));
    }

    #[test]
    fn both_layouts_give_back_the_very_point_stored() {
        // Points at the edges of the packed range, and the sentinels' own
        // coordinates' neighbours.
        let pts = [
            (0, 0),
            (-32767, -32767),
            (32767, 32767),
            (-32767, 32767),
            (1, -32767),
            (-32767, 1),
            (-1, -1),
        ];
        let mut a = [0u32; 16];
        let mut b = [0u32; 4];
        let mut indexed = VertexCache::new(&mut a);
        let mut tagged = VertexCache::tagged(&mut b);
        indexed.clear();
        tagged.clear();
        for (v, &(x, y)) in pts.iter().enumerate() {
            let p = ScreenPt { x, y };
            let v = v as u32;
            assert_eq!(indexed.insert(v, Some(p)), Some(p));
            assert_eq!(tagged.insert(v, Some(p)), Some(p));
            assert_eq!(indexed.get(v), Slot::Point(p));
            assert_eq!(tagged.get(v), Slot::Point(p));
        }
    }
}
