//! `fpt frames`: the firmware's frames, drawn on the host by the same no_std
//! code ([`fpt_frames`]), one line per frame:
//! `frame scene=NAME view=K crc=XXXXXXXX`.
//!
//! The trees are built here from the procedural scenes
//! ([`crate::scenes`]) with a fixed method, seed and encoding
//! ([`scene_tree`]), so the same source always gives the same bytes.
//! `fpt frames --export DIR` also writes them, with the lines, as the files
//! the firmware embeds:
//!
//! ```text
//! cargo run --release -p host-sim --bin fpt -- frames --export firmware/trees
//! ```
//!
//! writes `firmware/trees/{vise,house,bench_city}.fpt` and
//! `firmware/trees/frames.txt` (the expected lines, which the firmware
//! checks its own checksums against). `--trees DIR` draws the trees found
//! in `DIR` instead of building them.
//!
//! Every frame is drawn twice, into a full framebuffer and through a band
//! buffer; the two checksums must agree (the firmware's two features rely
//! on it), otherwise the command fails.
//!
//! The accuracy configurations ([`fpt_frames::accuracy`], the
//! firmware's `accuracy` binary) draw the benchmark scene from trees in
//! every vertex encoding, with records pinned by the study
//! ([`tree_options`]) rather than the default file options: `--export`
//! also writes `bench_city.f32.fpt`, `bench_city.q16.fpt`,
//! `bench_city.q32.fpt` and their lines, `accuracy.txt`;
//! `fpt frames --accuracy` prints those lines.
//!
//! `fpt frames --work` prints what each frame is made of instead
//! ([`fpt_frames::work`]: polygons handed out by the walk, their
//! vertices, polygons drawn, spans, pixels painted), the counts that the
//! firmware's instruction counts divide into.

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::Args;
use fpt_frames::accuracy::{
    render_config, vertex_format, AccuracyLine, Full, ACCURACY_SCENE, CONFIGS,
};
use fpt_frames::work::frame_work;
use fpt_frames::{
    render_banded, render_full, FrameLine, FrameRenderer, NoProbe, BAND_WORDS, FRAME_WORDS, HEIGHT,
    SCENES, VIEWS, WIDTH,
};
use fpt_nostd::format::VertexFormat;
use fpt_nostd::reader::Tree;

use super::accuracy::eval::tree_options;
use super::{CliError, CliResult};
use crate::build::{build, NoProgress, DEFAULT_SEED};
use crate::cli_err;
use crate::output::write_atomic;
use crate::scenes::Scene;
use crate::serialize::{serialize, SerializeOptions};
use crate::tree::Method;

/// The file of expected lines next to the trees.
pub const EXPECTED_FILE: &str = "frames.txt";

/// The file of expected accuracy lines next to the trees.
pub const ACCURACY_FILE: &str = "accuracy.txt";

/// The builder the committed trees come from.
pub const METHOD: Method = Method::Static;

/// Arguments of `fpt frames`.
#[derive(Args, Debug)]
pub struct FramesArgs {
    /// Draw the trees DIR/NAME.fpt instead of building them.
    #[arg(long, value_name = "DIR", conflicts_with = "export")]
    pub trees: Option<PathBuf>,
    /// Also write the trees and the expected lines (frames.txt,
    /// accuracy.txt) into DIR, e.g. firmware/trees.
    #[arg(long, value_name = "DIR")]
    pub export: Option<PathBuf>,
    /// Print the accuracy configurations' lines instead of the frames'.
    #[arg(long)]
    pub accuracy: bool,
    /// Print each frame's work instead (`work scene=NAME view=K
    /// polygons=N vertices=N drawn=N spans=N pixels=N`): what the
    /// firmware's instruction counts divide into.
    #[arg(long, conflicts_with = "accuracy")]
    pub work: bool,
}

/// The procedural scene of one of [`SCENES`].
fn scene(name: &str) -> Result<Scene, CliError> {
    match name {
        "vise" => Ok(crate::scenes::vise()),
        "house" => Ok(crate::scenes::house()),
        "bench_city" => Ok(crate::scenes::bench_city()),
        _ => Err(cli_err!("no procedural scene named '{name}'")),
    }
}

/// The tree file of scene `name`: [`METHOD`], [`DEFAULT_SEED`], the
/// default file options ([`SerializeOptions::default`]: the firmware's
/// trees are what `fpt build` writes), the default effects of the scene's
/// kind. Deterministic.
pub fn scene_tree(name: &str) -> Result<Vec<u8>, CliError> {
    let mut trees = scene_tree_with(name, &[SerializeOptions::default()])?;
    Ok(trees.remove(0))
}

/// [`scene_tree`] written with each of `opts`, the tree built once.
fn scene_tree_with(name: &str, opts: &[SerializeOptions]) -> Result<Vec<Vec<u8>>, CliError> {
    let s = scene(name)?;
    let tree = build(s.polygons, s.closed, METHOD, DEFAULT_SEED, &mut NoProgress);
    opts.iter()
        .map(|o| serialize(&tree, o).map_err(|e| cli_err!("{name}: {e}")))
        .collect()
}

/// The file name of the accuracy scene's tree in `f`
/// (`bench_city.f32.fpt`, ...: its own files, in the study's pinned
/// encodings, not the frame set's `bench_city.fpt`).
pub fn accuracy_tree_file(f: VertexFormat) -> String {
    format!("{ACCURACY_SCENE}.{}.fpt", f.name())
}

/// The accuracy scene's trees in every vertex encoding, built now with
/// the study's pinned options ([`tree_options`]).
pub fn accuracy_trees() -> Result<Vec<(VertexFormat, Vec<u8>)>, CliError> {
    let opts = VertexFormat::ALL.map(tree_options);
    let trees = scene_tree_with(ACCURACY_SCENE, &opts)?;
    Ok(VertexFormat::ALL.into_iter().zip(trees).collect())
}

/// Reads the accuracy scene's trees from `dir`.
pub fn read_accuracy_trees(dir: &Path) -> Result<Vec<(VertexFormat, Vec<u8>)>, CliError> {
    VertexFormat::ALL
        .into_iter()
        .map(|f| {
            let path = dir.join(accuracy_tree_file(f));
            let bytes = std::fs::read(&path)
                .map_err(|e| cli_err!("cannot read {}: {e}", path.display()))?;
            Ok((f, bytes))
        })
        .collect()
}

/// The lines of every accuracy configuration and view
/// ([`AccuracyLine`]), configurations in [`CONFIGS`] order.
pub fn accuracy_lines(trees: &[(VertexFormat, Vec<u8>)]) -> Result<Vec<String>, CliError> {
    let mut buf = vec![0u16; FRAME_WORDS];
    let mut lines = Vec::new();
    for config in CONFIGS {
        let want = vertex_format(config);
        let bytes = trees
            .iter()
            .find(|(f, _)| *f == want)
            .map(|t| &t.1)
            .ok_or_else(|| cli_err!("no {} tree for {config}", want.name()))?;
        let tree = Tree::from_bytes(bytes).map_err(|e| cli_err!("{config}: {e}"))?;
        for (k, v) in VIEWS.iter().enumerate() {
            let crc = render_config(config, &tree, v, Full(&mut buf), &NoProbe)
                .map_err(|e| cli_err!("{config} view {k}: {e}"))?;
            let line = AccuracyLine {
                config,
                view: k as u32,
                crc,
            };
            lines.push(line.to_string());
        }
    }
    Ok(lines)
}

/// The tree files of all [`SCENES`], in order.
pub fn scene_trees() -> Result<Vec<(String, Vec<u8>)>, CliError> {
    SCENES
        .iter()
        .map(|&n| Ok((n.to_string(), scene_tree(n)?)))
        .collect()
}

/// Reads `DIR/NAME.fpt` for every scene.
pub fn read_trees(dir: &Path) -> Result<Vec<(String, Vec<u8>)>, CliError> {
    SCENES
        .iter()
        .map(|&n| {
            let path = dir.join(format!("{n}.fpt"));
            let bytes = std::fs::read(&path)
                .map_err(|e| cli_err!("cannot read {}: {e}", path.display()))?;
            Ok((n.to_string(), bytes))
        })
        .collect()
}

/// The lines of every frame of `trees` (name and file bytes), in order:
/// scenes as given, views as in [`VIEWS`]. Fails on a tree that does not
/// validate, or when the banded checksum differs from the full one.
pub fn frame_lines(trees: &[(String, Vec<u8>)]) -> Result<Vec<String>, CliError> {
    let mut r = FrameRenderer::new(WIDTH, HEIGHT).ok_or_else(|| cli_err!("renderer size"))?;
    let mut full = vec![0u16; FRAME_WORDS];
    let mut band = vec![0u16; BAND_WORDS];
    let mut lines = Vec::new();
    for (name, bytes) in trees {
        let tree = Tree::from_bytes(bytes).map_err(|e| cli_err!("{name}: {e}"))?;
        // The full frame without memory, the bands with all they need.
        let mut memory = vec![0u32; fpt_nostd::render::memory_words(&tree)];
        for (k, v) in VIEWS.iter().enumerate() {
            let a = render_full(&mut r, &tree, v, &mut full, &mut [], &NoProbe)
                .map_err(|e| cli_err!("{name} view {k}: {e}"))?;
            let b = render_banded(&mut r, &tree, v, &mut band, &mut memory, &NoProbe)
                .map_err(|e| cli_err!("{name} view {k}: {e}"))?;
            if a.crc != b.crc {
                return Err(cli_err!(
                    "{name} view {k}: banded crc {:08x} differs from full-frame crc {:08x}",
                    b.crc,
                    a.crc
                ));
            }
            let line = FrameLine {
                scene: name,
                view: k as u32,
                crc: a.crc,
            };
            lines.push(line.to_string());
        }
    }
    Ok(lines)
}

/// The work lines of every frame of `trees` ([`fpt_frames::work`]),
/// in the order of [`frame_lines`].
pub fn work_lines(trees: &[(String, Vec<u8>)]) -> Result<Vec<String>, CliError> {
    let mut r = FrameRenderer::new(WIDTH, HEIGHT).ok_or_else(|| cli_err!("renderer size"))?;
    let mut lines = Vec::new();
    for (name, bytes) in trees {
        let tree = Tree::from_bytes(bytes).map_err(|e| cli_err!("{name}: {e}"))?;
        for (k, v) in VIEWS.iter().enumerate() {
            let w = frame_work(&mut r, &tree, v).map_err(|e| cli_err!("{name} view {k}: {e}"))?;
            lines.push(format!("work scene={name} view={k} {w}"));
        }
    }
    Ok(lines)
}

/// The text of [`EXPECTED_FILE`] for `lines`.
pub fn expected_text(lines: &[String]) -> String {
    let mut s = String::from(
        "# Generated: the frames of the trees in this directory, drawn on the host.\n\
         # Regenerate with: cargo run --release -p host-sim --bin fpt -- frames --export firmware/trees\n",
    );
    for l in lines {
        s.push_str(l);
        s.push('\n');
    }
    s
}

/// `fpt frames`.
pub fn run(a: &FramesArgs) -> CliResult {
    let trees = match &a.trees {
        Some(dir) => read_trees(dir)?,
        None => scene_trees()?,
    };
    let frame_lines = frame_lines(&trees)?;
    let acc_trees = match &a.trees {
        Some(dir) => read_accuracy_trees(dir)?,
        None => accuracy_trees()?,
    };
    let acc_lines = accuracy_lines(&acc_trees)?;
    if let Some(dir) = &a.export {
        std::fs::create_dir_all(dir)
            .map_err(|e| cli_err!("cannot create {}: {e}", dir.display()))?;
        let mut files: Vec<(PathBuf, Vec<u8>)> = trees
            .iter()
            .map(|(n, b)| (dir.join(format!("{n}.fpt")), b.clone()))
            .collect();
        files.push((
            dir.join(EXPECTED_FILE),
            expected_text(&frame_lines).into_bytes(),
        ));
        for (f, b) in &acc_trees {
            files.push((dir.join(accuracy_tree_file(*f)), b.clone()));
        }
        files.push((
            dir.join(ACCURACY_FILE),
            expected_text(&acc_lines).into_bytes(),
        ));
        for (path, bytes) in files {
            write_atomic(&path, &bytes)
                .map_err(|e| cli_err!("cannot write {}: {e}", path.display()))?;
        }
    }
    // Written by hand rather than with println!, so that a closed pipe
    // (`fpt frames | head`) ends the output quietly instead of panicking.
    let lines = if a.accuracy {
        acc_lines
    } else if a.work {
        work_lines(&trees)?
    } else {
        frame_lines
    };
    let mut out = std::io::stdout().lock();
    for l in &lines {
        match writeln!(out, "{l}") {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => return Ok(()),
            Err(e) => return Err(cli_err!("cannot write to stdout: {e}")),
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unknown_scene_is_an_error() {
        assert!(scene_tree("nope").is_err());
    }

    #[test]
    fn expected_text_lines_parse_back() {
        let lines = vec!["frame scene=vise view=0 crc=0000abcd".to_string()];
        let text = expected_text(&lines);
        let parsed: Vec<_> = text.lines().filter_map(FrameLine::parse).collect();
        assert_eq!(parsed.len(), 1);
        assert_eq!(parsed[0].crc, 0xabcd);
        assert!(text.lines().all(|l| l.starts_with('#') || l == lines[0]));
    }

    #[test]
    fn a_bad_tree_is_an_error_naming_the_scene() {
        let trees = vec![("vise".to_string(), vec![1u8, 2, 3])];
        match frame_lines(&trees) {
            Err(CliError(m)) => assert!(m.starts_with("vise:"), "{m}"),
            Ok(l) => panic!("{l:?}"),
        }
    }
}
