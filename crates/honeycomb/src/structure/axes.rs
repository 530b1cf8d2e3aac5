//! Node axes: the line common to the walls at a node, by principal component analysis of the
//! wall normals there (the eigenvector of the smallest eigenvalue of `sum_j n_ij n_ij^T`).

use crate::geometry::{smallest_eigenvector, sum_of_outer_products, Vec3};
use crate::mesh::Connectivity;

/// One unit axis per vertex, oriented to the side of `side(v)` (the surface normal at v).
pub fn node_axes(
    conn: &Connectivity,
    wall_normals: &[Vec3],
    side: impl Fn(usize) -> Vec3,
) -> Vec<Vec3> {
    (0..conn.vertex_edges.len())
        .map(|v| {
            let normals = conn.vertex_edges[v].iter().map(|&e| wall_normals[e]);
            let axis = smallest_eigenvector(sum_of_outer_products(normals));
            if axis.dot(side(v)) < 0.0 {
                -axis
            } else {
                axis
            }
        })
        .collect()
}
