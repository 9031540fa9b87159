//! Vertex normals per polygon corner: the serializer's input to the
//! `smooth` effect (the optional corner normal section of a file, see
//! `fpt_nostd::format`).
//!
//! Computed from the file's own polygons, after splitting and welding, so
//! that split pieces and the vertices splitting added get normals too: the
//! normal of corner `v` of polygon `p` is the mean of the plane normals of
//! the polygons around vertex `v` whose plane turns from `p`'s by at most
//! the crease angle (`fpt build --crease DEG`, default 30°, the one the
//! outline effect uses), each weighted by its corner's angle at `v` (so a
//! face counts the same however it was cut into pieces or triangles). A
//! vertex where faces meet at a crease thus has a different normal in the
//! corners on either side: feature edges stay sharp, while a tessellated
//! curved surface gets one normal per vertex.
//!
//! Normals written in the mesh file (OBJ `vn`, PLY `nx ny nz`) take the
//! place of the computed ones where a polygon carries them
//! ([`crate::geom::Polygon::normals`], interpolated at the vertices that
//! splitting added): [`stored_corner_normals`]. The crease angle then
//! plays no part for those corners: the file's author chose them.

use glam::DVec3;

/// A unit normal as stored: times 127, rounded, each component in
/// `−127..=127`. A zero or non-finite vector gives `fallback`'s.
fn quantize(n: DVec3, fallback: [f32; 3]) -> [i8; 3] {
    let fallback = DVec3::new(
        f64::from(fallback[0]),
        f64::from(fallback[1]),
        f64::from(fallback[2]),
    );
    let unit = n
        .try_normalize()
        .or_else(|| fallback.try_normalize())
        .unwrap_or(DVec3::Z);
    // A unit vector has a component of at least 1/√3, so 73 or more after
    // scaling: never the zero record the reader rejects.
    unit.to_array()
        .map(|c| (c * 127.0).round().clamp(-127.0, 127.0) as i8)
}

/// The angle of loop `l` at its corner `i` (positions `pos`), in radians;
/// 0 for a degenerate corner.
fn corner_angle(l: &[u32], i: usize, pos: &[DVec3]) -> f64 {
    let n = l.len();
    let at = |k: usize| pos.get(l[k] as usize).copied().unwrap_or(DVec3::ZERO);
    let (a, b, c) = (at((i + n - 1) % n), at(i), at((i + 1) % n));
    let (u, v) = (a - b, c - b);
    if u.length_squared() == 0.0 || v.length_squared() == 0.0 {
        return 0.0;
    }
    u.angle_between(v)
}

/// The normal of every corner of every polygon, in index-list order: for
/// polygons given as vertex id loops `loops` (into `positions`) with plane
/// normals `plane_normals` (unit, outward), smoothed across edges whose
/// faces meet at no more than `crease_deg` degrees (see the module docs).
pub fn corner_normals(
    loops: &[&[u32]],
    plane_normals: &[[f32; 3]],
    positions: &[DVec3],
    crease_deg: f32,
) -> Vec<[i8; 3]> {
    let normal = |p: usize| {
        let n = plane_normals.get(p).copied().unwrap_or([0.0; 3]);
        DVec3::new(f64::from(n[0]), f64::from(n[1]), f64::from(n[2]))
    };
    // The corners around each vertex: (polygon, angle-weighted normal).
    let mut around: Vec<Vec<(usize, DVec3)>> = vec![Vec::new(); positions.len()];
    for (p, l) in loops.iter().enumerate() {
        for (i, &v) in l.iter().enumerate() {
            if let Some(list) = around.get_mut(v as usize) {
                list.push((p, normal(p) * corner_angle(l, i, positions)));
            }
        }
    }
    let cos_crease = f64::from(crease_deg).to_radians().cos();
    let mut out = Vec::with_capacity(loops.iter().map(|l| l.len()).sum());
    for (p, l) in loops.iter().enumerate() {
        let own = normal(p);
        for &v in l.iter() {
            let sum: DVec3 = around
                .get(v as usize)
                .into_iter()
                .flatten()
                .filter(|&&(q, _)| normal(q).dot(own) >= cos_crease - 1e-9)
                .map(|&(_, w)| w)
                .sum();
            let fallback = plane_normals.get(p).copied().unwrap_or([0.0, 0.0, 1.0]);
            out.push(quantize(sum, fallback));
        }
    }
    out
}

/// What the serializer stores: [`corner_normals`], except that the
/// corners of polygon `p` with `file[p]` (one normal per corner, from the
/// mesh file) store those, quantized the same way (a zero or non-finite
/// one gives the plane's normal).
pub fn stored_corner_normals(
    loops: &[&[u32]],
    plane_normals: &[[f32; 3]],
    positions: &[DVec3],
    crease_deg: f32,
    file: &[Option<&[DVec3]>],
) -> Vec<[i8; 3]> {
    let mut out = corner_normals(loops, plane_normals, positions, crease_deg);
    let mut first = 0;
    for (p, l) in loops.iter().enumerate() {
        if let Some(given) = file.get(p).copied().flatten() {
            let fallback = plane_normals.get(p).copied().unwrap_or([0.0, 0.0, 1.0]);
            for (slot, &n) in out.iter_mut().skip(first).take(l.len()).zip(given) {
                *slot = quantize(n, fallback);
            }
        }
        first += l.len();
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube's six faces as quads (outward, counter-clockwise).
    fn cube() -> (Vec<DVec3>, Vec<Vec<u32>>, Vec<[f32; 3]>) {
        let pos = (0..8)
            .map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
            .collect();
        let faces = vec![
            (vec![0, 2, 3, 1], [0.0, 0.0, -1.0]),
            (vec![4, 5, 7, 6], [0.0, 0.0, 1.0]),
            (vec![0, 1, 5, 4], [0.0, -1.0, 0.0]),
            (vec![2, 6, 7, 3], [0.0, 1.0, 0.0]),
            (vec![0, 4, 6, 2], [-1.0, 0.0, 0.0]),
            (vec![1, 3, 7, 5], [1.0, 0.0, 0.0]),
        ];
        let (loops, normals) = faces.into_iter().unzip();
        (pos, loops, normals)
    }

    #[test]
    fn a_crease_keeps_each_face_its_own_normal_and_a_wide_angle_smooths() {
        let (pos, loops, normals) = cube();
        let refs: Vec<&[u32]> = loops.iter().map(|l| l.as_slice()).collect();
        let sharp = corner_normals(&refs, &normals, &pos, 30.0);
        assert_eq!(sharp.len(), 24);
        for (k, n) in sharp.iter().enumerate() {
            let want = normals[k / 4].map(|c| (c * 127.0) as i8);
            assert_eq!(*n, want, "corner {k}");
        }
        // Above 90°, every corner of a vertex takes the mean of its three
        // faces: the diagonal, away from the cube's centre.
        let smooth = corner_normals(&refs, &normals, &pos, 100.0);
        for (k, n) in smooth.iter().enumerate() {
            let v = pos[loops[k / 4][k % 4] as usize] - DVec3::splat(0.5);
            let want = v.normalize().to_array().map(|c| (c * 127.0).round() as i8);
            assert_eq!(*n, want, "corner {k}");
        }
    }

    #[test]
    fn file_normals_replace_the_computed_ones_of_their_polygons() {
        let (pos, loops, normals) = cube();
        let refs: Vec<&[u32]> = loops.iter().map(|l| l.as_slice()).collect();
        let given: Vec<DVec3> = loops[1]
            .iter()
            .map(|&v| pos[v as usize] - DVec3::splat(0.5))
            .collect();
        let mut file: Vec<Option<&[DVec3]>> = vec![None; 6];
        file[1] = Some(&given);
        let n = stored_corner_normals(&refs, &normals, &pos, 30.0, &file);
        let computed = corner_normals(&refs, &normals, &pos, 30.0);
        for (k, (a, b)) in n.iter().zip(&computed).enumerate() {
            if k / 4 == 1 {
                let want = given[k % 4].normalize().to_array();
                assert_eq!(*a, want.map(|c| (c * 127.0).round() as i8), "corner {k}");
                assert_ne!(a, b, "corner {k}");
            } else {
                assert_eq!(a, b, "corner {k}");
            }
        }
    }

    #[test]
    fn a_split_face_counts_once_by_its_angles() {
        // Two faces meeting at 20° along the edge x = 0; the left one is cut
        // into two triangles, whose angles at the shared vertex add up to
        // the quad's, so the normal there is the plain mean of the two.
        let t = 10f64.to_radians();
        let pos = vec![
            DVec3::new(-1.0, 0.0, -t.tan()),
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(-1.0, 1.0, -t.tan()),
            DVec3::new(1.0, 0.0, -t.tan()),
            DVec3::new(1.0, 1.0, -t.tan()),
        ];
        let left = [(-t.sin()) as f32, 0.0, t.cos() as f32];
        let right = [t.sin() as f32, 0.0, t.cos() as f32];
        let loops: Vec<&[u32]> = vec![&[0, 1, 2], &[0, 2, 3], &[1, 4, 5, 2]];
        let n = corner_normals(&loops, &[left, left, right], &pos, 30.0);
        // Corner 1 of the first triangle and corner 0 of the quad: vertex 1.
        assert_eq!(n[1], [0, 0, 127]);
        assert_eq!(n[6], [0, 0, 127]);
        // Vertex 2, where the cut runs: both triangles' corners (45° each)
        // weigh as much as the quad's one right angle.
        for k in [2, 4, 9] {
            assert_eq!(n[k], [0, 0, 127], "corner {k}");
        }
        // Far corners keep their own face's normal.
        assert_eq!(n[0], quantize(DVec3::new(-t.sin(), 0.0, t.cos()), left));
        // A crease of 10° keeps the edge sharp.
        let sharp = corner_normals(&loops, &[left, left, right], &pos, 10.0);
        assert_eq!(sharp[6], quantize(DVec3::new(t.sin(), 0.0, t.cos()), right));
    }
}
