//! The walls of one cell with their normals turned into the cell, as resize and subdivide
//! move them.

use crate::geometry::Vec3;
use crate::mesh::Connectivity;
use crate::structure::Honeycomb;

/// For each side `k` of `cell`: its edge and the unit wall normal pointing into the cell.
pub(crate) fn inward_walls(
    h: &Honeycomb,
    conn: &Connectivity,
    cell: usize,
    normal: impl Fn(usize) -> Vec3,
) -> Vec<(usize, Vec3)> {
    let (face, p) = (&h.base.faces[cell], &h.base.vertices);
    let centroid = h.base.face_centroid(cell);
    let n = face.len();
    (0..n)
        .map(|k| {
            let e = conn.face_edges[cell][k];
            let m = normal(e);
            let mid = (p[face[k]] + p[face[(k + 1) % n]]) * 0.5;
            (e, if m.dot(centroid - mid) >= 0.0 { m } else { -m })
        })
        .collect()
}
