//! What a firmware that draws trees needs, in one `use`: the tree, the
//! renderer and its errors, the frame and its camera, the band loops, the
//! pixel formats and arithmetic choices. Everything here stays where it is
//! documented (`reader`, `render`, `raster`); this is only the one place
//! to import it from.
//!
//! ```
//! use fpt_nostd::prelude::*;
//!
//! static TREE: &[u8] = include_bytes!("../../firmware/trees/vise.fpt");
//! let tree = Tree::from_bytes(TREE).unwrap();
//! let mut r = TreeRenderer::<FloatLibm<4>, 56>::new(64, 64).unwrap();
//! let orbit = Orbit::framing::<Libm>(tree.bounding_radius(), 0.5, 0.4, 1.0, 1.0);
//! let frame = Frame::relative(&tree, &orbit.camera_up::<Libm>(1.0, Up::Z));
//! r.renderer.set_light(frame.light());
//! let mut pixels = [0u16; 64 * 64];
//! let mut fb = Framebuffer::<Rgb565BeFormat>::new(&mut pixels, 64, 64).unwrap();
//! let stats: RenderStats = r.render::<40, _>(&tree, &frame, &mut fb).unwrap();
//! assert!(stats.drawn > 0);
//! let too_small: Result<_, RenderError> = TreeRenderer::<FloatLibm<4>, 8>::new(64, 64)
//!     .unwrap()
//!     .render::<40, _>(&tree, &frame, &mut fb);
//! assert!(matches!(too_small, Err(RenderError::Capacity(CapacityError::Vertices { need: 56, .. }))));
//! ```

pub use crate::raster::{
    BinaryFormat, Camera, Dither, FixedPrecision, FloatLibm, Framebuffer, Gray8Format,
    IntPrecision, Libm, Light, Mat4, Orbit, PixelFormat, RenderStats, Rgb565BeFormat, Rgb565Format,
    Rgb888Format, Up,
};
pub use crate::reader::Tree;
pub use crate::render::{
    memory_words, BandBuffer, BandBuffers, BandError, BandTransfer, CapacityError, Frame,
    RenderError, TreeRenderer,
};
