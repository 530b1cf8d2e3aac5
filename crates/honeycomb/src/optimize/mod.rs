//! `optimize`: guided projection of a hexagonal base mesh onto the honeycomb conditions.

mod frame;
mod problem;
mod variants;
mod weights;

pub use frame::Frame;
pub use problem::{
    boundary_vertices_on_surface_boundary, families, initial_normals, min_edge_family,
};
pub use variants::{shading_axes, unit_light, AxesOptions, ParallelOptions};
pub use weights::Weights;

use crate::constraints::{
    ConstantDepth, EdgeParallelity, Layout, OffsetBlock, OffsetOnAxis, PrescribedAxes,
};
use crate::error::{Error, Result};
use crate::geometry::Vec3;
use crate::mesh::{validate_base_mesh, validate_surface_mesh, Connectivity, PolyMesh};
use crate::solve::{Constraint, GuidedProjection, IterationInfo, Role, SolveReport, SolverOptions};
use crate::structure::{node_axes, Honeycomb};
use crate::surface::Surface;

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
}

impl OptimizeOptions {
    fn validate(&self, num_vertices: usize) -> Result<()> {
        self.weights.validate()?;
        if let Some(t) = self.thickness {
            if !t.is_finite() || t <= 0.0 {
                return Err(Error::Parameter(format!(
                    "thickness {t}: expected a positive length in model units"
                )));
            }
        }
        if let Some(length) = self.min_edge {
            if !length.is_finite() || length <= 0.0 {
                return Err(Error::Parameter(format!(
                    "minimum edge length {length}: expected a positive length"
                )));
            }
        }
        if let Some(p) = &self.parallel {
            p.validate()?;
        }
        if let Some(a) = &self.axes {
            a.validate(num_vertices)?;
        }
        Ok(())
    }
}

/// The result of `optimize`, in model units.
pub struct Optimized {
    pub honeycomb: Honeycomb,
    pub connectivity: Connectivity,
    /// The solver's unit wall normals, one per edge (as seen from the edge's first vertex).
    pub normals: Vec<Vec3>,
    pub solve: SolveReport,
    pub frame: Frame,
    /// The unit prescribed axes (zero where none), when axes were prescribed.
    pub prescribed_axes: Option<Vec<Vec3>>,
}

/// The unknowns and constraint families of one optimization, in the normalized frame.
pub struct Problem<'a> {
    pub layout: Layout,
    /// Initial unknowns: the honeycomb's, then each variant's block.
    pub x: Vec<f64>,
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
        let layout = Layout::new(mesh.vertices.len(), conn.num_edges());
        let normals = initial_normals(mesh, conn, surface);
        let mut x = layout.pack(&mesh.vertices, &normals);
        let mut families = families(mesh, conn, surface, weights);
        if let Some(length) = options.min_edge {
            let family = min_edge_family(mesh, conn, length / frame.unit);
            debug_assert_eq!(family.dummy_start, x.len());
            x.extend(family.initial_dummies(&mesh.vertices));
            families.push(Box::new(family));
        }
        let mut offset = None;
        if let Some(p) = &options.parallel {
            // M' starts as M moved along S's normal (the paper's initialization).
            let depth = p.depth.or(options.thickness).unwrap_or(0.3 * frame.unit) / frame.unit;
            let block = OffsetBlock { start: x.len() };
            for &v in &mesh.vertices {
                x.extend_from_slice(&(v + surface.normal_at(v) * depth).to_array());
            }
            families.push(Box::new(OffsetOnAxis {
                layout,
                offset: block,
                edges: conn.edges.clone(),
                weight: weights.consistency,
            }));
            families.push(Box::new(EdgeParallelity {
                layout,
                offset: block,
                edges: conn.edges.clone(),
                weight: p.weight,
            }));
            if let Some(c) = p.depth {
                if p.depth_weight > 0.0 {
                    families.push(Box::new(ConstantDepth {
                        layout,
                        offset: block,
                        depth: c / frame.unit,
                        weight: p.depth_weight,
                    }));
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
            families.push(Box::new(PrescribedAxes {
                layout,
                ends,
                weight: a.weight,
                role: Role::Condition,
            }));
        }
        Problem {
            layout,
            x,
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
    options.validate(base.vertices.len())?;
    let conn = validate_base_mesh(base)?;
    let mut weights = options.weights;
    if let Some(s) = surface {
        validate_surface_mesh(s)?;
    } else {
        weights.boundary = 0.0;
    }
    let surface = surface.unwrap_or(base);
    let frame = Frame::of(base);
    let mesh = frame.to_normalized(base);
    let normalized_surface = Surface::from_mesh(&frame.to_normalized(surface))?;

    let problem = Problem::build(&mesh, &conn, &normalized_surface, options, &weights, &frame);
    let (layout, offset, mut x) = (problem.layout, problem.offset, problem.x);
    let mut solver = GuidedProjection::new(x.len(), problem.families)?;
    let solve = solver.solve(&mut x, &options.solver, progress)?;

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
            let thickness = options.thickness.unwrap_or(0.3 * frame.unit);
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
    })
}
