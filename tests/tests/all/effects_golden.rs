//! Golden images of every scene effect, on and off, made by the reference
//! path and checked pixel for pixel against the product.
//!
//! For each effect a small picture is rendered twice, with the effect on and
//! off (the rest of the scene's default effects unchanged), by
//!
//! * **the reference path**: the float64 z-buffer of the tree's polygons
//!   ([`host_sim::reference::zbuffer`]: visibility, with its own back-face
//!   test, near-plane clipping, or, without clipping, the polygons that
//!   would need it left out), then, per pixel, the visible face's colour:
//!   its file colour, lit by the same light with the shared shading
//!   function (its normal flipped when two-sided lighting shows its back),
//!   faded by a depth weight computed in `f64` from the exact eye depths,
//!   and, for monochrome pictures, thresholded or dithered by the Bayer
//!   formula written out here pixel by pixel; with smooth shading, the
//!   corner colours (each corner lit by the tree's corner normal) blended
//!   by the pixel centre's barycentric weights in the exact projected
//!   triangle, rounded. Pixels the reference is not
//!   sure of (near an outline, depth ties, and with outlines on, within
//!   1.5 px of a visible polygon's edge) are magenta;
//! * **the product**: the no_std pipeline with that effect set
//!   ([`fpt_nostd::render`]), into an `Rgb888` or `BinaryColor` framebuffer
//!   (the latter through [`fpt_nostd::raster::Dither`] when dithering).
//!
//! The goldens live in `tests/golden/effects/` and are the reference
//! pictures; the test recomputes the reference picture and requires it to
//! equal the golden file exactly (so a change to the reference shows as a
//! changed file), and requires the product to equal it on every pixel that
//! is not magenta (with smooth shading within 2 levels a channel: the
//! product interpolates from vertices snapped to 1/16 px, in 8.16 fixed
//! point). With outlines on, every outline pixel the product draws
//! must also lie within 1.5 px of an edge of a visible polygon. Regenerate
//! the goldens with `FPT_BLESS=1 cargo test -p fpt-tests --test all effects_golden`.

use crate::render_common;

use std::path::PathBuf;

use embedded_graphics::pixelcolor::{BinaryColor, Gray8, GrayColor, Rgb888, RgbColor};
use fpt_nostd::effects::Effects;
use fpt_nostd::raster::shade::{shade, shade_color};
use fpt_nostd::raster::{
    BinaryFramebuffer, DefaultPrecision, DepthCue, Dither, Light, Paint, Rgb888Framebuffer,
    ShadeMode, SpanSink,
};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{near_w_for, TreeRenderer};
use glam::DVec3;
use host_sim::build::{build, NoProgress, DEFAULT_SEED};
use host_sim::geom::Polygon;
use host_sim::reference::{zbuffer, Camera, Projection, RefOptions};
use host_sim::scenes::Scene;
use host_sim::serialize::{serialize, SerializeOptions};
use host_sim::tree::Method;
use render_common::{edge_px, frame, rows, seg_dist, STACK, VERTS};

const W: usize = 128;
const H: usize = 128;
/// Background (not black, so that black outlines stand out from it).
const BG: Rgb888 = Rgb888::new(30, 50, 70);
/// Unsure pixels in a golden picture.
const UNSURE: [u8; 3] = [255, 0, 255];
/// Outline ink.
const INK: [u8; 3] = [0, 0, 0];
/// Pixels this close to a visible polygon's edge may hold outline ink.
const OUTLINE_PX: f64 = 1.5;

/// One golden picture pair.
struct Case {
    effect: &'static str,
    scene: fn() -> Scene,
    /// Eye distance in bounding radii, yaw and pitch in degrees.
    orbit: (f64, f64, f64),
    mono: bool,
}

const CASES: [Case; 8] = [
    Case {
        effect: "culling",
        scene: host_sim::scenes::vise,
        orbit: (2.2, 35.0, 25.0),
        mono: false,
    },
    Case {
        effect: "two-sided",
        scene: host_sim::scenes::open_sheet,
        orbit: (2.2, 200.0, -30.0),
        mono: false,
    },
    Case {
        effect: "clipping",
        scene: host_sim::scenes::vise,
        orbit: (0.8, 60.0, 20.0),
        mono: false,
    },
    Case {
        effect: "lighting",
        scene: host_sim::scenes::vise,
        orbit: (2.2, 35.0, 25.0),
        mono: false,
    },
    Case {
        effect: "depth-cue",
        scene: host_sim::scenes::vise,
        orbit: (1.6, -40.0, 30.0),
        mono: false,
    },
    Case {
        effect: "dither",
        scene: host_sim::scenes::vise,
        orbit: (2.2, 35.0, 25.0),
        mono: true,
    },
    Case {
        effect: "outline",
        scene: host_sim::scenes::vise,
        orbit: (2.2, 35.0, 25.0),
        mono: false,
    },
    Case {
        effect: "smooth",
        scene: ball,
        orbit: (2.6, 30.0, 20.0),
        mono: false,
    },
];

/// A closed ball of 160 triangles (UV sphere, 8 bands of 10), coloured in
/// two hues by band: curved, convex, so the tree needs no splits and every
/// polygon is a triangle.
fn ball() -> Scene {
    let (bands, around) = (8usize, 10usize);
    let tau = std::f64::consts::TAU;
    let at = |i: usize, j: usize| {
        let th = std::f64::consts::PI * i as f64 / bands as f64;
        let ph = tau * j as f64 / around as f64;
        DVec3::new(th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos())
    };
    let mut polygons = Vec::new();
    let mut tri = |a: DVec3, b: DVec3, c: DVec3, band: usize| {
        let colour = if band & 1 == 0 {
            [230, 180, 90]
        } else {
            [120, 170, 240]
        };
        let id = polygons.len() as u32;
        polygons.push(Polygon::new(vec![a, b, c], id, colour).expect("triangle"));
    };
    for i in 0..bands {
        for j in 0..around {
            let (a, b) = (at(i, j), at(i, j + 1));
            let (c, d) = (at(i + 1, j + 1), at(i + 1, j));
            // Outward and counter-clockwise; the poles' rings are triangles.
            if i > 0 {
                tri(a, d, b, i);
            }
            if i + 1 < bands {
                tri(b, d, c, i);
            }
        }
    }
    let n = polygons.len();
    Scene {
        name: "ball".into(),
        polygons,
        closed: true,
        parts: std::iter::once(0..n).collect(),
    }
}

/// The scene's tree; a scene drawn with smooth shading declares it, so
/// that the tree carries corner normals.
fn tree_bytes(scene: fn() -> Scene, smooth: bool) -> Vec<u8> {
    let s = scene();
    let t = build(
        s.polygons,
        s.closed,
        Method::Static,
        DEFAULT_SEED,
        &mut NoProgress,
    );
    let effects = smooth.then(|| Effects::defaults(s.closed).with(Effects::SMOOTH).bits());
    let opts = SerializeOptions {
        effects,
        ..SerializeOptions::default()
    };
    serialize(&t, &opts).expect("serialize")
}

/// The orbit camera (z up) around the bounding-sphere centre.
fn camera(tree: &Tree<'_>, (dist, yaw, pitch): (f64, f64, f64)) -> Camera {
    let r = f64::from(tree.bounding_radius());
    let c = DVec3::from(tree.origin());
    let (y, p) = (yaw.to_radians(), pitch.to_radians());
    let dir = DVec3::new(p.cos() * y.sin(), -p.cos() * y.cos(), p.sin());
    let eye = c + dir * dist * r;
    let proj = Projection::Perspective {
        fov_y_deg: 50.0,
        near: 0.01 * r,
        far: 10.0 * r + dist * r,
    };
    Camera::look_at(eye, c, DVec3::Z, proj, W as f64 / H as f64).expect("camera")
}

/// The tree's polygons as the reference draws them, by file id.
fn polygons(tree: &Tree<'_>) -> Vec<Polygon> {
    (0..tree.polygon_count())
        .map(|id| {
            let p = tree.polygon(id).expect("polygon");
            let verts: Vec<DVec3> = (0..p.vertex_count())
                .map(|i| DVec3::from(p.vertex_model(i)))
                .collect();
            let c = p.color();
            Polygon::new(verts, p.source(), c).expect("non-degenerate polygon")
        })
        .collect()
}

/// The product's picture as RGB triples (mono: white on, black off).
fn product(tree: &Tree<'_>, cam: &Camera, fx: Effects, mono: bool) -> Vec<[u8; 3]> {
    let f = frame(tree, cam);
    let mut tr = Box::new(
        TreeRenderer::<DefaultPrecision, VERTS>::new(W as u32, H as u32).expect("renderer"),
    );
    tr.renderer.set_light(Light::new(f.key_light(), 0.25, 0.75));
    tr.renderer.set_effects(Some(fx));
    let (near, far) = f.depth_range(tree);
    tr.renderer.set_depth_cue(DepthCue {
        near,
        far,
        fog: BG,
        ..DepthCue::default()
    });
    if mono {
        let mut buf = vec![0u8; BinaryFramebuffer::required_len(W as u32, H as u32)];
        let mut fb = BinaryFramebuffer::new(&mut buf, W as u32, H as u32).expect("fb");
        if fx.contains(Effects::DITHER) {
            let mut d = Dither::new(&mut fb, 2);
            let bg = d.color(&Paint { rgb: BG, id: 0 });
            for y in 0..H as i32 {
                d.span(y, 0, W as i32, bg);
            }
            tr.render::<STACK, _>(tree, &f, &mut d).expect("walk");
        } else {
            fb.fill_all(BinaryColor::from(BG));
            tr.render::<STACK, _>(tree, &f, &mut fb).expect("walk");
        }
        (0..H)
            .flat_map(|y| (0..W).map(move |x| (x, y)))
            .map(|(x, y)| {
                let on = fb.pixel(x as u32, y as u32).expect("pixel").is_on();
                [if on { 255 } else { 0 }; 3]
            })
            .collect()
    } else {
        let mut buf = vec![0u8; 3 * W * H];
        let mut fb = Rgb888Framebuffer::new(&mut buf, W as u32, H as u32).expect("fb");
        fb.fill_all(BG);
        tr.render::<STACK, _>(tree, &f, &mut fb).expect("walk");
        buf.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()
    }
}

/// The 4×4 Bayer threshold rule of the `dither` effect, per pixel.
fn bayer_on(luma: u8, x: usize, y: usize) -> bool {
    const M: [[u32; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];
    (u32::from(luma) + M[y % 4][x % 4] * 16 + 8) / 255 >= 1
}

/// Pixel position of a model point, or `None` behind the eye.
fn to_pixel(cam: &Camera, p: DVec3) -> Option<(f64, f64)> {
    let c = cam.clip(p);
    (c.w > 0.0).then(|| {
        (
            (c.x / c.w + 1.0) * 0.5 * W as f64,
            (1.0 - c.y / c.w) * 0.5 * H as f64,
        )
    })
}

/// Per pixel: within `px` of an edge of a polygon visible in `ids`.
fn near_visible_edges(polys: &[Polygon], cam: &Camera, ids: &[u32], px: f64) -> Vec<bool> {
    let mut visible = vec![false; polys.len()];
    for &id in ids.iter().filter(|&&id| id > 0) {
        visible[id as usize - 1] = true;
    }
    let mut near = vec![false; W * H];
    for (p, _) in polys.iter().zip(&visible).filter(|(_, &v)| v) {
        let pts: Vec<Option<(f64, f64)>> = p.verts.iter().map(|&v| to_pixel(cam, v)).collect();
        for k in 0..pts.len() {
            let (Some(a), Some(b)) = (pts[k], pts[(k + 1) % pts.len()]) else {
                continue;
            };
            let (x0, x1) = (a.0.min(b.0) - px, a.0.max(b.0) + px);
            let (y0, y1) = (a.1.min(b.1) - px, a.1.max(b.1) + px);
            for y in (y0.max(0.0) as usize)..(y1.min(H as f64).max(0.0) as usize + 1).min(H) {
                for x in (x0.max(0.0) as usize)..(x1.min(W as f64).max(0.0) as usize + 1).min(W) {
                    if seg_dist(a, b, x as f64 + 0.5, y as f64 + 0.5).0 <= px {
                        near[y * W + x] = true;
                    }
                }
            }
        }
    }
    near
}

/// A reference picture.
struct Reference {
    /// Unsure pixels magenta.
    pic: Vec<[u8; 3]>,
    /// Per pixel: near a visible polygon's edge.
    near_edges: Vec<bool>,
    /// Pixels showing a face, and how many of them are sure.
    face_pixels: (usize, usize),
}

/// The reference picture of `tree` with effects `fx`.
fn reference(tree: &Tree<'_>, cam: &Camera, fx: Effects, mono: bool) -> Reference {
    let all = polygons(tree);
    let r = rows(cam);
    // Without clipping, a polygon that would need it is not drawn.
    let near_w = f64::from(near_w_for(&r, tree));
    let keep: Vec<bool> = all
        .iter()
        .map(|p| {
            fx.contains(Effects::CLIPPING)
                || p.verts.iter().all(|&v| {
                    let c = cam.clip(v);
                    c.w >= near_w && c.x.abs() <= 4.0 * c.w && c.y.abs() <= 4.0 * c.w
                })
        })
        .collect();
    let drawn: Vec<usize> = (0..all.len()).filter(|&i| keep[i]).collect();
    let polys: Vec<Polygon> = drawn.iter().map(|&i| all[i].clone()).collect();
    let opt = RefOptions {
        cull_backfaces: fx.contains(Effects::CULLING),
        edge_px: edge_px(4),
        ..RefOptions::default()
    };
    let zb = zbuffer(&polys, cam, W, H, opt);
    let ids: Vec<u32> = zb
        .ids
        .iter()
        .map(|&i| {
            if i == 0 {
                0
            } else {
                drawn[i as usize - 1] as u32 + 1
            }
        })
        .collect();
    let f = frame(tree, cam);
    let light = Light::new(f.key_light(), 0.25, 0.75);
    let view = cam.view();
    // Depth cueing: exact mean eye depth against the bounding sphere's range.
    let row_w = glam::DVec4::from(r[3]);
    let centre = DVec3::from(tree.origin());
    let w_c = row_w.truncate().dot(centre) + row_w.w;
    let rho = f64::from(tree.bounding_radius()) * row_w.truncate().length();
    let smooth = fx.contains(Effects::SMOOTH) && fx.contains(Effects::LIGHTING);
    let colour = |id: usize, px: usize| -> Rgb888 {
        let p = &all[id];
        let stored = tree.polygon(id as u32).expect("polygon").plane();
        let mut n = stored.normal;
        if fx.contains(Effects::TWO_SIDED) && !view.faces(&p.plane) {
            n = n.map(|c| -c);
        }
        let c = tree.polygon(id as u32).expect("polygon").color();
        let mut rgb = if smooth {
            smooth_colour(tree, cam, &light, id as u32, px)
        } else if fx.contains(Effects::LIGHTING) {
            shade(ShadeMode::Lambert, &light, n, c)
        } else {
            Rgb888::new(c[0], c[1], c[2])
        };
        if fx.contains(Effects::DEPTH_CUE) {
            let w = p.verts.iter().map(|&v| cam.clip(v).w).sum::<f64>() / p.verts.len() as f64;
            let t = ((w - (w_c - rho)) / (2.0 * rho)).clamp(0.0, 1.0);
            let a = (t * 192.0).floor() as u32;
            let mix =
                |c: u8, f: u8| ((u32::from(c) * (256 - a) + u32::from(f) * a + 128) >> 8) as u8;
            rgb = Rgb888::new(
                mix(rgb.r(), BG.r()),
                mix(rgb.g(), BG.g()),
                mix(rgb.b(), BG.b()),
            );
        }
        rgb
    };
    let outline = fx.contains(Effects::OUTLINE);
    let near_edges = near_visible_edges(&all, cam, &ids, OUTLINE_PX);
    let faces = ids.iter().filter(|&&id| id != 0).count();
    let sure_faces = (0..W * H)
        .filter(|&i| ids[i] != 0 && !zb.unsure(i) && !(outline && near_edges[i]))
        .count();
    let pic = (0..W * H)
        .map(|i| {
            if zb.unsure(i) || (outline && near_edges[i]) {
                return UNSURE;
            }
            let rgb = match ids[i] {
                0 => BG,
                id => colour(id as usize - 1, i),
            };
            if mono {
                let on = if fx.contains(Effects::DITHER) {
                    bayer_on(Gray8::from(rgb).luma(), i % W, i / W)
                } else {
                    BinaryColor::from(rgb).is_on()
                };
                [if on { 255 } else { 0 }; 3]
            } else {
                [rgb.r(), rgb.g(), rgb.b()]
            }
        })
        .collect();
    Reference {
        pic,
        near_edges,
        face_pixels: (faces, sure_faces),
    }
}

/// The smooth-shaded colour of pixel `px` on triangle `id`: its corners
/// lit by their stored normals (the shared shading functions), blended by
/// the pixel centre's barycentric weights in the exact projection, rounded.
fn smooth_colour(tree: &Tree<'_>, cam: &Camera, light: &Light, id: u32, px: usize) -> Rgb888 {
    let p = tree.polygon(id).expect("polygon");
    assert_eq!(p.vertex_count(), 3, "the smooth case draws triangles");
    let corner = |k: usize| {
        let n = tree.corner_normal(id, k).expect("corner normal");
        let c = shade_color(ShadeMode::Lambert, p.color(), light.intensity_i8(n));
        let xy = to_pixel(cam, DVec3::from(p.vertex_model(k))).expect("in front");
        (xy, [c.r(), c.g(), c.b()].map(f64::from))
    };
    let [(a, ca), (b, cb), (c, cc)] = [corner(0), corner(1), corner(2)];
    let (x, y) = ((px % W) as f64 + 0.5, (px / W) as f64 + 0.5);
    let area = (b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1);
    let wb = ((x - a.0) * (c.1 - a.1) - (c.0 - a.0) * (y - a.1)) / area;
    let wc = ((b.0 - a.0) * (y - a.1) - (x - a.0) * (b.1 - a.1)) / area;
    let ch = |k: usize| {
        let v = ca[k] + wb * (cb[k] - ca[k]) + wc * (cc[k] - ca[k]);
        (v + 0.5).floor().clamp(0.0, 255.0) as u8
    };
    Rgb888::new(ch(0), ch(1), ch(2))
}

fn golden_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("golden/effects")
        .join(format!("{name}.png"))
}

fn write_png(path: &PathBuf, pic: &[[u8; 3]]) {
    std::fs::create_dir_all(path.parent().expect("parent")).expect("golden dir");
    let file = std::fs::File::create(path).expect("golden file");
    let mut enc = png::Encoder::new(std::io::BufWriter::new(file), W as u32, H as u32);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut w = enc.write_header().expect("png header");
    w.write_image_data(pic.as_flattened()).expect("png data");
}

fn read_png(path: &PathBuf) -> Option<Vec<[u8; 3]>> {
    let bytes = std::fs::read(path).ok()?;
    let dec = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = dec.read_info().ok()?;
    let mut buf = vec![0u8; reader.output_buffer_size()?];
    let info = reader.next_frame(&mut buf).ok()?;
    if (info.width, info.height, info.color_type) != (W as u32, H as u32, png::ColorType::Rgb) {
        return None;
    }
    Some(
        buf[..info.buffer_size()]
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect(),
    )
}

#[test]
fn every_effect_on_and_off_matches_its_reference_golden() {
    let bless = std::env::var_os("FPT_BLESS").is_some();
    let mut failures = Vec::new();
    for case in &CASES {
        let bytes = tree_bytes(case.scene, case.effect == "smooth");
        let tree = Tree::from_bytes(&bytes).expect("valid tree");
        let cam = camera(&tree, case.orbit);
        let e = Effects::parse(case.effect).expect("effect name");
        let base = Effects::from_bits(tree.effects());
        for (state, fx) in [("on", base.with(e)), ("off", base.without(e))] {
            let name = format!("{}-{state}", case.effect);
            let Reference {
                pic: want,
                near_edges,
                face_pixels: (faces, sure_faces),
            } = reference(&tree, &cam, fx, case.mono);
            let path = golden_path(&name);
            if bless {
                write_png(&path, &want);
            }
            match read_png(&path) {
                Some(g) if g == want => {}
                Some(_) => failures.push(format!(
                    "{name}: the reference picture differs from {} (bless with FPT_BLESS=1 if the reference changed on purpose)",
                    path.display()
                )),
                None => failures.push(format!("{name}: no golden {} (FPT_BLESS=1 makes it)", path.display())),
            }
            let got = product(&tree, &cam, fx, case.mono);
            let sure = want.iter().filter(|&&p| p != UNSURE).count();
            let tol = if fx.contains(Effects::SMOOTH) { 2 } else { 0 };
            let differs = |a: [u8; 3], b: [u8; 3]| (0..3).any(|k| a[k].abs_diff(b[k]) > tol);
            let wrong: Vec<usize> = (0..W * H)
                .filter(|&i| want[i] != UNSURE && differs(got[i], want[i]))
                .collect();
            if let Some(&i) = wrong.first() {
                failures.push(format!(
                    "{name}: {} of {sure} sure pixels differ, first at ({}, {}): {:?}, reference {:?}",
                    wrong.len(),
                    i % W,
                    i / W,
                    got[i],
                    want[i]
                ));
            }
            // Enough of the model is checked to mean something (outlines
            // make every pixel near an edge unsure).
            let needed = if fx.contains(Effects::OUTLINE) { 4 } else { 2 };
            if faces < W * H / 8 || sure_faces * needed < faces {
                failures.push(format!(
                    "{name}: only {sure_faces} of {faces} face pixels are sure"
                ));
            }
            if fx.contains(Effects::OUTLINE) {
                let ink: Vec<usize> = (0..W * H).filter(|&i| got[i] == INK).collect();
                if ink.len() < 200 {
                    failures.push(format!("{name}: only {} outline pixels", ink.len()));
                }
                if let Some(&i) = ink.iter().find(|&&i| !near_edges[i]) {
                    failures.push(format!(
                        "{name}: outline ink at ({}, {}), far from every visible edge",
                        i % W,
                        i / W
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
