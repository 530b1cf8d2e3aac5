//! Resizing one cell (paper Fig. 13): its walls move inwards by the same distance, the walls
//! leaving its corners stay. At a corner the two cell walls move by +t and -t as seen from
//! the corner, so the node condition holds for any t.

use super::cell_walls::inward_walls;
use super::translate_walls;
use crate::error::{Error, Result};
use crate::mesh::Connectivity;
use crate::structure::Honeycomb;

/// Moves every wall of `cell` inwards by `by` (model units; negative grows the cell).
pub fn resize_cell(h: &Honeycomb, conn: &Connectivity, cell: usize, by: f64) -> Result<Honeycomb> {
    let faces = &h.base.faces;
    let face = faces.get(cell).ok_or_else(|| {
        Error::Parameter(format!(
            "cell {cell} does not exist (the honeycomb has {} cells)",
            faces.len()
        ))
    })?;
    if !by.is_finite() {
        return Err(Error::Parameter(format!("resize by {by}: not a number")));
    }
    let p = &h.base.vertices;
    let mut lambda = vec![0.0; h.edges.len()];
    for (e, inward) in inward_walls(h, conn, cell, |e| h.wall_normal(e)) {
        // lambda moves the wall along its stored normal n_e; inward is +-n_e.
        lambda[e] = by * inward.dot(h.wall_normal(e));
    }
    let resized = translate_walls(h, conn, &lambda)?;
    // Refuse a resize that turns an edge of the cell or at its corners around.
    for &v in face {
        for &e in &conn.vertex_edges[v] {
            let [a, b] = h.edges[e];
            let (old, new) = (
                p[b] - p[a],
                resized.base.vertices[b] - resized.base.vertices[a],
            );
            if new.dot(old) <= 0.0 {
                return Err(Error::Parameter(format!(
                    "resize of cell {cell} by {by} turns edge {a}-{b} around: the cell (or its \
                     neighbour) would invert; use a smaller amount (edge length there {:.3})",
                    old.norm()
                )));
            }
        }
    }
    Ok(resized)
}
