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
//! (20 bytes each); it refuses a tree deeper than `N`. Classes that end up
//! empty after culling are skipped. The walk is bounded: each node is entered
//! at most once, and a node's frame only moves forward through its phases.
//!
//! # Cost
//!
//! The work per view is what the tree's shape makes it, with little on top:
//!
//! - per **run** of polygons sharing a plane (see [`crate::format`]): one
//!   facing test (3 multiplications, 3 additions, read straight from the
//!   contiguous run section), and a passing run is handed out whole as a
//!   range of ids ([`Class::next_range`]), so a flat face split into many
//!   polygons costs one test; the walk's own hand-out
//!   ([`Order::next_range`]) joins the runs that pass in a row into one
//!   range;
//! - per **bunch** visited: two offsets read; an empty one (common: most
//!   levels have only `F_j` or only `B_j`, and a closed volume looks at one
//!   of the two per pass) costs no class;
//! - per **connecting node**: its 12-byte record copied into a frame, one
//!   facing test for its switch; empty leaves (no levels, no switch: the
//!   children of a BSP tree's leaf switches) are never entered, whether a
//!   child is pushed is decided without a branch, and a node without levels
//!   (every node of a BSP tree) hands its frame over to its near group, as a
//!   tail call would, instead of being resumed once more only to be popped.
//!
//! - per **class**: nothing copied out when the caller takes ranges
//!   ([`Order::next_range`]): the walk keeps the class's hand-out in its own
//!   state (a [`Class`] is that state plus the run section, for callers that
//!   need class boundaries).
//!
//! What remains per node is mostly the branches on the tree's shape and on
//! the facing tests, which no predictor can learn: they, more than the
//! arithmetic, set the time of a walk.
//!
//! So a feudal tree is cheaper to walk than a BSP tree of the same model in
//! proportion to how much fewer nodes and classes it has; every read is one
//! range check on a section sliced once at validation (see
//! [`crate::reader`]).
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
//! // A renderer needs no class boundaries: ranges of ids straight from the
//! // walk, in the same order, with no class built or copied.
//! let mut order = Order::<32>::new(&tree, view)?;
//! while let Some(ids) = order.next_range() {
//!     ids.filter_map(|id| tree.polygon(id)).for_each(draw);
//! }
//! ```

use core::cell::Cell;
use core::fmt;

/// Evaluates `$body` with `$R` the [`class::RunRecord`] layout of the
/// runs `$runs`: the one test of the layout that each entry into the walk
/// makes, each layout's walk then compiled on its own (without the
/// `plane-table` and `compact-planes` features the tests are constants and
/// only the narrow walk is compiled).
macro_rules! by_layout {
    ($runs:expr, $R:ident => $body:expr) => {
        if $runs.is_compact() {
            type $R = $crate::order::class::CompactRun;
            $body
        } else if $runs.is_table() {
            type $R = $crate::order::class::TableRun;
            $body
        } else {
            type $R = $crate::order::class::InlineRun;
            $body
        }
    };
}

mod class;
mod facing;

pub(crate) use facing::MEMO;

use crate::format::NO_SWITCH;
use crate::reader::{Plane, PolygonRef, Tree, WalkData};
pub use class::Class;
use class::{Cursor, Pick, RunRecord, Seg};
use facing::Facing;

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

// Frame phases of a connecting node. DOWN walks the levels down (then tests
// the switch and pushes the far group), ON emits O_k and pushes the near
// group, UP walks the levels back up; FAR_IS_BACK remembers the far side
// between pushing it and pushing the near one.
const DOWN: u8 = 0;
const ON: u8 = 1;
const UP: u8 = 2;
const FAR_IS_BACK: u8 = 0x80;

/// One connecting node being visited, its record copied in when pushed.
#[derive(Clone, Copy, Debug, Default)]
#[repr(C)]
struct Frame {
    first_bunch: u32,
    levels: u32,
    switch: u32,
    /// Next level (DOWN: counting up; UP: counting down).
    j: u32,
    phase: u8,
}

impl Frame {
    /// All zero: a constant, so that a fresh stack is one block clear.
    const EMPTY: Frame = Frame {
        first_bunch: 0,
        levels: 0,
        switch: 0,
        j: 0,
        phase: 0,
    };
}

/// Words of a memo that holds every plane of `tree` for
/// [`Order::with_memo`]: two bits a plane run and a switch record, or with
/// a plane table ([`crate::format::FLAG_PLANES`]) a table entry.
pub fn memo_words(tree: &Tree<'_>) -> usize {
    let planes = if tree.has_plane_table() {
        tree.plane_table_len() as usize
    } else {
        tree.run_count() as usize + tree.switch_count() as usize
    };
    planes.div_ceil(16)
}

/// The walk of one view: an iterator over the classes, back to front.
#[derive(Clone, Debug)]
pub struct Order<'a, const N: usize> {
    w: WalkData<'a>,
    face: Facing<'a>,
    /// The memo's plane number of switch record 0 (the run count).
    switch_base: u32,
    view: LocalView,
    closed: bool,
    /// Runs still to hand out as the away-facing prelude (0 when none).
    prelude_runs: u32,
    /// Its value at the start of the walk.
    prelude: u32,
    /// The current class's hand-out (see [`Order::next_range`]).
    at: Cursor,
    len: usize,
    stack: [Frame; N],
    /// The root is still to be entered (by the first [`Order::advance`]).
    root_pending: bool,
}

impl<'a, const N: usize> Order<'a, N> {
    /// Starts the walk of `tree` for `view`; fails if the tree is deeper
    /// than `N`.
    pub fn new(tree: &Tree<'a>, view: View) -> Result<Self, OrderError> {
        Self::with_culling(tree, view, tree.is_closed())
    }

    /// The walk with back-face culling chosen by the caller (the `culling`
    /// effect, [`crate::effects`]) instead of by the tree's kind:
    ///
    /// * culling an **open** tree walks it with the closed-volume rule,
    ///   which is its open-volume order with the faces turned away left
    ///   out (the starred terms of the module docs);
    /// * not culling a **closed** tree first emits one class with all the
    ///   faces turned away from the viewer, then the usual walk. A closed
    ///   tree's order says nothing about its back faces, but none is needed:
    ///   seen from outside every volume, a ray meets a closed volume's front
    ///   face before its back face, so every back face lies behind some
    ///   front face and drawing them all first leaves the same picture (it
    ///   only costs time; what it shows when the near plane cuts a volume
    ///   open is in no particular order).
    pub fn with_culling(tree: &Tree<'a>, view: View, cull: bool) -> Result<Self, OrderError> {
        Self::with_memo(tree, view, cull, &[])
    }

    /// [`Order::with_culling`] remembering each plane's facing test in
    /// `memo` (two bits a plane, [`memo_words`] words for the whole tree;
    /// a shorter memo holds the first planes only). The memo belongs to
    /// one view: the caller zeroes it when the view changes, and walks of
    /// the same view (the several walks of a banded frame with little
    /// memory) then test each plane once. The order is the same with or
    /// without it. On targets with an FPU the memo is not consulted (a
    /// facing test there costs what its look-up does; this crate's own
    /// tests consult it everywhere).
    ///
    /// ```
    /// # use fpt_nostd::order::{memo_words, Order, View};
    /// # use fpt_nostd::reader::Tree;
    /// # fn walk(tree: &Tree<'_>, view: View) -> Result<(), fpt_nostd::order::OrderError> {
    /// let mut words = [0u32; 64]; // zeroed: nothing known yet
    /// // A memo too short for the tree remembers its first planes only.
    /// let n = memo_words(tree).min(words.len());
    /// let memo = core::cell::Cell::from_mut(&mut words[..n]).as_slice_of_cells();
    /// for _ in 0..2 {
    ///     let mut order = Order::<64>::with_memo(tree, view, tree.is_closed(), memo)?;
    ///     while let Some(ids) = order.next_range() {
    ///         let _ = ids;
    ///     }
    /// }
    /// # Ok(())
    /// # }
    /// ```
    pub fn with_memo(
        tree: &Tree<'a>,
        view: View,
        cull: bool,
        memo: &'a [Cell<u32>],
    ) -> Result<Self, OrderError> {
        Self::check_depth(tree)?;
        Ok(Self::unchecked(tree, view, cull, memo))
    }

    /// Whether the walk's stack holds `tree`'s depth.
    pub(crate) fn check_depth(tree: &Tree<'_>) -> Result<(), OrderError> {
        let depth = tree.max_depth();
        if depth as usize > N {
            return Err(OrderError::StackTooSmall { depth, capacity: N });
        }
        Ok(())
    }

    /// [`Order::with_memo`] after [`Order::check_depth`]: returned by value
    /// rather than in a `Result`, so that it is built in the caller's slot
    /// (an `Order` is large: moving it out of a `Result` kept two of them on
    /// the stack, which a 16 KiB Cortex-M0 felt). Were the tree deeper
    /// than `N` after all, the subtrees below the stack's depth would be
    /// skipped, never a panic.
    pub(crate) fn unchecked(
        tree: &Tree<'a>,
        view: View,
        cull: bool,
        memo: &'a [Cell<u32>],
    ) -> Self {
        let view = view.local(tree);
        let prelude = if tree.is_closed() && !cull {
            tree.run_count()
        } else {
            0
        };
        // Built in the caller's slot (no named local to move from: an
        // `Order` is large), the root entered by the first `advance`.
        Order {
            w: tree.walk_data(),
            face: Facing::of(&view, memo, tree.facing_scale()),
            switch_base: tree.run_count(),
            view,
            closed: tree.is_closed() || cull,
            prelude_runs: prelude,
            prelude,
            at: Cursor::EMPTY,
            len: 0,
            stack: [Frame::EMPTY; N],
            root_pending: true,
        }
    }

    /// Starts the same walk again from the beginning, in place: a banded
    /// frame with little memory walks the same view several times, and an
    /// `Order` is large (its stack), so it is made once a frame and not
    /// built and moved through the stack for every walk.
    pub fn restart(&mut self) {
        self.prelude_runs = self.prelude;
        self.at = Cursor::EMPTY;
        self.len = 0;
        self.root_pending = true;
    }

    /// The view relative to the origin, as the walk tests it.
    pub fn view(&self) -> LocalView {
        self.view
    }

    /// The faces this walk of `tree` culls, apart from its order: for a
    /// culling walk of a **closed** tree, one [`Class`] with every polygon whose plane
    /// is turned away from the viewer (not backward), in file order; empty
    /// for any other walk (an open tree's culls no face of a closed volume,
    /// and a closed tree's walk without culling emits them itself, first).
    /// The walk's own hand-out is untouched: it still emits no such face.
    ///
    /// What it is for: the rasterizer snaps vertices to its sub-pixel
    /// grid, and a face turned away but seen almost edge-on can come out
    /// of the snap wound toward the viewer, covering a sliver that no face
    /// toward the viewer covers (see `render::cached`, which draws those
    /// first).
    ///
    /// ```
    /// # use fpt_nostd::order::{Order, View};
    /// # use fpt_nostd::reader::Tree;
    /// # fn walk(tree: &Tree<'_>) -> Result<(), fpt_nostd::order::OrderError> {
    /// let order = Order::<64>::new(tree, View::parallel([0.0, 0.0, -1.0]))?;
    /// for id in order.culled(tree) {
    ///     let plane = tree.polygon(id).map(|p| p.plane());
    ///     assert!(plane.is_some_and(|p| !order.view().is_backward(&p)));
    /// }
    /// # Ok(())
    /// # }
    /// ```
    pub fn culled(&self, tree: &Tree<'a>) -> Class<'a> {
        let mut at = Cursor::EMPTY;
        if self.closed && self.prelude == 0 && tree.is_closed() {
            let seg = Seg::new(&self.w, (0, self.switch_base), Pick::Forward);
            at.start(&self.w.runs, &self.face, [seg, Seg::EMPTY]);
        }
        Class::resume(&self.w, self.face, at)
    }

    /// Enters connecting node `node`, unless it is an empty leaf (no levels,
    /// no switch: a BSP tree has one below every leaf switch), which has
    /// nothing to emit.
    #[inline]
    fn push(&mut self, node: u32) {
        let n = self.w.node(node);
        // Branch-free: the frame is written in any case and kept by moving
        // the length, since whether a child is empty is data the branch
        // predictor cannot guess (about half the children of a BSP tree).
        let keep = !n.empty;
        // Validation bounds the depth by N, so there is always room; were
        // there none, the subtree would be skipped rather than panic.
        if let Some(slot) = self.stack.get_mut(self.len) {
            *slot = Frame {
                first_bunch: n.first_bunch,
                levels: n.level_count,
                switch: n.switch,
                j: 0,
                phase: DOWN,
            };
            self.len = (self.len + usize::from(keep)).min(N);
        }
    }

    /// Stores the progress of frame `top` back (its level and phase: the
    /// rest of a frame never changes once pushed).
    #[inline(always)]
    fn put(&mut self, top: usize, f: Frame) {
        if let Some(slot) = self.stack.get_mut(top) {
            slot.j = f.j;
            slot.phase = f.phase;
        }
    }

    /// Starts the class of level `j` of `f` on the way down (`down`) or
    /// up: backward faces of `B_j` (down) or `F_j` (up), with the forward
    /// faces of the other bunch for an open volume; false if nothing passes.
    #[inline(always)]
    fn start_level<R: RunRecord>(&mut self, f: &Frame, j: u32, down: bool) -> bool {
        // F_j and B_j of level j (0-based) are bunches fb + 2j and fb + 2j + 1.
        let fj = f.first_bunch.wrapping_add(j.wrapping_mul(2));
        let bj = fj.wrapping_add(1);
        let (near, far) = if down { (bj, fj) } else { (fj, bj) };
        let a = self.w.bunch(near);
        // Both bunches empty is the common case, made cheap: a closed
        // volume's class is one bunch, tested alone (the far one neither
        // read nor tested as empty).
        if self.closed {
            if a.0 >= a.1 {
                return false;
            }
            return self.begin_one::<R>(a, Pick::Backward);
        }
        let b = self.w.bunch(far);
        if a.0 >= a.1 && b.0 >= b.1 {
            return false;
        }
        self.begin::<R>(a, Pick::Backward, b)
    }

    /// Starts a class of the runs `a` (picked by `pick`) and the runs `b`
    /// (forward faces) in the walk's own hand-out; false if nothing passes.
    /// Out of line: the walk's loop over the tree calls it only for a class
    /// that has runs, and keeps its own registers for the empty ones.
    #[inline(never)]
    fn begin<R: RunRecord>(&mut self, a: (u32, u32), pick: Pick, b: (u32, u32)) -> bool {
        let segs = [
            Seg::new_as::<R>(&self.w, a, pick),
            Seg::new_as::<R>(&self.w, b, Pick::Forward),
        ];
        self.at.start_walk::<R>(&self.w.runs, &self.face, segs)
    }

    /// [`Order::begin`] of a class of one bunch (a closed volume's level
    /// and on-plane bunch, the prelude): compiled apart, the second
    /// segment a constant, so that neither its start, its scan nor its
    /// arguments cost the most common class anything.
    #[inline(never)]
    fn begin_one<R: RunRecord>(&mut self, a: (u32, u32), pick: Pick) -> bool {
        let segs = [Seg::new_as::<R>(&self.w, a, pick), Seg::EMPTY];
        self.at.start_walk::<R>(&self.w.runs, &self.face, segs)
    }

    /// The way up through the levels of `f` (frame `top`, in phase `UP`)
    /// below its level `f.j`: starts the next class that has runs and
    /// stores `f`'s progress, true; with none left, pops the frame, false.
    #[inline(always)]
    fn up<R: RunRecord>(&mut self, top: usize, f: &mut Frame) -> bool {
        while f.j > 0 {
            f.j -= 1;
            if self.start_level::<R>(f, f.j, false) {
                self.put(top, *f);
                return true;
            }
        }
        self.len = top;
        false
    }

    /// Starts the class of the on-plane bunch of `f`'s switch; false if
    /// nothing passes.
    #[inline]
    fn start_on<R: RunRecord>(&mut self, f: &Frame) -> bool {
        let on = f.first_bunch.wrapping_add(f.levels.wrapping_mul(2));
        let runs = self.w.bunch(on);
        if runs.0 >= runs.1 {
            return false;
        }
        let pick = if self.closed {
            Pick::Backward
        } else {
            Pick::All
        };
        self.begin_one::<R>(runs, pick)
    }

    /// The next range of polygon ids back to front, whole runs where it
    /// can (and every run that passes in a row within a bunch joined into
    /// one range: their ids are contiguous), ignoring class boundaries:
    /// what a renderer needs, without a [`Class`] built and copied per
    /// class, and with one call per range. Every id comes exactly as
    /// iterating the classes and their ids would give it, in the same
    /// order. Mixing both is allowed: after `next_range` stopped inside a
    /// class, [`Iterator::next`] returns the rest of that class.
    #[inline(never)]
    pub fn next_range(&mut self) -> Option<core::ops::Range<u32>> {
        // One test of the run layout a call (see `by_layout`): a table
        // tree's walk then costs a narrow tree's.
        by_layout!(self.w.runs, R => self.next_range_as::<R>())
    }

    /// [`Order::next_range`] over the run records of layout `R`.
    #[inline(always)]
    fn next_range_as<R: RunRecord>(&mut self) -> Option<core::ops::Range<u32>> {
        loop {
            if let Some(r) = self.at.next_range_walk::<R>(&self.w.runs, &self.face) {
                return Some(r);
            }
            if !self.advance::<R>() {
                return None;
            }
        }
    }

    /// Moves to the next class that has a passing run (its hand-out in
    /// `self.at`); false at the end of the walk. Inlined into
    /// [`Order::next_range`] (out of line), which nearly every hand-out of
    /// a class goes through: one call a range, not two.
    #[inline(always)]
    fn advance<R: RunRecord>(&mut self) -> bool {
        if self.root_pending {
            self.root_pending = false;
            self.push(0);
        }
        if self.prelude_runs != 0 {
            let runs = (0, core::mem::take(&mut self.prelude_runs));
            if self.begin_one::<R>(runs, Pick::Forward) {
                return true;
            }
        }
        loop {
            let Some(top) = self.len.checked_sub(1) else {
                return false;
            };
            let Some(mut f) = self.stack.get(top).copied() else {
                return false;
            };
            match f.phase & !FAR_IS_BACK {
                DOWN => {
                    while f.j < f.levels {
                        let j = f.j;
                        f.j += 1;
                        if self.start_level::<R>(&f, j, true) {
                            self.put(top, f);
                            return true;
                        }
                    }
                    if f.switch == NO_SWITCH {
                        // A leaf: straight on to the way up, without
                        // storing the frame and reading it back (half the
                        // nodes of a feudal tree).
                        f.phase = UP;
                        if self.up::<R>(top, &mut f) {
                            return true;
                        }
                        continue;
                    }
                    // The back group is farther when the eye is in front.
                    let (plane, rec) = R::switch_at(&self.w, f.switch, self.switch_base);
                    let back_is_far = self.face.backward_at(plane, rec);
                    f.phase = ON | if back_is_far { FAR_IS_BACK } else { 0 };
                    self.put(top, f);
                    self.push(child(f.switch, back_is_far));
                }
                ON => {
                    let back_is_far = f.phase & FAR_IS_BACK != 0;
                    if f.levels == 0 {
                        // Nothing left to do here after the near group (no
                        // level to walk back up): the near group takes this
                        // frame's place, as a tail call would. Every node
                        // of a BSP tree is such a node.
                        self.len = top;
                    } else {
                        f.phase = UP;
                        self.put(top, f);
                    }
                    // The near group is walked after this class is drawn.
                    self.push(child(f.switch, !back_is_far));
                    if self.start_on::<R>(&f) {
                        return true;
                    }
                }
                _ => {
                    if self.up::<R>(top, &mut f) {
                        return true;
                    }
                }
            }
        }
    }
}

/// The children of switch `k`: `G_f` is node `2k + 1`, `G_b` node `2k + 2`.
#[inline(always)]
fn child(k: u32, back: bool) -> u32 {
    k.wrapping_mul(2).wrapping_add(1 + u32::from(back))
}

impl<'a, const N: usize> Iterator for Order<'a, N> {
    type Item = Class<'a>;

    fn next(&mut self) -> Option<Class<'a>> {
        // What is left of the current class first (nothing, unless
        // `next_range` stopped inside it).
        let advanced = |o: &mut Self| by_layout!(o.w.runs, R => o.advance::<R>());
        if !self.at.pending(&self.w.runs, &self.face) && !advanced(self) {
            return None;
        }
        let at = core::mem::replace(&mut self.at, Cursor::EMPTY);
        Some(Class::resume(&self.w, self.face, at))
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
