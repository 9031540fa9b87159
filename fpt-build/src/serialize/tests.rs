use super::*;
use crate::geom::Polygon;
use crate::tree::{Level, Method, Stats, Switch};
use fpt_nostd::format::Sections;
use fpt_nostd::reader::Tree;

fn quad(z: f64, flip: bool, source: u32) -> Polygon {
    let mut v = vec![
        DVec3::new(0.0, 0.0, z),
        DVec3::new(1.0, 0.0, z),
        DVec3::new(1.0, 1.0, z),
        DVec3::new(0.0, 1.0, z),
    ];
    if flip {
        v.reverse();
    }
    Polygon::new(v, source, [source as u8, 2, 3]).unwrap()
}

/// Three stacked quads sharing x/y corners; a switch at z = 1.
fn sample(offset: DVec3) -> FpTree {
    let mut polygons = vec![quad(0.0, true, 0), quad(1.0, false, 1), quad(2.0, false, 2)];
    for p in &mut polygons {
        p.verts.iter_mut().for_each(|v| *v += offset);
        p.plane = Plane::newell(&p.verts).unwrap();
    }
    let plane = polygons[1].plane;
    FpTree {
        polygons,
        closed: false,
        root: Connecting {
            levels: vec![Level {
                front: vec![],
                back: vec![2],
            }],
            switch: Some(Box::new(Switch {
                plane,
                on: vec![1],
                front: Connecting::default(),
                back: Connecting {
                    levels: vec![Level {
                        front: vec![0],
                        back: vec![],
                    }],
                    switch: None,
                },
            })),
        },
        method: Method::Static,
        stats: Stats::default(),
    }
}

#[test]
fn renumbers_bunches_breadth_first() {
    let t = sample(DVec3::ZERO);
    assert_eq!(polygon_order(&t).unwrap(), vec![2, 1, 0]);
    let mut dup = t.clone();
    dup.root.levels[0].front.push(2);
    assert_eq!(
        polygon_order(&dup),
        Err(SerializeError::DuplicatePolygon(2))
    );
    let mut lost = t.clone();
    lost.root.levels.clear();
    assert_eq!(
        polygon_order(&lost),
        Err(SerializeError::UnplacedPolygon(2))
    );
    let mut unknown = t;
    unknown.root.levels[0].back.push(9);
    assert_eq!(
        polygon_order(&unknown),
        Err(SerializeError::UnknownPolygon(9))
    );
}

#[test]
fn every_format_reads_back() {
    let t = sample(DVec3::new(1e5, -2e5, 3e5));
    for f in VertexFormat::ALL {
        let opts = SerializeOptions {
            vertex_format: f,
            effects: Some(0xABCD),
            up: UpAxis::Z,
            ..SerializeOptions::default()
        };
        let bytes = serialize(&t, &opts).unwrap();
        let r = Tree::from_bytes(&bytes).unwrap();
        assert_eq!(r.vertex_format(), f);
        assert_eq!(r.effects(), 0xABCD);
        assert_eq!(r.up_axis(), UpAxis::Z);
        assert!(!r.is_closed());
        // 12 corners, but the x/y corners repeat on each z: 12 distinct.
        assert_eq!(r.vertex_count(), 12);
        assert_eq!(
            (r.polygon_count(), r.node_count(), r.switch_count()),
            (3, 3, 1)
        );
        assert_eq!((r.max_depth(), r.level_count(), r.bunch_count()), (2, 2, 5));
        let tol = match f {
            VertexFormat::Q16 => 2.0 / 32767.0,
            _ => 1e-9,
        };
        for (fid, &tid) in polygon_order(&t).unwrap().iter().enumerate() {
            let p = r.polygon(fid as u32).unwrap();
            let src = &t.polygons[tid as usize];
            assert_eq!(p.source(), src.source);
            assert_eq!(p.color(), src.color);
            for (i, v) in src.verts.iter().enumerate() {
                let got = DVec3::from_array(p.vertex_model(i));
                assert!((got - *v).length() <= tol, "{f:?}: {got} vs {v}");
            }
            let pl = p.plane();
            let d_model = f64::from(pl.d)
                - DVec3::from_array(pl.normal.map(f64::from)).dot(DVec3::from_array(r.origin()));
            assert!((d_model - src.plane.d).abs() < 1e-2 * src.plane.d.abs().max(1.0));
        }
    }
}

#[test]
fn up_axis_is_recorded_and_checked() {
    let t = sample(DVec3::ZERO);
    for up in UpAxis::ALL {
        let opts = SerializeOptions {
            up,
            ..SerializeOptions::default()
        };
        let mut bytes = serialize(&t, &opts).unwrap();
        assert_eq!(bytes[h::UP_AXIS], up.code());
        assert_eq!(Tree::from_bytes(&bytes).unwrap().up_axis(), up);
        // An unknown code is refused (with a valid checksum).
        bytes[h::UP_AXIS] = 3;
        let n = bytes.len() - 4;
        let crc = crc32(&bytes[..n]);
        bytes[n..].copy_from_slice(&crc.to_le_bytes());
        assert_eq!(
            Tree::from_bytes(&bytes).unwrap_err(),
            fpt_nostd::format::FormatError::BadHeader("up_axis")
        );
    }
    // The default is y, code 0: what files written before the field
    // existed hold.
    let bytes = serialize(&t, &SerializeOptions::default()).unwrap();
    assert_eq!(bytes[h::UP_AXIS], 0);
}

#[test]
fn the_edge_section_is_written_with_outlines_only_and_validated() {
    use fpt_nostd::effects::Effects;
    use fpt_nostd::format::{FormatError, EDGE_DRAWN};
    let t = sample(DVec3::ZERO);
    // 16-byte records: the offsets below come from `Sections::new`,
    // which lays out the sections of a file without the compact
    // records' layout section and colour table.
    let wide = SerializeOptions {
        compact: false,
        ..SerializeOptions::default()
    };
    let plain = serialize(&t, &wide).unwrap();
    let opts = SerializeOptions {
        effects: Some(Effects::defaults(false).with(Effects::OUTLINE).bits()),
        ..wide
    };
    let bytes = serialize(&t, &opts).unwrap();
    let (a, b) = (
        Tree::from_bytes(&plain).unwrap(),
        Tree::from_bytes(&bytes).unwrap(),
    );
    assert!(!a.has_edges() && b.has_edges());
    assert_eq!(
        bytes.len(),
        plain.len() + (b.index_count() as usize * EDGE_LEN).next_multiple_of(4)
    );
    // Three separate quads: every edge is a boundary, drawn.
    for id in 0..b.polygon_count() {
        let p = b.polygon(id).unwrap();
        for i in 0..p.vertex_count() {
            assert_eq!(p.edge(i), Some((EDGE_DRAWN, [0; 3])));
        }
        assert_eq!(p.edge(p.vertex_count()), None);
        assert_eq!(a.polygon(id).unwrap().edge(0), None);
    }
    let with_crc = |mut v: Vec<u8>| {
        let n = v.len() - 4;
        let c = crc32(&v[..n]);
        v[n..].copy_from_slice(&c.to_le_bytes());
        v
    };
    let s = Sections::new(
        &Counts {
            vertices: b.vertex_count(),
            polygons: b.polygon_count(),
            indices: b.index_count(),
            bunches: b.bunch_count(),
            nodes: b.node_count(),
            switches: b.switch_count(),
            runs: b.run_count(),
            edges: b.index_count(),
            normals: 0,
            small: b.has_small_records(),
        },
        b.vertex_format(),
        usize::from(b.index_size()),
    )
    .unwrap();
    let mut bad_kind = bytes.clone();
    bad_kind[s.edges + EDGE_LEN + 3] = 3;
    assert_eq!(
        Tree::from_bytes(&with_crc(bad_kind)).err(),
        Some(FormatError::BadEdge(1))
    );
    // Without the flag, the section makes the length wrong.
    let mut no_flag = bytes.clone();
    no_flag[h::FLAGS] &= !(FLAG_EDGES as u8);
    assert_eq!(
        Tree::from_bytes(&with_crc(no_flag)).err(),
        Some(FormatError::SectionSizes)
    );
}

#[test]
fn q32_shift_is_the_largest_that_fits() {
    let t = sample(DVec3::ZERO);
    let bytes = serialize(
        &t,
        &SerializeOptions {
            vertex_format: VertexFormat::Q32,
            ..SerializeOptions::default()
        },
    )
    .unwrap();
    let r = Tree::from_bytes(&bytes).unwrap();
    // Offsets reach 1.0 (z from 0 to 2 around origin z = 1): 2^30 · 1 < 2^31 ≤ 2^31 · 1.
    assert_eq!(r.q32_shift(), 30);
}

#[test]
fn many_vertices_use_u32_indices() {
    // 22 000 triangles with distinct corners: 66 000 vertices > 65 536.
    let polygons: Vec<Polygon> = (0..22_000)
        .map(|i| {
            let z = f64::from(i);
            let v = vec![
                DVec3::new(0.0, 0.0, z),
                DVec3::new(1.0, 0.0, z),
                DVec3::new(0.0, 1.0, z),
            ];
            Polygon::new(v, i, [0; 3]).unwrap()
        })
        .collect();
    let t = FpTree {
        root: Connecting {
            levels: vec![Level {
                front: (0..22_000).collect(),
                back: vec![],
            }],
            switch: None,
        },
        polygons,
        closed: true,
        method: Method::Static,
        stats: Stats::default(),
    };
    let bytes = serialize(&t, &SerializeOptions::default()).unwrap();
    let r = Tree::from_bytes(&bytes).unwrap();
    assert_eq!((r.index_size(), r.vertex_count()), (4, 66_000));
    let p = r.polygon(21_999).unwrap();
    assert_eq!(p.vertex_model(1), [1.0, 0.0, 21_999.0]);
    let fast: Vec<[f32; 3]> = p.vertices().collect();
    assert_eq!(fast, (0..3).map(|i| p.vertex(i)).collect::<Vec<_>>());
}

#[test]
fn coplanar_polygons_of_a_bunch_share_a_run() {
    // One level: F_1 = [a z=0, b z=1, c z=0, d z=1 facing down, e z=1],
    // B_1 = [f z=0]: a and c (same plane), b and e (same plane) are
    // grouped; d (reversed normal) and f (another bunch) are not merged.
    let shifted = |z: f64, flip: bool, source: u32, dx: f64| {
        let mut p = quad(z, flip, source);
        p.verts.iter_mut().for_each(|v| v.x += dx);
        p
    };
    let mut polygons = vec![
        quad(0.0, false, 0),
        quad(1.0, false, 1),
        shifted(0.0, false, 2, 2.0),
        quad(1.0, true, 3),
        shifted(1.0, false, 4, 2.0),
        shifted(0.0, false, 5, 4.0),
    ];
    // Same plane, exactly, as a builder gives coplanar pieces.
    polygons[2].plane = polygons[0].plane;
    polygons[4].plane = polygons[1].plane;
    polygons[5].plane = polygons[0].plane;
    let t = FpTree {
        polygons,
        closed: true,
        root: Connecting {
            levels: vec![Level {
                front: vec![0, 1, 2, 3, 4],
                back: vec![5],
            }],
            switch: None,
        },
        method: Method::Static,
        stats: Stats::default(),
    };
    assert_eq!(polygon_order(&t).unwrap(), vec![0, 2, 1, 4, 3, 5]);
    let bytes = serialize(&t, &SerializeOptions::default()).unwrap();
    let r = Tree::from_bytes(&bytes).unwrap();
    // Runs {0, 2}, {1, 4}, {3} in F_1 and {5} in B_1.
    assert_eq!((r.run_count(), r.bunch_count()), (4, 2));
    let plane = |id: u32| r.polygon(id).unwrap().plane();
    assert_eq!(plane(0), plane(1));
    assert_eq!(plane(2), plane(3));
    assert_ne!(plane(1), plane(2));
    assert_eq!(plane(5), plane(0));
    // Looking down at the closed level: backward faces of F_1 on the
    // way up (file ids 0..4 face up), B_1's on the way down.
    let classes: Vec<Vec<u32>> =
        fpt_nostd::order::Order::<1>::new(&r, fpt_nostd::order::View::parallel([0.0, 0.0, -1.0]))
            .unwrap()
            .map(|c| c.collect())
            .collect();
    assert_eq!(classes, vec![vec![5], vec![0, 1, 2, 3]]);
}

#[test]
fn shared_vertices_are_stored_once() {
    let mut t = sample(DVec3::ZERO);
    // Same corners at the same z twice: a duplicate face.
    t.polygons[2] = quad(1.0, true, 2);
    let bytes = serialize(&t, &SerializeOptions::default()).unwrap();
    assert_eq!(Tree::from_bytes(&bytes).unwrap().vertex_count(), 8);
}
