//! The largest work an option may ask for, checked before anything is allocated: beyond these a
//! run would exhaust the memory of a 24 GiB machine or run for days, and a typo (an extra
//! zero) should get an error at once rather than either. The lattice's own bounds are in
//! [`crate::init`] ([`crate::init::MAX_CELLS`], [`crate::init::edge_length_range`]), the
//! picture's in `render::WIDTHS`.

use crate::error::{Error, Result};
use crate::init::{hexagon_area, CellSize, InitOptions};
use crate::mesh::PolyMesh;

/// Base-mesh vertices one solve takes at most: its factorization's fill grows faster than the
/// mesh (140k vertices take about 3.5 GiB), so this is about 9 GiB.
pub const MAX_SOLVE_VERTICES: usize = 300_000;

/// Iterations times base-mesh vertices at most: about an hour at 140k vertices, half an hour
/// at 10k.
pub const MAX_VERTEX_ITERATIONS: usize = 100_000_000;

/// A hexagonal mesh has about two vertices per cell.
const VERTICES_PER_CELL: usize = 2;

/// Cells a solve takes at most.
pub const MAX_SOLVE_CELLS: usize = MAX_SOLVE_VERTICES / VERTICES_PER_CELL;

/// Vertices a built-in surface's mesh may be asked for (`demo --vertices`, `bench --sizes`):
/// [`crate::generate::lifted_hex_patch`] comes up to 1% above the count asked (a whole ring
/// of cells, or a whole row of the roof), and the mesh must stay within a solve's
/// [`MAX_SOLVE_VERTICES`].
pub const MAX_GENERATED_VERTICES: usize = 295_000;
/// And at least: fewer make a patch of a handful of cells.
pub const MIN_GENERATED_VERTICES: usize = 50;

/// `option` (`--vertices`, `--sizes`) asking for a built-in surface's mesh of `vertices`:
/// refused outside [`MIN_GENERATED_VERTICES`] to [`MAX_GENERATED_VERTICES`].
pub fn check_generated_vertices(option: &str, vertices: usize) -> Result<()> {
    if !(MIN_GENERATED_VERTICES..=MAX_GENERATED_VERTICES).contains(&vertices) {
        return Err(Error::Parameter(format!(
            "{option} {vertices}: expected {MIN_GENERATED_VERTICES} to \
             {MAX_GENERATED_VERTICES} vertices (a built-in surface's mesh comes up to 1% \
             larger than asked, and a solve takes at most {MAX_SOLVE_VERTICES})"
        )));
    }
    Ok(())
}

/// `option value` (e.g. `--vertices 5000000`) asks for a solve of `vertices` vertices:
/// refused beyond [`MAX_SOLVE_VERTICES`].
pub fn check_solve_vertices(option: &str, vertices: usize) -> Result<()> {
    if vertices > MAX_SOLVE_VERTICES {
        return Err(Error::Parameter(format!(
            "{option}: a solve of about {vertices} vertices; expected at most \
             {MAX_SOLVE_VERTICES} (its factorization would need more memory than a machine \
             of 24 GiB has)"
        )));
    }
    Ok(())
}

/// The cells of `init`'s size that a solve will take: `--cells` as asked, `--edge-length` on
/// `surface`'s area (and within the lattice's own range there,
/// [`crate::init::check_edge_length`]).
pub fn check_solve_cells(init: &InitOptions, surface: &PolyMesh) -> Result<()> {
    crate::init::check_edge_length(surface, init)?;
    let (field, value, cells) = match init.size {
        CellSize::Cells(n) => ("cells", n.to_string(), n as f64),
        CellSize::EdgeLength(l) => (
            "edge_length",
            crate::error::rounded(l, 6).to_string(),
            surface.area() / hexagon_area(1.0) / l / l,
        ),
    };
    if cells > MAX_SOLVE_CELLS as f64 {
        return Err(Error::option(
            field,
            value,
            format!(
                "{} to solve; expected at most {MAX_SOLVE_CELLS} (a solve takes at most \
                 {MAX_SOLVE_VERTICES} vertices)",
                crate::error::about(cells, "cells")
            ),
        ));
    }
    Ok(())
}

/// `iterations` of a solve of `base`: refused beyond [`MAX_VERTEX_ITERATIONS`] and beyond
/// [`MAX_SOLVE_VERTICES`].
pub fn check_solve(base: &PolyMesh, iterations: usize) -> Result<()> {
    let vertices = base.vertices.len();
    if vertices > MAX_SOLVE_VERTICES {
        return Err(Error::Parameter(format!(
            "the base mesh has {vertices} vertices; a solve takes at most {MAX_SOLVE_VERTICES} \
             (its factorization would need more memory than a machine of 24 GiB has)"
        )));
    }
    let most = MAX_VERTEX_ITERATIONS / vertices.max(1);
    if iterations > most {
        return Err(Error::option(
            "iterations",
            iterations,
            format!(
                "on {vertices} vertices expected at most {most} ({MAX_VERTEX_ITERATIONS:e} \
                 vertex-iterations, about an hour at 140k vertices)"
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_beyond_the_bounds_are_refused_naming_the_option() {
        let sized = InitOptions::new;
        let e = check_solve_vertices("--vertices 2000000", 2_000_000).unwrap_err();
        assert!(
            e.to_string()
                .contains("--vertices 2000000: a solve of about"),
            "{e}"
        );
        check_solve_vertices("--vertices 1500", 1500).unwrap();
        // A unit square: 1e-3 edges make about 385k cells.
        let square = PolyMesh::unit_square();
        let e = check_solve_cells(&sized(CellSize::EdgeLength(1e-3)), &square).unwrap_err();
        assert!(
            e.to_string()
                .contains("edge_length 0.001: about 384900 cells"),
            "{e}"
        );
        let e = check_solve_cells(&sized(CellSize::Cells(1_000_000)), &square).unwrap_err();
        assert!(
            e.to_string().contains("cells 1000000: about 1000000 cells"),
            "{e}"
        );
        check_solve_cells(&sized(CellSize::Cells(150_000)), &square).unwrap();
        check_solve_cells(&sized(CellSize::EdgeLength(0.5)), &square).unwrap();
        let e = check_solve_cells(&sized(CellSize::EdgeLength(1e308)), &square).unwrap_err();
        assert!(
            e.to_string()
                .contains("--edge-length 1e308: no cell of that size fits"),
            "{e}"
        );
        let e = check_solve(&square, 30_000_000).unwrap_err();
        assert!(
            e.to_string()
                .contains("iterations 30000000: on 4 vertices expected at most 25000000"),
            "{e}"
        );
        check_solve(&square, 10_000).unwrap();
    }

    /// The largest mesh of a built-in surface that may be asked for is one a solve takes:
    /// `demo --vertices 295000` is not refused for its size.
    #[test]
    fn the_largest_generated_mesh_is_within_a_solve() {
        use crate::generate::{lifted_hex_patch, Shape};
        for shape in [
            Shape::Saddle,
            Shape::Dome,
            Shape::Cylinder,
            Shape::Cone,
            Shape::Wave,
            Shape::Roof,
        ] {
            let (base, _) = lifted_hex_patch(shape, MAX_GENERATED_VERTICES);
            let n = base.vertices.len();
            assert!(n <= MAX_SOLVE_VERTICES, "{shape:?}: {n} vertices");
            check_solve(&base, 10).unwrap();
            // Up to 1% over the count asked, as the message says.
            assert!(
                n as f64 <= 1.01 * MAX_GENERATED_VERTICES as f64,
                "{shape:?}: {n}"
            );
        }
        check_generated_vertices("--vertices", MAX_GENERATED_VERTICES).unwrap();
        check_generated_vertices("--vertices", 50).unwrap();
        for bad in [49, MAX_GENERATED_VERTICES + 1, 300_000] {
            let e = check_generated_vertices("--vertices", bad).unwrap_err();
            let shown = format!("--vertices {bad}: expected 50 to 295000 vertices");
            assert!(e.to_string().contains(&shown), "{e}");
        }
    }
}
