//! Compact plane table entries ([`fpt_nostd::format::FLAG_COMPACT_PLANES`]):
//! the writer's half of `fpt_nostd::format::compact_side` (the layout and
//! its error bound are described there).

use fpt_nostd::format::{COMPACT_PLANE_LEN, Q16_MAX};

/// The compact entry of the plane `[n, d]` (unit normal `n`, offset `d`
/// relative to the origin) in a file of plane unit `unit`
/// ([`fpt_nostd::format::plane_unit`] of its half extent): the normal
/// times 32767 and the offset times `32767 / unit`, rounded (the offset
/// clamped to the `i16` range, which only rounding can leave: `|d|` is at
/// most the bounding radius, at most `unit`). `None` for a normal that
/// is not a unit one within what an `f32` plane's rounding allows.
pub(super) fn encode(plane: [f32; 4], unit: f32) -> Option<[u8; COMPACT_PLANE_LEN]> {
    let n = [plane[0], plane[1], plane[2]].map(f64::from);
    let len = n.iter().map(|c| c * c).sum::<f64>().sqrt();
    // NaN fails too.
    if (len - 1.0).abs() >= 1e-5 || !len.is_finite() {
        return None;
    }
    let q = f64::from(Q16_MAX);
    let round = |x: f64| x.round().clamp(-q, q) as i16;
    // Scaled by 1 / |n| too: the entry's rounding is then the only error.
    let m = n.map(|c| round(c / len * q));
    let e = if unit > 0.0 {
        round(f64::from(plane[3]) / len * q / f64::from(unit))
    } else {
        0
    };
    let mut out = [0u8; COMPACT_PLANE_LEN];
    for (chunk, v) in out.chunks_exact_mut(2).zip([m[0], m[1], m[2], e]) {
        chunk.copy_from_slice(&v.to_le_bytes());
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use fpt_nostd::format::{compact_plane, compact_plane_ok};

    /// Round trip: a well-formed entry within the stated error bound of
    /// the plane it encodes, on random planes through the bounding sphere.
    #[test]
    fn round_trip_within_bound() {
        let radius = 3.5f32;
        let unit = fpt_nostd::format::plane_unit([radius, 1.0, 2.0]);
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        let mut worst = 0f64;
        for _ in 0..10_000 {
            let v = [rnd(), rnd(), rnd()];
            let l = v.iter().map(|c| c * c).sum::<f64>().sqrt();
            if l < 1e-3 {
                continue;
            }
            let n = v.map(|c| (c / l) as f32);
            let d = (rnd() * f64::from(radius)) as f32;
            let e = encode([n[0], n[1], n[2], d], unit).unwrap();
            assert!(compact_plane_ok(&e));
            let (m, dd) = compact_plane(&e, unit);
            // Distance between the planes over the bounding sphere: the
            // offsets at the foot point, plus the tilt times the radius.
            let tilt = (0..3)
                .map(|i| f64::from(m[i] - n[i]).powi(2))
                .sum::<f64>()
                .sqrt();
            let err = f64::from(dd - d).abs() + tilt * f64::from(radius) * 2.0;
            worst = worst.max(err / f64::from(radius));
        }
        // unit / 65534 for the offset, √3 / 65534 of a radian for the tilt.
        assert!(worst < 2e-4, "worst relative error {worst}");
        assert!(encode([0.0; 4], unit).is_none());
    }
}
