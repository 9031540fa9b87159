use super::eval::max_vertex_error;
use super::*;
use crate::cli::render::{resolve_precision, ALIASES, PRECISIONS, PRECISION_NAMES};
use fpt_nostd::format::VertexFormat;
use fpt_nostd::raster::{FixedPrecision, FloatLibm};
use fpt_nostd::reader::Tree;

const W: u32 = 96;
const H: u32 = 72;

fn house_case() -> Case {
    let s = crate::scenes::house();
    Case::new(&s.name, s.polygons, s.closed).expect("house builds")
}

fn config(name: &str) -> Config {
    *CONFIGS
        .iter()
        .find(|c| c.name == name)
        .expect("configuration")
}

#[test]
fn precision_names_are_the_full_names_then_the_aliases() {
    let mut want: Vec<&str> = PRECISIONS.to_vec();
    want.extend(ALIASES.iter().map(|(a, _)| *a));
    assert_eq!(PRECISION_NAMES.to_vec(), want);
    for (a, full) in ALIASES {
        assert!(PRECISIONS.contains(&full), "{a} -> {full}");
        assert_eq!(resolve_precision(a), full);
    }
    assert_eq!(resolve_precision("f32-libm-subpx-2"), "f32-libm-subpx-2");
}

#[test]
fn every_render_time_row_is_a_render_precision_name() {
    for c in CONFIGS {
        assert!(PRECISIONS.contains(&c.precision), "{}", c.name);
        // `vertex-*` and the raw q16 rows change the tree, not the
        // arithmetic: no `fpt render` name of their own.
        if !c.name.starts_with("vertex-") && !c.raw_q16 {
            assert!(PRECISION_NAMES.contains(&c.name), "{}", c.name);
            assert_eq!(resolve_precision(c.name), c.precision, "{}", c.name);
        }
    }
    let names: Vec<&str> = CONFIGS.iter().map(|c| c.name).collect();
    for n in [
        "vertex-f32",
        "vertex-q16",
        "vertex-q32",
        "f32-libm",
        "f32-micromath",
        "fixed",
        "subpx-0",
        "subpx-8",
        "trig-libm",
        "trig-micromath",
        "int",
        "int-q16",
    ] {
        assert!(names.contains(&n), "{n}");
    }
}

#[test]
fn views_are_fixed_and_spread() {
    let a = views(8);
    assert_eq!(a, views(8));
    assert!(a
        .iter()
        .all(|v| (0.0..360.0).contains(&v.yaw) && v.pitch.abs() <= 60.0));
    let first = a[0];
    assert!(a.iter().any(|v| (v.yaw - first.yaw).abs() > 30.0));
}

#[test]
fn exact_vertices_match_the_stored_ones() {
    let case = house_case();
    let bytes = case.tree_bytes(VertexFormat::F32).expect("f32 tree");
    let tree = Tree::from_bytes(bytes).expect("valid tree");
    let r = f64::from(tree.bounding_radius());
    for id in 0..tree.polygon_count() {
        let p = tree.polygon(id).expect("polygon");
        let ex = &case.exact[id as usize];
        assert_eq!(ex.len(), p.vertex_count());
        for (i, e) in ex.iter().enumerate() {
            let m = p.vertex_model(i);
            let d = (glam::DVec3::from(m) - *e).length();
            assert!(d <= 1e-6 * r, "polygon {id} vertex {i}: {d}");
        }
    }
}

#[test]
fn the_exact_orbit_matches_the_f32_orbit_of_fpt_render() {
    // The f64 orbit and the renderer's f32 orbit (libm) must describe the
    // same camera: a vertex lands at nearly the same place through both.
    let case = house_case();
    let bytes = case.tree_bytes(VertexFormat::F32).expect("f32 tree");
    let tree = Tree::from_bytes(bytes).expect("valid tree");
    for v in views(4) {
        let cam = reference_camera(&orbit_rows(&tree, v, W, H)).expect("camera");
        let spec = camera_spec(&config("trig-libm"), &tree, v, W, H);
        let e = max_vertex_error::<FloatLibm<8>>(&tree, &spec, &case.exact, &cam, W, H)
            .expect("vertex error");
        assert!(e < 0.05, "{v:?}: {e} px");
    }
}

#[test]
fn vertex_error_shrinks_with_sub_pixel_bits_and_detects_a_wrong_camera() {
    let case = house_case();
    let bytes = case.tree_bytes(VertexFormat::F32).expect("f32 tree");
    let tree = Tree::from_bytes(bytes).expect("valid tree");
    let v = views(1)[0];
    let rows = orbit_rows(&tree, v, W, H);
    let cam = reference_camera(&rows).expect("camera");
    let spec = render_spec(rows);
    let e0 =
        max_vertex_error::<FixedPrecision<0>>(&tree, &spec, &case.exact, &cam, W, H).expect("e0");
    let e8 =
        max_vertex_error::<FixedPrecision<8>>(&tree, &spec, &case.exact, &cam, W, H).expect("e8");
    // Snapping to whole pixels moves a vertex by up to √2/2 px.
    assert!(e0 > 0.1 && e0 <= 0.72, "{e0}");
    assert!(e8 < 0.01, "{e8}");
    // Another view's camera must show as a large error.
    let other = orbit_rows(&tree, views(2)[1], W, H);
    let bad =
        max_vertex_error::<FixedPrecision<8>>(&tree, &render_spec(other), &case.exact, &cam, W, H)
            .expect("bad");
    assert!(bad > 2.0, "{bad}");
}

fn render_spec(rows: [[f64; 4]; 4]) -> crate::cli::render::CameraSpec {
    crate::cli::render::CameraSpec::Mvp(rows)
}

#[test]
fn compare_ids_counts_wrong_and_sure_pixels() {
    let reference = crate::reference::RefFrame {
        ids: vec![0, 1, 2, 2],
        near_edge: vec![false, true, false, false],
        tie: vec![false, false, false, true],
        w: 2,
        h: 2,
    };
    let c = compare_ids(&reference, &[0, 2, 1, 0]).expect("same size");
    assert_eq!((c.pixels, c.wrong_face, c.sure, c.wrong_sure), (4, 3, 2, 1));
    assert!((c.wrong_face_frac() - 0.75).abs() < 1e-12);
    assert!((c.wrong_pixel_frac() - 0.5).abs() < 1e-12);
    assert!(compare_ids(&reference, &[0; 3]).is_err());
}

#[test]
fn more_sub_pixel_bits_give_fewer_wrong_pixels_on_the_house() {
    let case = house_case();
    let vs = views(3);
    let cfgs = [config("subpx-0"), config("subpx-8"), config("fixed")];
    let rows = rows_for(std::slice::from_ref(&case), &cfgs, &vs, W, H).expect("rows");
    let (r0, r8) = (&rows[0].counts, &rows[1].counts);
    assert_eq!(r0.pixels, u64::from(W * H) * 3);
    assert!(r0.wrong_face > r8.wrong_face, "{r0:?} vs {r8:?}");
    // A correct renderer with 8 bits is nearly exact where the reference
    // is sure.
    assert!(r8.wrong_pixel_frac() < 0.002, "{r8:?}");
    let line = rows[2].csv();
    assert_eq!(line.split(',').count(), CSV_HEADER.split(',').count());
    assert!(line.starts_with("fixed,"));
}

#[test]
fn the_firmware_measures_exactly_the_csv_rows() {
    let names: Vec<&str> = CONFIGS.iter().map(|c| c.name).collect();
    assert_eq!(names, fpt_frames::accuracy::CONFIGS.to_vec());
    for c in &CONFIGS {
        assert_eq!(fpt_frames::accuracy::vertex_format(c.name), c.vertex);
    }
}

#[test]
fn mcu_means_average_the_views_and_need_every_row() {
    let views = fpt_frames::VIEWS.len() as u64;
    let mut text = String::from("calib whatever\n");
    for (i, c) in CONFIGS.iter().enumerate() {
        for k in 0..views {
            text.push_str(&format!(
                "accuracy config={} view={k} crc=0000abcd instr={}\n",
                c.name,
                1000 * (i as u64 + 1) + 10 * k
            ));
        }
    }
    let m = super::mcu_means(&text).expect("means");
    assert_eq!(m.len(), CONFIGS.len());
    let avg_k = 10 * (views - 1) / 2;
    assert_eq!(m[0], (CONFIGS[0].name.to_string(), 1000 + avg_k));
    assert_eq!(m[12].1, 13_000 + avg_k);
    // A missing row, or a line without its cost, is an error.
    let short: String = text
        .lines()
        .filter(|l| !l.contains("config=subpx-8 "))
        .map(|l| format!("{l}\n"))
        .collect();
    assert!(super::mcu_means(&short).is_err());
    let bare = text.replacen(" instr=1000", "", 1);
    assert!(super::mcu_means(&bare).is_err());
}

/// The integer path's rows (`int` on the f32 tree, `int-q16` drawing the
/// q16 tree as stored) are as accurate as the 16.16 fixed path at the
/// same sub-pixel bits, up to a few pixels of edge rounding, and place
/// every visible vertex within a fraction of a pixel.
#[test]
fn the_integer_rows_are_as_accurate_as_fixed_point() {
    let case = house_case();
    let vs = views(3);
    let cfgs = [config("fixed"), config("int"), config("int-q16")];
    let rows = rows_for(std::slice::from_ref(&case), &cfgs, &vs, W, H).expect("rows");
    let fixed = &rows[0].counts;
    for r in &rows[1..] {
        let c = &r.counts;
        assert_eq!(c.pixels, fixed.pixels);
        assert!(
            c.wrong_face <= fixed.wrong_face + fixed.pixels / 500,
            "{c:?} vs {fixed:?}"
        );
        assert!(c.wrong_pixel_frac() < 0.002, "{c:?}");
        assert!(c.max_vertex_err_px < 0.25, "{c:?}");
    }
}
