//! Host frame time of every configuration of the accuracy study
//! (`fpt bench-accuracy`), with criterion: the house and the vise from the
//! study's first four views at 160×120, one benchmark per configuration
//! (`accuracy/CONFIG`), all frames of a configuration per iteration.
//! Criterion's times divided by that of `accuracy/fixed` are the
//! `host_rel_time` column that `fpt bench-accuracy` measures in-process.
//!
//! Run: `cargo bench -p host-sim --features bench --bench accuracy` (about 1 minute); each
//! benchmark once: `cargo bench -p host-sim --features bench --bench accuracy -- --test`.

use criterion::{criterion_group, criterion_main, Criterion};
use fpt_nostd::reader::Tree;
use host_sim::cli::accuracy::{draw, views, Case, CONFIGS};
use std::hint::black_box;
use std::time::Duration;

const W: u32 = 160;
const H: u32 = 120;

fn bench(c: &mut Criterion) {
    let cases: Vec<Case> = [host_sim::scenes::house(), host_sim::scenes::vise()]
        .into_iter()
        .map(|s| Case::new(&s.name, s.polygons, s.closed).expect("scene builds"))
        .collect();
    let vs = views(4);
    let mut g = c.benchmark_group("accuracy");
    g.measurement_time(Duration::from_secs(3))
        .warm_up_time(Duration::from_millis(500))
        .sample_size(20);
    for config in &CONFIGS {
        let trees: Vec<Tree<'_>> = cases
            .iter()
            .map(|case| {
                Tree::from_bytes(case.tree_bytes(config.vertex).expect("tree")).expect("valid")
            })
            .collect();
        g.bench_function(config.name, |b| {
            b.iter(|| {
                for tree in &trees {
                    for &v in &vs {
                        draw(black_box(tree), config, v, W, H).expect("draws");
                    }
                }
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
