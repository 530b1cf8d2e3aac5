//! Resizing one cell (paper Fig. 13): its walls move inwards by the same distance, the walls
//! leaving its corners stay. At a corner the two cell walls move by +t and -t as seen from
//! the corner, so the node condition holds for any t.

use super::cell_walls::inward_walls;
use super::translate::wall_shifts;
use super::validated;
use crate::error::{rounded, short_number, Error, Result};
use crate::mesh::{Connectivity, PolyMesh};
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
    let what = format!("resize of cell {cell} by {}", short_number(by));
    if !by.is_finite() {
        return Err(Error::Parameter(format!("{what}: not a finite distance")));
    }
    let p = &h.base.vertices;
    let mut lambda = vec![0.0; h.edges.len()];
    for (e, inward) in inward_walls(h, conn, cell, |e| h.wall_normal(e)) {
        // A unit amount: lambda moves the wall along its stored normal n_e; inward is +-n_e.
        lambda[e] = inward.dot(h.wall_normal(e));
    }
    // The corners move linearly with the amount: by * unit.
    let unit = wall_shifts(h, conn, &lambda)?;
    // An edge at a corner, d = p_b - p_a, keeps its direction while |d|^2 + by (u_b - u_a).d > 0:
    // the amounts between the tightest bounds from below and above, each with its edge.
    let (mut shrink, mut grow) = ((f64::INFINITY, 0), (f64::NEG_INFINITY, 0));
    for &v in face {
        for &e in &conn.vertex_edges[v] {
            let [a, b] = h.edges[e];
            let d = p[b] - p[a];
            let rate = (unit[b] - unit[a]).dot(d);
            let limit = -d.norm_squared() / rate;
            if rate < 0.0 && limit < shrink.0 {
                shrink = (limit, e);
            } else if rate > 0.0 && limit > grow.0 {
                grow = (limit, e);
            }
        }
    }
    if !(grow.0 < by && by < shrink.0) {
        let [a, b] = h.edges[if by > 0.0 { shrink.1 } else { grow.1 }];
        return Err(Error::Parameter(format!(
            "{what} turns edge {a}-{b} around: the cell (or its neighbour) would invert; \
             expected an amount between {} and {} (edge length there {})",
            rounded(grow.0, 3),
            rounded(shrink.0, 3),
            rounded((p[b] - p[a]).norm(), 3)
        )));
    }
    let vertices = p.iter().zip(&unit).map(|(&q, &u)| q + u * by).collect();
    let base = PolyMesh::new(vertices, faces.clone());
    validated(&what, &base)?;
    Ok(Honeycomb::new(base, conn, h.axes.clone(), h.thickness))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{inner_cell, upright_hex_disk};

    /// The middle hexagon of a disk of regular hexagons of edge 1: its sides vanish when its
    /// walls move in by sqrt(3)/2, the edges leaving its corners when they move out as far.
    #[test]
    fn the_range_is_where_no_edge_turns_around() {
        let (h, conn) = upright_hex_disk(2.0, 0.3);
        let middle = inner_cell(&h, &conn);
        let limit = 3f64.sqrt() / 2.0;
        for by in [0.99 * limit, -0.99 * limit] {
            resize_cell(&h, &conn, middle, by).unwrap();
        }
        for by in [1.01 * limit, -1.01 * limit, 1e308, -1e308] {
            let message = resize_cell(&h, &conn, middle, by).unwrap_err().to_string();
            assert!(
                message.contains(&format!("cell {middle} by {}", short_number(by))),
                "{message}"
            );
            assert!(message.contains("turns edge"), "{message}");
            assert!(
                message.contains("expected an amount between -0.866 and 0.866"),
                "{message}"
            );
        }
    }
}
