//! `fpt bench-memory`: how much working memory a tree's frames need, and
//! what less costs.
//!
//! For each tree, every frame of the standard orbit
//! ([`fpt_frames::orbit`]) is drawn in bands through the same
//! `no_std` code the firmware runs, first with all the memory a frame
//! could want ([`fpt_nostd::render::memory_words`]), which gives the words
//! a frame really uses (vertex cache plus the display list's peak), then
//! with fractions of the largest of those: the picture is checked to be the
//! same, and the number of tree walks the frame took is what less memory
//! costs (each walk repeats the walk and the per-polygon set-up of the
//! polygons it skips; the instructions on a microcontroller are
//! `fpt mcu-bench --memory WORDS`).
//!
//! Output: one line per tree,
//! `memory tree=NAME vertices=N polygons=N needed_max=W needed_median=W
//! walks@100%=.. walks@75%=.. walks@50%=.. walks@25%=.. walks@10%=..`
//! (walks: the median over the frames), then `walks@W=..` for each
//! `--memory W` asked for (the words a given RAM leaves, say).

use std::path::PathBuf;

use clap::Args;
use fpt_frames::orbit::{band_words, frame_crc};
use fpt_nostd::raster::FloatLibm;
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{memory_words, TreeRenderer};

use super::CliResult;
use crate::cli_err;

/// Walk stack of the measurement (deeper trees are refused).
const DEPTH: usize = 4096;
/// Vertex capacity of the measurement.
const VERTS: usize = 256;
/// The fractions of the needed memory measured, in per cent.
const FRACTIONS: [usize; 5] = [100, 75, 50, 25, 10];

/// Arguments of `fpt bench-memory`.
#[derive(Args, Debug)]
pub struct BenchMemoryArgs {
    /// Tree files.
    #[arg(required = true)]
    pub trees: Vec<PathBuf>,
    /// Display size WxH.
    #[arg(long, default_value = "240x240")]
    pub size: String,
    /// Rows per band.
    // Negative values get clap's "invalid value" message, not "unexpected
    // argument" (here and below).
    #[arg(long, default_value_t = 16, allow_negative_numbers = true,
          value_parser = clap::value_parser!(u32).range(1..=16384))]
    pub band: u32,
    /// Frames of the orbit.
    #[arg(long, default_value_t = 20, allow_negative_numbers = true,
          value_parser = clap::value_parser!(u32).range(1..=10_000))]
    pub frames: u32,
    /// Also measure with this many words of memory (repeatable).
    #[arg(long, allow_negative_numbers = true)]
    pub memory: Vec<usize>,
}

/// Runs `fpt bench-memory`.
pub fn run(a: &BenchMemoryArgs) -> CliResult {
    let (w, h) = super::mcu_bench::parse_size(&a.size)?;
    let mut r = Box::new(
        TreeRenderer::<FloatLibm<4>, VERTS>::new(w, h)
            .ok_or_else(|| cli_err!("the renderer cannot draw {w}x{h}"))?,
    );
    let mut buf = vec![0u16; band_words(w, h, a.band)];
    for path in &a.trees {
        let bytes = std::fs::read(path).map_err(|e| cli_err!("reading {}: {e}", path.display()))?;
        let tree = Tree::from_bytes(&bytes).map_err(|e| cli_err!("{}: {e}", path.display()))?;
        if tree.max_depth() as usize > DEPTH {
            return Err(cli_err!("{}: deeper than {DEPTH}", path.display()));
        }
        let name = path
            .file_stem()
            .map_or("tree".into(), |s| s.to_string_lossy().into_owned());
        let n = a.frames;
        let mut all = vec![0u32; memory_words(&tree)];
        let mut crcs = Vec::new();
        let mut used = Vec::new();
        for i in 0..n {
            let (crc, s) =
                frame_crc::<_, DEPTH, VERTS>(&mut r, &tree, (i, n), (&mut buf, &mut all), a.band)
                    .map_err(|e| cli_err!("{name} frame {i}: {e}"))?;
            crcs.push(crc);
            used.push(s.memory_used as usize);
        }
        let max = used.iter().copied().max().unwrap_or(0);
        let mut line = format!(
            "memory tree={name} vertices={} polygons={} needed_max={max} needed_median={}",
            tree.vertex_count(),
            tree.polygon_count(),
            median(&used)
        );
        let sizes = FRACTIONS
            .iter()
            .map(|&pct| (format!("{pct}%"), max * pct / 100));
        let asked = a.memory.iter().map(|&m| (m.to_string(), m));
        for (label, words) in sizes.chain(asked) {
            let mut memory = vec![0u32; words];
            let mut walks = Vec::new();
            for (i, &want) in crcs.iter().enumerate() {
                let (crc, s) = frame_crc::<_, DEPTH, VERTS>(
                    &mut r,
                    &tree,
                    (i as u32, n),
                    (&mut buf, &mut memory),
                    a.band,
                )
                .map_err(|e| cli_err!("{name} frame {i}: {e}"))?;
                if crc != want {
                    return Err(cli_err!(
                        "{name} frame {i}: {label} of the memory drew another picture"
                    ));
                }
                walks.push(s.walks as usize);
            }
            line += &format!(" walks@{label}={}", median(&walks));
        }
        println!("{line}");
    }
    Ok(())
}

/// The median (the upper one of an even count).
fn median(v: &[usize]) -> usize {
    let mut s = v.to_vec();
    s.sort_unstable();
    s.get(s.len() / 2).copied().unwrap_or(0)
}
