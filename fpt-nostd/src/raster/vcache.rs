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
//! * Storage: `&mut [u32]`, one word per cached vertex; vertices with an
//!   index at or beyond the slice's length are simply not cached (they are
//!   transformed per polygon, as without a cache). Any length works,
//!   0 included.
//! * A slot holds either nothing yet ([`Slot::Unset`]), a screen point
//!   packed as two `i16` ([`Slot::Point`]), or a note that the vertex must
//!   take the per-polygon path ([`Slot::Slow`]): it lies outside a clip
//!   plane (its polygons need clipping, which needs clip coordinates), its
//!   transform was not finite, or its screen point does not fit 16 bits
//!   (far into the guard band of a large viewport).
//! * Projection is a pure function of the clip vertex, and the clip vertex
//!   a pure function of the vertex and the frame's matrix, so a point read
//!   from the cache is bit-identical to the one the per-polygon path
//!   computes: pictures do not depend on whether, or how much, memory is
//!   given.
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

/// One slot per vertex index (see the module docs).
#[derive(Debug)]
pub struct VertexCache<'m> {
    slots: &'m mut [u32],
}

impl<'m> VertexCache<'m> {
    /// A cache over `slots` (one word per vertex index `0..slots.len()`).
    /// Call [`VertexCache::clear`] before the first frame.
    pub const fn new(slots: &'m mut [u32]) -> Self {
        VertexCache { slots }
    }

    /// Vertices it can hold.
    pub fn capacity(&self) -> usize {
        self.slots.len()
    }

    /// Forgets every vertex (a new frame or camera).
    pub fn clear(&mut self) {
        self.slots.fill(UNSET);
    }

    /// The slot of vertex `v`; [`Slot::Slow`] beyond the capacity.
    #[inline]
    pub fn get(&self, v: u32) -> Slot {
        match self.slots.get(v as usize) {
            None | Some(&SLOW) => Slot::Slow,
            Some(&UNSET) => Slot::Unset,
            Some(&w) => Slot::Point(unpack(w)),
        }
    }

    /// Records vertex `v`'s screen point (`None`: not cacheable). A point
    /// that does not fit 16 bits is recorded as [`Slot::Slow`]; `v` beyond
    /// the capacity is ignored.
    #[inline]
    pub fn set(&mut self, v: u32, p: Option<ScreenPt>) {
        if let Some(slot) = self.slots.get_mut(v as usize) {
            *slot = p.and_then(pack).unwrap_or(SLOW);
        }
    }

    /// [`VertexCache::set`], returning the point when the slot now holds
    /// it (`None`: the vertex takes the per-polygon path).
    #[inline]
    pub fn insert(&mut self, v: u32, p: Option<ScreenPt>) -> Option<ScreenPt> {
        let slot = self.slots.get_mut(v as usize)?;
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
}

/// `p` as two `i16` (x low, y high), or `None` when a coordinate is
/// outside ±(2^15 − 1).
#[inline]
pub(crate) fn pack(p: ScreenPt) -> Option<u32> {
    const LIM: i32 = i16::MAX as i32;
    let ok = (-LIM..=LIM).contains(&p.x) && (-LIM..=LIM).contains(&p.y);
    ok.then_some((p.x as u16 as u32) | ((p.y as u16 as u32) << 16))
}

/// The inverse of [`pack`].
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
}
