//! Round trips through the flat format: host serializer → fpt-nostd reader
//! and walk, against the in-memory tree and a reference walk of it.

use crate::format_common;

use std::collections::HashSet;

use format_common::*;
use fpt_nostd::format::VertexFormat;
use fpt_nostd::reader::Tree;
use glam::DVec3;
use host_sim::build::{build, NoProgress};
use host_sim::serialize::{polygon_order, serialize, SerializeOptions};
use host_sim::tree::{FpTree, Method};

/// Narrow records without the plane table (the default before session
/// 27), which the tests below vary one option at a time.
fn opts(f: VertexFormat) -> SerializeOptions {
    SerializeOptions {
        vertex_format: f,
        effects: Some(0x1234_5678),
        plane_table: false,
        compact_planes: false,
        ..SerializeOptions::default()
    }
}

/// The largest distance a vertex may move by being stored in `tree`'s format.
fn vertex_tolerance(tree: &Tree<'_>) -> f64 {
    let extent = tree.half_extent().iter().fold(0f32, |m, &x| m.max(x)) as f64;
    match tree.vertex_format() {
        // Relative offsets in f32: half an ulp of the largest offset per axis.
        VertexFormat::F32 => extent * 2f64.powi(-23),
        VertexFormat::Q16 => extent / 32767.0,
        VertexFormat::Q32 => 2f64.powi(-i32::from(tree.q32_shift())),
    }
}

/// Distinct vertices of `t` (exact equality).
fn exact_vertices(t: &FpTree) -> usize {
    let set: HashSet<[u64; 3]> = t
        .polygons
        .iter()
        .flat_map(|p| {
            p.verts
                .iter()
                .map(|v| (*v + DVec3::ZERO).to_array().map(f64::to_bits))
        })
        .collect();
    set.len()
}

/// Checks geometry and structure of `bytes` against `t`; returns the file id
/// → tree id map.
fn check_round_trip(t: &FpTree, bytes: &[u8], f: VertexFormat) -> Vec<u32> {
    let r = Tree::from_bytes(bytes).expect("serialized tree validates");
    let order = polygon_order(t).unwrap();
    assert_eq!(r.vertex_format(), f);
    assert_eq!(r.is_closed(), t.closed);
    assert_eq!(r.effects(), 0x1234_5678);
    assert_eq!(r.polygon_count() as usize, t.polygons.len());
    assert_eq!(r.node_count() as usize, t.root.count_connecting());
    assert_eq!(r.switch_count() as usize, t.root.count_switches());
    assert_eq!(r.level_count() as usize, t.root.count_levels());
    assert_eq!(r.max_depth() as usize, t.root.depth());
    assert!(
        r.vertex_count() as usize <= exact_vertices(t),
        "vertices deduplicated"
    );
    let tol = vertex_tolerance(&r) * 1.01 + 1e-12;
    let origin = DVec3::from_array(r.origin());
    let mut radius = 0f64;
    for (fid, &tid) in order.iter().enumerate() {
        let p = r.polygon(fid as u32).unwrap();
        let src = &t.polygons[tid as usize];
        assert_eq!(p.source(), src.source);
        assert_eq!(p.color(), src.color);
        assert_eq!(p.vertex_count(), src.verts.len());
        for (i, v) in src.verts.iter().enumerate() {
            let got = DVec3::from_array(p.vertex_model(i));
            let err = (got - *v).abs().max_element();
            assert!(
                err <= tol,
                "{f:?} polygon {tid} vertex {i}: error {err} > {tol}"
            );
            let rel = DVec3::from_array(p.vertex(i).map(f64::from));
            // The f32 decoding rounds the offset once more.
            let tol32 = 1e-6 * rel.abs().max_element() + 1e-12 * (1.0 + origin.abs().max_element());
            assert!((rel + origin - got).abs().max_element() <= tol32);
            radius = radius.max(rel.length()).max((*v - origin).length());
        }
        // The drawing fast path decodes exactly what `vertex` does.
        let fast: Vec<[f32; 3]> = p.vertices().collect();
        let slow: Vec<[f32; 3]> = (0..p.vertex_count()).map(|i| p.vertex(i)).collect();
        assert_eq!(fast, slow, "{f:?} polygon {tid}");
        let pl = p.plane();
        let n = DVec3::from_array(pl.normal.map(f64::from));
        let d_rel = src.plane.d + src.plane.normal.dot(origin);
        if r.has_compact_planes() {
            // Rounded to the `i16` lattice: radius · √3 / 65534 for the
            // offset, about 1 / 32767 for the normal's components.
            let rad = f64::from(r.bounding_radius());
            assert!((n - src.plane.normal).length() < 1e-4);
            assert!((f64::from(pl.d) - d_rel).abs() <= 1e-4 * rad.max(d_rel.abs()));
        } else {
            assert!((n - src.plane.normal).length() < 1e-6);
            assert!((f64::from(pl.d) - d_rel).abs() <= 1e-6 * d_rel.abs().max(1.0));
        }
    }
    assert!(f64::from(r.bounding_radius()) >= radius * (1.0 - 1e-7));
    order
}

/// `compact` (compact or narrow records) and `wide` (16-byte records, as
/// older files have) are the same tree: every polygon field reads the same,
/// and with 8-byte records the sizes differ by exactly the 8 bytes a
/// polygon saved less the layout and the colour table.
fn same_polygons(compact: &[u8], wide: &[u8]) {
    let (c, w) = (
        Tree::from_bytes(compact).unwrap(),
        Tree::from_bytes(wide).unwrap(),
    );
    assert!(c.is_compact() && !w.is_compact());
    assert_eq!(w.colour_count(), 0);
    assert!(c.colour_count() >= 1 || c.polygon_count() == 0);
    assert_eq!(c.polygon_count(), w.polygon_count());
    for id in 0..c.polygon_count() {
        let (a, b) = (c.polygon(id).unwrap(), w.polygon(id).unwrap());
        assert_eq!(a.source(), b.source());
        assert_eq!(a.color(), b.color());
        assert_eq!(a.hidden_edges(), b.hidden_edges());
        assert_eq!(a.plane(), b.plane());
        let ia: Vec<u32> = a.vertex_indices().collect();
        let ib: Vec<u32> = b.vertex_indices().collect();
        assert_eq!(ia, ib);
        // The renderers' path (the record read once, with the next
        // polygon's first index; the last polygon ends at the index count)
        // gives the same indices.
        let fast: Vec<u32> = c.polygon_vertex_indices(id).collect();
        assert_eq!(fast, ia, "polygon {id}");
    }
    // The record kinds as the reader reports them (the switch planes,
    // shared or not, are checked by the walks of `check_round_trip`).
    let (rc, rw) = (c.records().unwrap(), w.records());
    assert_eq!(rw, None);
    assert_eq!(c.has_shared_planes(), rc.narrow.is_some());
    if rc.narrow.is_none() {
        let n = c.polygon_count() as usize;
        let table = (3 * c.colour_count() as usize).next_multiple_of(4);
        assert_eq!(compact.len() + 8 * n, wide.len() + 8 + table);
    }
}

/// Compares the no_std walk with the reference walk for `views`; returns
/// how many views were compared (ambiguous near-ties are skipped).
fn check_orders(t: &FpTree, bytes: &[u8], order: &[u32], views: &[RefView], scale: f64) -> usize {
    let r = Tree::from_bytes(bytes).unwrap();
    let mut compared = 0;
    for v in views {
        if v.margin(t) < 1e-4 * scale {
            continue;
        }
        let view = v.to_view(&r);
        let got = normalized(nostd_classes(&r, view, order));
        let want = normalized(reference_classes(t, v));
        assert_eq!(got, want, "view {v:?}");
        check_walk(&r, view);
        compared += 1;
    }
    compared
}

#[test]
fn random_trees_round_trip_in_every_format() {
    let mut compared = 0;
    for seed in 0..48u64 {
        let n = 1 + (seed as usize * 7) % 30;
        let (scale, offset) = match seed % 3 {
            0 => (1.0, DVec3::ZERO),
            1 => (250.0, DVec3::new(1e5, -3e4, 2e5)),
            _ => (1e-3, DVec3::new(-0.5, 0.25, 3.0)),
        };
        let t = random_tree(seed, n, seed % 2 == 0, seed % 4 == 3, scale, offset);
        let mut rng = Rng::new(seed ^ 0xABCD);
        let views = some_views(&mut rng, scale * 4.0, offset, 8);
        for f in VertexFormat::ALL {
            let bytes = serialize(&t, &opts(f)).unwrap();
            let order = check_round_trip(&t, &bytes, f);
            // The 16-byte records of older files read the same.
            let wide = serialize(
                &t,
                &SerializeOptions {
                    compact: false,
                    ..opts(f)
                },
            )
            .unwrap();
            assert_eq!(check_round_trip(&t, &wide, f), order);
            same_polygons(&bytes, &wide);
            // And the 8-byte compact records of sessions 10 to 16.
            let compact = serialize(
                &t,
                &SerializeOptions {
                    narrow: false,
                    ..opts(f)
                },
            )
            .unwrap();
            assert_eq!(check_round_trip(&t, &compact, f), order);
            same_polygons(&compact, &wide);
            // And the plane table of `f32` entries (session 21).
            let table = serialize(
                &t,
                &SerializeOptions {
                    plane_table: true,
                    ..opts(f)
                },
            )
            .unwrap();
            assert_eq!(check_round_trip(&t, &table, f), order);
            same_polygons(&table, &wide);
            let (tn, tt) = (
                Tree::from_bytes(&bytes).unwrap(),
                Tree::from_bytes(&table).unwrap(),
            );
            assert!(!tn.has_plane_table());
            if tt.has_plane_table() {
                assert!(tt.plane_table_len() <= tt.run_count() + tt.switch_count());
            }
            assert!(table.len() <= bytes.len(), "the table made a file larger");
            compared += check_orders(&t, &table, &order, &views, scale);
            // Compact table entries (session 25): the same order in every
            // view that is no near-tie, in a file no larger.
            let small = serialize(
                &t,
                &SerializeOptions {
                    plane_table: true,
                    compact_planes: true,
                    ..opts(f)
                },
            )
            .unwrap();
            assert_eq!(check_round_trip(&t, &small, f), order);
            let ts = Tree::from_bytes(&small).unwrap();
            assert_eq!(ts.has_compact_planes(), ts.has_plane_table());
            assert!(ts.has_plane_table() || !tt.has_plane_table());
            assert!(small.len() <= table.len());
            check_orders(&t, &small, &order, &views, scale);
            assert!(Tree::from_bytes(&compact)
                .unwrap()
                .records()
                .unwrap()
                .narrow
                .is_none());
            if f == VertexFormat::F32 {
                // Grid corners are far apart: only exact duplicates merge.
                let r = Tree::from_bytes(&bytes).unwrap();
                assert_eq!(r.vertex_count() as usize, exact_vertices(&t));
            }
            compared += check_orders(&t, &bytes, &order, &views, scale);
        }
    }
    // Nearly every view is compared (few are near-ties).
    assert!(
        compared > 48 * 3 * 8 * 9 / 10,
        "only {compared} views compared"
    );
}

#[test]
fn bsp_shaped_trees_walk_the_same() {
    for seed in 100..120u64 {
        let t = random_tree(seed, 25, seed % 2 == 0, true, 1.0, DVec3::ZERO);
        assert!(t.root.levels.is_empty() && t.root.switch.is_some());
        let bytes = serialize(&t, &opts(VertexFormat::F32)).unwrap();
        let r = Tree::from_bytes(&bytes).unwrap();
        assert_eq!(r.level_count(), 0);
        let order = check_round_trip(&t, &bytes, VertexFormat::F32);
        let views = some_views(&mut Rng::new(seed), 4.0, DVec3::ZERO, 8);
        assert!(check_orders(&t, &bytes, &order, &views, 1.0) >= 6);
    }
}

#[test]
fn far_from_the_origin_keeps_precision() {
    // A model of size 1e3 at 1e5: f32 model coordinates would round to
    // 1e5 · 2^-24 ≈ 6e-3; offsets from the stored origin keep ~6e-5.
    let t = random_tree(7, 20, true, false, 125.37, DVec3::new(1e5, 1e5, -1e5));
    let bytes = serialize(&t, &opts(VertexFormat::F32)).unwrap();
    let r = Tree::from_bytes(&bytes).unwrap();
    let order = polygon_order(&t).unwrap();
    let (mut worst, mut worst_naive) = (0f64, 0f64);
    for (fid, &tid) in order.iter().enumerate() {
        let p = r.polygon(fid as u32).unwrap();
        for (i, v) in t.polygons[tid as usize].verts.iter().enumerate() {
            worst = worst.max(
                (DVec3::from_array(p.vertex_model(i)) - *v)
                    .abs()
                    .max_element(),
            );
            let naive = v.to_array().map(|x| f64::from(x as f32));
            worst_naive = worst_naive.max((DVec3::from_array(naive) - *v).abs().max_element());
        }
    }
    assert!(worst < 1e-4, "error {worst}");
    assert!(
        worst_naive > 10.0 * worst,
        "the test model must be one f32 cannot hold"
    );
}

#[test]
fn quantized_formats_are_smaller() {
    let t = random_tree(3, 30, true, false, 1.0, DVec3::ZERO);
    let size = |f| serialize(&t, &opts(f)).unwrap().len();
    let r = Tree::from_bytes(&serialize(&t, &opts(VertexFormat::F32)).unwrap())
        .unwrap()
        .vertex_count() as usize;
    // q16 saves 6 bytes a vertex (up to 3 of section padding).
    let saved = size(VertexFormat::F32) - size(VertexFormat::Q16);
    assert!(
        saved + 3 >= 6 * r && saved <= 6 * r + 3,
        "saved {saved} for {r} vertices"
    );
    assert_eq!(size(VertexFormat::F32), size(VertexFormat::Q32));
}

#[test]
fn built_trees_round_trip() {
    for (name, methods) in [
        (
            "wallhole.obj",
            &[Method::Static, Method::Dynamic, Method::Bsp][..],
        ),
        ("shuttle.obj", &[Method::Dynamic, Method::Bsp][..]),
    ] {
        let Some(model) = fpt_tests::shared_mesh(name) else {
            continue;
        };
        for &method in methods {
            let t = build(
                model.polygons.clone(),
                model.closed,
                method,
                1,
                &mut NoProgress,
            );
            let (lo, hi) = host_sim::geom::bounds(&t.polygons);
            let scale = (hi - lo).length();
            let views = some_views(&mut Rng::new(5), scale, (lo + hi) * 0.5, 16);
            for f in VertexFormat::ALL {
                let bytes = serialize(&t, &opts(f)).unwrap();
                let order = check_round_trip(&t, &bytes, f);
                let compared = check_orders(&t, &bytes, &order, &views, scale);
                assert!(
                    compared >= 12,
                    "{name} {method:?}: {compared} views compared"
                );
            }
        }
    }
}
