//! Mesh import: OBJ, OFF, STL (binary and ASCII) and PLY files to planar
//! [`Polygon`]s for the tree builders.
//!
//! Contract:
//! - [`load`] picks the format from the file extension (case-insensitive),
//!   [`load_bytes`] takes it explicitly. Neither panics, hangs or makes
//!   allocations larger than the input justifies, whatever the bytes.
//! - Every parser only turns bytes into a vertex list and a face list (indices
//!   into the vertex list, in file order); [`from_faces`] then does the common
//!   work: weld vertices within `1e-6 × bounding-box diagonal`, drop
//!   degenerate faces, split non-planar faces into planar pieces, merge
//!   coplanar neighbours of one colour into convex polygons (unless
//!   [`ImportOptions::no_merge`]; see `coplanar`) and decide whether the
//!   mesh is a closed volume.
//! - Each output polygon's `source` is the index of its face among the faces
//!   of the input (from 0, in file order), also for pieces of a split face;
//!   a polygon of a merged coplanar region has the region's first face's.
//! - Windings are kept: a face counter-clockwise seen from outside gets an
//!   outward plane normal. The exception: a closed connected part whose
//!   faces all wind inward (negative volume; not a cavity inside another
//!   part) is turned outward, and counted in the [`ImportReport`], unless
//!   [`ImportOptions::keep_orientation`] (see `parts`).
//! - Vertices of every output polygon lie within half the builder's
//!   tolerance of its plane, so the builder sees them as coplanar, and they
//!   are the welded input vertices, never moved: faces that share a vertex
//!   in the file share it bit for bit, so neighbouring faces conform.
//! - Vertex normals in the file (OBJ `vn`, PLY `nx ny nz`) become each
//!   polygon's [`crate::geom::Polygon::normals`] (one per vertex, unit, on
//!   its plane's side; see [`from_faces_normals`]); faces without them get
//!   `None`.

mod coplanar;
mod obj;
mod off;
mod parts;
mod planar;
mod ply;
mod prepare;
mod stl;

#[cfg(test)]
mod fuzz_tests;
#[cfg(test)]
mod shared_models_tests;

use crate::geom::Polygon;
use std::fmt;
use std::path::Path;

pub use obj::write_obj_mtl;
pub use planar::triangulate;
pub use prepare::{
    from_faces, from_faces_normals, from_faces_with, is_closed, is_closed_faces, FaceNormals,
};

/// A mesh ready for the tree builders.
#[derive(Clone, Debug)]
pub struct Model {
    /// Planar polygons, each with the index of the input face it came from.
    pub polygons: Vec<Polygon>,
    /// Whether the welded mesh is a closed volume: every edge is shared by
    /// exactly two faces, used in opposite directions.
    pub closed: bool,
    /// What the import did to the input.
    pub report: ImportReport,
}

/// How many edges of one kind make a mesh open, and the first few of
/// them (in file order) as their two end positions.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct OpenEdgeKind {
    /// Edges of this kind.
    pub count: usize,
    /// The first [`OPEN_EDGE_EXAMPLES`] of them, in the order the faces
    /// use them.
    pub first: [Option<[[f64; 3]; 2]>; OPEN_EDGE_EXAMPLES],
}

/// Examples of each kind of open edge kept in an [`OpenEdges`].
pub const OPEN_EDGE_EXAMPLES: usize = 3;

/// The edges that are not shared by exactly two faces winding opposite
/// ways across them, by kind: what makes a mesh open.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct OpenEdges {
    /// Edges of one face only: the rim of a hole or the border of a sheet.
    pub boundary: OpenEdgeKind,
    /// Edges of three or more faces.
    pub non_manifold: OpenEdgeKind,
    /// Edges of two faces that wind the same way across them (one of the
    /// faces is flipped).
    pub misoriented: OpenEdgeKind,
}

/// Counts of what the import did, for the user and for tests.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ImportReport {
    /// Faces in the input.
    pub faces_read: usize,
    /// Faces dropped because they had fewer than three distinct vertices or
    /// no area (within tolerance).
    pub dropped_degenerate: usize,
    /// Faces that were not planar and were split into planar pieces.
    pub nonplanar_split: usize,
    /// Polygons merged away into their coplanar neighbours (the `coplanar`
    /// module): the kept faces and pieces minus the polygons of the model.
    pub coplanar_merged: usize,
    /// Referenced vertices merged into another vertex by welding.
    pub welded_vertices: usize,
    /// Connected parts whose every edge is shared by two faces in opposite
    /// directions (see the `parts` module).
    pub closed_parts: usize,
    /// The other connected parts.
    pub open_parts: usize,
    /// Closed parts whose faces wound inward (negative volume).
    pub inverted_parts: usize,
    /// Whether the inverted parts were left as they are
    /// ([`ImportOptions::keep_orientation`]); otherwise they were turned
    /// outward.
    pub orientation_kept: bool,
    /// Edges not shared by exactly two faces in opposite directions (the
    /// sum of the counts in `open_edges`).
    pub boundary_edges: usize,
    /// Those edges by kind, with the first few of each.
    pub open_edges: OpenEdges,
    /// OBJ `mtllib` files not found next to the OBJ file.
    pub missing_material_files: usize,
    /// OBJ `usemtl` materials with a diffuse colour in no material file
    /// (counted when every material file was found).
    pub undefined_materials: usize,
}

/// The largest bounding-box diagonal a model may have: trees store sizes
/// in `f32`, and the renderer's default camera stands three bounding radii
/// from the centre, a position that must be an `f32` too (3 × 1e38 is just
/// below `f32::MAX`).
pub const MAX_SIZE: f64 = 2e38;

/// Choices of the import.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ImportOptions {
    /// Leave closed parts that wind inward as they are instead of turning
    /// them outward (they are then drawn inside out: their inner walls).
    pub keep_orientation: bool,
    /// Keep one polygon per file face (or planar piece of one) instead of
    /// merging neighbouring coplanar faces of one colour into convex
    /// polygons (see the `coplanar` module). Merging never changes the
    /// picture of a flat-shaded tree, but a tree declaring `smooth`
    /// interpolates vertex normals across a polygon, so `fpt build` turns
    /// it off there.
    pub no_merge: bool,
}

/// A number as a person writes it: plain when moderate, else `1e30`.
fn short(v: f64) -> String {
    if v == 0.0 || (1e-4..1e6).contains(&v.abs()) {
        // Four decimals say enough about a size in a message.
        format!("{}", (v * 1e4).round() / 1e4)
    } else {
        format!("{v:e}")
    }
}

/// `n` and the noun, with an `s` unless `n` is 1.
fn count(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

impl ImportReport {
    /// One line for the user when degenerate faces were dropped, else `None`.
    pub fn warning_line(&self) -> Option<String> {
        match self.dropped_degenerate {
            0 => None,
            n => Some(format!("warning: dropped {}", count(n, "degenerate face"))),
        }
    }

    /// The line about closed parts that wound inward, else `None`: a file
    /// that is drawn inside out otherwise shows no sign of it.
    pub fn orientation_line(&self) -> Option<String> {
        let (n, of) = (self.inverted_parts, count(self.closed_parts, "closed part"));
        match (n, self.orientation_kept) {
            (0, _) => None,
            (1, false) => Some(format!(
                "warning: 1 of {of} was inside out; flipped it (--keep-orientation keeps it)"
            )),
            (_, false) => Some(format!(
                "warning: {n} of {of} were inside out; flipped them (--keep-orientation keeps them)"
            )),
            (1, true) => Some(format!(
                "warning: 1 of {of} is inside out; kept as it is (--keep-orientation): \
                 its inner walls are drawn"
            )),
            (_, true) => Some(format!(
                "warning: {n} of {of} are inside out; kept as they are (--keep-orientation): \
                 their inner walls are drawn"
            )),
        }
    }

    /// The line about a mesh that mixes closed and open parts, else `None`:
    /// the whole model is then built open (every face drawn from both
    /// sides), which the closed parts do not need and `--closed` would undo
    /// at the price of holes.
    pub fn mixed_line(&self) -> Option<String> {
        (self.closed_parts > 0 && self.open_parts > 0).then(|| {
            format!(
                "warning: the mesh mixes {} with {} ({}); it is built open: \
                 every face is drawn from both sides, none is culled",
                count(self.closed_parts, "closed part"),
                count(self.open_parts, "open part"),
                count(self.boundary_edges, "boundary edge")
            )
        })
    }

    /// The line about OBJ materials whose colours are missing, else
    /// `None`: their faces are drawn in the default grey.
    pub fn material_line(&self) -> Option<String> {
        match (self.missing_material_files, self.undefined_materials) {
            (0, 0) => None,
            (0, n) => Some(format!(
                "warning: {} used by usemtl {} no Kd in the material files; {} faces are grey",
                count(n, "material"),
                if n == 1 { "has" } else { "have" },
                if n == 1 { "its" } else { "their" }
            )),
            (n, _) => Some(format!(
                "warning: {} named by mtllib {} not found next to the OBJ file; \
                 faces without a material colour are grey",
                count(n, "material file"),
                if n == 1 { "was" } else { "were" }
            )),
        }
    }

    /// Why the mesh is open, one line per kind of open edge with its count
    /// and the first few as end positions, e.g. `240 boundary edges (of
    /// one face only), the first at (0, 0, 0)-(1, 0, 0); ...`. Empty when
    /// every edge is closed.
    pub fn open_edge_lines(&self) -> Vec<String> {
        let e = &self.open_edges;
        let point = |p: &[f64; 3]| format!("({}, {}, {})", short(p[0]), short(p[1]), short(p[2]));
        [
            (&e.boundary, "boundary edge", "of one face only"),
            (
                &e.non_manifold,
                "non-manifold edge",
                "of three or more faces",
            ),
            (
                &e.misoriented,
                "inconsistently wound edge",
                "of two faces winding the same way",
            ),
        ]
        .into_iter()
        .filter(|(k, _, _)| k.count > 0)
        .map(|(k, noun, what)| {
            let at: Vec<String> = k
                .first
                .iter()
                .flatten()
                .map(|[a, b]| format!("{}-{}", point(a), point(b)))
                .collect();
            format!(
                "{} ({what}), the first at {}",
                count(k.count, noun),
                at.join("; ")
            )
        })
        .collect()
    }

    /// Every warning line of the import, in the order they are printed.
    pub fn warning_lines(&self) -> Vec<String> {
        [
            self.warning_line(),
            self.orientation_line(),
            self.mixed_line(),
            self.material_line(),
        ]
        .into_iter()
        .flatten()
        .collect()
    }
}

/// The mesh file formats that can be read.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MeshFormat {
    /// Wavefront OBJ.
    Obj,
    /// Object File Format (Geomview OFF).
    Off,
    /// STL, binary or ASCII (told apart by the file size).
    Stl,
    /// Stanford PLY, ASCII or binary of either byte order.
    Ply,
}

impl MeshFormat {
    /// All formats, for tests and fuzzing.
    pub const ALL: [MeshFormat; 4] = [
        MeshFormat::Obj,
        MeshFormat::Off,
        MeshFormat::Stl,
        MeshFormat::Ply,
    ];

    /// The format for a file extension (without dot, any case).
    pub fn from_extension(ext: &str) -> Option<MeshFormat> {
        match ext.to_ascii_lowercase().as_str() {
            "obj" => Some(MeshFormat::Obj),
            "off" => Some(MeshFormat::Off),
            "stl" => Some(MeshFormat::Stl),
            "ply" => Some(MeshFormat::Ply),
            _ => None,
        }
    }

    /// The up axis `fpt build --up auto` records for files of this format:
    /// z for STL (CAD parts are z-up), y for the others.
    pub fn up_axis(self) -> fpt_nostd::format::UpAxis {
        match self {
            MeshFormat::Stl => fpt_nostd::format::UpAxis::Z,
            _ => fpt_nostd::format::UpAxis::Y,
        }
    }

    /// The short name used in messages, e.g. `"OBJ"`.
    pub fn name(self) -> &'static str {
        match self {
            MeshFormat::Obj => "OBJ",
            MeshFormat::Off => "OFF",
            MeshFormat::Stl => "STL",
            MeshFormat::Ply => "PLY",
        }
    }
}

/// Why a mesh could not be imported.
#[derive(Debug)]
pub enum MeshError {
    /// The file could not be read.
    Io(std::io::Error),
    /// The bytes are not a valid file of the format.
    Parse {
        /// Format name, e.g. `"OFF"`.
        format: &'static str,
        /// 1-based line number, when the parser knows it.
        line: Option<usize>,
        /// What is wrong.
        msg: String,
    },
    /// No face with a non-zero area is left.
    Empty,
    /// The file holds no face at all.
    NoFaces {
        /// Format name, e.g. `"OBJ"`.
        format: &'static str,
        /// Lines (or records) the parser skipped because it did not know
        /// them: a text of some other kind is recognisable by this.
        unknown_lines: usize,
    },
    /// The model is larger than [`MAX_SIZE`].
    TooLarge {
        /// Its bounding-box diagonal.
        diag: f64,
    },
    /// One vertex is so far from all the others that, at the scale it
    /// gives the model, the others weld into one point.
    FarVertex {
        /// Its index in the file (from 0).
        index: usize,
        /// Its position.
        position: [f64; 3],
        /// The size (bounding-box diagonal) of all the other used vertices.
        rest: f64,
    },
    /// The file extension names no known format.
    UnknownFormat(String),
    /// A vertex used by a face has a NaN or infinite coordinate.
    NonFinite,
    /// A face refers to a vertex that does not exist.
    BadIndex {
        /// Index of the face (from 0).
        face: usize,
        /// The vertex index it uses (from 0).
        index: u64,
        /// How many vertices there are.
        vertices: usize,
    },
}

impl MeshError {
    /// A parse error of `format` with no line number.
    pub(crate) fn parse(format: &'static str, msg: impl Into<String>) -> MeshError {
        MeshError::Parse {
            format,
            line: None,
            msg: msg.into(),
        }
    }

    /// A parse error of `format` at 1-based `line`.
    pub(crate) fn parse_at(format: &'static str, line: usize, msg: impl Into<String>) -> MeshError {
        MeshError::Parse {
            format,
            line: Some(line),
            msg: msg.into(),
        }
    }
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MeshError::Io(e) => write!(f, "cannot read the mesh file: {e}"),
            MeshError::Parse {
                format,
                line: Some(line),
                msg,
            } => write!(f, "invalid {format} file, line {line}: {msg}"),
            MeshError::Parse {
                format,
                line: None,
                msg,
            } => write!(f, "invalid {format} file: {msg}"),
            MeshError::Empty => write!(f, "the mesh has no face with a non-zero area"),
            MeshError::NoFaces {
                format,
                unknown_lines: 0,
            } => write!(f, "no faces found in the {format} file"),
            MeshError::NoFaces {
                format,
                unknown_lines,
            } => write!(
                f,
                "no faces found in the {format} file ({} not understood)",
                count(*unknown_lines, "line")
            ),
            MeshError::TooLarge { diag } if !diag.is_finite() => write!(
                f,
                "the model is too large: its size overflows f64 (at most {} across); \
                 scale it down",
                short(MAX_SIZE)
            ),
            MeshError::TooLarge { diag } => write!(
                f,
                "the model is too large: its bounding box is {} across, more than {} \
                 (a camera three radii away must fit in f32); scale it down",
                short(*diag),
                short(MAX_SIZE)
            ),
            MeshError::FarVertex {
                index,
                position: [x, y, z],
                rest,
            } => write!(
                f,
                "vertex {index} (from 0) at ({}, {}, {}) is out of range: the other vertices \
                 span only {}, which at the size it gives the model is below the weld \
                 distance, so every face near them would vanish",
                short(*x),
                short(*y),
                short(*z),
                short(*rest)
            ),
            MeshError::UnknownFormat(ext) => write!(
                f,
                "unknown mesh format {ext:?} (expected a .obj, .off, .stl or .ply file)"
            ),
            MeshError::NonFinite => {
                write!(
                    f,
                    "the mesh has a vertex coordinate that is NaN or infinite"
                )
            }
            MeshError::BadIndex {
                face,
                index,
                vertices,
            } => write!(
                f,
                "face {face} uses vertex {index}, but the mesh has only {vertices} vertices"
            ),
        }
    }
}

impl std::error::Error for MeshError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            MeshError::Io(e) => Some(e),
            _ => None,
        }
    }
}

impl From<std::io::Error> for MeshError {
    fn from(e: std::io::Error) -> Self {
        MeshError::Io(e)
    }
}

/// What a parser hands to [`from_faces`]: positions and index faces in file
/// order, with optional per-face colours.
#[derive(Debug, Default)]
pub(crate) struct RawMesh {
    pub vertices: Vec<[f64; 3]>,
    pub faces: Vec<Vec<u32>>,
    pub colors: Option<Vec<[u8; 3]>>,
    /// The vertex normals of the faces (OBJ `vn`, PLY `nx ny nz`): empty
    /// when the file has none, else one entry per face (see
    /// [`FaceNormals`]).
    pub normals: Vec<Option<Vec<[f64; 3]>>>,
    /// An OBJ file's `mtllib` files and faces' `usemtl` materials.
    pub obj_materials: obj::ObjMaterials,
    /// Lines the parser skipped without knowing what they were (only the
    /// formats that skip anything count them).
    pub unknown_lines: usize,
}

impl RawMesh {
    pub(crate) fn into_model(
        self,
        format: MeshFormat,
        options: &ImportOptions,
    ) -> Result<Model, MeshError> {
        if self.faces.is_empty() {
            return Err(MeshError::NoFaces {
                format: format.name(),
                unknown_lines: self.unknown_lines,
            });
        }
        let normals = (!self.normals.is_empty()).then_some(&self.normals[..]);
        from_faces_normals(
            &self.vertices,
            &self.faces,
            self.colors.as_deref(),
            normals,
            options,
        )
    }
}

/// Reads a mesh file; the format comes from the extension (any case).
pub fn load(path: &Path) -> Result<Model, MeshError> {
    load_with(path, &ImportOptions::default())
}

/// [`load`] with options.
pub fn load_with(path: &Path, options: &ImportOptions) -> Result<Model, MeshError> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().into_owned())
        .unwrap_or_default();
    let format = MeshFormat::from_extension(&ext).ok_or(MeshError::UnknownFormat(ext))?;
    let bytes = std::fs::read(path)?;
    let mut raw = parse_raw(format, &bytes)?;
    let mut materials = obj::MaterialReport::default();
    if format == MeshFormat::Obj {
        let dir = path.parent().unwrap_or(Path::new("."));
        materials = obj::apply_materials(&mut raw, dir)?;
    }
    let mut model = raw.into_model(format, options)?;
    model.report.missing_material_files = materials.missing_files;
    model.report.undefined_materials = materials.undefined;
    Ok(model)
}

/// Parses a mesh of `format` from memory.
pub fn load_bytes(format: MeshFormat, bytes: &[u8]) -> Result<Model, MeshError> {
    parse_raw(format, bytes)?.into_model(format, &ImportOptions::default())
}

/// Only the parsing step, without the common pipeline.
pub(crate) fn parse_raw(format: MeshFormat, bytes: &[u8]) -> Result<RawMesh, MeshError> {
    match format {
        MeshFormat::Obj => obj::parse(bytes),
        MeshFormat::Off => off::parse(bytes),
        MeshFormat::Stl => stl::parse(bytes),
        MeshFormat::Ply => ply::parse(bytes),
    }
}

/// At most this many elements are reserved ahead for a count read from a
/// file: the rest grows on demand, so a lying header cannot make us allocate
/// more than the data actually present needs.
pub(crate) fn capped_capacity(count: u64, bytes_left: usize, min_bytes_each: usize) -> usize {
    let fit = bytes_left / min_bytes_each.max(1);
    usize::try_from(count).unwrap_or(usize::MAX).min(fit)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn warning_line_only_when_faces_dropped() {
        let mut r = ImportReport::default();
        assert_eq!(r.warning_line(), None);
        r.dropped_degenerate = 1;
        assert_eq!(
            r.warning_line().as_deref(),
            Some("warning: dropped 1 degenerate face")
        );
        r.dropped_degenerate = 3;
        assert_eq!(
            r.warning_line().as_deref(),
            Some("warning: dropped 3 degenerate faces")
        );
    }

    #[test]
    fn extension_is_case_insensitive() {
        assert_eq!(MeshFormat::from_extension("STL"), Some(MeshFormat::Stl));
        assert_eq!(MeshFormat::from_extension("Obj"), Some(MeshFormat::Obj));
        assert_eq!(MeshFormat::from_extension("off"), Some(MeshFormat::Off));
        assert_eq!(MeshFormat::from_extension("pLy"), Some(MeshFormat::Ply));
        assert_eq!(MeshFormat::from_extension("3ds"), None);
    }

    #[test]
    fn load_rejects_unknown_extension_and_missing_file() {
        let e = load(Path::new("/nonexistent/model.xyz")).unwrap_err();
        assert!(
            matches!(e, MeshError::UnknownFormat(ref x) if x == "xyz"),
            "{e}"
        );
        let e = load(Path::new("/nonexistent/model.OBJ")).unwrap_err();
        assert!(matches!(e, MeshError::Io(_)), "{e}");
        assert!(e.to_string().starts_with("cannot read the mesh file"));
    }

    #[test]
    fn load_reads_a_file_by_extension() {
        let dir = std::env::temp_dir().join(format!("fpt-mesh-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("tri.OFF");
        std::fs::write(&path, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap();
        let m = load(&path).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(m.polygons.len(), 1);
        assert_eq!(m.report.faces_read, 1);
    }

    #[test]
    fn error_messages_are_one_line() {
        let errors = [
            MeshError::parse_at("OFF", 3, "expected 3 coordinates"),
            MeshError::parse("PLY", "no end_header"),
            MeshError::Empty,
            MeshError::UnknownFormat("xyz".into()),
            MeshError::NonFinite,
            MeshError::BadIndex {
                face: 2,
                index: 9,
                vertices: 4,
            },
            MeshError::Io(std::io::Error::other("boom")),
            MeshError::NoFaces {
                format: "OBJ",
                unknown_lines: 3,
            },
            MeshError::FarVertex {
                index: 8,
                position: [0.0, 1e30, -2.5],
                rest: 1.7,
            },
            MeshError::TooLarge { diag: 1e100 },
            MeshError::TooLarge {
                diag: f64::INFINITY,
            },
        ];
        for e in errors {
            let s = e.to_string();
            assert!(!s.is_empty() && !s.contains('\n'), "{s:?}");
        }
        assert_eq!(
            MeshError::parse_at("OFF", 3, "bad").to_string(),
            "invalid OFF file, line 3: bad"
        );
    }

    #[test]
    fn capacity_is_capped_by_bytes() {
        assert_eq!(capped_capacity(1 << 40, 1000, 10), 100);
        assert_eq!(capped_capacity(5, 1000, 10), 5);
        assert_eq!(capped_capacity(u64::MAX, 0, 0), 0);
    }
}
