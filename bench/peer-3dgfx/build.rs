//! Build script of the peer benchmark.
//!
//! 1. Reads `socket.off` (never copied into the repository): the path in
//!    `PEER_MODEL`, else `../../../shared/models/socket.off` relative to this
//!    crate. Fails the build with a clear message when it is absent.
//! 2. Converts it to a compact little-endian binary in `OUT_DIR`
//!    (`model.bin`: vertices, triangles, face normals), decoded into flash
//!    arrays at compile time by `src/model.rs`. The vertices are moved to
//!    the bounding-sphere centre (the centre of the bounding box, radius the
//!    farthest vertex, as our tree format defines it) and scaled so that the
//!    radius is [`WORLD_RADIUS`]: the peer stores depth as the integer part
//!    of `ndc.z · (far − near) + near` in world units, so the world must be
//!    large for its 16-bit z-buffer to have any precision (a uniform scale
//!    of the whole scene does not change the image).
//! 3. Writes `config.rs`: the display size (`PEER_SIZE`, square), the frames
//!    of the orbit (`PEER_FRAMES`, default 100), the triangles recorded per
//!    command buffer (`PEER_CHUNK`, 0 = the whole mesh at once) and the
//!    command-buffer capacity that this needs, found by running the peer's
//!    back-face test over the orbit here; `PEER_DUMP=1` prints frame 0's
//!    pixels (`dump` lines, hex RGB565 words, one row a line).
//! 4. Puts the memory map where cortex-m-rt's `link.x` finds it: the
//!    repository's `memory.x` (STM32F405-class, QEMU `netduinoplus2`) for
//!    `thumbv7em-none-eabihf`, the nRF51822's (QEMU `microbit`: 256 KiB
//!    flash, 16 KiB RAM) for `thumbv6m-none-eabi`; and links with `link.x`.
use std::{env, fmt::Write as _, fs, path::PathBuf};

/// Bounding radius of the model in world units (see the module docs).
const WORLD_RADIUS: f64 = 16384.0;
/// The standard orbit: eye distance in bounding radii, pitch in degrees.
const DISTANCE: f64 = 2.1;
const PITCH_DEGREES: f64 = 25.0;

fn main() {
    let manifest = PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").expect("CARGO_MANIFEST_DIR"));
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("OUT_DIR"));
    for var in [
        "PEER_MODEL",
        "PEER_SIZE",
        "PEER_FRAMES",
        "PEER_CHUNK",
        "PEER_DUMP",
    ] {
        println!("cargo:rerun-if-env-changed={var}");
    }
    println!("cargo:rerun-if-changed=build.rs");

    let model_path = env::var_os("PEER_MODEL")
        .map(PathBuf::from)
        .unwrap_or_else(|| manifest.join("../../../shared/models/socket.off"));
    println!("cargo:rerun-if-changed={}", model_path.display());
    let text = fs::read_to_string(&model_path).unwrap_or_else(|e| {
        panic!(
            "\n\nthe benchmark model is missing: cannot read {} ({e}).\n\
             It is not part of the repository: put socket.off there, or set \
             PEER_MODEL=/path/to/socket.off.\n\n",
            model_path.display()
        )
    });
    let (verts, tris) = parse_off(&text)
        .unwrap_or_else(|e| panic!("{}: not a usable OFF file: {e}", model_path.display()));

    // Bounding sphere: centre of the bounding box, radius to the farthest
    // vertex (the definition of our tree format, so the orbits match).
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for v in &verts {
        for k in 0..3 {
            lo[k] = lo[k].min(v[k]);
            hi[k] = hi[k].max(v[k]);
        }
    }
    let centre: [f64; 3] = std::array::from_fn(|k| 0.5 * (lo[k] + hi[k]));
    let radius = verts
        .iter()
        .map(|v| norm(sub(*v, centre)))
        .fold(0.0, f64::max);
    assert!(radius > 0.0, "degenerate model");
    let scale = WORLD_RADIUS / radius;
    let world: Vec<[f64; 3]> = verts
        .iter()
        .map(|v| sub(*v, centre).map(|c| c * scale))
        .collect();

    // The peer culls a face when (eye − v0) · n < 0, so its normals must
    // point outwards: a closed mesh wound clockwise (negative volume) is
    // turned around.
    let mut tris = tris;
    let volume: f64 = tris
        .iter()
        .map(|t| dot(world[t[0]], cross(world[t[1]], world[t[2]])))
        .sum();
    if volume < 0.0 {
        for t in &mut tris {
            t.swap(1, 2);
        }
    }
    let normals: Vec<[f64; 3]> = tris
        .iter()
        .map(|t| {
            let n = cross(sub(world[t[1]], world[t[0]]), sub(world[t[2]], world[t[0]]));
            let l = norm(n);
            if l > 0.0 {
                n.map(|c| c / l)
            } else {
                [0.0; 3]
            }
        })
        .collect();

    let size = env_usize("PEER_SIZE", 64);
    let frames = env_usize("PEER_FRAMES", 100).max(1);
    let chunk = match env_usize("PEER_CHUNK", 0) {
        0 => tris.len(),
        c => c.min(tris.len()),
    };
    assert!(size >= 8, "PEER_SIZE must be at least 8");

    // Command-buffer capacity: the most front faces of one chunk in any
    // frame of the orbit (the peer records one command per front face it
    // can project, plus one depth clear), with a small margin for faces
    // whose test is decided differently in f32 on the target.
    let d = DISTANCE * WORLD_RADIUS;
    let pitch = PITCH_DEGREES.to_radians();
    let mut most = 0;
    for i in 0..frames {
        let yaw = 2.0 * std::f64::consts::PI * i as f64 / frames as f64;
        let eye = [
            d * pitch.cos() * yaw.sin(),
            d * pitch.sin(),
            d * pitch.cos() * yaw.cos(),
        ];
        for (ts, ns) in tris.chunks(chunk).zip(normals.chunks(chunk)) {
            let front = ts
                .iter()
                .zip(ns)
                .filter(|(t, n)| dot(sub(eye, world[t[0]]), **n) >= 0.0)
                .count();
            most = most.max(front);
        }
    }
    let cmd_cap = (most + 8).min(chunk) + 1;

    // model.bin: u32 vertex count, u32 triangle count, then vertices
    // (f32 × 3), triangles (u16 × 3, padded to 4 bytes), face normals
    // (f32 × 3); little endian.
    assert!(
        verts.len() <= usize::from(u16::MAX),
        "too many vertices for u16 indices"
    );
    let mut bin = Vec::new();
    bin.extend((verts.len() as u32).to_le_bytes());
    bin.extend((tris.len() as u32).to_le_bytes());
    for v in &world {
        for c in v {
            bin.extend((*c as f32).to_le_bytes());
        }
    }
    for t in &tris {
        for &i in t {
            bin.extend((i as u16).to_le_bytes());
        }
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    for n in &normals {
        for c in n {
            bin.extend((*c as f32).to_le_bytes());
        }
    }
    fs::write(out.join("model.bin"), &bin).expect("writing model.bin");

    let target = env::var("TARGET").unwrap_or_default();
    let m0 = target.starts_with("thumbv6m");
    let mut cfg = String::new();
    let _ = writeln!(cfg, "/// Side of the square display, pixels.");
    let _ = writeln!(cfg, "pub const SIZE: usize = {size};");
    let _ = writeln!(cfg, "/// Frames of the orbit.");
    let _ = writeln!(cfg, "pub const FRAMES: usize = {frames};");
    let _ = writeln!(cfg, "/// Triangles recorded and executed at a time.");
    let _ = writeln!(cfg, "pub const CHUNK: usize = {chunk};");
    let _ = writeln!(cfg, "/// Command-buffer capacity (commands).");
    let _ = writeln!(cfg, "pub const CMD_CAP: usize = {cmd_cap};");
    let _ = writeln!(cfg, "/// Vertices and triangles of the model.");
    let _ = writeln!(cfg, "pub const NV: usize = {};", verts.len());
    let _ = writeln!(cfg, "pub const NF: usize = {};", tris.len());
    let _ = writeln!(cfg, "/// Bounding radius in world units.");
    let _ = writeln!(cfg, "pub const RADIUS: f32 = {WORLD_RADIUS:?};");
    let dump = env::var("PEER_DUMP").is_ok_and(|v| v == "1");
    let _ = writeln!(
        cfg,
        "/// Print frame 0's pixels (`PEER_DUMP=1`, for looking at the image)."
    );
    let _ = writeln!(cfg, "pub const DUMP: bool = {dump};");
    let _ = writeln!(cfg, "/// The CPU's name in the output.");
    let _ = writeln!(
        cfg,
        "pub const CPU: &str = {:?};",
        if m0 { "m0" } else { "m4f" }
    );
    fs::write(out.join("config.rs"), cfg).expect("writing config.rs");

    // Memory map and linker script.
    println!("cargo::rustc-check-cfg=cfg(fpt_armv6m)");
    let memory = if m0 {
        println!("cargo::rustc-cfg=fpt_armv6m");
        "/* nRF51822 (BBC micro:bit), QEMU microbit: 256 KiB flash, 16 KiB RAM. */\n\
         MEMORY\n{\n  FLASH : ORIGIN = 0x00000000, LENGTH = 256K\n  \
         RAM   : ORIGIN = 0x20000000, LENGTH = 16K\n}\n"
            .to_string()
    } else {
        let path = manifest.join("../../memory.x");
        println!("cargo:rerun-if-changed={}", path.display());
        fs::read_to_string(&path).expect("reading the repository's memory.x")
    };
    fs::write(out.join("memory.x"), memory).expect("writing memory.x");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rustc-link-arg=-Tlink.x");
}

fn env_usize(name: &str, default: usize) -> usize {
    match env::var(name) {
        Ok(s) if !s.trim().is_empty() => s
            .trim()
            .parse()
            .unwrap_or_else(|_| panic!("{name}={s:?} is not a number")),
        _ => default,
    }
}

/// Vertices and triangles of a mesh.
type Mesh = (Vec<[f64; 3]>, Vec<[usize; 3]>);

/// Vertices and triangles (polygons fanned) of an OFF file.
fn parse_off(text: &str) -> Result<Mesh, String> {
    let mut tokens = text
        .lines()
        .map(|l| l.split('#').next().unwrap_or(""))
        .flat_map(str::split_whitespace);
    if tokens.next() != Some("OFF") {
        return Err("no OFF header".into());
    }
    let mut num = |what: &str| -> Result<f64, String> {
        tokens
            .next()
            .ok_or_else(|| format!("file ends before {what}"))?
            .parse::<f64>()
            .map_err(|e| format!("{what}: {e}"))
    };
    let nv = num("the vertex count")? as usize;
    let nf = num("the face count")? as usize;
    let _edges = num("the edge count")?;
    let mut verts = Vec::with_capacity(nv);
    for _ in 0..nv {
        verts.push([num("a vertex")?, num("a vertex")?, num("a vertex")?]);
    }
    let mut tris = Vec::with_capacity(nf);
    for _ in 0..nf {
        let n = num("a face")? as usize;
        let mut idx = Vec::with_capacity(n);
        for _ in 0..n {
            let i = num("a face index")? as usize;
            if i >= nv {
                return Err(format!("face index {i} out of range"));
            }
            idx.push(i);
        }
        for k in 1..n.saturating_sub(1) {
            tris.push([idx[0], idx[k], idx[k + 1]]);
        }
    }
    Ok((verts, tris))
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}
