//! Shared helpers for the integration tests in `tests/tests/`.
//!
//! The order checks: build a tree with each method, take the back-to-front
//! classes for many random views, draw them with the reference painter and
//! compare with the exact z-buffer of the same output polygons
//! (`host_sim::reference`). A correct order differs on no pixel that the
//! reference does not mark as unsure.
//!
//! Where the classes come from is one function, [`order_source`]: the
//! product's no_std traversal of the serialized tree ([`NostdWalk`]), or the
//! test-only walk of the in-memory tree that follows the digest's
//! postprocessing pseudo-code ([`TreeWalk`], [`order_classes`]); switching is
//! a one-line change there. `order_scenes` also checks that the two emit the
//! same classes.

pub mod tiling;

use fpt_nostd::order::{Order, View as NostdView};
use fpt_nostd::reader::Tree;
use host_sim::build::{build, NoProgress};
use host_sim::geom::{bounds, centroid, Plane, Polygon};
use host_sim::reference::{painter_ids, zbuffer, Camera, Projection, RefOptions, View};
use host_sim::serialize::{polygon_order, serialize, SerializeOptions};
use host_sim::tree::{Connecting, FpTree, Method};
use std::collections::HashSet;

/// Anything that gives the back-to-front classes of a tree for a view.
pub trait OrderSource {
    /// Classes of polygon ids (into the tree's polygons), farthest first.
    fn classes(&mut self, view: &View) -> Vec<Vec<u32>>;
}

/// The test-only reference walk of the in-memory tree.
pub struct TreeWalk<'a>(pub &'a FpTree);

impl OrderSource for TreeWalk<'_> {
    fn classes(&mut self, view: &View) -> Vec<Vec<u32>> {
        order_classes(self.0, view)
    }
}

/// The order that the checks test: the product's no_std traversal. To
/// test the in-memory reference walk instead, return
/// `Box::new(TreeWalk(tree))`.
pub fn order_source(tree: &FpTree) -> Box<dyn OrderSource + '_> {
    Box::new(NostdWalk::new(tree))
}

/// Stack frames for the no_std walk: deeper trees are refused by it.
const NOSTD_STACK: usize = 2048;

/// The product path: the tree serialized once (the default layout, a plane
/// table, but of exact `f32` entries), read and walked by `fpt_nostd`, its
/// file polygon ids mapped back to tree ids. Exact entries because these
/// checks hold the walk to the exact planes in every view, edge-on ones
/// included: the default compact entries move a plane by about radius /
/// 20,000, which can flip the facing of a polygon seen within that of
/// edge-on (shuttle's view 56); their order is checked on every view that
/// is no such near tie by `format_roundtrip`.
/// When the tree cannot be serialized or walked, every view gets no classes
/// and the class checks report each missing polygon.
pub struct NostdWalk {
    bytes: Vec<u8>,
    /// Tree polygon id of each file polygon id.
    tree_id: Vec<u32>,
}

impl NostdWalk {
    /// Serializes `tree`.
    pub fn new(tree: &FpTree) -> NostdWalk {
        let opts = SerializeOptions {
            compact_planes: false,
            ..SerializeOptions::default()
        };
        let bytes = serialize(tree, &opts).unwrap_or_default();
        let tree_id = polygon_order(tree).unwrap_or_default();
        NostdWalk { bytes, tree_id }
    }
}

impl OrderSource for NostdWalk {
    fn classes(&mut self, view: &View) -> Vec<Vec<u32>> {
        // Reading only validates and borrows; doing it per view keeps this
        // struct free of self-reference.
        let Ok(t) = Tree::from_bytes(&self.bytes) else {
            return Vec::new();
        };
        let v = match *view {
            View::Parallel { dir } => NostdView::parallel(dir.as_vec3().to_array()),
            View::Perspective { eye } => NostdView::perspective_f64(&t, eye.to_array()),
        };
        let Ok(order) = Order::<NOSTD_STACK>::new(&t, v) else {
            return Vec::new();
        };
        let map = |id: u32| self.tree_id.get(id as usize).copied().unwrap_or(u32::MAX);
        order.map(|class| class.map(map).collect()).collect()
    }
}

/// The digest's postprocessing walk on the in-memory tree: classes from
/// farthest to nearest, empty classes left out. For a closed tree only faces
/// turned to the viewer are emitted (back-face culling); for an open one
/// forward faces join the classes marked `*` in the digest.
pub fn order_classes(tree: &FpTree, view: &View) -> Vec<Vec<u32>> {
    let mut out = Vec::new();
    visit(tree, &tree.root, view, &mut out);
    out
}

fn visit(tree: &FpTree, c: &Connecting, view: &View, out: &mut Vec<Vec<u32>>) {
    let faces = |id: u32| {
        tree.polygons
            .get(id as usize)
            .is_some_and(|p| view.faces(&p.plane))
    };
    // Backward faces of `towards`, and forward faces of `away` when open.
    let class = |towards: &[u32], away: &[u32]| -> Vec<u32> {
        let mut v: Vec<u32> = towards.iter().copied().filter(|&i| faces(i)).collect();
        if !tree.closed {
            v.extend(away.iter().copied().filter(|&i| !faces(i)));
        }
        v
    };
    let emit = |v: Vec<u32>, out: &mut Vec<Vec<u32>>| {
        if !v.is_empty() {
            out.push(v);
        }
    };
    for l in &c.levels {
        emit(class(&l.back, &l.front), out);
    }
    if let Some(s) = &c.switch {
        let facing = view.faces(&s.plane);
        let (far, near) = if facing {
            (&s.back, &s.front)
        } else {
            (&s.front, &s.back)
        };
        visit(tree, far, view, out);
        let on: Vec<u32> = if tree.closed {
            s.on.iter().copied().filter(|&i| faces(i)).collect()
        } else {
            s.on.clone()
        };
        emit(on, out);
        visit(tree, near, view, out);
    }
    for l in c.levels.iter().rev() {
        emit(class(&l.front, &l.back), out);
    }
}

/// A small deterministic random generator (SplitMix64).
pub struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next_u64() >> 11) as f64 / (1u64 << 53) as f64)
    }

    /// A uniform index below `n` (`n > 0`).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    /// A uniformly random unit vector.
    pub fn unit(&mut self) -> glam::DVec3 {
        loop {
            let v = glam::DVec3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            let l = v.length();
            if l > 0.1 && l <= 1.0 {
                return v / l;
            }
        }
    }
}

/// `n` random square cameras around `polys`, seeded: in turn parallel views
/// from outside, perspective views from outside, and perspective views from
/// very close to a face or from inside the bounding box (which may be inside
/// a solid: the order must still be right for what can be seen).
pub fn random_cameras(polys: &[Polygon], n: usize, seed: u64) -> Vec<Camera> {
    let mut rng = Rng(seed);
    let (lo, hi) = bounds(polys);
    let c = (lo + hi) * 0.5;
    let r = ((hi - lo).length() * 0.5).max(f64::MIN_POSITIVE);
    let mut cams = Vec::with_capacity(n);
    let mut k = 0usize;
    while cams.len() < n && !polys.is_empty() {
        let up = rng.unit();
        let cam = match k % 5 {
            0 | 1 => {
                let dir = rng.unit();
                let target = c + rng.unit() * (0.2 * r * rng.range(0.0, 1.0));
                let p = Projection::Parallel {
                    half_height: r * rng.range(0.5, 1.1),
                    near: 0.0,
                    far: 6.0 * r,
                };
                Camera::look_at(target - dir * (3.0 * r), target, up, p, 1.0)
            }
            2 | 3 => {
                let eye = c + rng.unit() * (r * rng.range(1.3, 4.0));
                let target = c + rng.unit() * (0.3 * r * rng.range(0.0, 1.0));
                let p = Projection::Perspective {
                    fov_y_deg: rng.range(30.0, 75.0),
                    near: 1e-3 * r,
                    far: 20.0 * r,
                };
                Camera::look_at(eye, target, up, p, 1.0)
            }
            _ => {
                let (eye, target) = if k % 10 == 4 {
                    // Just in front of a face, looking at it or past it.
                    let p = &polys[rng.below(polys.len())];
                    let n = p.plane.normal;
                    // The jitter keeps the eye off the planes through the
                    // centroid (round coordinates are common in scenes).
                    let jitter = rng.unit() * (r * 1e-3);
                    let eye = centroid(&p.verts) + n * (r * rng.range(1e-3, 0.05)) + jitter;
                    (eye, eye - n + rng.unit() * rng.range(0.0, 0.8))
                } else {
                    let t = glam::DVec3::new(
                        rng.range(0.0, 1.0),
                        rng.range(0.0, 1.0),
                        rng.range(0.0, 1.0),
                    );
                    let eye = lo + (hi - lo) * t;
                    (eye, eye + rng.unit())
                };
                let p = Projection::Perspective {
                    fov_y_deg: rng.range(60.0, 110.0),
                    near: 1e-4 * r,
                    far: 20.0 * r,
                };
                Camera::look_at(eye, target, up, p, 1.0)
            }
        };
        if let Some(cam) = cam {
            cams.push(cam);
            k += 1;
        }
    }
    cams
}

/// Facing tests within this (relative) of edge-on may go either way in a
/// walk that rounds differently (the no_std walk tests `f32` planes).
pub const EDGE_ON_REL: f64 = 1e-6;

/// Whether `view` sees `plane` within [`EDGE_ON_REL`] of edge-on.
fn edge_on(view: &View, plane: &Plane, diag: f64) -> bool {
    match *view {
        View::Parallel { dir } => plane.normal.dot(dir).abs() <= EDGE_ON_REL,
        View::Perspective { eye } => plane.distance(eye).abs() <= EDGE_ON_REL * diag,
    }
}

/// Checks the classes of one view: ids in range, every polygon at most
/// once, and every polygon that can be seen present: for a closed tree all
/// faces turned to the viewer and no other (faces seen almost edge-on may go
/// either way), for an open one all.
pub fn check_classes(tree: &FpTree, view: &View, classes: &[Vec<u32>]) -> Result<(), String> {
    let n = tree.polygons.len();
    let (lo, hi) = bounds(&tree.polygons);
    let diag = (hi - lo).length();
    let unclear = |p: &Polygon| tree.closed && edge_on(view, &p.plane, diag);
    let mut seen = HashSet::new();
    for &id in classes.iter().flatten() {
        if id as usize >= n {
            return Err(format!("id {id} out of range ({n} polygons)"));
        }
        if !seen.insert(id) {
            return Err(format!("polygon {id} emitted twice"));
        }
        let p = &tree.polygons[id as usize];
        if tree.closed && !view.faces(&p.plane) && !unclear(p) {
            return Err(format!("polygon {id} faces away but was emitted"));
        }
    }
    for (id, p) in tree.polygons.iter().enumerate() {
        let wanted = !tree.closed || (view.faces(&p.plane) && !unclear(p));
        if wanted && !seen.contains(&(id as u32)) {
            return Err(format!("polygon {id} is missing"));
        }
    }
    Ok(())
}

/// Outline margin, pixels, within which the order checks ignore a pixel.
pub const EDGE_PX: f64 = 0.5;

/// Totals of [`check_order`].
#[derive(Clone, Debug, Default)]
pub struct OrderReport {
    /// Views checked.
    pub views: usize,
    /// Pixels compared.
    pub compared: usize,
    /// Pixels left out as unsure.
    pub unsure: usize,
    /// Compared pixels where the painter differs from the z-buffer.
    pub wrong: usize,
    /// One line per failed view.
    pub failures: Vec<String>,
}

/// Compares, for each camera, the painter picture of the order with the
/// exact z-buffer of the tree's output polygons (`w × h` pixels), and
/// checks the classes themselves.
pub fn check_order(
    tree: &FpTree,
    source: &mut dyn OrderSource,
    cams: &[Camera],
    w: usize,
    h: usize,
) -> OrderReport {
    let mut rep = OrderReport::default();
    let opt = RefOptions {
        cull_backfaces: tree.closed,
        edge_px: EDGE_PX,
        edge_on_rel: EDGE_ON_REL,
        ..RefOptions::default()
    };
    for (k, cam) in cams.iter().enumerate() {
        let view = cam.view();
        let classes = source.classes(&view);
        rep.views += 1;
        if let Err(e) = check_classes(tree, &view, &classes) {
            rep.failures.push(format!("view {k} {view:?}: {e}"));
        }
        let frame = zbuffer(&tree.polygons, cam, w, h, opt);
        let painted = painter_ids(&tree.polygons, &classes, cam, w, h);
        let d = frame.diff(&painted);
        rep.compared += d.compared;
        rep.unsure += d.unsure;
        rep.wrong += d.wrong;
        if let Some((x, y, want, got)) = d.first_wrong {
            rep.failures.push(format!(
                "view {k} {view:?}: {} wrong pixels, first at ({x}, {y}): \
                 z-buffer shows polygon {}, the order shows {}",
                d.wrong,
                want as i64 - 1,
                got as i64 - 1
            ));
        }
    }
    rep
}

/// Builds `polys` with every method and checks the orders for `views`
/// random cameras at `size × size` pixels; prints one line per method and
/// panics listing the failures, if any.
pub fn assert_orders(name: &str, polys: &[Polygon], closed: bool, views: usize, size: usize) {
    let cams = random_cameras(polys, views, 0x0DE5_u64 ^ polys.len() as u64);
    let mut failures = Vec::new();
    for method in [Method::Static, Method::Dynamic, Method::Bsp] {
        let tree = build(polys.to_vec(), closed, method, 7, &mut NoProgress);
        let mut source = order_source(&tree);
        let rep = check_order(&tree, source.as_mut(), &cams, size, size);
        println!(
            "{name} {:7}: {} in, {} out ({} splittings), build {:.0} ms; {} views, \
             {} px compared, {} unsure, {} wrong",
            method.name(),
            polys.len(),
            tree.polygons.len(),
            tree.stats.splittings,
            tree.stats.build_ms,
            rep.views,
            rep.compared,
            rep.unsure,
            rep.wrong
        );
        failures.extend(
            rep.failures
                .iter()
                .take(5)
                .map(|f| format!("{}: {f}", method.name())),
        );
    }
    assert!(
        failures.is_empty(),
        "{name}: wrong orders:\n{}",
        failures.join("\n")
    );
}

/// The third-party models folder, `../shared/models` from the project root.
pub const SHARED_MODELS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/models");

/// The path of `file` in [`SHARED_MODELS`], or `None` (with a printed
/// "skipping: ..." line) when the folder or the file is absent, as in a
/// fresh clone of the project.
pub fn shared_model(file: &str) -> Option<std::path::PathBuf> {
    let dir = std::path::Path::new(SHARED_MODELS);
    if !dir.is_dir() {
        skipping("../shared/models not found");
        return None;
    }
    let p = dir.join(file);
    if !p.is_file() {
        skipping(&format!("../shared/models/{file} not found"));
        return None;
    }
    Some(p)
}

/// Prints `skipping: WHY` where the person running the tests sees it.
///
/// The test harness captures what `println!` and `eprintln!` print and shows
/// it only for failing tests, so a test that skips and passes would say
/// nothing; a write to the process's standard error handle is not captured.
pub fn skipping(why: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr(), "skipping: {why}");
}

/// The model `file` of [`SHARED_MODELS`] loaded, or `None` (with the
/// "skipping: ..." line of [`shared_model`]) when it is absent; a model
/// that is there but does not load fails the test, naming the file.
pub fn shared_mesh(file: &str) -> Option<host_sim::mesh::Model> {
    let path = shared_model(file)?;
    match host_sim::mesh::load(&path) {
        Ok(m) => Some(m),
        Err(e) => panic!("{file}: {e}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use host_sim::tree::{Level, Stats, Switch};

    fn square(z: f64, id: u32) -> Polygon {
        let v = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
            .map(|(x, y)| DVec3::new(x, y, z))
            .to_vec();
        Polygon::new(v, id, [0; 3]).unwrap()
    }

    /// A at z = 0 as switch plane, B at z = 1 as an F bunch in front of it.
    fn tiny_tree(closed: bool) -> FpTree {
        let front = Connecting {
            levels: vec![Level {
                front: vec![1],
                back: vec![],
            }],
            switch: None,
        };
        let switch = Switch {
            plane: square(0.0, 0).plane,
            on: vec![0],
            front,
            back: Connecting::default(),
        };
        FpTree {
            polygons: vec![square(0.0, 0), square(1.0, 1)],
            closed,
            root: Connecting {
                levels: vec![],
                switch: Some(Box::new(switch)),
            },
            method: Method::Static,
            stats: Stats::default(),
        }
    }

    #[test]
    fn walk_follows_the_digest() {
        let above = View::Parallel { dir: -DVec3::Z };
        let below = View::Parallel { dir: DVec3::Z };
        let closed = tiny_tree(true);
        assert_eq!(order_classes(&closed, &above), vec![vec![0], vec![1]]);
        assert_eq!(order_classes(&closed, &below), Vec::<Vec<u32>>::new());
        let open = tiny_tree(false);
        assert_eq!(order_classes(&open, &below), vec![vec![1], vec![0]]);
        // Between the planes, looking up: A faces the eye, B does not.
        let mid = View::Perspective {
            eye: DVec3::new(0.5, 0.5, 0.5),
        };
        assert_eq!(order_classes(&closed, &mid), vec![vec![0]]);
        assert_eq!(order_classes(&open, &mid), vec![vec![0], vec![1]]);
    }

    #[test]
    fn class_checks_catch_duplicates_and_omissions() {
        let t = tiny_tree(true);
        let above = View::Parallel { dir: -DVec3::Z };
        assert!(check_classes(&t, &above, &[vec![0], vec![1]]).is_ok());
        assert!(check_classes(&t, &above, &[vec![0, 1], vec![1]]).is_err());
        assert!(check_classes(&t, &above, &[vec![0]]).is_err());
        assert!(check_classes(&t, &above, &[vec![0], vec![1], vec![2]]).is_err());
        let below = View::Parallel { dir: DVec3::Z };
        assert!(check_classes(&t, &below, &[vec![0]]).is_err());
    }

    #[test]
    fn random_cameras_are_valid_and_varied() {
        let s = host_sim::scenes::cube_grid();
        let cams = random_cameras(&s.polygons, 50, 1);
        assert_eq!(cams.len(), 50);
        let parallel = cams
            .iter()
            .filter(|c| matches!(c.view(), View::Parallel { .. }))
            .count();
        assert!((15..=25).contains(&parallel), "{parallel}");
        // Some eyes are inside the bounding box.
        let (lo, hi) = bounds(&s.polygons);
        let inside = cams
            .iter()
            .filter(|c| match c.view() {
                View::Perspective { eye } => eye.cmpge(lo).all() && eye.cmple(hi).all(),
                View::Parallel { .. } => false,
            })
            .count();
        assert!(inside >= 5, "{inside}");
    }
}
