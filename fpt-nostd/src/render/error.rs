//! What can stop a frame: a renderer too small for the tree ([`CapacityError`],
//! checked once before anything is drawn), a display that fails during a
//! banded frame ([`BandError`]) and their sum ([`RenderError`]).

use crate::order::OrderError;
use crate::raster::FramebufferError;
use crate::reader::Tree;

/// A capacity of the renderer, a const generic parameter, that is smaller
/// than the tree needs ([`crate::reader::Tree::capacities`]): the drawing
/// functions check them before they draw, so that no polygon is ever
/// skipped for want of room and no walk is cut short. `fpt info TREE`
/// prints the values to write.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CapacityError {
    /// The walk's stack `N` is smaller than the tree's depth.
    WalkDepth {
        /// What `N` must be at least.
        need: u32,
        /// The `N` given.
        have: usize,
    },
    /// The vertex capacity `V` (of [`TreeRenderer`](super::TreeRenderer) or
    /// [`Scratch`](crate::raster::Scratch)) is
    /// smaller than the tree's polygons need after clipping.
    Vertices {
        /// What `V` must be at least.
        need: u32,
        /// The `V` given.
        have: usize,
    },
}

impl core::fmt::Display for CapacityError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            CapacityError::WalkDepth { need, have } => write!(
                f,
                "walk stack N = {have} is smaller than the tree's depth: N must be at least {need}"
            ),
            CapacityError::Vertices { need, have } => write!(
                f,
                "vertex capacity V = {have} is too small for the tree's polygons: \
                 V must be at least {need} (TreeRenderer<P, {need}>)"
            ),
        }
    }
}

/// Checks that a walk stack of `N` levels and a vertex capacity of `V`
/// hold what `tree` needs ([`crate::reader::Tree::capacities`]). Every
/// drawing function of this module calls it first.
///
/// ```
/// use fpt_nostd::reader::Tree;
/// use fpt_nostd::render::{check_capacities, CapacityError};
///
/// let tree = Tree::from_bytes(include_bytes!("../../../firmware/trees/vise.fpt")).unwrap();
/// let need = tree.capacities();
/// assert!(matches!(
///     check_capacities::<64, 8>(&tree),
///     Err(CapacityError::Vertices { have: 8, .. })
/// ));
/// assert_eq!(check_capacities::<64, 64>(&tree), Ok(()));
/// assert!(need.walk_depth <= 64 && need.vertices <= 64);
/// ```
pub fn check_capacities<const N: usize, const V: usize>(
    tree: &Tree<'_>,
) -> Result<(), CapacityError> {
    let c = tree.capacities();
    if c.walk_depth as usize > N {
        return Err(CapacityError::WalkDepth {
            need: c.walk_depth,
            have: N,
        });
    }
    if c.vertices as usize > V {
        return Err(CapacityError::Vertices {
            need: c.vertices,
            have: V,
        });
    }
    Ok(())
}

/// Why a banded frame with a fallible display
/// ([`TreeRenderer::try_render_banded_in`](super::TreeRenderer::try_render_banded_in)) stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BandError<D> {
    /// The renderer refused the frame (before any band was sent).
    Render(RenderError),
    /// The display driver's error for a band: no later band was drawn.
    Display(D),
}

impl<D: core::fmt::Debug> core::fmt::Display for BandError<D> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            BandError::Render(e) => write!(f, "{e}"),
            BandError::Display(e) => write!(f, "display: {e:?}"),
        }
    }
}

/// Why a frame could not be drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RenderError {
    /// The walk refused the tree (deeper than its stack; after
    /// [`check_capacities`] it cannot).
    Order(OrderError),
    /// The band buffer is too small or the band has a bad size.
    Band(FramebufferError),
    /// A capacity of the renderer is smaller than the tree needs.
    Capacity(CapacityError),
}

impl From<CapacityError> for RenderError {
    fn from(e: CapacityError) -> Self {
        RenderError::Capacity(e)
    }
}

impl From<OrderError> for RenderError {
    fn from(e: OrderError) -> Self {
        RenderError::Order(e)
    }
}

impl core::fmt::Display for RenderError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            RenderError::Order(e) => write!(f, "{e}"),
            RenderError::Band(e) => write!(f, "band buffer: {e}"),
            RenderError::Capacity(e) => write!(f, "{e}"),
        }
    }
}
