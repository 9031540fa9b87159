//! The common pipeline after parsing: weld, clean, drop degenerate faces,
//! planarize, merge coplanar neighbours (`super::coplanar`), decide
//! closedness.
//!
//! Tolerances, all relative to the bounding-box diagonal `D` of the vertices
//! that faces use:
//! - vertices closer than [`WELD_REL`]` × D` are welded into one (the first
//!   one met keeps its position);
//! - a face is degenerate when it has fewer than three distinct vertices
//!   after welding, or when it is thinner than the builder's tolerance
//!   (`geom::REL_EPS × D`): `4·area ≤ tol·perimeter`;
//! - a face is planar when no vertex is farther than [`PLANAR_REL`]` × D` from
//!   its Newell plane (see [`super::planar`] for what happens otherwise);
//!   no vertex is ever moved onto a plane.
//!
//! Closedness is decided on the welded, cleaned index loops of the kept
//! input faces (before any planar split), so the split's internal diagonals
//! play no part in it.

use super::planar::{self, Planarized, Tols};
use super::{ImportOptions, ImportReport, MeshError, Model};
use crate::geom::{Polygon, Tolerance, DEFAULT_COLOR};
use glam::DVec3;
use std::collections::{HashMap, VecDeque};

/// Welding distance, relative to the bounding-box diagonal.
pub const WELD_REL: f64 = 1e-6;

/// Planarity tolerance, relative to the bounding-box diagonal: half the
/// builder's [`crate::geom::REL_EPS`], so that the builder classifies every
/// vertex of a face as on the face's own plane, with room to spare for
/// rounding, *without moving it*. Snapping each face onto its own plane
/// (as the import once did, within ten times this) moves a vertex that
/// several faces share to a different point for each of them, so
/// neighbouring faces no longer meet edge for edge and the rasterizer can
/// open a crack between them (`violin_case.obj`: about 1300 such edges).
/// A face farther from planar (print noise of six-decimal files included:
/// up to 1.1e-7 of the diagonal in `shuttle.obj`) is cut into planar
/// pieces between its own vertices instead; `rabbit.obj` and
/// `wallhole.obj` stay under 1e-9 and are kept whole.
pub const PLANAR_REL: f64 = 0.5 * crate::geom::REL_EPS;

/// The common post-parse pipeline: builds a [`Model`] from positions and
/// faces given as vertex-index loops (counter-clockwise seen from the front).
///
/// `faces[i]` becomes polygons with `source == i`. `colors`, when given,
/// holds one colour per face (missing entries get
/// [`DEFAULT_COLOR`]). Vertices that no face uses are ignored (they do not
/// widen the model's size nor have to be finite).
///
/// Errors: [`MeshError::BadIndex`] for an index past the vertex list,
/// [`MeshError::NonFinite`] for a NaN/infinite used coordinate,
/// [`MeshError::TooLarge`] for a model larger than [`super::MAX_SIZE`],
/// [`MeshError::FarVertex`] when one vertex alone stretches the model so
/// far that the others weld into a point, [`MeshError::Empty`] when no
/// face with area is left otherwise.
pub fn from_faces(
    vertices: &[[f64; 3]],
    faces: &[Vec<u32>],
    colors: Option<&[[u8; 3]]>,
) -> Result<Model, MeshError> {
    from_faces_with(vertices, faces, colors, &ImportOptions::default())
}

/// [`from_faces`] with options: closed parts that wind inward are turned
/// outward unless `options.keep_orientation` (see the `parts` module; the
/// report counts them either way).
pub fn from_faces_with(
    vertices: &[[f64; 3]],
    faces: &[Vec<u32>],
    colors: Option<&[[u8; 3]]>,
    options: &ImportOptions,
) -> Result<Model, MeshError> {
    from_faces_normals(vertices, faces, colors, None, options)
}

/// The vertex normals a mesh file gives its faces: entry `i`, when
/// `Some`, holds one normal per corner of face `i` (in its corner order);
/// a face without normals (or a list too short) gets `None`.
pub type FaceNormals = [Option<Vec<[f64; 3]>>];

/// [`from_faces_with`] with the file's vertex normals (see
/// [`FaceNormals`]), for the `smooth` effect: every polygon of a face with
/// normals gets [`Polygon::normals`], one per vertex, the normal of the
/// face's corner at that vertex (after welding, the first corner of the
/// face at a welded vertex). A face whose normals are not all finite and
/// non-zero gets none (the serializer then computes its corners' with the
/// crease angle). Normals are made unit, and a polygon whose normals point
/// mostly against its plane (their sum behind it: a file whose normals
/// follow the other winding, or a part turned outward here) gets them
/// negated, so that they are on the side its plane faces.
pub fn from_faces_normals(
    vertices: &[[f64; 3]],
    faces: &[Vec<u32>],
    colors: Option<&[[u8; 3]]>,
    normals: Option<&FaceNormals>,
    options: &ImportOptions,
) -> Result<Model, MeshError> {
    let mut used = vec![false; vertices.len()];
    for (fi, f) in faces.iter().enumerate() {
        for &i in f {
            let slot = used.get_mut(i as usize).ok_or(MeshError::BadIndex {
                face: fi,
                index: u64::from(i),
                vertices: vertices.len(),
            })?;
            *slot = true;
        }
    }
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    let mut used_count = 0usize;
    for (v, _) in vertices.iter().zip(&used).filter(|(_, &u)| u) {
        let p = DVec3::from(*v);
        if !p.is_finite() {
            return Err(MeshError::NonFinite);
        }
        lo = lo.min(p);
        hi = hi.max(p);
        used_count += 1;
    }
    if used_count == 0 {
        return Err(MeshError::Empty);
    }
    let diag = (hi - lo).length();
    // Finite coordinates whose span overflows are a model too large too.
    if !diag.is_finite() || diag > super::MAX_SIZE {
        return Err(MeshError::TooLarge { diag });
    }
    // A model that is one point still gets non-zero tolerances; all its faces
    // are then degenerate and the result is `Empty`.
    let scale = if diag > 0.0 { diag } else { 1.0 };
    let tols = Tols {
        planar: PLANAR_REL * scale,
        build: Tolerance::for_diagonal(diag).0,
    };
    let (map, reps) = weld(vertices, &used, lo, WELD_REL * scale);

    let mut report = ImportReport {
        faces_read: faces.len(),
        welded_vertices: used_count - reps.len(),
        ..ImportReport::default()
    };
    let mut polygons = Vec::with_capacity(faces.len());
    let mut kept_loops = Vec::with_capacity(faces.len());
    // The first polygon of each kept loop (its pieces follow it).
    let mut first_polygon = Vec::with_capacity(faces.len());
    for (fi, face) in faces.iter().enumerate() {
        let ids = clean_loop(face.iter().map(|&i| map[i as usize]));
        if ids.len() < 3 {
            report.dropped_degenerate += 1;
            continue;
        }
        let pts: Vec<DVec3> = ids.iter().map(|&i| reps[i as usize]).collect();
        let color = colors
            .and_then(|c| c.get(fi))
            .copied()
            .unwrap_or(DEFAULT_COLOR);
        let source = u32::try_from(fi).unwrap_or(u32::MAX);
        let start = polygons.len();
        match planar::planarize(&pts, source, color, tols) {
            Planarized::Degenerate => {
                report.dropped_degenerate += 1;
                continue;
            }
            Planarized::Whole(p) => polygons.push(p),
            Planarized::Split(pieces) => {
                report.nonplanar_split += 1;
                polygons.extend(pieces);
            }
        }
        if let Some(corners) = normals.and_then(|n| n.get(fi)).and_then(Option::as_ref) {
            let at = |i: u32| reps[map[i as usize] as usize];
            attach_normals(&mut polygons[start..], face, corners, at);
        }
        kept_loops.push(ids);
        first_polygon.push(start);
    }
    if polygons.is_empty() {
        return Err(far_vertex(vertices, &used, diag).unwrap_or(MeshError::Empty));
    }
    if report.dropped_degenerate > 0 {
        if let Some(e) = far_vertex(vertices, &used, diag) {
            return Err(e);
        }
    }
    let parts = super::parts::analyse(&kept_loops, &reps);
    report.closed_parts = parts.closed_count();
    report.open_parts = parts.open_count();
    report.inverted_parts = parts.inverted_count();
    report.boundary_edges = parts.boundary_edges;
    report.open_edges = parts.open_edges;
    report.orientation_kept = options.keep_orientation;
    if !options.keep_orientation && report.inverted_parts > 0 {
        let ends = first_polygon
            .iter()
            .skip(1)
            .copied()
            .chain([polygons.len()]);
        for ((&start, end), &part) in first_polygon.iter().zip(ends).zip(&parts.part_of) {
            if parts.inverted[part as usize] {
                polygons[start..end].iter_mut().for_each(flip);
            }
        }
    }
    if !options.no_merge {
        let before = polygons.len();
        polygons =
            super::coplanar::merge_coplanar(polygons, tols, super::coplanar::MAX_MERGED_VERTS);
        report.coplanar_merged = before - polygons.len();
    }
    polygons.iter_mut().for_each(orient_normals);
    Ok(Model {
        polygons,
        closed: is_closed_faces(&kept_loops),
        report,
    })
}

/// Gives `polygons` (the pieces of face `face`, whose vertices are the
/// face's welded vertices, at `at(index)`) the normals `corners` of the
/// face's corners, matched by position; leaves them without when a normal
/// is not finite and non-zero or a vertex is not the face's.
fn attach_normals(
    polygons: &mut [Polygon],
    face: &[u32],
    corners: &[[f64; 3]],
    at: impl Fn(u32) -> DVec3,
) {
    if corners.len() != face.len() {
        return;
    }
    let key = |v: DVec3| v.to_array().map(f64::to_bits);
    let mut of: HashMap<[u64; 3], DVec3> = HashMap::with_capacity(face.len());
    for (&i, &n) in face.iter().zip(corners) {
        let Some(unit) = DVec3::from(n).try_normalize() else {
            return;
        };
        // The first corner at a (welded) vertex wins.
        of.entry(key(at(i))).or_insert(unit);
    }
    for p in polygons {
        p.normals = p.verts.iter().map(|&v| of.get(&key(v)).copied()).collect();
    }
}

/// Negates `p`'s normals when their sum points behind its plane (see
/// [`from_faces_normals`]).
fn orient_normals(p: &mut Polygon) {
    let normal = p.plane.normal;
    if let Some(n) = &mut p.normals {
        if n.iter().map(|&v| v.dot(normal)).sum::<f64>() < 0.0 {
            n.iter_mut().for_each(|v| *v = -*v);
        }
    }
}

/// Turns a polygon to face the other way: the same vertices in reverse
/// order, the plane's normal and offset negated (exactly).
fn flip(p: &mut Polygon) {
    p.verts.reverse();
    if let Some(n) = &mut p.normals {
        n.reverse();
    }
    p.plane = p.plane.flipped();
}

/// The one used vertex that alone stretches the model: without it the other
/// used vertices span no more than the weld distance of the whole model, so
/// at the model's scale they all weld into one point and every face near
/// them loses its area. `None` when there is no such vertex (then the
/// faces were degenerate for their own reasons).
///
/// Only the vertices at the six extremes of the bounding box can be it;
/// each is tried by recomputing the box without it (linear).
fn far_vertex(vertices: &[[f64; 3]], used: &[bool], diag: f64) -> Option<MeshError> {
    let pts = || {
        vertices
            .iter()
            .enumerate()
            .zip(used)
            .filter(|(_, &u)| u)
            .map(|((i, v), _)| (i, DVec3::from(*v)))
    };
    let mut extremes: Vec<usize> = Vec::with_capacity(6);
    for axis in 0..3 {
        let key = |p: &(usize, DVec3)| p.1[axis];
        let lo = pts().min_by(|a, b| key(a).total_cmp(&key(b)));
        let hi = pts().max_by(|a, b| key(a).total_cmp(&key(b)));
        extremes.extend(lo.into_iter().chain(hi).map(|(i, _)| i));
    }
    extremes.sort_unstable();
    extremes.dedup();
    extremes.into_iter().find_map(|far| {
        let (lo, hi) = pts().filter(|&(i, _)| i != far).fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), (_, p)| (lo.min(p), hi.max(p)),
        );
        let rest = (hi - lo).length();
        let position = *vertices.get(far)?;
        (rest.is_finite() && rest > 0.0 && rest <= WELD_REL * diag).then_some(
            MeshError::FarVertex {
                index: far,
                position,
                rest,
            },
        )
    })
}

/// Welds the used vertices within `tol` with a uniform grid of cell size
/// `tol`: a vertex joins the first representative within `tol` in the 27
/// cells around it, else becomes a representative. Representatives are then
/// pairwise farther apart than `tol`, so a cell holds only a few of them and
/// the whole pass is linear.
///
/// Returns, for every input vertex, its representative's index (`u32::MAX`
/// for unused vertices) and the representatives' positions.
fn weld(vertices: &[[f64; 3]], used: &[bool], origin: DVec3, tol: f64) -> (Vec<u32>, Vec<DVec3>) {
    let inv = 1.0 / tol;
    let cell = |p: DVec3| -> [i64; 3] {
        let c = ((p - origin) * inv).floor();
        // Coordinates are at most diag/tol = 1e6 cells from the origin.
        [c.x as i64, c.y as i64, c.z as i64]
    };
    let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    let mut map = vec![u32::MAX; vertices.len()];
    let mut reps: Vec<DVec3> = Vec::new();
    for (i, v) in vertices.iter().enumerate() {
        if !used[i] {
            continue;
        }
        let p = DVec3::from(*v);
        let c = cell(p);
        let mut found = None;
        'search: for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let key = [c[0] + dx, c[1] + dy, c[2] + dz];
                    if let Some(list) = grid.get(&key) {
                        if let Some(&r) = list
                            .iter()
                            .find(|&&r| reps[r as usize].distance_squared(p) <= tol * tol)
                        {
                            found = Some(r);
                            break 'search;
                        }
                    }
                }
            }
        }
        map[i] = match found {
            Some(r) => r,
            None => {
                // `vertices.len()` fits in u32 for every parser; saturate
                // rather than wrap if a caller passes more.
                let r = u32::try_from(reps.len()).unwrap_or(u32::MAX);
                reps.push(p);
                grid.entry(c).or_default().push(r);
                r
            }
        };
    }
    (map, reps)
}

/// Removes consecutive repeats (also across the wrap) and "spikes" `x a x`
/// that go out to a vertex and straight back, in linear time.
fn clean_loop(ids: impl Iterator<Item = u32>) -> Vec<u32> {
    let mut out: VecDeque<u32> = VecDeque::new();
    for v in ids {
        if out.back() == Some(&v) {
            continue;
        }
        if out.len() >= 2 && out[out.len() - 2] == v {
            out.pop_back();
            continue;
        }
        out.push_back(v);
    }
    // The same two rules across the seam between the end and the start; each
    // step removes a vertex, so this is linear too.
    while out.len() >= 3 {
        let n = out.len();
        if out[0] == out[n - 1] {
            out.pop_back();
        } else if out[n - 2] == out[0] {
            // ... x a | x ...: the spike is the last vertex.
            out.pop_back();
        } else if out[n - 1] == out[1] {
            // ... x | a x ...: the spike is the first vertex.
            out.pop_front();
        } else {
            break;
        }
    }
    if out.len() == 2 && out[0] == out[1] {
        out.pop_back();
    }
    out.into()
}

/// Whether index loops form a closed volume: every directed edge `a→b`
/// (consecutive equal indices ignored) is used exactly once and its reverse
/// `b→a` exactly once too. No faces means not closed.
pub fn is_closed_faces(faces: &[Vec<u32>]) -> bool {
    let mut count: HashMap<(u32, u32), u32> = HashMap::new();
    for f in faces {
        for (k, &a) in f.iter().enumerate() {
            let b = f[(k + 1) % f.len()];
            if a != b {
                *count.entry((a, b)).or_insert(0) += 1;
            }
        }
    }
    !count.is_empty()
        && count
            .iter()
            .all(|(&(a, b), &c)| c == 1 && count.get(&(b, a)) == Some(&1))
}

/// Whether polygons form a closed volume, their vertices welded within `tol`
/// (absolute distance). Pieces of one split face close up along their shared
/// diagonals, so this works on an imported [`Model`]'s polygons with `tol`
/// at least the import's weld and planarity distances (e.g. `2e-6 × diag`).
pub fn is_closed(polygons: &[Polygon], tol: f64) -> bool {
    let points: Vec<[f64; 3]> = polygons
        .iter()
        .flat_map(|p| p.verts.iter().map(|v| v.to_array()))
        .collect();
    if points.is_empty() || points.iter().flatten().any(|c| !c.is_finite()) {
        return false;
    }
    let origin = points
        .iter()
        .fold(DVec3::splat(f64::INFINITY), |m, &p| m.min(DVec3::from(p)));
    let tol = if tol.is_finite() && tol > 0.0 {
        tol
    } else {
        f64::MIN_POSITIVE
    };
    let (map, _) = weld(&points, &vec![true; points.len()], origin, tol);
    let mut next = 0usize;
    let loops: Vec<Vec<u32>> = polygons
        .iter()
        .map(|p| {
            let ids = map[next..next + p.verts.len()].iter().copied();
            next += p.verts.len();
            clean_loop(ids)
        })
        .collect();
    is_closed_faces(&loops)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::area;

    /// Unit cube, faces counter-clockwise seen from outside.
    fn cube() -> (Vec<[f64; 3]>, Vec<Vec<u32>>) {
        let v = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [1.0, 1.0, 1.0],
            [0.0, 1.0, 1.0],
        ];
        let f = vec![
            vec![0, 3, 2, 1], // bottom, normal -z
            vec![4, 5, 6, 7], // top, +z
            vec![0, 1, 5, 4], // front, -y
            vec![2, 3, 7, 6], // back, +y
            vec![1, 2, 6, 5], // right, +x
            vec![3, 0, 4, 7], // left, -x
        ];
        (v, f)
    }

    #[test]
    fn cube_is_closed_with_outward_normals() {
        let (v, f) = cube();
        let m = from_faces(&v, &f, None).unwrap();
        assert!(m.closed);
        assert_eq!(m.polygons.len(), 6);
        let centre = DVec3::splat(0.5);
        for p in &m.polygons {
            let c = crate::geom::centroid(&p.verts);
            assert!(p.plane.normal.dot(c - centre) > 0.0, "inward normal");
            assert_eq!(p.color, DEFAULT_COLOR);
        }
        let sources: Vec<u32> = m.polygons.iter().map(|p| p.source).collect();
        assert_eq!(sources, vec![0, 1, 2, 3, 4, 5]);
        assert!(is_closed(&m.polygons, 1e-9));
    }

    #[test]
    fn inside_out_cube_is_flipped_unless_kept() {
        let (v, mut f) = cube();
        f.iter_mut().for_each(|l| l.reverse());
        let centre = DVec3::splat(0.5);
        let outward = |m: &Model| {
            m.polygons.iter().all(|p| {
                let c = crate::geom::centroid(&p.verts);
                p.plane.normal.dot(c - centre) > 0.0 && p.plane.distance(c).abs() < 1e-12
            })
        };
        let m = from_faces(&v, &f, None).unwrap();
        assert!(m.closed);
        assert_eq!((m.report.closed_parts, m.report.inverted_parts), (1, 1));
        assert!(!m.report.orientation_kept);
        assert!(outward(&m));
        let opts = ImportOptions {
            keep_orientation: true,
            ..ImportOptions::default()
        };
        let kept = from_faces_with(&v, &f, None, &opts).unwrap();
        assert!(kept.closed && kept.report.orientation_kept);
        assert!(kept.polygons.iter().all(|p| {
            let c = crate::geom::centroid(&p.verts);
            p.plane.normal.dot(c - centre) < 0.0
        }));
        let correct = from_faces(&v, &cube().1, None).unwrap();
        assert_eq!(correct.report.inverted_parts, 0);
        assert!(outward(&correct));
    }

    #[test]
    fn one_far_vertex_is_named_instead_of_an_empty_mesh() {
        let (mut v, mut f) = cube();
        v.push([0.0, 1e30, 0.0]);
        f.push(vec![0, 1, 8]);
        match from_faces(&v, &f, None) {
            Err(MeshError::FarVertex { index: 8, rest, .. }) => {
                assert!((rest - 3f64.sqrt()).abs() < 1e-12)
            }
            other => panic!("{other:?}"),
        }
        // Two far vertices: no single one is to blame.
        v.push([0.0, -1e30, 0.0]);
        f.push(vec![0, 9, 1]);
        assert!(matches!(from_faces(&v, &f, None), Err(MeshError::Empty)));
        // A large model whose size comes from all its vertices is fine.
        let big: Vec<[f64; 3]> = cube().0.iter().map(|p| p.map(|c| c * 1e30)).collect();
        assert!(from_faces(&big, &cube().1, None).unwrap().closed);
    }

    #[test]
    fn cube_missing_a_face_is_open() {
        let (v, mut f) = cube();
        f.pop();
        let m = from_faces(&v, &f, None).unwrap();
        assert!(!m.closed);
        assert!(!is_closed(&m.polygons, 1e-9));
    }

    #[test]
    fn cube_with_a_flipped_face_is_not_closed() {
        let (v, mut f) = cube();
        f[2].reverse();
        let m = from_faces(&v, &f, None).unwrap();
        assert!(!m.closed);
    }

    #[test]
    fn cube_with_a_doubled_face_is_not_closed() {
        let (v, mut f) = cube();
        f.push(f[0].clone());
        assert!(!from_faces(&v, &f, None).unwrap().closed);
    }

    #[test]
    fn welding_joins_separate_face_vertices() {
        // Each face gets its own copies of the corners, slightly perturbed
        // (well under the weld distance): closed only after welding.
        let (v, f) = cube();
        let mut verts = Vec::new();
        let mut faces = Vec::new();
        for (k, face) in f.iter().enumerate() {
            let mut loop_ = Vec::new();
            for &i in face {
                let mut p = v[i as usize];
                p[0] += 1e-9 * k as f64;
                loop_.push(verts.len() as u32);
                verts.push(p);
            }
            faces.push(loop_);
        }
        let m = from_faces(&verts, &faces, None).unwrap();
        assert!(m.closed);
        assert_eq!(m.report.welded_vertices, 24 - 8);
        assert_eq!(m.report.dropped_degenerate, 0);
    }

    #[test]
    fn vertices_farther_than_weld_distance_stay_apart() {
        let (mut v, mut f) = cube();
        // A second copy of corner 6 at 1e-3 (far above 1e-6 × diag) used by
        // the right face: the cube is no longer closed.
        v.push([1.0, 1.0, 1.0 + 1e-3]);
        f[4] = vec![1, 2, 8, 5];
        let m = from_faces(&v, &f, None).unwrap();
        assert_eq!(m.report.welded_vertices, 0);
        assert!(!m.closed);
    }

    #[test]
    fn degenerate_faces_are_dropped_and_counted() {
        let (mut v, mut f) = cube();
        v.push([0.5, 0.5, 0.0]); // 8: on the bottom's diagonal
        f.push(vec![0, 1]); // two vertices
        f.push(vec![0, 0, 1, 1]); // two distinct
        f.push(vec![0, 8, 2]); // collinear: zero area
        f.push(vec![0, 1, 0]); // spike
        f.push(vec![]);
        let m = from_faces(&v, &f, None).unwrap();
        assert_eq!(m.report.dropped_degenerate, 5);
        assert_eq!(m.report.faces_read, 11);
        assert_eq!(m.polygons.len(), 6);
        assert!(m.closed, "dropped faces take no part in closedness");
        assert_eq!(
            m.report.warning_line().as_deref(),
            Some("warning: dropped 5 degenerate faces")
        );
    }

    #[test]
    fn thin_sliver_is_degenerate_but_thin_legit_triangle_is_kept() {
        let v = vec![
            [0.0, 0.0, 0.0],
            [10.0, 0.0, 0.0],
            [5.0, 1e-8, 0.0],
            [5.0, 1e-3, 0.0],
        ];
        let m = from_faces(&v, &[vec![0, 1, 2], vec![0, 1, 3]], None).unwrap();
        assert_eq!(m.report.dropped_degenerate, 1);
        assert_eq!(m.polygons.len(), 1);
        assert_eq!(m.polygons[0].source, 1);
    }

    #[test]
    fn repeated_and_closing_duplicate_indices_are_removed() {
        let v = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let m = from_faces(&v, &[vec![0, 1, 1, 2, 3, 3, 0]], None).unwrap();
        assert_eq!(m.polygons[0].verts.len(), 4);
        assert!((area(&m.polygons[0].verts) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn clean_loop_rules() {
        let c = |v: &[u32]| clean_loop(v.iter().copied());
        assert_eq!(c(&[1, 2, 3]), vec![1, 2, 3]);
        assert_eq!(c(&[1, 1, 2, 2, 3, 1]), vec![1, 2, 3]);
        assert_eq!(c(&[1, 2, 9, 2, 3]), vec![1, 2, 3]);
        assert_eq!(c(&[9, 1, 2, 3, 1]), vec![1, 2, 3]);
        assert_eq!(c(&[1, 2, 3, 1, 9]), vec![1, 2, 3]);
        assert!(c(&[1, 2, 1, 2, 1, 2]).len() < 3);
        assert_eq!(c(&[4, 4, 4]), vec![4]);
        assert!(c(&[]).is_empty());
    }

    #[test]
    fn errors_for_bad_input() {
        let (v, mut f) = cube();
        f[1][2] = 8;
        assert!(matches!(
            from_faces(&v, &f, None),
            Err(MeshError::BadIndex {
                face: 1,
                index: 8,
                vertices: 8
            })
        ));
        let (mut v, f) = cube();
        v[3][1] = f64::NAN;
        assert!(matches!(
            from_faces(&v, &f, None),
            Err(MeshError::NonFinite)
        ));
        let (mut v, f) = cube();
        v[3] = [f64::MAX, -f64::MAX, 0.0];
        assert!(matches!(
            from_faces(&v, &f, None),
            Err(MeshError::TooLarge { .. })
        ));
        let big: Vec<[f64; 3]> = cube().0.iter().map(|p| p.map(|c| c * 1e100)).collect();
        assert!(matches!(
            from_faces(&big, &f, None),
            Err(MeshError::TooLarge { .. })
        ));
        assert!(matches!(from_faces(&v, &[], None), Err(MeshError::Empty)));
        let same = vec![[1.0, 2.0, 3.0]; 3];
        assert!(matches!(
            from_faces(&same, &[vec![0, 1, 2]], None),
            Err(MeshError::Empty)
        ));
    }

    #[test]
    fn unused_vertices_do_not_matter() {
        let (mut v, f) = cube();
        v.push([f64::NAN, 1e300, 0.0]);
        let m = from_faces(&v, &f, None).unwrap();
        assert!(m.closed);
    }

    #[test]
    fn colours_follow_faces() {
        let (v, f) = cube();
        let colors: Vec<[u8; 3]> = (0..5).map(|i| [i * 10, 1, 2]).collect();
        let m = from_faces(&v, &f, Some(&colors)).unwrap();
        for p in &m.polygons {
            let want = if p.source < 5 {
                [p.source as u8 * 10, 1, 2]
            } else {
                DEFAULT_COLOR
            };
            assert_eq!(p.color, want);
        }
    }

    #[test]
    fn is_closed_faces_basics() {
        assert!(!is_closed_faces(&[]));
        // Two triangles back to back: a closed (flat) volume by the edge rule.
        assert!(is_closed_faces(&[vec![0, 1, 2], vec![0, 2, 1]]));
        assert!(!is_closed_faces(&[vec![0, 1, 2]]));
        // Edge 0-1 used by three faces.
        assert!(!is_closed_faces(&[
            vec![0, 1, 2],
            vec![1, 0, 3],
            vec![1, 0, 4]
        ]));
    }

    #[test]
    fn weld_is_linear_on_a_dense_grid() {
        // 40³ points on a grid of spacing well above the weld distance, each
        // duplicated: every duplicate welds, no original does.
        let mut v = Vec::new();
        for i in 0..40 {
            for j in 0..40 {
                for k in 0..40 {
                    let p = [i as f64, j as f64, k as f64];
                    v.push(p);
                    v.push([p[0] + 1e-7, p[1], p[2]]);
                }
            }
        }
        let used = vec![true; v.len()];
        let (map, reps) = weld(&v, &used, DVec3::ZERO, 1e-6 * 70.0);
        assert_eq!(reps.len(), 40 * 40 * 40);
        assert!(map.chunks(2).all(|c| c[0] == c[1]));
    }
}
