//! Fuzzes the tree reader and the postprocessing walk on untrusted bytes.
//! How to run it (and what runs found) is in the docs of
//! `fpt_nostd::reader`, section "Fuzzing".
//!
//! The first byte is a control byte: bit 0 rewrites the file length field
//! and bit 1 the trailing CRC-32 of the rest, so that the fuzzer gets past
//! those two checks and exercises the structural validation; bit 2 takes the
//! classes by ranges ([`Class::next_range`]) instead of id by id. The
//! contract (see `fpt_nostd::reader`): `Tree::from_bytes` either fails or
//! gives a tree whose every accessor and walk completes without panicking,
//! emits only ids below the polygon count, never an empty class, each id at
//! most once per view (exactly once for an open volume), within the bounds
//! of the class's `size_hint`. The walk with the other culling choice
//! (`Order::with_culling`: an open tree culled, a closed one not) keeps the
//! same promises (a closed tree not culled emits every id exactly once),
//! and drawing the tree through every effect (outlines, depth cue,
//! clipping off, dithering) completes.
#![no_main]

use fpt_nostd::effects::Effects;
use fpt_nostd::format::{crc32, header};
use fpt_nostd::order::{Class, Order, View};
use fpt_nostd::raster::{
    BinaryFramebuffer, DepthCue, Dither, FixedPrecision, FloatLibm, Libm, Orbit, Rgb565Framebuffer,
};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{Frame, TreeRenderer};
use libfuzzer_sys::fuzz_target;

const VIEWS: [View; 5] = [
    View::Parallel {
        dir: [0.3, -0.5, 0.8],
    },
    View::Parallel {
        dir: [0.0, 0.0, -1.0],
    },
    View::Perspective {
        eye: [10.0, 3.0, -2.0],
    },
    View::PerspectiveRelative {
        eye: [0.0, 0.0, 0.0],
    },
    View::Parallel {
        dir: [f32::NAN, 1.0, 0.0],
    },
];

/// The ids of a class, taken one by one or by ranges.
fn ids(mut class: Class<'_>, by_range: bool) -> Vec<u32> {
    let (lo, hi) = class.size_hint();
    let mut out = Vec::new();
    if by_range {
        while let Some(r) = class.next_range() {
            assert!(r.start < r.end, "empty range {r:?}");
            out.extend(r);
        }
    } else {
        out.extend(class);
    }
    assert!(lo <= out.len() && out.len() <= hi.unwrap_or(usize::MAX));
    out
}

fuzz_target!(|data: &[u8]| {
    let Some((&control, rest)) = data.split_first() else {
        return;
    };
    let mut bytes = rest.to_vec();
    let n = bytes.len();
    if control & 1 != 0 && n >= header::FILE_LEN + 4 {
        bytes[header::FILE_LEN..header::FILE_LEN + 4].copy_from_slice(&(n as u32).to_le_bytes());
    }
    if control & 2 != 0 && n >= 4 {
        let crc = crc32(&bytes[..n - 4]);
        bytes[n - 4..].copy_from_slice(&crc.to_le_bytes());
    }
    let Ok(tree) = Tree::from_bytes(&bytes) else {
        return;
    };
    let count = tree.polygon_count();
    assert!(tree.run_count() <= count);
    for id in 0..count {
        let p = tree.polygon(id).expect("id below the count");
        assert!(p.vertex_count() >= 3);
        let _ = (p.plane(), p.source(), p.color());
        for i in 0..p.vertex_count() {
            let _ = (p.vertex(i), p.vertex_raw(i), p.vertex_model(i));
            assert!(p.vertex_index(i) < tree.vertex_count());
        }
    }
    assert!(tree.polygon(count).is_none());
    let mut seen = vec![false; count as usize];
    for (view, cull) in VIEWS
        .into_iter()
        .flat_map(|v| [(v, tree.is_closed()), (v, !tree.is_closed())])
    {
        let Ok(order) = Order::<64>::with_culling(&tree, view, cull) else {
            continue;
        };
        seen.iter_mut().for_each(|s| *s = false);
        let mut flat = Vec::new();
        for class in order {
            let ids = ids(class, control & 4 != 0);
            assert!(!ids.is_empty(), "empty class");
            flat.extend_from_slice(&ids);
            for id in ids {
                let slot = seen.get_mut(id as usize).expect("id in range");
                assert!(!*slot, "polygon {id} emitted twice");
                *slot = true;
            }
        }
        if !cull {
            assert!(
                seen.iter().all(|&s| s),
                "without culling: a polygon was not emitted"
            );
        }
        // The walk's own ranges: the same ids in the same order.
        let mut walk = Order::<64>::with_culling(&tree, view, cull).expect("built above");
        let mut by_walk = Vec::new();
        while let Some(r) = walk.next_range() {
            assert!(r.start < r.end, "empty range {r:?}");
            by_walk.extend(r);
        }
        assert_eq!(by_walk, flat, "walk ranges against class ids");
    }
    draw(&tree, control);
});

/// Draws the tree with every effect (and with its own), in fixed point and
/// in f32, into a colour and a dithered 1-bit frame: must not panic.
fn draw(tree: &Tree<'_>, control: u8) {
    const W: u32 = 24;
    const H: u32 = 16;
    let r = tree.bounding_radius();
    let distance = if control & 8 != 0 { 0.5 * r } else { 2.5 * r };
    let orbit = Orbit::new([0.0; 3], 0.7, 0.4, distance, 0.9);
    let effects = [
        Effects::ALL,
        Effects::from_bits(tree.effects()),
        Effects::NONE,
    ];
    let mut words = vec![0u16; (W * H) as usize];
    let mut bits = vec![0u8; BinaryFramebuffer::required_len(W, H)];
    macro_rules! with {
        ($p:ty) => {{
            let Some(mut tr) = TreeRenderer::<$p, 12>::new(W, H) else {
                return;
            };
            let frame = Frame::relative(tree, &orbit.camera::<Libm>(W as f32 / H as f32));
            let (near, far) = frame.depth_range(tree);
            tr.renderer.set_depth_cue(DepthCue {
                near,
                far,
                ..DepthCue::default()
            });
            for fx in effects {
                tr.renderer.set_effects(Some(fx));
                if let Ok(mut fb) = Rgb565Framebuffer::new(&mut words, W, H) {
                    let _ = tr.render::<64, _>(tree, &frame, &mut fb);
                }
                if let Ok(mut fb) = BinaryFramebuffer::new(&mut bits, W, H) {
                    let _ = tr.render::<64, _>(tree, &frame, &mut Dither::new(&mut fb, 2));
                }
            }
        }};
    }
    with!(FixedPrecision<4>);
    with!(FloatLibm<4>);
}
