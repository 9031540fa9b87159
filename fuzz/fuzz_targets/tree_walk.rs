//! Fuzzes the tree reader and the postprocessing walk on untrusted bytes.
//! Run with `cargo +nightly fuzz run tree_walk` from the repository root.
//!
//! The first byte is a control byte: bit 0 rewrites the file length field
//! and bit 1 the trailing CRC-32 of the rest, so that the fuzzer gets past
//! those two checks and exercises the structural validation. The contract
//! (see `fpt_nostd::reader`): `Tree::from_bytes` either fails or gives a tree
//! whose every accessor and walk completes without panicking, emits only ids
//! below the polygon count, each at most once per view (exactly once for an
//! open volume).
#![no_main]

use fpt_nostd::format::{crc32, header};
use fpt_nostd::order::{Order, View};
use fpt_nostd::reader::Tree;
use libfuzzer_sys::fuzz_target;

const VIEWS: [View; 4] = [
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
];

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
    for id in 0..count {
        let p = tree.polygon(id).expect("id below the count");
        assert!(p.vertex_count() >= 3);
        let _ = (p.plane(), p.source(), p.color());
        for i in 0..p.vertex_count() {
            let _ = (p.vertex(i), p.vertex_raw(i), p.vertex_model(i));
            assert!(p.vertex_index(i) < tree.vertex_count());
        }
    }
    let mut seen = vec![false; count as usize];
    for view in VIEWS {
        let Ok(order) = Order::<64>::new(&tree, view) else {
            continue;
        };
        seen.iter_mut().for_each(|s| *s = false);
        for class in order {
            for id in class {
                let slot = seen.get_mut(id as usize).expect("id in range");
                assert!(!*slot, "polygon {id} emitted twice");
                *slot = true;
            }
        }
        if !tree.is_closed() {
            assert!(
                seen.iter().all(|&s| s),
                "open volume: a polygon was not emitted"
            );
        }
    }
});
