//! `fpt polygons`, `fpt order`, `fpt info` and `fpt bench-order`: all of them
//! read the serialized tree through `fpt-nostd` ([`Tree::from_bytes`]) and
//! walk it with its [`Order`]: the host has no traversal of its own.

use std::ops::Range;
use std::path::Path;
use std::time::Instant;

use fpt_nostd::order::{Class, Order, View};
use fpt_nostd::reader::Tree;
use serde_json::json;

use super::{parse_vec3, BenchOrderArgs, CliError, CliResult, InfoArgs, OrderArgs, PolygonsArgs};
use crate::cli_err;

/// Reads a tree file whole.
fn read(path: &Path) -> Result<Vec<u8>, CliError> {
    std::fs::read(path).map_err(|e| cli_err!("cannot read {}: {e}", path.display()))
}

/// Validates the bytes of `path`.
fn parse<'a>(path: &Path, bytes: &'a [u8]) -> Result<Tree<'a>, CliError> {
    Tree::from_bytes(bytes).map_err(|e| cli_err!("{}: {e}", path.display()))
}

/// What a walk hands over: its classes ([`Classes`]: `fpt order`, the
/// counts) or only its ranges of ids ([`Ranges`]: the timed loop, which
/// takes them as a renderer does, through [`Order::next_range`]).
trait Visitor {
    /// Takes the whole walk.
    fn visit<const N: usize>(&mut self, order: Order<'_, N>);
}

/// Calls the closure with each class.
struct Classes<F>(F);

impl<F: FnMut(Class<'_>)> Visitor for Classes<F> {
    fn visit<const N: usize>(&mut self, order: Order<'_, N>) {
        order.for_each(&mut self.0);
    }
}

/// Calls the closure with each range of ids.
struct Ranges<F>(F);

impl<F: FnMut(Range<u32>)> Visitor for Ranges<F> {
    fn visit<const N: usize>(&mut self, mut order: Order<'_, N>) {
        while let Some(r) = order.next_range() {
            (self.0)(r);
        }
    }
}

/// Walks `tree` for `view` with a stack of `N` frames.
///
/// Not inlined: each stack size gets its own function, so a walk only
/// reserves (and probes) the stack frame of the size it uses.
#[inline(never)]
fn walk_with<const N: usize, V: Visitor>(
    tree: &Tree<'_>,
    view: View,
    v: &mut V,
) -> Result<(), CliError> {
    v.visit(Order::<N>::new(tree, view)?);
    Ok(())
}

/// Walks `tree` for `view` with the smallest stack that holds its depth
/// (a small stack is cheaper to set up for every view).
fn walk<V: Visitor>(tree: &Tree<'_>, view: View, mut v: V) -> Result<(), CliError> {
    match tree.max_depth() {
        0..=16 => walk_with::<16, V>(tree, view, &mut v),
        17..=64 => walk_with::<64, V>(tree, view, &mut v),
        65..=256 => walk_with::<256, V>(tree, view, &mut v),
        257..=2048 => walk_with::<2048, V>(tree, view, &mut v),
        _ => walk_with::<16384, V>(tree, view, &mut v),
    }
}

/// The view of `fpt order`: exactly one of `--view-dir` and `--eye`.
fn view_of(a: &OrderArgs, tree: &Tree<'_>) -> Result<View, CliError> {
    match (&a.view_dir, &a.eye) {
        (Some(d), None) => {
            let d = parse_vec3("--view-dir", d)?;
            let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            if !(len > 0.0 && len.is_finite()) {
                return Err(cli_err!("--view-dir must be a non-zero vector"));
            }
            // Normalised in f64 so that tiny or huge vectors survive f32.
            Ok(View::parallel(d.map(|x| (x / len) as f32)))
        }
        (None, Some(e)) => Ok(View::perspective_f64(tree, parse_vec3("--eye", e)?)),
        (None, None) => Err(cli_err!("give a view: --view-dir X,Y,Z or --eye X,Y,Z")),
        (Some(_), Some(_)) => Err(cli_err!("give only one of --view-dir and --eye")),
    }
}

/// `fpt polygons`.
pub fn polygons(a: &PolygonsArgs) -> CliResult {
    let bytes = read(&a.tree)?;
    let tree = parse(&a.tree, &bytes)?;
    let polys: Vec<_> = (0..tree.polygon_count())
        .filter_map(|id| tree.polygon(id))
        .map(|p| {
            let verts: Vec<[f64; 3]> = (0..p.vertex_count()).map(|i| p.vertex_model(i)).collect();
            json!({"id": p.id(), "source": p.source(), "color": p.color(), "vertices": verts})
        })
        .collect();
    let out = json!({"closed": tree.is_closed(), "polygons": polys});
    println!("{}", serde_json::to_string(&out)?);
    Ok(())
}

/// `fpt order`.
pub fn order(a: &OrderArgs) -> CliResult {
    let bytes = read(&a.tree)?;
    let tree = parse(&a.tree, &bytes)?;
    let view = view_of(a, &tree)?;
    let mut classes: Vec<Vec<u32>> = Vec::new();
    walk(
        &tree,
        view,
        Classes(|c: Class<'_>| classes.push(c.collect())),
    )?;
    println!("{}", serde_json::to_string(&json!({ "classes": classes }))?);
    Ok(())
}

/// `fpt info`.
pub fn info(a: &InfoArgs) -> CliResult {
    let bytes = read(&a.tree)?;
    let t = parse(&a.tree, &bytes)?;
    let o = t.origin();
    let e = t.half_extent();
    let format = t.vertex_format();
    let per_polygon = if t.polygon_count() > 0 {
        format!("{:.1}", bytes.len() as f64 / f64::from(t.polygon_count()))
    } else {
        "-".to_string()
    };
    let shift = if format == fpt_nostd::format::VertexFormat::Q32 {
        format!(", shift {}", t.q32_shift())
    } else {
        String::new()
    };
    println!("file:              {}", a.tree.display());
    println!(
        "format:            version {}, {} bytes, crc32 {:08x}",
        t.version(),
        bytes.len(),
        t.crc()
    );
    println!(
        "volume:            {}",
        if t.is_closed() { "closed" } else { "open" }
    );
    println!(
        "effects:           0x{:08x} ({})",
        t.effects(),
        fpt_nostd::effects::Effects::from_bits(t.effects())
    );
    println!(
        "vertex format:     {} ({} bytes a vertex{shift})",
        format.name(),
        format.vertex_len()
    );
    println!("index size:        {} bytes", t.index_size());
    println!("up axis:           {}", t.up_axis().name());
    println!("origin:            {} {} {}", o[0], o[1], o[2]);
    println!("half extent:       {} {} {}", e[0], e[1], e[2]);
    println!("bounding radius:   {}", t.bounding_radius());
    println!("polygons:          {}", t.polygon_count());
    println!("vertices:          {}", t.vertex_count());
    println!("vertex indices:    {}", t.index_count());
    println!("plane runs:        {}", t.run_count());
    println!(
        "bunches:           {} ({} non-empty)",
        t.bunch_count(),
        t.nonempty_bunch_count()
    );
    println!("levels:            {}", t.level_count());
    println!("connecting nodes:  {}", t.node_count());
    println!("switch nodes:      {}", t.switch_count());
    if t.has_plane_table() {
        println!(
            "plane table:       {} planes of {} bytes, shared by the runs and the switches",
            t.plane_table_len(),
            if t.has_compact_planes() {
                fpt_nostd::format::COMPACT_PLANE_LEN
            } else {
                fpt_nostd::format::PLANE_LEN
            }
        );
    } else if t.has_shared_planes() {
        println!(
            "switch planes:     shared with the runs, {} extra plane records",
            t.extra_plane_count()
        );
    }
    println!("max depth:         {}", t.max_depth());
    // Small records are what a firmware built without `large-trees`
    // reads: say which the file has, so a user knows before flashing.
    println!(
        "walk records:      {}",
        if t.has_small_records() {
            "small (16-bit bunch offsets, 8-byte nodes)"
        } else {
            "large (32-bit bunch offsets, 12-byte nodes; the firmware needs fpt-nostd's `large-trees` feature)"
        }
    );
    println!("bytes per polygon: {per_polygon}");
    if t.is_compact() {
        println!(
            "polygon records:   {}, {} bytes each{}, {} colours in the table",
            if t.has_shared_planes() {
                "narrow"
            } else {
                "compact"
            },
            t.record_len(),
            if t.has_run_offsets() {
                " (run offsets)"
            } else {
                ""
            },
            t.colour_count()
        );
    } else {
        println!(
            "polygon records:   {} bytes each",
            fpt_nostd::format::POLYGON_LEN
        );
    }
    // Where the bytes go, per section (padding counted with the section
    // it follows), and per polygon: what to shrink next.
    let n = f64::from(t.polygon_count().max(1));
    let parts: Vec<String> = t
        .section_bytes()
        .iter()
        .filter(|&&(_, b)| b > 0)
        .map(|&(name, b)| format!("{name} {b} ({:.1})", b as f64 / n))
        .collect();
    println!(
        "bytes by section:  {} (per polygon in brackets)",
        parts.join(", ")
    );
    // What a renderer of this tree needs, from the header (checked by the
    // renderer before it draws: a smaller `N` or `V` is a
    // `CapacityError` naming the one to raise).
    let c = t.capacities();
    println!("largest polygon:   {} vertices", c.polygon_vertices);
    println!(
        "renderer needs:    TreeRenderer<P, {v}> (vertex capacity V = {v}), walk stack N = {n} \
         (render::<{n}, _>, render_banded_in::<{n}, _>), working memory {m} words for one walk a frame",
        v = c.vertices,
        n = c.walk_depth,
        m = c.memory_words
    );
    Ok(())
}

/// `n` directions spread evenly over the unit sphere (Fibonacci sphere).
pub fn fibonacci_sphere(n: u32) -> Vec<[f32; 3]> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let y = 1.0 - 2.0 * (f64::from(i) + 0.5) / f64::from(n);
            let r = (1.0 - y * y).max(0.0).sqrt();
            let phi = golden * f64::from(i);
            [(phi.cos() * r) as f32, y as f32, (phi.sin() * r) as f32]
        })
        .collect()
}

/// `fpt bench-order`: times the whole postprocessing of a view, the same
/// way for every tree (feudal or BSP): the timed loop takes every polygon id
/// the walk emits, in ranges as a renderer takes them
/// ([`Order::next_range`]), so the facing tests of the culling are
/// included. Besides the timings, the JSON gives the tree's
/// counts that the cost is made of (see the `Cost` section of
/// `fpt_nostd::order`).
pub fn bench_order(a: &BenchOrderArgs) -> CliResult {
    if a.views == 0 {
        return Err(cli_err!("--views must be at least 1"));
    }
    if !(a.min_seconds.is_finite() && a.min_seconds >= 0.0) {
        return Err(cli_err!("--min-seconds must be a non-negative number"));
    }
    let bytes = read(&a.tree)?;
    let tree = parse(&a.tree, &bytes)?;
    let views: Vec<View> = fibonacci_sphere(a.views)
        .into_iter()
        .map(View::parallel)
        .collect();

    // One untimed pass for the counts (and to warm the caches).
    let (mut emitted, mut classes) = (0u64, 0u64);
    for &v in &views {
        walk(
            &tree,
            v,
            Classes(|c: Class<'_>| {
                classes += 1;
                emitted += c.count() as u64;
            }),
        )?;
    }

    let start = Instant::now();
    let mut passes = 0u64;
    let mut sink = 0u64;
    while passes == 0 || start.elapsed().as_secs_f64() < a.min_seconds {
        for &v in &views {
            walk(
                &tree,
                std::hint::black_box(v),
                Ranges(|r: Range<u32>| {
                    sink = r.fold(sink, |s, id| s.wrapping_add(u64::from(id)));
                }),
            )?;
        }
        passes += 1;
    }
    let elapsed = start.elapsed().as_secs_f64();
    std::hint::black_box(sink);
    let walks = (passes * u64::from(a.views)) as f64;
    let n = f64::from(a.views);
    let out = json!({
        "views": a.views,
        "passes": passes,
        "polygons": tree.polygon_count(),
        "closed": tree.is_closed(),
        "max_depth": tree.max_depth(),
        "nodes": tree.node_count(),
        "switches": tree.switch_count(),
        "levels": tree.level_count(),
        "bunches": tree.bunch_count(),
        "nonempty_bunches": tree.nonempty_bunch_count(),
        "runs": tree.run_count(),
        "ns_per_view": elapsed * 1e9 / walks,
        "emitted_per_view": emitted as f64 / n,
        "classes_per_view": classes as f64 / n,
    });
    println!("{}", serde_json::to_string(&out)?);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::fibonacci_sphere;

    #[test]
    fn fibonacci_directions_are_unit_and_spread() {
        let d = fibonacci_sphere(200);
        assert_eq!(d.len(), 200);
        for v in &d {
            let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            assert!((l - 1.0).abs() < 1e-5);
        }
        // Spread: the mean direction is near zero and both hemispheres are hit.
        let mean: [f32; 3] = [0, 1, 2].map(|a| d.iter().map(|v| v[a]).sum::<f32>() / 200.0);
        assert!(mean.iter().all(|m| m.abs() < 0.05), "{mean:?}");
        for a in 0..3 {
            assert!(d.iter().any(|v| v[a] > 0.9) && d.iter().any(|v| v[a] < -0.9));
        }
    }
}
