//! `optimize`: guided projection of a hexagonal base mesh onto the honeycomb conditions.

mod frame;
mod problem;
mod weights;

pub use frame::Frame;
pub use problem::{
    boundary_vertices_on_surface_boundary, families, initial_normals, min_edge_family,
};
pub use weights::Weights;

use crate::constraints::Layout;
use crate::error::Result;
use crate::geometry::Vec3;
use crate::mesh::{validate_base_mesh, validate_surface_mesh, Connectivity, PolyMesh};
use crate::solve::{GuidedProjection, IterationInfo, SolveReport, SolverOptions};
use crate::structure::{node_axes, Honeycomb};
use crate::surface::Surface;

#[derive(Clone, Debug, Default)]
pub struct OptimizeOptions {
    pub weights: Weights,
    pub solver: SolverOptions,
    /// Distance between M and M' in model units; `None`: 0.3 mean edge lengths.
    pub thickness: Option<f64>,
    /// Every edge at least this long (model units), by dummy unknowns.
    pub min_edge: Option<f64>,
}

/// The result of `optimize`, in model units.
pub struct Optimized {
    pub honeycomb: Honeycomb,
    pub connectivity: Connectivity,
    /// The solver's unit wall normals, one per edge (as seen from the edge's first vertex).
    pub normals: Vec<Vec3>,
    pub solve: SolveReport,
    pub frame: Frame,
}

/// Optimizes `base` into a honeycomb that follows the design surface `surface` (`None`: the
/// base mesh itself, whose own zigzag boundary is then not imposed). Both are validated first.
pub fn optimize(
    base: &PolyMesh,
    surface: Option<&PolyMesh>,
    options: &OptimizeOptions,
    progress: &mut dyn FnMut(&IterationInfo),
) -> Result<Optimized> {
    options.weights.validate()?;
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

    let layout = Layout::new(mesh.vertices.len(), conn.num_edges());
    let normals = initial_normals(&mesh, &conn, &normalized_surface);
    let mut x = layout.pack(&mesh.vertices, &normals);
    let mut families = families(&mesh, &conn, &normalized_surface, &weights);
    if let Some(length) = options.min_edge {
        if !length.is_finite() || length <= 0.0 {
            return Err(crate::Error::Parameter(format!(
                "minimum edge length {length}: expected a positive length"
            )));
        }
        let family = min_edge_family(&mesh, &conn, length / frame.unit);
        x.extend(family.initial_dummies(&mesh.vertices));
        families.push(Box::new(family));
    }
    let mut solver = GuidedProjection::new(x.len(), families)?;
    let solve = solver.solve(&mut x, &options.solver, progress)?;

    let vertices: Vec<Vec3> = (0..layout.num_vertices)
        .map(|v| frame.to_model(layout.vertex_at(&x, v)))
        .collect();
    let normals: Vec<Vec3> = (0..layout.num_edges)
        .map(|e| layout.normal_at(&x, e).normalized())
        .collect();
    let optimized = PolyMesh::new(vertices, base.faces.clone());
    let axes = node_axes(&conn, &normals, |v| {
        normalized_surface.normal_at(layout.vertex_at(&x, v))
    });
    let thickness = options.thickness.unwrap_or(0.3 * frame.unit);
    let honeycomb = Honeycomb::new(optimized, &conn, axes, thickness);
    Ok(Optimized {
        honeycomb,
        connectivity: conn,
        normals,
        solve,
        frame,
    })
}
