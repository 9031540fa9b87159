//! Drawing a whole tree into a sink in one pass ([`render_tree`],
//! [`draw_frame`]) and what each walked polygon needs from the effects:
//! its face ([`face_of`]), its lighting side and its outline mask.

use super::{cached, check_capacities, FaceIds, Frame, NoProbe, RenderError};
use crate::effects::{Compiled, Effects};
use crate::format::{EDGE_HIDDEN, EDGE_SOFT};
use crate::order::LocalView;
use crate::raster::{Camera, Face, Normal, Precision, RenderStats, Renderer, Scratch, SpanSink};
use crate::reader::{Plane, PolygonAt, Tree};

/// Draws `tree` through `camera` into `sink`: derives the [`Frame`], sets
/// it as `renderer`'s camera, zeroes its counters, walks the classes back
/// to front (a stack of `N` frames) and draws every polygon; returns the
/// counters. The renderer's light, shading mode and fill rule are used as
/// set, its effects as [`Renderer::begin_tree`] decides (the tree's own
/// unless overridden). Fails only when `N` or `V` is smaller than the tree
/// needs ([`check_capacities`]); then nothing is drawn.
pub fn render_tree<P: Precision, const N: usize, const V: usize, E: Compiled, K: SpanSink>(
    tree: &Tree<'_>,
    camera: &Camera,
    renderer: &mut Renderer<P, E>,
    scratch: &mut Scratch<P, V>,
    ids: FaceIds,
    sink: &mut K,
) -> Result<RenderStats, RenderError> {
    let frame = Frame::new(tree, camera);
    draw_frame::<P, N, V, E, K>(tree, &frame, renderer, scratch, ids, sink)
}

/// [`render_tree`] for an already derived [`Frame`] (saves deriving it
/// again per band).
///
/// Effects ([`crate::effects`]) handled here: `culling` chooses the walk
/// ([`crate::order::Order::with_culling`]); `two-sided` lights a face seen from behind
/// with its normal flipped toward the viewer (without it, such a face is
/// lit by its own normal, usually only by the ambient term). The others
/// are the renderer's.
pub fn draw_frame<P: Precision, const N: usize, const V: usize, E: Compiled, K: SpanSink>(
    tree: &Tree<'_>,
    frame: &Frame,
    renderer: &mut Renderer<P, E>,
    scratch: &mut Scratch<P, V>,
    ids: FaceIds,
    sink: &mut K,
) -> Result<RenderStats, RenderError> {
    check_capacities::<N, V>(tree)?;
    Ok(cached::draw_direct::<P, E, K, NoProbe, N, V, false>(
        tree,
        frame,
        renderer,
        scratch,
        ids,
        &mut [],
        sink,
        &NoProbe,
    )?)
}

/// What the walk of a frame needs from the effects (see
/// [`walk_effects`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct WalkFx {
    /// Cull back faces (choose the culling walk).
    pub(crate) cull: bool,
    /// Light back sides as if they faced the viewer.
    pub(crate) two_sided: bool,
    /// Lighting is on: the face needs its normal.
    pub(crate) lit: bool,
    /// Outlines are on: the face needs its outline mask.
    pub(crate) outline: bool,
    /// Gouraud shading is on (with lighting, and the tree has corner
    /// normals): each polygon gets its colour plane
    /// ([`crate::raster::gouraud`]).
    pub(crate) smooth: bool,
}

/// What the walk of a frame needs from the effects `fx` (the renderer's,
/// settled for the frame by [`Renderer::begin_tree`]) in the code compiled
/// for pipeline `X` ([`crate::effects`]'s dispatch): an effect outside
/// `X`'s set is off there at compile time. Shared by the loops of
/// `render::cached`. (The walk itself is built by each caller: handing a
/// walk back by value would copy its whole stack every frame.)
#[inline(always)]
pub(crate) fn walk_effects<X: Compiled>(tree: &Tree<'_>, fx: Effects) -> WalkFx {
    let fx = fx.and(X::SET);
    WalkFx {
        cull: fx.contains(Effects::CULLING),
        two_sided: fx.contains(Effects::TWO_SIDED),
        lit: fx.contains(Effects::LIGHTING),
        outline: fx.contains(Effects::OUTLINE),
        // Without corner normals every corner has the flat colour: nothing
        // to interpolate.
        smooth: fx.contains(Effects::SMOOTH)
            && fx.contains(Effects::LIGHTING)
            && tree.has_normals(),
    }
}

/// The face the rasterizer draws for polygon `p` of the walk: its colour,
/// `id`, its outline mask, and the normal that lighting uses (a compact
/// plane entry's integers as stored, see [`PolygonAt::normal`]): with
/// `two_sided`, a face seen from behind is lit as if it faced the viewer.
/// Without lighting the plane is not read at all (the normal is zero), so
/// that lighting switched off costs what lighting compiled out does.
/// Shared by [`draw_frame`] and the loops of `render::cached`, so all draw
/// alike.
#[inline(always)]
pub(crate) fn face_of(
    tree: &Tree<'_>,
    p: &PolygonAt<'_, '_>,
    view: &LocalView,
    fx: WalkFx,
    id: u32,
) -> Face {
    let normal = if fx.lit {
        let normal = p.normal();
        // The facing test on the plane as decoded, as before compact
        // normals were lit as integers (an `f32` plane is read once: the
        // two reads are inlined and merged).
        if fx.two_sided && !view.is_backward(&p.plane()) {
            normal.flipped()
        } else {
            normal
        }
    } else {
        Normal::from_f32([0.0; 3])
    };
    Face {
        normal,
        color: p.color(),
        id,
        hidden_edges: if fx.outline {
            outline_mask(tree, p.id(), *view)
        } else {
            0
        },
    }
}

/// `sin²` of the angle within which a soft edge's neighbour counts as
/// edge-on (14.5°, see [`outline_mask`]).
const EDGE_ON_SIN2: f32 = 0.0625;

/// The edges of `p` that the `outline` effect leaves out in this view
/// (bit `i`: edge `i`; see [`crate::format`]). With the file's edge
/// section: the hidden edges, and the soft ones that are no silhouette:
/// the neighbour across the edge faces the viewer the same way as `p`,
/// and is not within 14.5° of edge-on. (An edge-on neighbour is the face
/// that draws the silhouette; it may be thinner than a pixel, and `p`,
/// painted after it, would cover that line, so `p` draws the edge too.)
/// Without the section, the polygon's 8-bit mask.
///
/// Out of line, and given the polygon by id and the view by value: the
/// walk's loop (where `face_of` is inlined) keeps its `PolygonRef` in
/// registers only while no call takes its address; passing it by
/// reference had it written to the stack for every polygon, outlines on or
/// off (3.6 % of a `bench_city` frame on the Cortex-M4).
#[inline(never)]
fn outline_mask(tree: &Tree<'_>, id: u32, view: LocalView) -> u64 {
    let Some(p) = tree.polygon(id) else {
        return 0;
    };
    let view = &view;
    if !p.has_edges() {
        return u64::from(p.hidden_edges());
    }
    let facing = view.is_backward(&p.plane());
    let mut mask = 0u64;
    for i in 0..p.vertex_count().min(64) {
        let hide = match p.edge(i) {
            Some((EDGE_HIDDEN, _)) => true,
            Some((EDGE_SOFT, n)) => {
                // The neighbour's plane through the edge's first vertex:
                // the same facing test as the walk's.
                let normal = n.map(f32::from);
                let v = p.vertex(i);
                let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
                let plane = Plane {
                    normal,
                    d: -dot(normal, v),
                };
                // The neighbour's facing, and the ray it is seen along.
                let ray = match view {
                    LocalView::Parallel(dir) => dir.map(|c| -c),
                    LocalView::Eye(e) => [e[0] - v[0], e[1] - v[1], e[2] - v[2]],
                };
                let s = dot(normal, ray);
                let edge_on = s * s <= EDGE_ON_SIN2 * dot(normal, normal) * dot(ray, ray);
                view.is_backward(&plane) == facing && !edge_on
            }
            _ => false,
        };
        mask |= u64::from(hide) << i;
    }
    mask
}
