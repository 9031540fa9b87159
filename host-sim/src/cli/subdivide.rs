//! `fpt subdivide` and the levels of `fpt bench-build --scaling
//! --subdivide K`: large curved meshes made from real ones by Loop
//! subdivision ([`crate::subdivide`]), to measure the builder at the sizes
//! users bring (issue 15).

use super::{CliError, CliResult};
use crate::cli_err;
use crate::mesh::Model;
use crate::output::write_atomic;
use crate::subdivide::TriMesh;
use clap::Args;
use std::path::{Path, PathBuf};

/// The most triangles a subdivision may make: 4 Mi triangles take about
/// 1 GiB to subdivide and far more than the 120 s to build.
pub const MAX_TRIANGLES: usize = 1 << 22;

/// Arguments of `fpt subdivide`.
#[derive(Args, Debug)]
pub struct SubdivideArgs {
    /// Mesh file: OBJ, OFF, STL (binary or ASCII) or PLY.
    pub mesh: PathBuf,
    /// Output OBJ file (vertices and triangles only).
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// Steps of Loop subdivision, each four times the triangles (faces of
    /// more than three vertices are cut into triangles first).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=8))]
    pub levels: u32,
}

/// Refuses `levels` steps on `mesh` of `triangles` triangles when they
/// would make more than [`MAX_TRIANGLES`], before any work is done.
fn check_size(mesh: &Path, triangles: usize, levels: u32) -> CliResult {
    let after = (triangles as u128) << (2 * levels);
    if after > MAX_TRIANGLES as u128 {
        return Err(cli_err!(
            "{}: {levels} subdivision step{} would make {after} triangles from {triangles} \
             (at most {MAX_TRIANGLES})",
            mesh.display(),
            if levels == 1 { "" } else { "s" }
        ));
    }
    Ok(())
}

/// `name` and `model` at subdivision levels 0 to `levels`: level 0 is
/// the model as loaded (its polygons untouched), level `k` the file's
/// faces ([`file_faces`]) triangulated and after `k` steps, named
/// `NAME Loop k`.
pub fn levels(
    name: &str,
    path: &Path,
    model: Model,
    levels: u32,
) -> Result<Vec<(String, Model)>, CliError> {
    if levels == 0 {
        // `--scaling` without `--subdivide`: nothing to triangulate.
        return Ok(vec![(name.to_string(), model)]);
    }
    let mut tri = TriMesh::from_polygons(&file_faces(path)?.polygons);
    check_size(path, tri.triangles.len(), levels)?;
    let mut out = vec![(name.to_string(), model)];
    for k in 1..=levels {
        tri = tri.loop_subdivide();
        let m = tri
            .to_model()
            .map_err(|e| cli_err!("{} after {k} subdivision steps: {e}", path.display()))?;
        out.push((format!("{name} Loop {k}"), m));
    }
    Ok(out)
}

/// The mesh at `path` with one polygon per face of the file
/// (`ImportOptions::no_merge`): subdivision cuts every polygon into
/// triangles anyway, and a merged coplanar polygon keeps the vertices its
/// edges pass straight through (so that its seams have no T-junction),
/// where ear clipping can cut triangles of no area.
fn file_faces(path: &Path) -> Result<Model, CliError> {
    let whole = crate::mesh::ImportOptions {
        no_merge: true,
        ..Default::default()
    };
    crate::mesh::load_with(path, &whole).map_err(|e| cli_err!("{}: {e}", path.display()))
}

/// The mesh as OBJ text: `v` lines with each coordinate in the shortest
/// form that reads back bit for bit (so `fpt build` of the file sees the
/// very mesh the benchmark builds), then `f` lines.
pub fn obj_text(m: &TriMesh) -> String {
    use std::fmt::Write;
    let mut s = String::with_capacity(40 * m.vertices.len() + 24 * m.triangles.len());
    s.push_str("# Loop subdivision, written by fpt subdivide\n");
    for [x, y, z] in &m.vertices {
        let _ = writeln!(s, "v {x} {y} {z}");
    }
    for [a, b, c] in &m.triangles {
        let _ = writeln!(s, "f {} {} {}", a + 1, b + 1, c + 1);
    }
    s
}

/// `fpt subdivide`.
pub fn run(a: &SubdivideArgs) -> CliResult {
    let mut tri = TriMesh::from_polygons(&file_faces(&a.mesh)?.polygons);
    check_size(&a.mesh, tri.triangles.len(), a.levels)?;
    let before = tri.triangles.len();
    for _ in 0..a.levels {
        tri = tri.loop_subdivide();
    }
    write_atomic(&a.output, obj_text(&tri).as_bytes())
        .map_err(|e| cli_err!("{}: {e}", a.output.display()))?;
    println!(
        "{}: {before} -> {} triangles, {} vertices ({} Loop step{})",
        a.output.display(),
        tri.triangles.len(),
        tri.vertices.len(),
        a.levels,
        if a.levels == 1 { "" } else { "s" }
    );
    Ok(())
}
