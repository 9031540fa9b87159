//! Fuzzes mesh import: the first byte picks the format, the rest is the file.
//! How to run it (and what a run found) is in the crate docs of `fpt_nostd`
//! and of `fpt_nostd::reader` ("Fuzzing"); the seeds are `seeds/mesh_import`.
//! Any panic, hang or huge allocation is a bug; so is an accepted model that
//! breaks the output contract checked below.
#![no_main]

use fpt_build::mesh::{load_bytes, MeshFormat};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&selector, file)) = data.split_first() else {
        return;
    };
    let format = MeshFormat::ALL[usize::from(selector) % MeshFormat::ALL.len()];
    if let Ok(model) = load_bytes(format, file) {
        assert!(!model.polygons.is_empty());
        for p in &model.polygons {
            assert!(p.verts.len() >= 3);
            assert!((p.source as usize) < model.report.faces_read);
            assert!(p.verts.iter().all(|v| v.is_finite()));
        }
        // Part counts agree with closedness (see fpt_build::mesh::ImportReport).
        let r = &model.report;
        assert!(r.inverted_parts <= r.closed_parts);
        assert!(!model.closed || (r.open_parts == 0 && r.boundary_edges == 0));
    }
});
