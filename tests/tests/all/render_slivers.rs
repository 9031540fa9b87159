//! Slivers (`fpt_nostd::render`'s sliver pass, `Renderer::set_slivers`):
//! the culling walk of a closed tree covers exactly the pixels that the walk
//! without culling covers,
//! whatever the sub-pixel snap does to faces seen almost edge-on, for
//! parallel and perspective views, mirrored matrices included, in every
//! arithmetic configuration. With whole-pixel snapping (0 sub-pixel bits)
//! a culled face wound toward the viewer by the snap is common, so the
//! test also checks that the pass had work to do.

use crate::render_common;

use fpt_nostd::effects::Effects;
use fpt_nostd::raster::{DefaultPrecision, FixedPrecision, FloatLibm, IdBuffer, Precision};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{FaceIds, TreeRenderer};
use glam::DVec3;
use host_sim::geom::bounds;
use host_sim::reference::{Camera, Projection};
use render_common::{build_tree, frame, STACK, VERTS};

const W: usize = 64;
const H: usize = 48;

/// Polygon ids + 1 of one render, culling as the tree says or not at all,
/// and the number of pixels that show a face turned away (a sliver, when
/// culling).
fn ids<P: Precision>(tree: &Tree<'_>, cam: &Camera, cull: bool) -> (Vec<u32>, usize) {
    let mut ids = vec![0u32; W * H];
    let mut sink = IdBuffer::new(&mut ids, W as u32, H as u32).expect("ids");
    let mut r = Box::new(TreeRenderer::<P, VERTS>::new(W as u32, H as u32).expect("renderer"));
    r.ids = FaceIds::Polygon;
    r.renderer.set_slivers(true);
    if !cull {
        let all = Effects::defaults(true).without(Effects::CULLING);
        r.renderer.set_effects(Some(all));
    }
    let f = frame(tree, cam);
    let stats = r.render::<STACK, _>(tree, &f, &mut sink).expect("walk");
    assert!(cull || stats.slivers == 0, "no sliver pass without culling");
    let view = f.view.local(tree);
    let away = |id: u32| {
        id != 0
            && tree
                .polygon(id - 1)
                .is_some_and(|p| !view.is_backward(&p.plane()))
    };
    let shown = ids.iter().filter(|&&id| away(id)).count();
    assert!(!cull || shown == 0 || stats.slivers > 0);
    (ids, shown)
}

/// `n` views from outside the bounding sphere (Fibonacci directions,
/// alternately parallel and perspective), each also mirrored left to
/// right (row x of the matrix negated: faces toward the viewer wind the
/// other way on screen).
fn cameras(polys: &[host_sim::geom::Polygon], n: usize) -> Vec<Camera> {
    let (lo, hi) = bounds(polys);
    let (c, r) = ((lo + hi) * 0.5, (hi - lo).length() * 0.5);
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let mut out = Vec::new();
    for k in 0..n {
        let z = 1.0 - (2.0 * k as f64 + 1.0) / n as f64;
        let s = (1.0 - z * z).sqrt();
        let a = golden * k as f64 + 0.7;
        let dir = DVec3::new(s * a.cos(), s * a.sin(), z);
        let up = if dir.y.abs() < 0.9 {
            DVec3::Y
        } else {
            DVec3::X
        };
        let (projection, dist) = if k % 2 == 0 {
            let p = Projection::Parallel {
                half_height: 1.05 * r,
                near: 0.0,
                far: 6.0 * r,
            };
            (p, 3.0 * r)
        } else {
            let p = Projection::Perspective {
                fov_y_deg: 55.0,
                near: 0.05 * r,
                far: 10.0 * r,
            };
            (p, 2.3 * r)
        };
        let aspect = W as f64 / H as f64;
        let Some(cam) = Camera::look_at(c + dir * dist, c, up, projection, aspect) else {
            continue;
        };
        let mut m = cam.mvp();
        m[..4].iter_mut().for_each(|v| *v = -*v);
        out.push(cam);
        out.extend(Camera::from_mvp(m));
    }
    out
}

/// Every view of `polys`' tree: the culled render covers what the unculled
/// one does. Returns the pixels that show slivers.
fn check<P: Precision>(name: &str, tree: &Tree<'_>, cams: &[Camera]) -> usize {
    let mut slivers = 0;
    for (k, cam) in cams.iter().enumerate() {
        let (culled, n) = ids::<P>(tree, cam, true);
        let (all, _) = ids::<P>(tree, cam, false);
        slivers += n;
        let differ: Vec<(usize, usize)> = (0..W * H)
            .filter(|&i| (culled[i] != 0) != (all[i] != 0))
            .map(|i| (i % W, i / W))
            .collect();
        assert!(
            differ.is_empty(),
            "{name}, {} sub-pixel bits, view {k}: coverage differs at {} pixels, first {:?}",
            P::SUB_BITS,
            differ.len(),
            differ.first()
        );
    }
    slivers
}

#[test]
fn culling_covers_what_drawing_every_face_covers() {
    let scenes = [
        host_sim::scenes::torus(24, 12),
        host_sim::scenes::torus(7, 40),
        host_sim::scenes::house(),
    ];
    let mut coarse = 0;
    // Off by default: the pass draws nothing.
    let built = build_tree(&scenes[0].polygons, true);
    let tree = Tree::from_bytes(&built.bytes).expect("tree");
    for cam in cameras(&scenes[0].polygons, 4) {
        let mut ids = vec![0u32; W * H];
        let mut sink = IdBuffer::new(&mut ids, W as u32, H as u32).expect("ids");
        let mut r =
            Box::new(TreeRenderer::<FixedPrecision<0>, VERTS>::new(W as u32, H as u32).unwrap());
        let stats = r
            .render::<STACK, _>(&tree, &frame(&tree, &cam), &mut sink)
            .expect("walk");
        assert_eq!(stats.slivers, 0);
    }
    for scene in &scenes {
        assert!(scene.closed, "{}", scene.name);
        let built = build_tree(&scene.polygons, true);
        let tree = Tree::from_bytes(&built.bytes).expect("tree");
        let cams = cameras(&scene.polygons, 24);
        coarse += check::<FixedPrecision<0>>(&scene.name, &tree, &cams);
        check::<DefaultPrecision>(&scene.name, &tree, &cams);
        check::<FloatLibm<2>>(&scene.name, &tree, &cams);
    }
    // Whole-pixel snapping turns many grazing faces over: pixels show
    // slivers, which the walk alone would have left as background (were
    // the test's views to miss them all, it would prove little).
    assert!(coarse > 0, "no pixel shows a sliver at 0 sub-pixel bits");
    println!("pixels showing slivers at 0 sub-pixel bits: {coarse}");
}
