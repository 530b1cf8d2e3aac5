//! Tests across modules: scenarios of the solver, the variants, the edits and the base
//! meshes on built-in surfaces (and on `../shared/data` where it is present).

mod cells;
mod edit;
mod init;
mod optimize;
mod parallel;
mod quads;
mod retries;
mod shading;
mod variants;

use crate::generate::{design_surface, Shape};
use crate::init::lifted_grid;
use crate::mesh::{validate_base_mesh, Connectivity, PolyMesh};
use crate::optimize::{OptimizeOptions, Weights};
use crate::solve::SolverOptions;
use crate::structure::Honeycomb;
use crate::surface::Surface;
use crate::{pipeline, PipelineOptions, Progress};
use std::path::PathBuf;

/// The guided projection with the node axes guided towards S's normals and no opposite-wall
/// fairness, 15 iterations: walls across a developable such as a cylinder.
fn guided_to_the_normals() -> OptimizeOptions {
    OptimizeOptions {
        weights: Weights {
            guide: 3.0,
            fairness: 0.0,
            ..Weights::default()
        },
        solver: SolverOptions {
            max_iterations: 15,
            ..SolverOptions::default()
        },
        ..OptimizeOptions::default()
    }
}

/// The height field `height` over the unit square, `n` x `n` squares each cut in two.
fn height_field(n: usize, height: impl Fn(f64, f64) -> f64) -> Surface {
    let (vertices, triangles) = lifted_grid(n, height);
    let faces = triangles.iter().map(|t| t.to_vec()).collect();
    Surface::new(PolyMesh::new(vertices, faces)).unwrap()
}

/// `../shared/data` beside the repository, when it is there (tests that read it skip otherwise).
fn shared_data() -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data");
    dir.is_dir().then_some(dir)
}

/// The default pipeline's honeycomb (walls across S) of about `cells` cells on a built-in
/// surface, with the surface and the honeycomb's connectivity: where the tests of what comes
/// after the solve (capping, deeper walls) start.
pub(crate) fn default_honeycomb(shape: Shape, cells: usize) -> (Surface, Honeycomb, Connectivity) {
    let surface = Surface::new(design_surface(shape)).unwrap();
    let options = PipelineOptions::new(cells);
    let out = pipeline(&surface, &options, &mut Progress::silent()).unwrap();
    let conn = validate_base_mesh(&out.honeycomb.base).unwrap();
    (surface, out.honeycomb, conn)
}
