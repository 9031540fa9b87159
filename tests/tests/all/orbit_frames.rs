//! The standard orbit of `fpt mcu-bench` (`fpt_frames::orbit`) on
//! a committed tree: the eye is where the definition puts it, the
//! checksum does not depend on the band height, and the frames differ.

use fpt_frames::orbit::{frame, frame_crc, MAX_VERTS};
use fpt_nostd::order::View;
use fpt_nostd::raster::{FixedPrecision, FloatLibm, Precision};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::TreeRenderer;

fn vise() -> Vec<u8> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../firmware/trees/vise.fpt");
    std::fs::read(path).expect("reading firmware/trees/vise.fpt")
}

#[test]
fn eye_is_on_the_standard_orbit() {
    let bytes = vise();
    let tree = Tree::from_bytes(&bytes).expect("vise.fpt validates");
    let r = f64::from(tree.bounding_radius());
    let n = 8;
    for i in 0..n {
        let f = frame(&tree, i, n, 240, 160);
        let View::PerspectiveRelative { eye } = f.view else {
            panic!("frame {i}: not a perspective view: {:?}", f.view);
        };
        let e = eye.map(f64::from);
        let dist = (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt();
        assert!((dist / r - 2.1).abs() < 1e-4, "frame {i}: {dist} vs {r}");
        let pitch = (e[1] / dist).asin().to_degrees();
        assert!((pitch - 25.0).abs() < 1e-3, "frame {i}: pitch {pitch}");
        // Yaw 360°·i/n about y, starting on +z.
        let yaw = e[0].atan2(e[2]).to_degrees().rem_euclid(360.0);
        let want = 360.0 * f64::from(i) / f64::from(n);
        assert!((yaw - want).abs() < 1e-3, "frame {i}: yaw {yaw} vs {want}");
    }
}

fn crcs<P: Precision>(tree: &Tree<'_>, band: u32, n: u32) -> Vec<u32> {
    let (w, h) = (96, 64);
    let mut r = TreeRenderer::<P, MAX_VERTS>::new(w, h).expect("renderer");
    let rows = if band == 0 { h } else { band };
    let mut buf = vec![0u16; (w * rows) as usize];
    (0..n)
        .map(|i| {
            frame_crc::<P, 64, MAX_VERTS>(&mut r, tree, (i, n), (&mut buf, &mut []), band)
                .unwrap()
                .0
        })
        .collect()
}

#[test]
fn checksum_is_the_same_for_every_band_height() {
    let bytes = vise();
    let tree = Tree::from_bytes(&bytes).expect("vise.fpt validates");
    for (name, full, bands) in [
        (
            "f32-libm",
            crcs::<FloatLibm<4>>(&tree, 0, 4),
            [7, 16].map(|b| crcs::<FloatLibm<4>>(&tree, b, 4)),
        ),
        (
            "fixed",
            crcs::<FixedPrecision<4>>(&tree, 0, 4),
            [7, 16].map(|b| crcs::<FixedPrecision<4>>(&tree, b, 4)),
        ),
    ] {
        for b in &bands {
            assert_eq!(b, &full, "{name}");
        }
        let mut distinct = full.clone();
        distinct.sort_unstable();
        distinct.dedup();
        assert_eq!(
            distinct.len(),
            full.len(),
            "{name}: frames repeat {full:08x?}"
        );
    }
}
