//! Subdivision by shrinking every cell (paper Fig. 14): each cell's walls move inwards, and the
//! space freed along every interior wall becomes a new hexagonal cell. Every new node sits on a
//! parallel copy of an old node's walls, so it has that node's axis: the spherical image is
//! unchanged, and angles are kept. Cells: one per old cell and one per interior wall (4x for a
//! large hexagonal patch).

use super::cell_walls::inward_walls;
use super::translate::axis_plane_shift;
use super::{validated, FINEST};
use crate::error::{short_number, Error, Result};
use crate::geometry::Vec3;
use crate::mesh::{Connectivity, PolyMesh};
use crate::structure::Honeycomb;
use std::collections::HashMap;

/// Shrinks every cell to `shrink` times its size (1e-6 to 1 - 1e-6; walls move inwards by
/// `1 - shrink` times the mean distance of the cell's walls from its centroid).
pub fn subdivide(
    h: &Honeycomb,
    conn: &Connectivity,
    shrink: f64,
) -> Result<(Honeycomb, Connectivity)> {
    let what = format!("subdivide with shrink {}", short_number(shrink));
    // Near 0 the old cells, near 1 the new ones along the walls, shrink to points.
    if !(FINEST..=1.0 - FINEST).contains(&shrink) {
        return Err(Error::Parameter(format!(
            "{what}: expected a fraction between {FINEST:e} and 1 - {FINEST:e} (0.5 gives \
             cells of about one size)"
        )));
    }
    let faces = &h.base.faces;
    let p = &h.base.vertices;
    let normals: Vec<Vec3> = (0..h.edges.len()).map(|e| h.wall_normal(e)).collect();
    let mut vertices: Vec<Vec3> = Vec::new();
    let mut axes: Vec<Vec3> = Vec::new();
    // The old nodes keep their place (when a new cell uses them), then one corner per cell corner.
    let mut node_index: HashMap<usize, usize> = HashMap::new();
    let mut corner_index: HashMap<(usize, usize), usize> = HashMap::new();
    let mut new_faces: Vec<Vec<usize>> = Vec::with_capacity(faces.len() + h.edges.len());

    for (c, face) in faces.iter().enumerate() {
        let n = face.len();
        let centroid = h.base.face_centroid(c);
        let inward = inward_walls(h, conn, c, |e| normals[e]);
        let radius = inward
            .iter()
            .zip(face)
            .map(|(&(_, m), &v)| m.dot(centroid - p[v]))
            .sum::<f64>()
            / n as f64;
        let t = (1.0 - shrink) * radius;
        let mut loop_ = Vec::with_capacity(n);
        for k in 0..n {
            let v = face[k];
            // At corner v the walls k-1 and k of the cell move inwards by t; its other walls stay.
            let walls: Vec<(Vec3, f64)> = conn.vertex_edges[v]
                .iter()
                .map(|&e| {
                    let s = conn.edge_sign(e, v);
                    let n_v = normals[e] * s;
                    let shift = [inward[k], inward[(k + n - 1) % n]]
                        .iter()
                        .find(|(ce, _)| *ce == e)
                        .map_or(0.0, |&(_, m)| t * m.dot(n_v));
                    (n_v, shift)
                })
                .collect();
            vertices.push(p[v] + axis_plane_shift(h.axes[v], &walls));
            axes.push(h.axes[v]);
            corner_index.insert((v, c), vertices.len() - 1);
            loop_.push(vertices.len() - 1);
        }
        new_faces.push(loop_);
    }
    let mut node = |v: usize, vertices: &mut Vec<Vec3>, axes: &mut Vec<Vec3>| -> usize {
        *node_index.entry(v).or_insert_with(|| {
            vertices.push(p[v]);
            axes.push(h.axes[v]);
            vertices.len() - 1
        })
    };
    for (e, &[i, j]) in h.edges.iter().enumerate() {
        let [Some(fa), Some(fb)] = conn.edge_faces[e] else {
            continue; // boundary wall: nothing on its outer side
        };
        // Cell A runs i -> j along this wall, cell B runs j -> i.
        let runs_i_to_j = |f: usize| {
            let face = &faces[f];
            let k = face
                .iter()
                .position(|&v| v == i)
                .expect("edge endpoint in its face");
            face[(k + 1) % face.len()] == j
        };
        let (a, b) = if runs_i_to_j(fa) { (fa, fb) } else { (fb, fa) };
        let (vi, vj) = (
            node(i, &mut vertices, &mut axes),
            node(j, &mut vertices, &mut axes),
        );
        new_faces.push(vec![
            corner_index[&(j, a)],
            corner_index[&(i, a)],
            vi,
            corner_index[&(i, b)],
            corner_index[&(j, b)],
            vj,
        ]);
    }
    let base = PolyMesh::new(vertices, new_faces);
    let conn = validated(&what, &base)?;
    Ok((Honeycomb::new(base, &conn, axes, h.thickness), conn))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::upright_hex_disk;

    #[test]
    fn a_shrink_that_leaves_points_is_refused() {
        let (h, conn) = upright_hex_disk(2.0, 0.3);
        for shrink in [1e-320, 1e-9, 1.0 - 1e-9, 0.0, 1.0, f64::NAN] {
            let message = subdivide(&h, &conn, shrink).unwrap_err().to_string();
            assert!(
                message.contains(&format!(
                    "shrink {}: expected a fraction between 1e-6 and 1 - 1e-6",
                    short_number(shrink)
                )),
                "{message}"
            );
        }
        for shrink in [1e-3, 0.5, 0.999] {
            subdivide(&h, &conn, shrink).unwrap();
        }
    }
}
