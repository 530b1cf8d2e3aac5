//! Field-aligned hexagonal remeshing, after "Instant Field-Aligned Meshes" (Jakob, Tarini,
//! Panozzo, Sorkine-Hornung 2015), for surfaces no flattening suits (the paper's section 3
//! starts from a hex mesh whose edges follow a 6-RoSy field, \[NPPZ12\] with \[BZK09\]).
//!
//! 1. `sampling`: S's triangles, refined until the fields have several samples per cell.
//! 2. `hierarchy`: coarser and coarser graphs over the samples, to solve fields fast.
//! 3. `orientation`: a smooth 6-RoSy field o (hex edge directions) aligned with S's boundary
//!    and with strokes.
//! 4. `position`: a smooth field of local triangular lattices whose points are cell centres.
//! 5. `extract`: the lattice points and triangles the two fields agree on.
//! 6. `tidy`: small holes filled, edge flips that annihilate neighbouring dislocations,
//!    light smoothing.
//! 7. `dual`: one hex vertex per lattice triangle, one cell per inner lattice vertex.

mod dual;
mod extract;
mod hierarchy;
mod orientation;
mod position;
mod sampling;
mod tangent;
mod tidy;

use crate::error::{Error, Result};
use crate::geometry::Vec3;
use crate::mesh::{validate_base_mesh, validate_surface_mesh, PolyMesh};
use crate::surface::Surface;
use hierarchy::Level;
use sampling::Sampling;
use tangent::SQRT3;

pub(crate) use extract::UnionFind;

/// Samples are refined until no edge is longer than this share of the lattice spacing. Any
/// point of such triangles is within 0.7 / sqrt 3 = 0.4 spacings of a sample, so each lattice
/// point has a sample nearer to it than to any other lattice point. Denser samples gave more
/// dislocations in measurements (at 0.5: 1 to 4 points fewer hexagons, twice the time).
const SAMPLE_SPACING: f64 = 0.7;

/// A trivalent hexagonal mesh on `surface` whose cells have edge length about `edge` (model units),
/// its hex edges following a smooth 6-RoSy field (aligned with S's boundary where S has one and
/// `follow_boundary` asks for it, and with `strokes` polylines if given), vertices exactly on
/// S. Deterministic for a seed.
///
/// "Aligned with the boundary" means hex edges along it or across it, whichever the field
/// finds closer (both keep a straight row of cells along the boundary); near a stroke the hex
/// edges run along it. Cells that S's boundary cuts are dropped, and of the rest the largest
/// piece is kept, so the result passes [`validate_base_mesh`]; its cells run counter-clockwise
/// seen from S's normals. Parameter and surface problems are [`Error::Parameter`] and
/// [`Error::Mesh`]; the function does not panic.
pub fn field_hex_mesh(
    surface: &PolyMesh,
    edge: f64,
    strokes: &[Vec<Vec3>],
    follow_boundary: bool,
    seed: u64,
) -> Result<PolyMesh> {
    crate::error::check_positive_length("edge_length", edge)?;
    if let Some((k, _)) = strokes
        .iter()
        .enumerate()
        .find(|(_, line)| line.iter().any(|p| !p.is_finite()))
    {
        return Err(Error::Parameter(format!(
            "stroke {k} has a non-finite point"
        )));
    }
    validate_surface_mesh(surface)?;
    let s = Surface::from_mesh(surface)?;
    let area = surface.area();
    let cells = area / super::hexagon_area(edge);
    if cells > super::MAX_CELLS as f64 {
        return Err(Error::Parameter(super::too_many_cells(
            "edge length",
            edge,
            area,
            cells,
        )));
    }
    let fits = cells >= 1.0; // false for a NaN area too
    if !fits {
        return Err(super::no_cell_fits("cell", edge, area, cells));
    }
    let spacing = SQRT3 * edge;
    let sampling = Sampling::new(&s, SAMPLE_SPACING * spacing)?;
    let fixed = orientation::constraints(&sampling, strokes, follow_boundary, spacing)?;
    let Sampling {
        points,
        normals,
        triangles,
        areas,
        ..
    } = sampling;
    let levels = hierarchy::build(Level::from_triangles(points, normals, areas, &triangles));
    let orientations = orientation::solve(&levels, &fixed, seed);
    let origins = position::solve(&levels, &orientations, spacing, seed);
    let mut lattice = extract::extract(&levels[0], &orientations[0], &origins, spacing);
    tidy::tidy(&mut lattice, spacing);
    let hex = dual::hex_mesh(&lattice, &s, edge);
    if hex.faces.is_empty() {
        return Err(super::no_cell_fits("whole cell", edge, area, cells));
    }
    validate_base_mesh(&hex).map_err(|e| {
        Error::Mesh(format!(
            "the field-aligned hex mesh is not a valid base mesh ({e}); try another seed"
        ))
    })?;
    Ok(hex)
}
