//! `optimize`: guided projection of a hexagonal base mesh onto the honeycomb conditions.

mod broken_cells;
mod dual_normals;
mod frame;
mod kept_walls;
mod made_mesh;
mod parallel_pair;
mod problem;
mod quads;
mod unknowns;
mod variants;
mod weights;

pub use broken_cells::{
    broken_boundary_cells, keeping_one_piece, kept_vertices, optimize_dropping_broken_cells,
    without_cells, Settled, MAX_DROPPED_SHARE,
};
pub use frame::Frame;
#[cfg(test)]
pub(crate) use kept_walls::realized_normals;
pub use made_mesh::{optimize_made_mesh, Attempt};
#[cfg(test)]
pub(crate) use parallel_pair::{pair, PairingProblem};
pub use problem::{block_positions, initial_normals, node_walls, ProblemBuilder, WallRows};
#[cfg(test)]
pub use problem::{boundary_vertices_on_surface_boundary, families};
pub use quads::QuadOptions;
#[cfg(test)]
pub use quads::QuadPattern;
#[cfg(test)]
pub(crate) use quads::{CappingProblem, CappingTry};
#[cfg(test)]
pub use unknowns::Block;
pub use variants::{shading_axes, unit_light, AxesOptions, ParallelOptions};
pub use weights::Weights;

pub(crate) use variants::check_weight;

use crate::constraints::{
    ConstantDepth, EdgeParallelity, Layout, NodeOrientation, OffsetBlock, OffsetOnAxis,
    PrescribedAxes,
};
use crate::error::{rounded, Error, Result};
use crate::geometry::Vec3;
use crate::mesh::{validate_base_mesh, validate_surface_mesh, Connectivity, PolyMesh};
use crate::solve::{Constraint, GuidedProjection, IterationInfo, Role, SolveReport, SolverOptions};
use crate::structure::{node_axes, Honeycomb};
use crate::surface::Surface;
use serde::Serialize;

#[derive(Clone, Debug, Default)]
pub struct OptimizeOptions {
    pub weights: Weights,
    pub solver: SolverOptions,
    /// Distance between M and M' in model units; `None`: 0.3 mean edge lengths. With parallel
    /// meshes it is the initial depth of M'.
    pub thickness: Option<f64>,
    /// Every edge at least this long (model units), by dummy unknowns.
    pub min_edge: Option<f64>,
    /// Parallel meshes: M' as unknowns, its edges parallel to M's.
    pub parallel: Option<ParallelOptions>,
    /// Prescribed node axes (also the shading system's).
    pub axes: Option<AxesOptions>,
    /// Quadrangulation: every hexagon split into two planar quads (Figs. 1, 11, 17).
    pub quads: Option<QuadOptions>,
    /// What the solver's unknowns for the wall normals are.
    pub wall_normals: WallNormals,
    /// Wall normals to start from, one per edge (else each edge turned about S's normal).
    pub initial_normals: Option<Vec<Vec3>>,
}

/// The unknowns behind the wall normals.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WallNormals {
    /// Cell points for a plain honeycomb (also the one quads cap), normals per edge with
    /// parallel meshes or prescribed axes, which constrain the normals one by one.
    #[default]
    Auto,
    /// One unit normal per edge (the paper's formulation, DESIGN.md section 2).
    PerEdge,
    /// One point per cell, each wall normal the difference of its two cells' points (see
    /// `dual_normals.rs`): the 120-degree condition holds at inner nodes by construction, the
    /// factor is about a third smaller and each iteration gains more. Not with parallel meshes
    /// or prescribed axes.
    CellPoints,
}

impl WallNormals {
    /// The default normalization weight. Per edge the paper's 10. With cell points the node
    /// condition is exact, and 10 holds the walls' lengths so hard that the iteration slows to
    /// a linear rate (omega 1.5e-2 instead of 3e-9 after 5 iterations on an 8.8k dome); 0.3
    /// converges fastest.
    pub fn normalization(self) -> f64 {
        match self {
            WallNormals::CellPoints => 0.3,
            WallNormals::PerEdge | WallNormals::Auto => 10.0,
        }
    }
}

/// The distance between M and M' unless one is given, in mean edge lengths of the base mesh.
pub const DEFAULT_THICKNESS: f64 = 0.3;

/// A distance between M and M' (model units) must be a positive length.
pub fn check_thickness(t: f64) -> Result<()> {
    crate::error::check_positive_length("thickness", t)
}

/// Thickness and depth beyond this many mean edge lengths are refused: no structure is that
/// deep, and the solve would lose the cells' scale in roundoff.
pub(crate) const MAX_LENGTH: f64 = 1e3;
/// A minimum edge length beyond this many mean edge lengths would have every edge grow as
/// much, which is a different mesh, not an optimized one.
const MAX_MIN_EDGE: f64 = 10.0;

/// Refuses a length parameter more than `ratio` mean edge lengths `edge` of the base mesh.
pub(crate) fn check_scale(field: &'static str, length: f64, ratio: f64, edge: f64) -> Result<()> {
    if length > ratio * edge {
        return Err(Error::option(
            field,
            rounded(length, 6),
            format!(
                "more than {ratio} times the base mesh's mean edge length {}; expected a \
                 length in the model's units",
                rounded(edge, 6)
            ),
        ));
    }
    Ok(())
}

/// The second try's minimum edge length, in mean edge lengths of the base mesh.
pub const SECOND_TRY_MIN_EDGE: f64 = 0.3;
/// The second try's iterations at least: without the fairness the iteration is slower (Yas
/// Island at 8k vertices needs about 200).
pub const SECOND_TRY_ITERATIONS: usize = 200;

impl OptimizeOptions {
    #[cfg(test)]
    /// The default options with wall normals as differences of cell points.
    pub fn cell_points() -> OptimizeOptions {
        OptimizeOptions {
            wall_normals: WallNormals::CellPoints,
            ..OptimizeOptions::default()
        }
    }

    /// The default options with one unknown normal per edge.
    #[cfg(test)]
    pub fn per_edge() -> OptimizeOptions {
        OptimizeOptions {
            wall_normals: WallNormals::PerEdge,
            ..OptimizeOptions::default()
        }
    }

    /// Parallel meshes, quads or prescribed axes: solved from the base mesh as given.
    pub fn is_variant(&self) -> bool {
        self.parallel.is_some() || self.axes.is_some() || self.quads.is_some()
    }

    /// Parallel meshes or prescribed axes, whose rows read the wall normals one by one (quads
    /// cap a finished honeycomb and keep its walls).
    pub fn constrains_normals(&self) -> bool {
        self.parallel.is_some() || self.axes.is_some()
    }

    /// These options with `Auto` wall normals decided and the normalization weight set.
    pub fn resolved(&self) -> OptimizeOptions {
        let wall_normals = match self.wall_normals {
            WallNormals::Auto if self.constrains_normals() => WallNormals::PerEdge,
            WallNormals::Auto => WallNormals::CellPoints,
            chosen => chosen,
        };
        OptimizeOptions {
            wall_normals,
            weights: self.weights.resolved(wall_normals),
            ..self.clone()
        }
    }

    /// The second try for a base mesh on a real surface that these options left short of a
    /// honeycomb: no opposite-wall fairness (it holds walls parallel that S shears, and on
    /// such surfaces keeps omega at degrees), every edge at least 0.3 mean edge lengths
    /// unless a minimum is set, and at least 200 iterations (the solve stops when it converges).
    pub fn second_try(&self, base: &PolyMesh) -> OptimizeOptions {
        let mut options = self.clone();
        options.weights.fairness = 0.0;
        options
            .min_edge
            .get_or_insert(SECOND_TRY_MIN_EDGE * base.mean_edge_length());
        options.solver.max_iterations = options.solver.max_iterations.max(SECOND_TRY_ITERATIONS);
        options
    }

    /// Checks the options against the (valid) base mesh they are for, naming an offender by
    /// its field in [`crate::Options`].
    pub fn validate(&self, base: &PolyMesh) -> Result<()> {
        self.weights.validate()?;
        crate::limits::check_solve(base, self.solver.max_iterations)?;
        let edge = base.mean_edge_length();
        if let Some(t) = self.thickness {
            crate::error::check_positive_length("thickness", t)?;
            check_scale("thickness", t, MAX_LENGTH, edge)?;
        }
        if let Some(length) = self.min_edge {
            crate::error::check_positive_length("min_edge", length)?;
            check_scale("min_edge", length, MAX_MIN_EDGE, edge)?;
        }
        if let Some(p) = &self.parallel {
            p.validate()?;
            if let Some(depth) = p.depth {
                check_scale("depth", depth, MAX_LENGTH, edge)?;
            }
        }
        if let Some(a) = &self.axes {
            a.validate(base.vertices.len())?;
        }
        if let Some(q) = &self.quads {
            q.validate()?;
        }
        if self.wall_normals == WallNormals::CellPoints && self.constrains_normals() {
            return Err(Error::Parameter(
                "wall normals as cell points: not with parallel meshes or prescribed axes".into(),
            ));
        }
        Ok(())
    }
}

/// The result of `optimize`, in model units.
#[derive(Clone)]
pub struct Optimized {
    pub honeycomb: Honeycomb,
    pub connectivity: Connectivity,
    /// The solver's unit wall normals, one per edge (as seen from the edge's first vertex).
    pub normals: Vec<Vec3>,
    pub solve: SolveReport,
    pub frame: Frame,
    /// The unit prescribed axes (zero where none), when axes were prescribed.
    pub prescribed_axes: Option<Vec<Vec3>>,
    /// M' was solved for as a mesh parallel to M.
    pub parallel: bool,
    /// With quads: the quad cover on the optimized M (split quads first, then unsplit cells).
    pub quads: Option<PolyMesh>,
    /// With quads: how the cells were split (the quads to measure, the polylines).
    pub quad_cover: Option<crate::structure::QuadCover>,
    /// With quads some of whose cells left the pattern (`QuadCover::off_pattern`): the quads'
    /// planarity as the pattern whole left them.
    pub quads_whole_pattern: Option<crate::structure::FaceMeasures>,
    /// The weights the solve used (normalization set; boundary 0 without a design surface).
    pub weights: Weights,
    /// The wall normals' unknowns the solve used (`Auto` decided).
    pub wall_normals: WallNormals,
}

/// The unknowns and constraint families of one optimization, in the normalized frame.
pub struct Problem<'a> {
    pub layout: Layout,
    /// Initial unknowns: the honeycomb's, then each variant's block.
    pub x: Vec<f64>,
    /// Where each block of `x` lies, in order.
    #[cfg(test)]
    pub blocks: Vec<Block>,
    pub families: Vec<Box<dyn Constraint + 'a>>,
    /// Where M' lives, with parallel meshes.
    pub offset: Option<OffsetBlock>,
}

impl<'a> Problem<'a> {
    /// `mesh` and `surface` in the normalized frame of `frame`; options in model units.
    pub fn build(
        mesh: &PolyMesh,
        conn: &Connectivity,
        surface: &'a Surface,
        options: &OptimizeOptions,
        weights: &Weights,
        frame: &Frame,
    ) -> Problem<'a> {
        let mut normals = initial_normals(mesh, conn, surface);
        if let Some(given) = options
            .initial_normals
            .as_ref()
            .filter(|g| g.len() == normals.len())
        {
            for (n, &g) in normals.iter_mut().zip(given) {
                *n = if g.dot(*n) < 0.0 { -g } else { g };
            }
        }
        if let Some(a) = &options.axes {
            // Walls that already contain the prescribed axes: a wall normal turning far from its
            // start (through the linearization) can come out flipped and meet its neighbour at 60
            // instead of 120 degrees.
            let targets = a.unit_targets();
            for (e, &[i, j]) in conn.edges.iter().enumerate() {
                let n_side = surface.normal_at((mesh.vertices[i] + mesh.vertices[j]) * 0.5);
                let oriented = |t: Vec3| if t.dot(n_side) < 0.0 { -t } else { t };
                let t = oriented(targets[i]) + oriented(targets[j]);
                let n = (mesh.vertices[i] - mesh.vertices[j]).normalized().cross(t);
                if n.norm() > 1e-3 {
                    normals[e] = n.normalized();
                }
            }
        }
        // With cell points no row may couple two vertices (see `WallRows::Planes`).
        let walls = match options.wall_normals {
            WallNormals::CellPoints => WallRows::Planes,
            WallNormals::PerEdge | WallNormals::Auto => WallRows::Consistency,
        };
        let mut problem = ProblemBuilder::new(
            mesh,
            conn,
            surface,
            weights,
            walls,
            &mesh.vertices,
            &normals,
        );
        let layout = problem.layout();
        if let Some(length) = options.min_edge {
            problem.min_edge_length(length / frame.unit);
        }
        // With prescribed axes the walls turn far from where they start, and a node could settle
        // in the mirrored solution (a valence-2 node at 60 degrees, a flipped wall normal): every
        // node keeps the side of its walls (see NodeOrientation). Without axes the guard is left
        // out: on bases with non-convex cells (hexagonalminimal) it fought the start and left
        // omega at 0.75 degrees instead of 3e-4.
        let (node3, node2) = node_walls(conn);
        let guarded: Vec<&[(usize, f64)]> = if options.axes.is_some() {
            let two = node2.iter().map(|w| &w[..]);
            two.chain(node3.iter().map(|w| &w[..])).collect()
        } else {
            Vec::new()
        };
        if !guarded.is_empty() {
            let x = problem.values();
            let rows = NodeOrientation::rows(layout, &conn.edges, &guarded, x);
            let dummies = NodeOrientation::initial_dummies(layout, &rows, x);
            let dummies = problem.allocate("orientation_dummies", dummies);
            problem.push(NodeOrientation {
                layout,
                rows,
                dummy_start: dummies.start,
                weight: weights.angle,
            });
        }
        let mut offset = None;
        if let Some(p) = &options.parallel {
            // M' starts as M moved along S's normal (the paper's initialization).
            let depth = p
                .depth
                .or(options.thickness)
                .unwrap_or(DEFAULT_THICKNESS * frame.unit)
                / frame.unit;
            let moved =
                (mesh.vertices.iter()).flat_map(|&v| (v + surface.normal_at(v) * depth).to_array());
            let block = OffsetBlock {
                start: problem.allocate("offset_vertices", moved).start,
            };
            problem.push(OffsetOnAxis {
                layout,
                offset: block,
                edges: conn.edges.clone(),
                weight: weights.consistency,
            });
            problem.push(EdgeParallelity {
                layout,
                offset: block,
                edges: conn.edges.clone(),
                weight: p.weight,
            });
            if let Some(c) = p.depth {
                if p.depth_weight > 0.0 {
                    problem.push(ConstantDepth {
                        layout,
                        offset: block,
                        depth: c / frame.unit,
                        weight: p.depth_weight,
                    });
                }
            }
            offset = Some(block);
        }
        if let Some(a) = &options.axes {
            let targets = a.unit_targets();
            let mut ends = Vec::new();
            for (v, &target) in targets.iter().enumerate() {
                if target.norm() > 0.0 {
                    for &e in &conn.vertex_edges[v] {
                        ends.push((e, conn.edge_sign(e, v), target));
                    }
                }
            }
            problem.push(PrescribedAxes {
                layout,
                ends,
                weight: a.weight,
                role: Role::Condition,
            });
        }
        let (unknowns, families) = problem.finish();
        let (x, _blocks) = unknowns.into_parts();
        Problem {
            layout,
            x,
            #[cfg(test)]
            blocks: _blocks,
            families,
            offset,
        }
    }
}

/// Optimizes `base` into a honeycomb that follows the design surface `surface` (`None`: the
/// base mesh itself, whose own zigzag boundary is then not imposed). Both are validated first.
pub fn optimize(
    base: &PolyMesh,
    surface: Option<&PolyMesh>,
    options: &OptimizeOptions,
    progress: &mut dyn FnMut(&IterationInfo),
) -> Result<Optimized> {
    let conn = validate_base_mesh(base)?;
    options.validate(base)?;
    if let Some(q) = &options.quads {
        let honeycomb = OptimizeOptions {
            quads: None,
            ..options.clone()
        };
        let solved = optimize(base, surface, &honeycomb, progress)?;
        let iterations = solved.solve.iterations;
        let mut capped = capped(
            solved,
            surface.unwrap_or(base),
            q,
            &options.solver,
            progress,
        )?;
        capped.solve.iterations += iterations;
        return Ok(capped);
    }
    let options = &options.resolved();
    let mut weights = options.weights;
    if surface.is_none() {
        weights.boundary = 0.0;
    }
    let frame = Frame::of(base);
    let mesh = frame.to_normalized(base);
    // A design surface is checked beside the making of its search tree: both read all of it,
    // and on a surface of 50k triangles each takes about 25 ms.
    let (checked, normalized_surface) = crate::parallel::both(
        || surface.map(validate_surface_mesh).transpose(),
        || Surface::from_mesh(&frame.to_normalized(surface.unwrap_or(base))),
    );
    checked?;
    let normalized_surface = normalized_surface?;

    let problem = Problem::build(&mesh, &conn, &normalized_surface, options, &weights, &frame);
    let (layout, offset, mut x) = (problem.layout, problem.offset, problem.x);
    let solve = if options.wall_normals == WallNormals::CellPoints {
        let d = dual_normals::dual_normals(&mesh, &conn, layout, &x)?;
        let mut y = d.y;
        // The vertices' blocks, which no row couples (see `WallRows::Planes`).
        let vertices: Vec<usize> = (0..layout.num_vertices).collect();
        let mut solver = GuidedProjection::with_substitution(
            problem.families,
            d.substitution,
            Some(&d.positions),
            &vertices,
        )?;
        let solve = solver.solve(&mut y, &options.solver, progress)?;
        x = solver.family_unknowns(&y);
        solve
    } else {
        let positions = block_positions(&mesh, &conn, x.len());
        let mut solver =
            GuidedProjection::with_positions(x.len(), problem.families, Some(&positions))?;
        solver.solve(&mut x, &options.solver, progress)?
    };

    let vertices: Vec<Vec3> = (0..layout.num_vertices)
        .map(|v| frame.to_model(layout.vertex_at(&x, v)))
        .collect();
    let normals: Vec<Vec3> = (0..layout.num_edges)
        .map(|e| layout.normal_at(&x, e).normalized())
        .collect();
    let optimized = PolyMesh::new(vertices, base.faces.clone());
    let honeycomb = match offset {
        // Parallel meshes: M' is the solved second mesh itself.
        Some(block) => {
            let offset = (0..layout.num_vertices)
                .map(|v| frame.to_model(block.vertex_at(&x, v)))
                .collect();
            Honeycomb::with_offset(optimized, &conn, offset)
        }
        None => {
            let axes = node_axes(&conn, &normals, |v| {
                normalized_surface.normal_at(layout.vertex_at(&x, v))
            });
            let thickness = options.thickness.unwrap_or(DEFAULT_THICKNESS * frame.unit);
            Honeycomb::new(optimized, &conn, axes, thickness)
        }
    };
    Ok(Optimized {
        honeycomb,
        connectivity: conn,
        normals,
        solve,
        frame,
        prescribed_axes: options.axes.as_ref().map(AxesOptions::unit_targets),
        parallel: options.parallel.is_some(),
        quads: None,
        quad_cover: None,
        quads_whole_pattern: None,
        weights,
        wall_normals: options.wall_normals,
    })
}

/// `solved` (a plain honeycomb) capped by planar quads on the design surface `surface` (see
/// [`quads::cap`]): its walls and node axes kept, its vertices moved; `solve` is the capping
/// solve's.
pub fn capped(
    solved: Optimized,
    surface: &PolyMesh,
    options: &QuadOptions,
    solver: &SolverOptions,
    progress: &mut dyn FnMut(&IterationInfo),
) -> Result<Optimized> {
    let h = &solved.honeycomb;
    let conn = &solved.connectivity;
    let normals = kept_walls::realized_normals(h, conn);
    let capped = quads::cap(h, conn, &normals, surface, options, solver, progress)?;
    let mesh = PolyMesh::new(capped.vertices, h.base.faces.clone());
    let axes = node_axes(conn, &normals, |v| h.axes[v]);
    let honeycomb = Honeycomb::new(mesh, conn, axes, h.thickness);
    Ok(Optimized {
        quads: Some(capped.cover.mesh(&honeycomb.base.vertices)),
        quad_cover: Some(capped.cover),
        quads_whole_pattern: capped.whole,
        honeycomb,
        solve: capped.solve,
        normals,
        ..solved
    })
}

/// `solved` (a plain honeycomb) as parallel meshes M, M' (see [`parallel_pair::pair`]): its
/// walls and node axes kept, M and M' placed on the axes; `solve` is the pairing solve's.
pub fn paired(
    solved: Optimized,
    options: &ParallelOptions,
    solver: &SolverOptions,
    progress: &mut dyn FnMut(&IterationInfo),
) -> Result<Optimized> {
    let h = &solved.honeycomb;
    let conn = &solved.connectivity;
    let normals = kept_walls::realized_normals(h, conn);
    let paired = parallel_pair::pair(h, conn, &normals, options, solver, progress)?;
    let mesh = PolyMesh::new(paired.vertices, h.base.faces.clone());
    let honeycomb = Honeycomb::with_offset(mesh, conn, paired.offset);
    Ok(Optimized {
        honeycomb,
        solve: paired.solve,
        normals,
        parallel: true,
        ..solved
    })
}
