//! Postprocessing: the classes of polygons of one view, back to front.
//!
//! This is the walk "Postprocessing (per view)" of the algorithm digest,
//! over a validated [`Tree`]:
//!
//! ```text
//! visit(connecting node C):
//!     for j = 1 .. n:  emit { backward faces of B_j } ∪ { forward faces of F_j }*
//!     if C has switch S:
//!         far, near = (G_f, G_b) if S is forward else (G_b, G_f)
//!         visit(far); emit O_S; visit(near)
//!     for j = n .. 1:  emit { backward faces of F_j } ∪ { forward faces of B_j }*
//! ```
//!
//! `*` forward faces only for an open volume; a closed volume culls them, and
//! of its on-plane bunch `O_S` emits only the backward faces (each tested
//! against its own plane); an open volume emits all of `O_S`.
//!
//! A face is **backward** when it faces the viewer ([`LocalView::is_backward`]):
//! for a parallel view looking along `dir`, `n · dir < 0`; for an eye, the
//! eye strictly on the front side, `n · (eye − origin) + d' > 0`. A tie (0)
//! counts as forward, everywhere, and the switch's far/near choice uses the
//! same test on the switch plane. The test is a pure function of the stored
//! plane and the view, so the two passes over a level agree on every face:
//! within one walk each polygon is emitted at most once (exactly once for an
//! open volume).
//!
//! [`Order`] walks without allocating, over an explicit stack of `N` frames
//! (12 bytes each); it refuses a tree deeper than `N`. Classes that end up
//! empty after culling are skipped. The walk is bounded: each node is entered
//! once, and a node's frame only moves forward through its phases.
//!
//! ```ignore
//! use fpt_nostd::order::{Order, View};
//! use fpt_nostd::reader::Tree;
//!
//! static TREE: &[u8] = include_bytes!("model.fpt");
//! let tree = Tree::from_bytes(TREE)?; // validate once, at start-up
//! let view = View::parallel([0.0, 0.0, -1.0]);
//! for class in Order::<32>::new(&tree, view)? {
//!     for polygon in class.polygons(&tree) {
//!         draw(polygon); // any order within a class
//!     }
//! }
//! ```

use core::fmt;

use crate::format::NO_SWITCH;
use crate::reader::{Plane, PlaneTable, PolygonRef, Tree};

/// A view, in the model's coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum View {
    /// Parallel projection looking along `dir` (from the viewer into the
    /// scene); its length does not matter.
    Parallel {
        /// Viewing direction.
        dir: [f32; 3],
    },
    /// Perspective projection from `eye`, in model coordinates.
    Perspective {
        /// Viewpoint.
        eye: [f32; 3],
    },
    /// Perspective projection from `eye` given relative to the tree's origin
    /// (keeps full precision for a model far from the coordinate origin).
    PerspectiveRelative {
        /// Viewpoint minus the origin.
        eye: [f32; 3],
    },
}

impl View {
    /// A parallel view looking along `dir`.
    pub fn parallel(dir: [f32; 3]) -> View {
        View::Parallel { dir }
    }

    /// A perspective view from `eye` in model coordinates.
    pub fn perspective(eye: [f32; 3]) -> View {
        View::Perspective { eye }
    }

    /// A perspective view from `eye` relative to the tree's origin.
    pub fn perspective_relative(eye: [f32; 3]) -> View {
        View::PerspectiveRelative { eye }
    }

    /// A perspective view from `eye` in `f64` model coordinates: the origin
    /// is subtracted in `f64` here, once.
    pub fn perspective_f64(tree: &Tree<'_>, eye: [f64; 3]) -> View {
        let o = tree.origin();
        View::PerspectiveRelative {
            eye: [
                (eye[0] - o[0]) as f32,
                (eye[1] - o[1]) as f32,
                (eye[2] - o[2]) as f32,
            ],
        }
    }

    /// The view relative to `tree`'s origin, ready for plane tests.
    pub fn local(&self, tree: &Tree<'_>) -> LocalView {
        match *self {
            View::Parallel { dir } => LocalView::Parallel(dir),
            View::PerspectiveRelative { eye } => LocalView::Eye(eye),
            View::Perspective { eye } => {
                let o = tree.origin();
                LocalView::Eye([
                    (f64::from(eye[0]) - o[0]) as f32,
                    (f64::from(eye[1]) - o[1]) as f32,
                    (f64::from(eye[2]) - o[2]) as f32,
                ])
            }
        }
    }
}

/// A view relative to a tree's origin: the form the facing test uses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LocalView {
    /// Viewing direction of a parallel projection.
    Parallel([f32; 3]),
    /// Eye position relative to the origin.
    Eye([f32; 3]),
}

impl LocalView {
    /// Whether a face in `plane` faces the viewer (is *backward*); a tie is
    /// forward. Also decides a switch node's far side: its back group is
    /// farther exactly when its plane is backward.
    #[inline]
    pub fn is_backward(&self, plane: &Plane) -> bool {
        match self {
            LocalView::Parallel(dir) => plane.normal_dot(*dir) < 0.0,
            LocalView::Eye(eye) => plane.eval(*eye) > 0.0,
        }
    }
}

/// Why a walk cannot start.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OrderError {
    /// The tree is deeper than the walk's stack.
    StackTooSmall {
        /// The tree's depth.
        depth: u32,
        /// The stack's capacity.
        capacity: usize,
    },
}

impl fmt::Display for OrderError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            OrderError::StackTooSmall { depth, capacity } => {
                write!(
                    f,
                    "tree depth {depth} exceeds the walk's stack of {capacity}"
                )
            }
        }
    }
}

/// Which faces of a bunch a class takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Pick {
    Backward,
    Forward,
    All,
}

/// A run of polygon ids `next..end` of one bunch, filtered by `pick`.
#[derive(Clone, Copy, Debug)]
struct Seg {
    next: u32,
    end: u32,
    pick: Pick,
}

const NO_SEG: Seg = Seg {
    next: 0,
    end: 0,
    pick: Pick::All,
};

/// One class: polygons of equal priority, already culled, as polygon ids.
///
/// Within a class no polygon can hide another, so they may be drawn in any
/// order; the ids come bunch by bunch in the order of the file.
#[derive(Clone, Copy, Debug)]
pub struct Class<'a> {
    planes: PlaneTable<'a>,
    view: LocalView,
    segs: [Seg; 2],
    cur: usize,
}

impl<'a> Class<'a> {
    /// Whether polygon `id` passes `pick`.
    #[inline]
    fn passes(&self, id: u32, pick: Pick) -> bool {
        match pick {
            Pick::All => true,
            Pick::Backward => self.view.is_backward(&self.planes.plane(id)),
            Pick::Forward => !self.view.is_backward(&self.planes.plane(id)),
        }
    }

    /// Moves the cursor to the next polygon that passes, without taking it;
    /// returns false when there is none. Each polygon is tested once.
    fn settle(&mut self) -> bool {
        while let Some(seg) = self.segs.get(self.cur).copied() {
            let mut next = seg.next;
            while next < seg.end {
                if self.passes(next, seg.pick) {
                    if let Some(s) = self.segs.get_mut(self.cur) {
                        s.next = next;
                    }
                    return true;
                }
                next += 1;
            }
            self.cur += 1;
        }
        false
    }

    /// The polygons of this class.
    pub fn polygons(self, tree: &Tree<'a>) -> impl Iterator<Item = PolygonRef<'a>> + 'a {
        let tree = *tree;
        self.filter_map(move |id| tree.polygon(id))
    }
}

impl Iterator for Class<'_> {
    type Item = u32;

    fn next(&mut self) -> Option<u32> {
        if !self.settle() {
            return None;
        }
        // `settle` left the cursor on a passing polygon.
        let seg = self.segs.get_mut(self.cur)?;
        let id = seg.next;
        seg.next += 1;
        Some(id)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left: u32 = self
            .segs
            .iter()
            .skip(self.cur)
            .map(|s| s.end.saturating_sub(s.next))
            .sum();
        (0, Some(left as usize))
    }
}

// Frame phases of a connecting node; FAR_IS_BACK remembers the far side
// between pushing it and pushing the near one.
const DOWN: u8 = 0;
const FAR: u8 = 1;
const ON: u8 = 2;
const NEAR: u8 = 3;
const UP: u8 = 4;
const FAR_IS_BACK: u8 = 0x80;

/// One connecting node being visited.
#[derive(Clone, Copy, Debug, Default)]
struct Frame {
    node: u32,
    /// Next level (DOWN: counting up; UP: counting down).
    j: u32,
    phase: u8,
}

/// The walk of one view: an iterator over the classes, back to front.
#[derive(Clone, Debug)]
pub struct Order<'a, const N: usize> {
    tree: Tree<'a>,
    view: LocalView,
    closed: bool,
    stack: [Frame; N],
    len: usize,
}

impl<'a, const N: usize> Order<'a, N> {
    /// Starts the walk of `tree` for `view`; fails if the tree is deeper
    /// than `N`.
    pub fn new(tree: &Tree<'a>, view: View) -> Result<Self, OrderError> {
        let depth = tree.max_depth();
        if depth as usize > N {
            return Err(OrderError::StackTooSmall { depth, capacity: N });
        }
        let mut o = Order {
            tree: *tree,
            view: view.local(tree),
            closed: tree.is_closed(),
            stack: [Frame::default(); N],
            len: 0,
        };
        o.push(0);
        Ok(o)
    }

    /// The view relative to the origin, as the walk tests it.
    pub fn view(&self) -> LocalView {
        self.view
    }

    fn push(&mut self, node: u32) {
        // Validation bounds the depth by N, so there is always room; were
        // there none, the subtree would be skipped rather than panic.
        if let Some(slot) = self.stack.get_mut(self.len) {
            *slot = Frame {
                node,
                j: 0,
                phase: DOWN,
            };
            self.len += 1;
        }
    }

    fn set_top(&mut self, f: Frame) {
        if let Some(slot) = self.len.checked_sub(1).and_then(|t| self.stack.get_mut(t)) {
            *slot = f;
        }
    }

    /// A class of two bunch segments, or `None` if nothing passes.
    fn class(&self, segs: [(u32, Option<Pick>); 2]) -> Option<Class<'a>> {
        let mut c = Class {
            planes: self.tree.planes(),
            view: self.view,
            segs: [NO_SEG; 2],
            cur: 0,
        };
        for (slot, (bunch, pick)) in c.segs.iter_mut().zip(segs) {
            if let Some(pick) = pick {
                let (next, end) = self.tree.bunch(bunch);
                *slot = Seg { next, end, pick };
            }
        }
        c.settle().then_some(c)
    }

    /// Faces of the far side of a level: culled away for a closed volume.
    fn forward_pick(&self) -> Option<Pick> {
        (!self.closed).then_some(Pick::Forward)
    }
}

impl<'a, const N: usize> Iterator for Order<'a, N> {
    type Item = Class<'a>;

    fn next(&mut self) -> Option<Class<'a>> {
        loop {
            let mut f = *self.stack.get(self.len.checked_sub(1)?)?;
            let n = self.tree.node(f.node);
            // F_j and B_j of level j (0-based) are bunches fb + 2j and fb + 2j + 1.
            let level = |j: u32| {
                let f = n.first_bunch.wrapping_add(j.wrapping_mul(2));
                (f, f.wrapping_add(1))
            };
            let flag = f.phase & FAR_IS_BACK;
            let k = n.switch;
            let (front, back) = (
                k.wrapping_mul(2).wrapping_add(1),
                k.wrapping_mul(2).wrapping_add(2),
            );
            match f.phase & !FAR_IS_BACK {
                DOWN if f.j < n.level_count => {
                    let (fj, bj) = level(f.j);
                    f.j += 1;
                    self.set_top(f);
                    let c = self.class([(bj, Some(Pick::Backward)), (fj, self.forward_pick())]);
                    if c.is_some() {
                        return c;
                    }
                }
                DOWN if k != NO_SWITCH => {
                    f.phase = FAR;
                    self.set_top(f);
                }
                DOWN => {
                    f.phase = UP;
                    f.j = n.level_count;
                    self.set_top(f);
                }
                FAR => {
                    // The back group is farther when the eye is in front.
                    let back_is_far = self.view.is_backward(&self.tree.switch_plane(k));
                    f.phase = ON | if back_is_far { FAR_IS_BACK } else { 0 };
                    self.set_top(f);
                    self.push(if back_is_far { back } else { front });
                }
                ON => {
                    f.phase = NEAR | flag;
                    self.set_top(f);
                    let on = n.first_bunch.wrapping_add(n.level_count.wrapping_mul(2));
                    let pick = if self.closed {
                        Pick::Backward
                    } else {
                        Pick::All
                    };
                    let c = self.class([(on, Some(pick)), (0, None)]);
                    if c.is_some() {
                        return c;
                    }
                }
                NEAR => {
                    f.phase = UP;
                    f.j = n.level_count;
                    self.set_top(f);
                    self.push(if flag != 0 { front } else { back });
                }
                UP if f.j > 0 => {
                    f.j -= 1;
                    self.set_top(f);
                    let (fj, bj) = level(f.j);
                    let c = self.class([(fj, Some(Pick::Backward)), (bj, self.forward_pick())]);
                    if c.is_some() {
                        return c;
                    }
                }
                _ => self.len -= 1,
            }
        }
    }
}

/// Calls `f` with every visible polygon of `tree` for `view`, back to front,
/// walking with a stack of `N` frames (see [`Order`]).
pub fn for_each_polygon_back_to_front<'a, const N: usize>(
    tree: &Tree<'a>,
    view: View,
    mut f: impl FnMut(PolygonRef<'a>),
) -> Result<(), OrderError> {
    for class in Order::<N>::new(tree, view)? {
        for p in class.polygons(tree) {
            f(p);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests;
