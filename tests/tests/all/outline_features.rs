//! Feature-edge outlines on STL parts written here: the `outline` effect
//! draws a part's edges, not its triangulation.
//!
//! * A box whose top face is a grid of 32 coplanar triangles, seen from
//!   above: every outline pixel lies on the face's border (no interior
//!   edge drawn), and the border is drawn.
//! * A 24-sided prism (facets 15° apart, under the default 30° crease):
//!   the facet edges are not drawn in the middle of its side, but its
//!   silhouettes are; with a 10° crease the facet edges are drawn.

use crate::render_common;

use embedded_graphics::pixelcolor::Rgb888;
use fpt_nostd::effects::Effects;
use fpt_nostd::format::FLAG_EDGES;
use fpt_nostd::raster::{DefaultPrecision, Light, Rgb888Framebuffer};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::TreeRenderer;
use glam::{DVec3, DVec4};
use host_sim::build::{build, NoProgress, DEFAULT_SEED};
use host_sim::mesh::{load_bytes, MeshFormat};
use host_sim::reference::{Camera, Projection};
use host_sim::serialize::{serialize, SerializeOptions};
use host_sim::tree::Method;
use render_common::{frame, rows, seg_dist, STACK, VERTS};

const W: usize = 128;
const H: usize = 128;
const BG: Rgb888 = Rgb888::new(30, 50, 70);
const INK: [u8; 3] = [0, 0, 0];

/// An ASCII STL of triangles.
fn stl(tris: &[[DVec3; 3]]) -> Vec<u8> {
    let mut s = String::from("solid part\n");
    for t in tris {
        s += " facet normal 0 0 0\n  outer loop\n";
        for v in t {
            s += &format!("   vertex {} {} {}\n", v.x, v.y, v.z);
        }
        s += "  endloop\n endfacet\n";
    }
    s += "endsolid part\n";
    s.into_bytes()
}

/// Two triangles for the quad `a b c d` (counter-clockwise from outside).
fn quad(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> [[DVec3; 3]; 2] {
    [[a, b, c], [a, c, d]]
}

/// A 2 × 2 × 1 box with its top (z = 1) split into a 4 × 4 grid of quads.
fn grid_box() -> Vec<[DVec3; 3]> {
    let v = DVec3::new;
    let mut t = vec![];
    let g = |i: i32, j: i32| v(-1.0 + 0.5 * f64::from(i), -1.0 + 0.5 * f64::from(j), 1.0);
    for i in 0..4 {
        for j in 0..4 {
            t.extend(quad(g(i, j), g(i + 1, j), g(i + 1, j + 1), g(i, j + 1)));
        }
    }
    // The sides and the bottom share the top's border vertices.
    for k in 0..4 {
        let (i0, i1) = (k, k + 1);
        let lo = |p: DVec3| v(p.x, p.y, 0.0);
        for (a, b) in [
            (g(i0, 0), g(i1, 0)),
            (g(4, i0), g(4, i1)),
            (g(4 - i0, 4), g(4 - i1, 4)),
            (g(0, 4 - i0), g(0, 4 - i1)),
        ] {
            t.extend(quad(lo(a), lo(b), b, a));
        }
    }
    // The bottom is the same grid at z = 0, facing down.
    let lo = |i, j| {
        let p: DVec3 = g(i, j);
        v(p.x, p.y, 0.0)
    };
    for i in 0..4 {
        for j in 0..4 {
            t.extend(quad(lo(i, j), lo(i, j + 1), lo(i + 1, j + 1), lo(i + 1, j)));
        }
    }
    t
}

/// A prism of `n` facets, radius 1, from z = -1 to 1, caps as fans.
fn prism(n: usize) -> Vec<[DVec3; 3]> {
    let p = |k: usize, z: f64| {
        let a = std::f64::consts::TAU * k as f64 / n as f64;
        DVec3::new(a.cos(), a.sin(), z)
    };
    let mut t = vec![];
    for k in 0..n {
        let k1 = (k + 1) % n;
        t.extend(quad(p(k, -1.0), p(k1, -1.0), p(k1, 1.0), p(k, 1.0)));
        t.push([DVec3::new(0.0, 0.0, 1.0), p(k, 1.0), p(k1, 1.0)]);
        t.push([DVec3::new(0.0, 0.0, -1.0), p(k1, -1.0), p(k, -1.0)]);
    }
    t
}

/// The tree of an STL part, with outlines declared (the edge section).
fn part_tree(tris: &[[DVec3; 3]], crease_deg: f32) -> Vec<u8> {
    let model = load_bytes(MeshFormat::Stl, &stl(tris)).expect("stl");
    assert!(model.closed, "{:?}", model.report);
    let t = build(
        model.polygons,
        true,
        Method::Static,
        DEFAULT_SEED,
        &mut NoProgress,
    );
    let fx = Effects::defaults(true).with(Effects::OUTLINE);
    let opts = SerializeOptions {
        effects: Some(fx.bits()),
        crease_deg,
        ..SerializeOptions::default()
    };
    serialize(&t, &opts).expect("serialize")
}

fn camera(tree: &Tree<'_>, yaw: f64, pitch: f64) -> Camera {
    let r = f64::from(tree.bounding_radius());
    let c = DVec3::from(tree.origin());
    let (y, p) = (yaw.to_radians(), pitch.to_radians());
    let dir = DVec3::new(p.cos() * y.sin(), -p.cos() * y.cos(), p.sin());
    let proj = Projection::Perspective {
        fov_y_deg: 50.0,
        near: 0.01 * r,
        far: 20.0 * r,
    };
    Camera::look_at(c + dir * 3.0 * r, c, DVec3::Z, proj, 1.0).expect("camera")
}

/// Pixel coordinates of a model point.
fn to_pixel(cam: &Camera, p: DVec3) -> (f64, f64) {
    let r = rows(cam);
    let c = r.map(|row| DVec4::from_array(row).dot(p.extend(1.0)));
    let (x, y) = (c[0] / c[3], c[1] / c[3]);
    ((x + 1.0) * 0.5 * W as f64, (1.0 - y) * 0.5 * H as f64)
}

/// The product's picture with outlines on.
fn picture(tree: &Tree<'_>, cam: &Camera) -> Vec<[u8; 3]> {
    let f = frame(tree, cam);
    let mut tr = Box::new(
        TreeRenderer::<DefaultPrecision, VERTS>::new(W as u32, H as u32).expect("renderer"),
    );
    tr.renderer.set_light(Light::new(f.key_light(), 0.25, 0.75));
    let mut buf = vec![0u8; 3 * W * H];
    let mut fb = Rgb888Framebuffer::new(&mut buf, W as u32, H as u32).expect("fb");
    fb.fill_all(BG);
    tr.render::<STACK, _>(tree, &f, &mut fb).expect("walk");
    buf.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()
}

#[test]
fn a_flat_stl_face_shows_its_border_not_its_triangles() {
    let bytes = part_tree(&grid_box(), 30.0);
    let tree = Tree::from_bytes(&bytes).expect("tree");
    assert!(tree.has_edges() && tree.version() == 3);
    let cam = camera(&tree, 10.0, 80.0);
    let pic = picture(&tree, &cam);
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(x, y)| to_pixel(&cam, DVec3::new(x, y, 1.0)));
    let near_border =
        |x: f64, y: f64| (0..4).any(|k| seg_dist(corners[k], corners[(k + 1) % 4], x, y).0 <= 1.5);
    let ink: Vec<(usize, usize)> = (0..W * H)
        .filter(|&i| pic[i] == INK)
        .map(|i| (i % W, i / W))
        .collect();
    let stray: Vec<_> = ink
        .iter()
        .filter(|&&(x, y)| !near_border(x as f64 + 0.5, y as f64 + 0.5))
        .collect();
    assert!(stray.is_empty(), "outline pixels off the border: {stray:?}");
    let perimeter: f64 = (0..4)
        .map(|k| {
            let (a, b) = (corners[k], corners[(k + 1) % 4]);
            (a.0 - b.0).abs().max((a.1 - b.1).abs())
        })
        .sum();
    assert!(
        ink.len() as f64 >= 0.95 * perimeter,
        "border drawn: {} pixels for a perimeter of {perimeter:.0}",
        ink.len()
    );
}

/// Ink pixels in the middle of the prism's side, and whether both
/// silhouettes are drawn on the middle row.
fn prism_side(crease_deg: f32) -> (usize, bool) {
    let bytes = part_tree(&prism(24), crease_deg);
    let tree = Tree::from_bytes(&bytes).expect("tree");
    assert_ne!(tree.as_bytes()[12] as u32 & FLAG_EDGES, 0);
    let cam = camera(&tree, 7.0, 12.0);
    let pic = picture(&tree, &cam);
    let mid = to_pixel(&cam, DVec3::ZERO).1 as usize;
    let row = |y: usize| &pic[y * W..(y + 1) * W];
    let lit = |y: usize| -> Vec<usize> { (0..W).filter(|&x| row(y)[x] != [30, 50, 70]).collect() };
    let band = mid - 8..mid + 8;
    // The rows of the band start and end with ink (within 2 pixels),
    // but for a row or two: a line's pixels are rounded from its
    // endpoints, a fill's sampled at pixel centres, so a thin facet can
    // leave a one-row gap.
    let inked = |side: fn(&[usize]) -> (usize, usize)| {
        band.clone()
            .filter(|&y| {
                let (a, b) = side(&lit(y));
                (a..=b).any(|x| row(y)[x] == INK)
            })
            .count()
    };
    let left = inked(|l| (l[0], l[0] + 1));
    let right = inked(|l| (l[l.len() - 1] - 1, l[l.len() - 1]));
    let silhouettes = left >= 14 && right >= 14;
    let l = lit(mid);
    let (xl, xr) = (l[0], l[l.len() - 1]);
    let q = (xr - xl) / 4;
    let inner = band
        .flat_map(|y| (xl + q..=xr - q).map(move |x| (x, y)))
        .filter(|&(x, y)| row(y)[x] == INK)
        .count();
    (inner, silhouettes)
}

#[test]
fn smooth_facets_show_their_silhouettes_only() {
    let (inner, silhouettes) = prism_side(30.0);
    assert_eq!(inner, 0, "facet edges drawn under a 30° crease");
    assert!(silhouettes, "both silhouettes drawn");
    let (inner, silhouettes) = prism_side(10.0);
    assert!(inner >= 16, "facet edges drawn under a 10° crease: {inner}");
    assert!(silhouettes);
}
