//! Resizing one cell (paper Fig. 13): its walls move inwards by the same distance, the walls
//! leaving its corners stay. At a corner the two cell walls move by +t and -t as seen from
//! the corner, so the node condition holds for any t.

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
    let centroid = face
        .iter()
        .fold(crate::geometry::Vec3::ZERO, |c, &v| c + p[v])
        / face.len() as f64;
    let mut lambda = vec![0.0; h.edges.len()];
    for (k, &e) in conn.face_edges[cell].iter().enumerate() {
        let (a, b) = (face[k], face[(k + 1) % face.len()]);
        // The wall normal seen from the edge's start, turned to point into the cell.
        let s = conn.edge_sign(e, a);
        let m = h.wall_normal(e) * s;
        let inward = if m.dot(centroid - (p[a] + p[b]) * 0.5) >= 0.0 {
            1.0
        } else {
            -1.0
        };
        lambda[e] = inward * by * s;
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
