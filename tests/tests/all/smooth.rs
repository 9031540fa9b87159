//! Smooth (Gouraud) shading end to end: the corner normal section is
//! written only when the scene declares `smooth`, follows the crease
//! angle, and the reader rejects a corrupt or truncated one; the picture
//! is the same full frame and in bands of any memory (with depth cueing
//! too), dithering applies the Bayer rule to the smooth colours, and a
//! tree without normals is drawn flat. (Its colours against the reference
//! path: `effects_golden.rs`.)

use embedded_graphics::pixelcolor::{BinaryColor, Gray8, GrayColor, Rgb888};
use fpt_nostd::effects::Effects;
use fpt_nostd::format::{crc32, header as h, Counts, FormatError, Sections, FLAG_NORMALS};
use fpt_nostd::raster::framebuffer::Rgb888Format;
use fpt_nostd::raster::{
    BinaryFramebuffer, DefaultPrecision, DepthCue, Dither, Libm, Light, Orbit, Rgb888Framebuffer,
};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{memory_words_for, BandBuffer, Frame, TreeRenderer};
use host_sim::build::{build, NoProgress, DEFAULT_SEED};
use host_sim::scenes;
use host_sim::serialize::{serialize, SerializeOptions};
use host_sim::tree::Method;

const W: u32 = 96;
const H: u32 = 72;
const STACK: usize = 256;
const VERTS: usize = 64;

/// A 16 × 8 torus: its facets turn by 22.5° around the ring and by 45°
/// around the tube.
fn torus(effects: Effects, crease_deg: f32) -> Vec<u8> {
    let s = scenes::torus(16, 8);
    let t = build(
        s.polygons,
        s.closed,
        Method::Static,
        DEFAULT_SEED,
        &mut NoProgress,
    );
    let opts = SerializeOptions {
        effects: Some(effects.bits()),
        crease_deg,
        ..SerializeOptions::default()
    };
    serialize(&t, &opts).expect("serialize")
}

fn smooth_fx() -> Effects {
    Effects::defaults(true).with(Effects::SMOOTH)
}

/// The angle in degrees between a stored corner normal and a plane normal.
fn angle(n: [i8; 3], p: [f32; 3]) -> f32 {
    let n = n.map(|c| f32::from(c) / 127.0);
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    let dot = (n[0] * p[0] + n[1] * p[1] + n[2] * p[2]) / len;
    dot.clamp(-1.0, 1.0).acos().to_degrees()
}

#[test]
fn the_section_is_written_when_declared_and_follows_the_crease() {
    let plain = torus(Effects::defaults(true), 30.0);
    let bytes = torus(smooth_fx(), 30.0);
    let (a, b) = (
        Tree::from_bytes(&plain).expect("plain"),
        Tree::from_bytes(&bytes).expect("smooth"),
    );
    assert!(!a.has_normals() && b.has_normals());
    assert_eq!(
        bytes.len(),
        plain.len() + (3 * b.index_count() as usize).next_multiple_of(4)
    );
    // Crease 30°: smooth around the ring (22.5°), sharp across the tube
    // (45°), so each corner leans from its face by half a ring step at
    // most (11.25°) and never toward the tube's neighbours.
    let mut leaning = 0;
    for id in 0..b.polygon_count() {
        let p = b.polygon(id).expect("polygon");
        let plane = p.plane().normal;
        for i in 0..p.vertex_count() {
            let n = b.corner_normal(id, i).expect("normal");
            let d = angle(n, plane);
            assert!(d < 12.5, "polygon {id} corner {i}: {d}°");
            if d > 5.0 {
                leaning += 1;
            }
        }
        assert_eq!(b.corner_normal(id, p.vertex_count()), None);
        assert_eq!(a.corner_normal(id, 0), None);
    }
    // (Near the top and bottom of the tube the ring turns the normals
    // little: about half the corners lean by more than 5°.)
    assert!(leaning > b.index_count() / 3, "{leaning}");
    assert_eq!(b.corner_normal(b.polygon_count(), 0), None);
    // Crease 5° (below the smallest turn between neighbours, 8.6° near
    // the tube's top): every corner keeps its face's normal (to rounding).
    let sharp = torus(smooth_fx(), 5.0);
    let s = Tree::from_bytes(&sharp).expect("sharp");
    for id in 0..s.polygon_count() {
        let p = s.polygon(id).expect("polygon");
        for i in 0..p.vertex_count() {
            let d = angle(s.corner_normal(id, i).expect("normal"), p.plane().normal);
            assert!(d < 1.0, "polygon {id} corner {i}: {d}°");
        }
    }
    // Crease 60°: smooth both ways, corners lean further.
    let round = torus(smooth_fx(), 60.0);
    let r = Tree::from_bytes(&round).expect("round");
    let most = (0..r.polygon_count())
        .flat_map(|id| {
            let p = r.polygon(id).expect("polygon");
            let plane = p.plane().normal;
            (0..p.vertex_count()).map(move |i| (id, i, plane))
        })
        .map(|(id, i, plane)| angle(r.corner_normal(id, i).expect("normal"), plane))
        .fold(0.0f32, f32::max);
    assert!(most > 20.0, "{most}");
}

/// `bytes` with its CRC recomputed.
fn with_crc(mut v: Vec<u8>) -> Vec<u8> {
    let n = v.len() - 4;
    let c = crc32(&v[..n]);
    v[n..].copy_from_slice(&c.to_le_bytes());
    v
}

#[test]
fn a_corrupt_or_truncated_section_is_rejected() {
    let bytes = torus(smooth_fx(), 30.0);
    let t = Tree::from_bytes(&bytes).expect("tree");
    let s = Sections::with_records(
        &Counts {
            vertices: t.vertex_count(),
            polygons: t.polygon_count(),
            indices: t.index_count(),
            bunches: t.bunch_count(),
            nodes: t.node_count(),
            switches: t.switch_count(),
            runs: t.run_count(),
            small: t.has_small_records(),
            edges: 0,
            normals: t.index_count(),
        },
        t.vertex_format(),
        usize::from(t.index_size()),
        t.records().as_ref(),
    )
    .expect("layout");
    assert_eq!(s.file_len, bytes.len());
    let edit = |at: usize, rec: [u8; 3]| {
        let mut v = bytes.clone();
        v[at..at + 3].copy_from_slice(&rec);
        Tree::from_bytes(&with_crc(v)).err()
    };
    // A zero vector, and −128 in any component.
    assert_eq!(
        edit(s.normals + 3, [0, 0, 0]),
        Some(FormatError::BadNormal(1))
    );
    assert_eq!(
        edit(s.normals + 6, [0x80, 0, 10]),
        Some(FormatError::BadNormal(2))
    );
    assert_eq!(
        edit(s.normals, [5, 0x80, 0]),
        Some(FormatError::BadNormal(0))
    );
    // The extreme valid values read back.
    let mut v = bytes.clone();
    v[s.normals..s.normals + 3].copy_from_slice(&[0x81, 127, 0]);
    let ok = with_crc(v);
    let t2 = Tree::from_bytes(&ok).expect("−127 and 127 are valid");
    assert_eq!(t2.corner_normal(0, 0), Some([-127, 127, 0]));
    // Without the flag, the section makes the length wrong.
    let mut v = bytes.clone();
    v[h::FLAGS] &= !(FLAG_NORMALS as u8);
    assert_eq!(
        Tree::from_bytes(&with_crc(v)).err(),
        Some(FormatError::SectionSizes)
    );
    // Truncated: the section cut out, the header's length and the CRC
    // made to match; and the file cut short.
    let mut v = bytes[..s.normals].to_vec();
    v.extend_from_slice(&bytes[s.runs..]);
    let len = v.len() as u32;
    v[h::FILE_LEN..h::FILE_LEN + 4].copy_from_slice(&len.to_le_bytes());
    assert_eq!(
        Tree::from_bytes(&with_crc(v)).err(),
        Some(FormatError::SectionSizes)
    );
    assert_eq!(
        Tree::from_bytes(&bytes[..bytes.len() - 8]).err(),
        Some(FormatError::LengthMismatch)
    );
}

/// A renderer with the frame set's light and a depth range.
fn renderer(tree: &Tree<'_>, f: &Frame, fx: Effects) -> Box<TreeRenderer<DefaultPrecision, VERTS>> {
    let mut r = Box::new(TreeRenderer::new(W, H).expect("renderer"));
    r.renderer.set_light(Light::new(f.key_light(), 0.25, 0.75));
    r.renderer.set_effects(Some(fx));
    let (near, far) = f.depth_range(tree);
    r.renderer.set_depth_cue(DepthCue {
        near,
        far,
        ..DepthCue::default()
    });
    r
}

fn view(tree: &Tree<'_>, yaw: f32) -> Frame {
    let o = Orbit::framing::<Libm>(tree.bounding_radius(), yaw, 0.6, 0.9, W as f32 / H as f32);
    Frame::relative(tree, &o.camera::<Libm>(W as f32 / H as f32))
}

/// The full frame in `Rgb888`.
fn full(tree: &Tree<'_>, f: &Frame, fx: Effects) -> Vec<u8> {
    let mut buf = vec![0u8; (3 * W * H) as usize];
    let mut fb = Rgb888Framebuffer::new(&mut buf, W, H).expect("fb");
    renderer(tree, f, fx)
        .render::<STACK, _>(tree, f, &mut fb)
        .expect("walk");
    buf
}

#[test]
fn bands_draw_the_full_frame_and_depth_cueing_applies() {
    let bytes = torus(smooth_fx(), 30.0);
    let tree = Tree::from_bytes(&bytes).expect("tree");
    for yaw in [0.3f32, 2.0] {
        let f = view(&tree, yaw);
        let flat = full(&tree, &f, Effects::defaults(true));
        for fx in [smooth_fx(), smooth_fx().with(Effects::DEPTH_CUE)] {
            let want = full(&tree, &f, fx);
            assert!(want != flat, "{fx}: smooth shading shows");
            let need = memory_words_for(&tree, fx);
            for rows in [1u32, 16, H] {
                for words in [0, need / 3, need] {
                    let mut r = renderer(&tree, &f, fx);
                    let mut got = vec![0u8; want.len()];
                    let mut buf = vec![0u8; (3 * W * rows) as usize];
                    let band = BandBuffer::<Rgb888Format> {
                        buf: &mut buf,
                        rows,
                        background: Rgb888::new(0, 0, 0),
                    };
                    let mut memory = vec![0u32; words];
                    r.render_banded_in::<STACK, Rgb888Format>(
                        &tree,
                        &f,
                        band,
                        &mut memory,
                        |y, b| {
                            let at = 3 * y as usize * W as usize;
                            got[at..at + b.data().len()].copy_from_slice(b.data());
                        },
                    )
                    .expect("bands");
                    assert!(got == want, "{fx}, yaw {yaw}: {rows} rows, {words} words");
                }
            }
        }
        let cued = full(&tree, &f, smooth_fx().with(Effects::DEPTH_CUE));
        assert!(cued != full(&tree, &f, smooth_fx()), "depth cueing shows");
    }
}

#[test]
fn dithering_applies_the_bayer_rule_to_the_smooth_colours() {
    const M: [[u32; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];
    let bytes = torus(smooth_fx(), 30.0);
    let tree = Tree::from_bytes(&bytes).expect("tree");
    let f = view(&tree, 0.8);
    let fx = smooth_fx().with(Effects::DITHER);
    let colours = full(&tree, &f, fx);
    let mut buf = vec![0u8; BinaryFramebuffer::required_len(W, H)];
    let mut fb = BinaryFramebuffer::new(&mut buf, W, H).expect("fb");
    fb.fill_all(BinaryColor::Off);
    renderer(&tree, &f, fx)
        .render::<STACK, _>(&tree, &f, &mut Dither::new(&mut fb, 2))
        .expect("walk");
    let (mut on, mut mixed) = (0, 0);
    for y in 0..H as usize {
        for x in 0..W as usize {
            let i = 3 * (y * W as usize + x);
            let rgb = Rgb888::new(colours[i], colours[i + 1], colours[i + 2]);
            let luma = u32::from(Gray8::from(rgb).luma());
            let want = (luma + M[y % 4][x % 4] * 16 + 8) / 255 >= 1;
            let got = fb.pixel(x as u32, y as u32).expect("pixel").is_on();
            assert_eq!(got, want, "({x}, {y}) luma {luma}");
            on += usize::from(got);
            mixed += usize::from(luma > 20 && luma < 235);
        }
    }
    assert!(on > 200 && mixed > 500, "{on} on, {mixed} mid-grey");
}

#[test]
fn a_tree_without_normals_is_drawn_flat() {
    let bytes = torus(Effects::defaults(true), 30.0);
    let tree = Tree::from_bytes(&bytes).expect("tree");
    let f = view(&tree, 1.1);
    for extra in [Effects::NONE, Effects::DEPTH_CUE] {
        let flat = Effects::defaults(true).with(extra);
        assert!(full(&tree, &f, flat.with(Effects::SMOOTH)) == full(&tree, &f, flat));
    }
}
