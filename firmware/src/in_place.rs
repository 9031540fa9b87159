//! The renderer built in place in a static: its per-polygon scratch
//! buffers are a few KiB, which should be neither built on the stack nor
//! copied through it (on a 16 KiB Cortex-M0 that alone would overflow).

use core::mem::MaybeUninit;

use fpt_nostd::raster::{Camera, Mat4, Precision, Renderer, Scratch};
use fpt_nostd::render::{FaceIds, TreeRenderer};

use crate::fail::fail;

/// Writes a `width × height` renderer into `slot` field by field and
/// returns it.
#[inline(never)]
pub fn renderer<P: Precision, const V: usize>(
    slot: &'static mut MaybeUninit<TreeRenderer<P, V>>,
    width: u32,
    height: u32,
) -> &'static mut TreeRenderer<P, V> {
    let camera = Camera::from_matrix(Mat4::IDENTITY, 1.0);
    let Some(renderer) = Renderer::new(width, height, &camera) else {
        fail(format_args!("renderer size {width}x{height}"))
    };
    let p = slot.as_mut_ptr();
    // SAFETY: `p` points to `slot`, which this function holds uniquely;
    // every field is written (without reading the uninitialised value)
    // before the value is used.
    unsafe {
        core::ptr::addr_of_mut!((*p).renderer).write(renderer);
        core::ptr::addr_of_mut!((*p).scratch).write(Scratch::new());
        core::ptr::addr_of_mut!((*p).ids).write(FaceIds::Source);
        &mut *p
    }
}
