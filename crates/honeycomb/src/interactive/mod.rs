//! Live editing of a honeycomb (paper section 4, "User interaction", Fig. 10): the three modes
//! (i) move a base-mesh vertex and re-optimize, (ii) slide a vertex along its node axis (no
//! optimization), (iii) turn a node axis, spread to its neighbours, re-optimize with the axes
//! as low-weight conditions; with undo and redo.
//!
//! An `EditSession` keeps one solver for its whole life: the targets of every mode live in
//! families with rows for every vertex, so the sparsity pattern and the symbolic factorization
//! never change, and each edit warm-starts from the current iterate. The caller drives the
//! solve one step at a time (`step`), so it can show every iterate and replace a stale edit
//! by a newer one between steps.

mod spread;
mod watch;

pub use spread::{damping, rings, rotate, spread_turn};
pub use watch::{Watch, Watched};

use crate::constraints::{AxisTargets, Layout, SharedTargets, VertexTargets};
use crate::error::{Error, Result};
use crate::geometry::Vec3;
use crate::mesh::{validate_base_mesh, validate_surface_mesh, Connectivity, PolyMesh};
use crate::optimize::{
    block_positions, check_thickness, initial_normals, Frame, ProblemBuilder, WallRows, Weights,
};
use crate::solve::{GuidedProjection, IterationInfo, SolveState, SolverOptions};
use crate::structure::{measure, node_axes, Honeycomb, Measures};
use crate::surface::Surface;
use std::sync::Arc;

/// What an editor works on: the base mesh and the design surface S, in the normalized frame
/// (mean edge length 1) for the solver and in model units for the measures.
pub struct Workspace {
    pub frame: Frame,
    /// M at the start, normalized.
    pub base: PolyMesh,
    pub conn: Connectivity,
    /// S, normalized (the solver's), shared with the session's families.
    pub surface: Arc<Surface>,
    /// S in model units (the measures' and the display's).
    pub model_surface: Surface,
    /// Wall normals to start from (a loaded structure's), as the solver orients them.
    pub normals: Vec<Vec3>,
    /// Distance of M' from M per vertex (model units).
    pub depths: Vec<f64>,
    /// The session starts from these vertices and walls as they are, without the first solve
    /// (see [`Workspace::as_it_is`]).
    pub as_it_is: bool,
}

impl Workspace {
    /// A base mesh to optimize on S (`None`: the base mesh itself), M' at `thickness` (model
    /// units; `None`: 0.3 mean edge lengths).
    pub fn new(
        base: &PolyMesh,
        surface: Option<&PolyMesh>,
        thickness: Option<f64>,
    ) -> Result<Workspace> {
        let conn = validate_base_mesh(base)?;
        if let Some(s) = surface {
            validate_surface_mesh(s)?;
        }
        let frame = Frame::of(base);
        let thickness = thickness.unwrap_or(crate::optimize::DEFAULT_THICKNESS * frame.unit);
        check_thickness(thickness)?;
        // As optimize bounds it: deeper, every wall's measures are noise and M' overflows.
        crate::optimize::check_scale(
            "thickness",
            thickness,
            crate::optimize::MAX_LENGTH,
            base.mean_edge_length(),
        )?;
        let of_base = surface.is_none();
        let surface_mesh = surface.unwrap_or(base);
        // S in model units (for the measures) and in the solver's frame, one on each thread.
        let (model_surface, surface) = crate::parallel::both(
            || Surface::from_mesh(surface_mesh),
            || Surface::from_mesh(&frame.to_normalized(surface_mesh)),
        );
        let (mut model_surface, mut surface) = (model_surface?, surface?);
        if of_base {
            (model_surface, surface) = (model_surface.marked_as_base(), surface.marked_as_base());
        }
        let normalized = frame.to_normalized(base);
        let normals = initial_normals(&normalized, &conn, &surface);
        Ok(Workspace {
            frame,
            depths: vec![thickness; base.vertices.len()],
            as_it_is: false,
            base: normalized,
            conn,
            surface: Arc::new(surface),
            model_surface,
            normals,
        })
    }

    /// A realized honeycomb (a saved structure) to go on editing: its walls are the start.
    pub fn from_honeycomb(h: &Honeycomb, surface: Option<&PolyMesh>) -> Result<Workspace> {
        let mut ws = Workspace::new(&h.base, surface, Some(h.thickness))?;
        ws.depths = h.depths().collect();
        if let Some(v) = ws.depths.iter().position(|d| d.is_nan() || *d <= 0.0) {
            return Err(Error::Parameter(format!(
                "vertex {v}: M' coincides with M (a depth of zero)"
            )));
        }
        for (e, n) in ws.normals.iter_mut().enumerate() {
            let wall = h.wall_normal(e);
            *n = if wall.dot(*n) < 0.0 { -wall } else { wall };
        }
        Ok(ws)
    }

    /// This workspace started as it is: a variant's honeycomb (quads, parallel meshes,
    /// shading) whose vertices left S on purpose, which the first solve's closeness would pull
    /// back and so undo part of the variant. Edits still solve with closeness.
    pub fn as_it_is(mut self) -> Workspace {
        self.as_it_is = true;
        self
    }
}

#[derive(Clone, Debug)]
pub struct SessionOptions {
    /// Weights of the first solve (the base mesh may be far from a honeycomb).
    pub first_weights: Weights,
    /// Weights of the edits, which start from a honeycomb.
    pub weights: Weights,
    /// Weight of a dragged vertex's target position (mode i).
    pub vertex_weight: f64,
    /// Weight of the target axes (mode iii): lower than the honeycomb conditions (paper: "given
    /// a lower weight than those expressing consistency and angles"). A spread turn is not a
    /// honeycomb's axis field: the result is a least-squares compromise whose omega grows with
    /// the weight. On a 1.5k dome, turns over 3 rings (8 steps): at 0.02 a 10-degree wish
    /// turns 6.5 degrees with omega_max 0.017, a 20-degree one 11.4 with 0.038 (at 0.1: 14.6
    /// with 0.096). Letting the targets go after a few steps makes omega vanish, but then the
    /// axes drift back most of the way.
    pub axis_weight: f64,
    /// Steps per edit at most; the first solve of a session may take `first_iterations`.
    pub iterations: usize,
    pub first_iterations: usize,
    /// An edit is done when every condition residual is below this (normalized units).
    pub tolerance: f64,
    /// Regularization each edit starts from.
    pub eps: f64,
    /// Undo steps kept.
    pub history: usize,
}

impl Default for SessionOptions {
    fn default() -> Self {
        SessionOptions {
            first_weights: Weights::default(),
            // No opposite-wall fairness while editing: the edits start from a fair honeycomb,
            // and without its rows (which couple the walls across every cell) the factor has
            // half the fill: a step costs 12 instead of 22 ms at 1.5k vertices.
            weights: Weights {
                fairness: 0.0,
                ..Weights::default()
            },
            vertex_weight: 1.0,
            axis_weight: 0.02,
            iterations: 8,
            first_iterations: 20,
            tolerance: 1e-10,
            eps: 1e-3,
            history: 100,
        }
    }
}

/// One user edit, in model units.
#[derive(Clone, Copy, Debug)]
pub enum Edit {
    /// Mode (i): the vertex goes to the point of S closest to `target` and is held there; the
    /// vertices up to `radius` rings away start the solve moved along with damping (a soft
    /// selection, so that the cells bend instead of folding); re-optimize. A gesture moves the vertex at most
    /// `MOVE_PER_RING * (radius + 1)` mean edge lengths from where it started.
    MoveVertex {
        vertex: usize,
        target: Vec3,
        radius: usize,
    },
    /// Mode (ii): the vertex moves `distance` along its node axis (towards M' when positive),
    /// M' stays: the wall planes do not change, nothing is optimized.
    SlideVertex { vertex: usize, distance: f64 },
    /// Mode (iii): the node axis of `vertex` turns to `direction`; the axes up to `radius`
    /// rings away follow with damping; re-optimize with the axes as targets.
    TurnAxis {
        vertex: usize,
        direction: Vec3,
        radius: usize,
    },
}

/// Largest ring radius of an axis turn: the whole mesh of a designer's model is within reach
/// long before this.
pub const MAX_RADIUS: usize = 50;

/// How far a dragged vertex may go per ring of its soft selection (mean edge lengths): the
/// damping's steepest slope is about 1.5 over the radius, so neighbours shift at most 0.3 edges
/// against each other and the cells bend without collapsing (at 0.35 per ring a 1.4-edge drag
/// over 3 rings left an edge of 0.17 edges; at 0.2 the shortest stays above half its length).
/// A single vertex (radius 0) moves at most 0.2 edges per gesture.
pub const MOVE_PER_RING: f64 = 0.2;

/// How far a slide (mode ii) may carry a vertex from S (mean edge lengths). A slide leaves M
/// off S, and the next re-solve (modes i and iii hold M to S) pulls it back: a slide far off S
/// is an edit that the next solve silently undoes, so it stops here. Beyond
/// `ON_S` (reciprocal) (S's tolerance) a slide comes with a warning.
pub const MAX_SLIDE_OFF_S: f64 = 0.25;

/// What an applied edit has to tell the user.
#[derive(Clone, Debug, Default)]
pub struct Applied {
    /// A slide that left its vertex off S, or was stopped at [`MAX_SLIDE_OFF_S`].
    pub warning: Option<String>,
}

#[derive(Clone)]
struct Snapshot {
    x: Vec<f64>,
    depths: Vec<f64>,
    /// Who made the gesture this step takes back (or brings back, on the redo stack).
    author: u64,
}

/// Vertex positions (normalized) and node axes at the start of a gesture.
struct StrokeStart {
    positions: Vec<Vec3>,
    axes: Vec<Vec3>,
}

/// What the editor shows after a step: the realized honeycomb and its measures.
pub struct View {
    pub honeycomb: Honeycomb,
    pub measures: Measures,
}

/// Owns its data (the workspace, shared): a session can be kept anywhere, as long as needed.
pub struct EditSession {
    ws: Arc<Workspace>,
    options: SessionOptions,
    layout: Layout,
    solver: GuidedProjection<'static>,
    solver_options: SolverOptions,
    x: Vec<f64>,
    depths: Vec<f64>,
    positions: SharedTargets,
    axes: SharedTargets,
    /// The solve of the latest edit, while it runs.
    active: Option<SolveState>,
    undo: Vec<Snapshot>,
    redo: Vec<Snapshot>,
    /// The gesture the last edit belonged to: one undo step per gesture.
    stroke: Option<u64>,
    /// The geometry when the gesture began: every message of a gesture is measured from it,
    /// so that the spread moves and turns of its messages do not pile up.
    stroke_start: Option<StrokeStart>,
}

impl EditSession {
    /// Solves the workspace into a honeycomb, then sets up the editing solver (its symbolic
    /// factorization is the only one of the session). `ws` is the session's own or shared.
    ///
    /// ```
    /// use honeycomb::generate::{lifted_hex_patch, Shape};
    /// use honeycomb::{Edit, EditSession, SessionOptions, Workspace};
    /// let (base, surface) = lifted_hex_patch(Shape::Dome, 200);
    /// let ws = Workspace::new(&base, Some(&surface), None)?;
    /// let mut session = EditSession::new(ws, SessionOptions::default())?;
    /// // Mode (ii): vertex 0 slides along its node axis; the walls stay honeycomb walls.
    /// session.apply(Edit::SlideVertex { vertex: 0, distance: 0.05 }, None)?;
    /// session.finish()?;
    /// assert!(session.view().measures.omega_max_deg < 0.01);
    /// assert!(session.undo());
    /// # Ok::<(), honeycomb::Error>(())
    /// ```
    pub fn new(ws: impl Into<Arc<Workspace>>, options: SessionOptions) -> Result<EditSession> {
        let ws: Arc<Workspace> = ws.into();
        options.weights.validate()?;
        options.first_weights.validate()?;
        let (base, conn) = (&ws.base, &ws.conn);
        // S is M itself: its zigzag boundary is not S's, as `optimize` has it.
        let on_s = |w: &Weights| Weights {
            boundary: if ws.surface.is_base() {
                0.0
            } else {
                w.boundary
            },
            ..*w
        };
        let (first_weights, weights) = (on_s(&options.first_weights), on_s(&options.weights));
        let nv = base.vertices.len();
        let layout = Layout::new(nv, conn.num_edges());
        let solver_options = SolverOptions {
            max_iterations: options.first_iterations,
            eps: options.eps,
            tolerance: options.tolerance,
            ..SolverOptions::default()
        };
        // The first solve as `optimize` does it (a loaded honeycomb converges at once).
        let first = ProblemBuilder::new(
            base,
            conn,
            &*ws.surface,
            &first_weights,
            WallRows::Consistency,
            &base.vertices,
            &ws.normals,
        );
        let (unknowns, first) = first.finish();
        let (mut x, _) = unknowns.into_parts();
        let blocks = block_positions(base, conn, x.len());
        if ws.as_it_is {
            drop(first);
        } else {
            GuidedProjection::with_positions(x.len(), first, Some(&blocks))?.solve(
                &mut x,
                &solver_options,
                &mut |_| {},
            )?;
        }
        // The edits' walls are planes with offsets, so the solver eliminates the vertices
        // before it factors: a step at 8.8k vertices then factors half the operations.
        let vertices: Vec<Vec3> = (0..nv).map(|v| layout.vertex_at(&x, v)).collect();
        let normals: Vec<Vec3> = (0..layout.num_edges)
            .map(|e| layout.normal_at(&x, e))
            .collect();
        let mut edits = ProblemBuilder::new(
            base,
            conn,
            Arc::clone(&ws.surface),
            &weights,
            WallRows::Planes,
            &vertices,
            &normals,
        );
        let positions = SharedTargets::new(nv);
        let axes = SharedTargets::new(nv);
        edits.push(VertexTargets {
            layout,
            targets: positions.clone(),
            weight: options.vertex_weight,
        });
        edits.push(AxisTargets::new(
            layout,
            &conn.edges,
            axes.clone(),
            options.axis_weight,
        ));
        let (unknowns, families) = edits.finish();
        let (x, _) = unknowns.into_parts();
        let blocks = block_positions(base, conn, x.len());
        let vertices: Vec<usize> = (0..nv).collect();
        let solver = GuidedProjection::eliminating(x.len(), families, Some(&blocks), &vertices)?;
        Ok(EditSession {
            layout,
            solver,
            x,
            depths: ws.depths.clone(),
            positions,
            axes,
            active: None,
            undo: Vec::new(),
            redo: Vec::new(),
            stroke: None,
            stroke_start: None,
            solver_options,
            options,
            ws,
        })
    }

    pub fn num_vertices(&self) -> usize {
        self.layout.num_vertices
    }

    pub fn workspace(&self) -> &Workspace {
        &self.ws
    }

    /// Applies an edit. Edits with the same `stroke` (one drag gesture) share an undo step.
    /// A solve still running is replaced by this edit's (warm-started where it stood).
    pub fn apply(&mut self, edit: Edit, stroke: Option<u64>) -> Result<Applied> {
        self.apply_by(edit, stroke, 0)
    }

    /// [`EditSession::apply`] on behalf of `author` (an editor's page), whose undo step it
    /// makes: see [`EditSession::undo_author`].
    pub fn apply_by(&mut self, edit: Edit, stroke: Option<u64>, author: u64) -> Result<Applied> {
        self.check(&edit)?;
        if stroke.is_none() || stroke != self.stroke {
            self.remember(author);
            self.stroke_start = None;
        }
        self.stroke = stroke;
        // Targets belong to one edit: a newer edit replaces the running one's.
        self.cancel();
        let unit = self.ws.frame.unit;
        match edit {
            Edit::MoveVertex {
                vertex,
                target,
                radius,
            } => {
                let start = self.stroke_start().positions.clone();
                let on_s = self.ws.surface.closest_point(self.normalized(target)).point;
                let mut shift = on_s - start[vertex];
                let reach = MOVE_PER_RING * (radius + 1) as f64;
                if shift.norm() > reach {
                    shift = shift * (reach / shift.norm());
                }
                // The soft selection moves the start of the solve; only the dragged vertex is
                // held (pinning its neighbours too fought the node conditions: omega 5 degrees
                // after a 0.4-edge move over 2 rings).
                for (v, d) in rings(&self.ws.conn, vertex, radius) {
                    let p = self
                        .ws
                        .surface
                        .closest_point(start[v] + shift * damping(d, radius))
                        .point;
                    let at = self.layout.vertex(v);
                    self.x[at..at + 3].copy_from_slice(&p.to_array());
                    if v == vertex {
                        self.positions.set_one(v, Some(p));
                    }
                }
                self.active = Some(SolveState::new(self.options.eps));
            }
            Edit::SlideVertex { vertex, distance } => {
                // M' stays; keep a twentieth of an edge between the two meshes.
                let keep = 0.05 * unit;
                let distance = distance.min(self.depths[vertex] - keep);
                let axis = self.axes_now()[vertex];
                let at = self.layout.vertex(vertex);
                let from = self.layout.vertex_at(&self.x, vertex);
                let (along, warning) = self.slide_near_s(vertex, from, axis, distance / unit);
                let moved = from + axis * along;
                self.x[at..at + 3].copy_from_slice(&moved.to_array());
                self.depths[vertex] -= along * unit;
                return Ok(Applied { warning });
            }
            Edit::TurnAxis {
                vertex,
                direction,
                radius,
            } => {
                let start = self.stroke_start().axes.clone();
                let turned = spread_turn(
                    &self.ws.conn,
                    &start,
                    vertex,
                    direction.normalized(),
                    radius,
                );
                for (v, a) in turned {
                    self.axes.set_one(v, Some(a));
                }
                self.active = Some(SolveState::new(self.options.eps));
            }
        }
        Ok(Applied::default())
    }

    /// How far (normalized) a slide of `vertex` from `from` by `along` on `axis` may go: as
    /// asked, unless that leaves it more than [`MAX_SLIDE_OFF_S`] from S; then as far as the
    /// limit lets it (a vertex already beyond it may only come closer). With a warning when
    /// the vertex ends off S.
    fn slide_near_s(
        &self,
        vertex: usize,
        from: Vec3,
        axis: Vec3,
        along: f64,
    ) -> (f64, Option<String>) {
        let off = |t: f64| {
            let p = from + axis * t;
            (self.ws.surface.closest_point(p).point - p).norm()
        };
        let mut t = along;
        let limited = off(along) > MAX_SLIDE_OFF_S;
        if limited {
            let start = off(0.0);
            if start >= MAX_SLIDE_OFF_S {
                // Already beyond the limit (a loaded structure): only towards S.
                t = if off(along) < start { along } else { 0.0 };
            } else {
                // The distance to S grows along the axis near S: bisect for the limit.
                let (mut lo, mut hi) = (0.0, along);
                for _ in 0..50 {
                    let mid = 0.5 * (lo + hi);
                    if off(mid) <= MAX_SLIDE_OFF_S {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                t = lo;
            }
        }
        let now = off(t);
        let on_s = crate::reciprocal::ON_S;
        let lengths = |x: f64| {
            format!(
                "{} mean edge lengths ({} model units)",
                crate::error::rounded(x, 3),
                crate::error::rounded(x * self.ws.frame.unit, 4)
            )
        };
        let warning = if limited {
            Some(format!(
                "slide of vertex {vertex} stopped {} off S, the limit: farther, the next \
                 re-solve (move vertex, turn axis) would pull it back to S and undo the slide",
                lengths(now)
            ))
        } else if now > on_s {
            Some(format!(
                "vertex {vertex} is {} off S (on S means within {on_s}): the next re-solve \
                 (move vertex, turn axis) pulls it back to S",
                lengths(now)
            ))
        } else {
            None
        };
        (t, warning)
    }

    /// The author of the gesture that [`EditSession::undo`] takes back, if any: an editor with
    /// several pages lets a page undo only its own gestures, newest first.
    pub fn undo_author(&self) -> Option<u64> {
        self.undo.last().map(|s| s.author)
    }

    /// The author of the gesture that [`EditSession::redo`] brings back, if any.
    pub fn redo_author(&self) -> Option<u64> {
        self.redo.last().map(|s| s.author)
    }

    fn check(&self, edit: &Edit) -> Result<()> {
        let nv = self.num_vertices();
        let vertex_ok = |v: usize| {
            if v < nv {
                Ok(())
            } else {
                Err(Error::Parameter(format!(
                    "vertex {v} does not exist (the base mesh has {nv})"
                )))
            }
        };
        let radius_ok = |radius: usize| {
            if radius <= MAX_RADIUS {
                Ok(())
            } else {
                Err(Error::Parameter(format!(
                    "radius {radius}: expected 0 to {MAX_RADIUS} rings"
                )))
            }
        };
        let finite = |what: &str, ok: bool| {
            if ok {
                Ok(())
            } else {
                Err(Error::Parameter(format!("{what} is not finite")))
            }
        };
        match *edit {
            Edit::MoveVertex {
                vertex,
                target,
                radius,
            } => {
                vertex_ok(vertex)?;
                radius_ok(radius)?;
                finite("target", target.is_finite())
            }
            Edit::SlideVertex { vertex, distance } => {
                vertex_ok(vertex)?;
                finite("distance", distance.is_finite())?;
                if distance.abs() > 10.0 * self.ws.frame.unit {
                    return Err(Error::Parameter(format!(
                        "slide by {}: more than 10 edge lengths at once",
                        crate::error::rounded(distance, 6)
                    )));
                }
                Ok(())
            }
            Edit::TurnAxis {
                vertex,
                direction,
                radius,
            } => {
                vertex_ok(vertex)?;
                finite("axis direction", direction.is_finite())?;
                if direction.norm() < 1e-12 {
                    return Err(Error::Parameter("axis direction is zero".into()));
                }
                radius_ok(radius)
            }
        }
    }

    fn stroke_start(&mut self) -> &StrokeStart {
        if self.stroke_start.is_none() {
            let positions = (0..self.num_vertices())
                .map(|v| self.layout.vertex_at(&self.x, v))
                .collect();
            let axes = self.axes_now();
            self.stroke_start = Some(StrokeStart { positions, axes });
        }
        self.stroke_start.as_ref().expect("set above")
    }

    fn normalized(&self, p: Vec3) -> Vec3 {
        (p - self.ws.frame.center) / self.ws.frame.unit
    }

    /// Whether a solve is running (call `step`).
    pub fn solving(&self) -> bool {
        self.active.is_some()
    }

    /// Stops the running solve where it stands.
    pub fn cancel(&mut self) {
        self.active = None;
        self.release();
    }

    /// Forgets the targets: they belong to one edit.
    fn release(&mut self) {
        let nv = self.num_vertices();
        self.positions.set(vec![None; nv]);
        self.axes.set(vec![None; nv]);
    }

    /// One step of the running solve; `None` when there is none or it has just finished (the
    /// conditions are met or its steps are used up).
    pub fn step(&mut self) -> Result<Option<IterationInfo>> {
        let Some(state) = self.active.as_mut() else {
            return Ok(None);
        };
        let result = self
            .solver
            .iterate(&mut self.x, state, &self.solver_options);
        let done = match &result {
            Ok(Some(_)) => state.iterations() >= self.options.iterations,
            _ => true,
        };
        if done {
            self.cancel();
        }
        result
    }

    /// Runs the current solve to its end; returns the steps taken.
    pub fn finish(&mut self) -> Result<usize> {
        let mut steps = 0;
        while self.step()?.is_some() {
            steps += 1;
        }
        Ok(steps)
    }

    fn snapshot(&self, author: u64) -> Snapshot {
        Snapshot {
            x: self.x.clone(),
            depths: self.depths.clone(),
            author,
        }
    }

    fn restore(&mut self, s: Snapshot) {
        self.x = s.x;
        self.depths = s.depths;
        self.cancel();
        self.stroke = None;
        self.stroke_start = None;
    }

    fn remember(&mut self, author: u64) {
        self.undo.push(self.snapshot(author));
        if self.undo.len() > self.options.history {
            self.undo.remove(0);
        }
        self.redo.clear();
    }

    /// Back to the state before the last gesture; false when there is none.
    pub fn undo(&mut self) -> bool {
        let Some(s) = self.undo.pop() else {
            return false;
        };
        // Redo brings back the same author's gesture.
        self.redo.push(self.snapshot(s.author));
        self.restore(s);
        true
    }

    pub fn redo(&mut self) -> bool {
        let Some(s) = self.redo.pop() else {
            return false;
        };
        self.undo.push(self.snapshot(s.author));
        self.restore(s);
        true
    }

    pub fn can_undo(&self) -> bool {
        !self.undo.is_empty()
    }

    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }

    /// Unit node axes of the current iterate (PCA of the wall normals, on S's normal side).
    fn axes_now(&self) -> Vec<Vec3> {
        let normals: Vec<Vec3> = (0..self.layout.num_edges)
            .map(|e| self.layout.normal_at(&self.x, e).normalized())
            .collect();
        node_axes(&self.ws.conn, &normals, |v| {
            self.ws.surface.normal_at(self.layout.vertex_at(&self.x, v))
        })
    }

    /// The realized honeycomb (model units): M from the iterate, M' on the node axes at each
    /// vertex's depth.
    pub fn honeycomb(&self) -> Honeycomb {
        let frame = self.ws.frame;
        let axes = self.axes_now();
        let vertices: Vec<Vec3> = (0..self.num_vertices())
            .map(|v| frame.to_model(self.layout.vertex_at(&self.x, v)))
            .collect();
        let offset = vertices
            .iter()
            .zip(&axes)
            .zip(&self.depths)
            .map(|((&v, &a), &d)| v + a * d)
            .collect();
        let base = PolyMesh::new(vertices, self.ws.base.faces.clone());
        Honeycomb::with_offset(base, &self.ws.conn, offset)
    }

    /// The honeycomb and its measures, from the realized geometry.
    pub fn view(&self) -> View {
        let honeycomb = self.honeycomb();
        let measures = measure(&honeycomb, &self.ws.model_surface);
        View {
            honeycomb,
            measures,
        }
    }
}
