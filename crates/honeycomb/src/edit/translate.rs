//! Parallel translation of walls (paper section 4, "Local edits"): moving walls keeps every
//! angle between them, so a honeycomb stays a honeycomb as long as the three walls of each node
//! still meet in a line, which is `lambda_ij + lambda_ik + lambda_il = 0` (their normals form
//! an equilateral triangle). Node axes keep their directions; each vertex moves to the closest
//! point of its moved axis, i.e. by the least-norm solution of `n_ij . dv = lambda_ij`.

use super::validated;
use crate::error::{Error, Result};
use crate::geometry::Vec3;
use crate::mesh::{Connectivity, PolyMesh};
use crate::structure::Honeycomb;

/// Moves the wall of every edge `e` by `lambda[e]` along its normal `n_e` (as seen from the
/// edge's first vertex). Fails, naming the nodes, when the walls of a trivalent node would no
/// longer share an axis.
pub fn translate_walls(h: &Honeycomb, conn: &Connectivity, lambda: &[f64]) -> Result<Honeycomb> {
    let shifts = wall_shifts(h, conn, lambda)?;
    let vertices: Vec<Vec3> = (h.base.vertices.iter().zip(&shifts))
        .map(|(&p, &d)| p + d)
        .collect();
    let base = PolyMesh::new(vertices, h.base.faces.clone());
    validated("the translation", &base)?;
    Ok(Honeycomb::new(base, conn, h.axes.clone(), h.thickness))
}

/// How far each vertex moves when the walls move by `lambda` (see [`translate_walls`]): linear
/// in `lambda`, so an edit can scale the shifts of a unit move.
pub(crate) fn wall_shifts(h: &Honeycomb, conn: &Connectivity, lambda: &[f64]) -> Result<Vec<Vec3>> {
    if lambda.len() != h.edges.len() {
        return Err(Error::Parameter(format!(
            "{} wall translations for {} walls",
            lambda.len(),
            h.edges.len()
        )));
    }
    if let Some(e) = lambda.iter().position(|l| !l.is_finite()) {
        return Err(Error::Parameter(format!(
            "translation of wall {e} is not finite"
        )));
    }
    let scale = lambda
        .iter()
        .fold(0.0f64, |m, l| m.max(l.abs()))
        .max(1e-300);
    let normals: Vec<Vec3> = (0..h.edges.len()).map(|e| h.wall_normal(e)).collect();
    // Per node: its walls as (normal seen from the node, translation seen from the node).
    let walls_at = |v: usize| -> Vec<(Vec3, f64)> {
        conn.vertex_edges[v]
            .iter()
            .map(|&e| {
                let s = conn.edge_sign(e, v);
                (normals[e] * s, lambda[e] * s)
            })
            .collect()
    };
    let broken: Vec<String> = (0..h.base.vertices.len())
        .filter(|&v| conn.valence(v) == 3)
        .filter_map(|v| {
            let sum: f64 = walls_at(v).iter().map(|w| w.1).sum();
            (sum.abs() > 1e-9 * scale).then(|| format!("node {v} (sum {sum:.3e})"))
        })
        .collect();
    if !broken.is_empty() {
        return Err(Error::Parameter(format!(
            "the translation breaks {} node(s): the three walls of a node must move by amounts \
             summing to 0 to keep a common axis: {}{}",
            broken.len(),
            broken[..broken.len().min(5)].join(", "),
            if broken.len() > 5 { ", ..." } else { "" }
        )));
    }
    Ok((0..h.base.vertices.len())
        .map(|v| axis_plane_shift(h.axes[v], &walls_at(v)))
        .collect())
}

/// The least-norm `dv` with `n . dv = lambda` for every wall `(n, lambda)` at a node: it lies
/// in the plane across the axis, where the walls' normals live, so the vertex stays on the
/// closest point of its (moved) axis.
pub(crate) fn axis_plane_shift(axis: Vec3, walls: &[(Vec3, f64)]) -> Vec3 {
    let u = axis.any_orthogonal();
    let w = axis.cross(u);
    // Least squares in (u, w): [sum p p^T] c = sum p lambda, p = (n.u, n.w).
    let (mut a, mut b, mut d, mut r0, mut r1) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for &(n, l) in walls {
        let (p0, p1) = (n.dot(u), n.dot(w));
        a += p0 * p0;
        b += p0 * p1;
        d += p1 * p1;
        r0 += p0 * l;
        r1 += p1 * l;
    }
    let det = a * d - b * b;
    if det.abs() < 1e-300 {
        return Vec3::ZERO;
    }
    let c0 = (d * r0 - b * r1) / det;
    let c1 = (a * r1 - b * r0) / det;
    u * c0 + w * c1
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{inner_cell, upright_hex_disk};

    /// The middle cell's walls moved inwards by 1e308 (a resize): every node sum holds, but
    /// the corners' shifts overflow.
    #[test]
    fn a_translation_beyond_the_numbers_is_refused() {
        let (h, conn) = upright_hex_disk(2.0, 0.3);
        let cell = inner_cell(&h, &conn);
        let mut lambda = vec![0.0; h.edges.len()];
        for (e, inward) in
            super::super::cell_walls::inward_walls(&h, &conn, cell, |e| h.wall_normal(e))
        {
            lambda[e] = 1e308 * inward.dot(h.wall_normal(e));
        }
        let message = translate_walls(&h, &conn, &lambda).unwrap_err().to_string();
        assert!(
            message.contains("the translation leaves no valid structure: vertex"),
            "{message}"
        );
        assert!(message.contains("non-finite coordinate"), "{message}");
    }
}
