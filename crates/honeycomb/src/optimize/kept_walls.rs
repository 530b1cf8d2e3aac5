//! Solves on a finished honeycomb that keep its walls: every wall normal is fixed data, so each
//! node keeps its angles and its axis, and each edge stays in its wall plane (a linear row).
//! What moves is where the vertices sit on their walls: along the node axes (off S, priced by
//! closeness) and, held harder, along S. Capping by quads is such a solve.

use crate::constraints::{
    BoundedCloseness, Closeness, FixedNormalRow, FixedNormals, Layout, TangentialHold,
};
use crate::geometry::Vec3;
use crate::mesh::{Connectivity, PolyMesh};
use crate::solve::{Constraint, Role};
use crate::structure::Honeycomb;
use crate::surface::Surface;

/// The kept walls outweigh every other family (and `onto_kept_walls` takes out what residual
/// is left).
const KEPT_WALLS_WEIGHT: f64 = 1000.0;
/// How far off its wall an edge may end after `onto_kept_walls`, in mean edge lengths.
const WALL_ROUNDOFF: f64 = 1e-14;
/// A bound on the conjugate gradient steps of `onto_kept_walls` (which converge in as many
/// steps as there are walls in exact arithmetic, in far fewer on a mesh).
const MAX_PROJECTION_STEPS: usize = 2000;
/// The hold of each vertex along S (see `TangentialHold`), where it is held.
pub(crate) const HOLD_WEIGHT: f64 = 0.3;

/// The honeycomb's walls as realized: each through its edge and the axes at its ends.
pub(crate) fn realized_normals(h: &Honeycomb, conn: &Connectivity) -> Vec<Vec3> {
    (conn.edges.iter())
        .map(|&[a, b]| {
            let edge = h.base.vertices[b] - h.base.vertices[a];
            edge.cross(h.axes[a] + h.axes[b]).normalized()
        })
        .collect()
}

/// The vertices nearest `vertices` (in the least-squares sense) on which every kept wall holds
/// exactly: `n_e . (v_a - v_b) = 0` for each edge `e = [a, b]` and its wall normal `n_e`. A
/// kept-walls solve holds its walls by weighted rows, which give way a little where the other
/// families pull hard; this takes that residual out, so that every node keeps its angles to
/// roundoff. The correction is `A^T lambda` for the rows `A`, with `lambda` from conjugate
/// gradients on `A A^T lambda = A v`: its residual is the walls' own.
pub(crate) fn onto_kept_walls(
    vertices: &[Vec3],
    edges: &[[usize; 2]],
    normals: &[Vec3],
) -> Vec<Vec3> {
    let rows = |v: &[Vec3], out: &mut Vec<f64>| {
        out.clear();
        out.extend((edges.iter().zip(normals)).map(|(&[a, b], n)| n.dot(v[a] - v[b])));
    };
    let spread = |lambda: &[f64], out: &mut Vec<Vec3>| {
        out.clear();
        out.resize(vertices.len(), Vec3::ZERO);
        for ((&[a, b], &n), &l) in edges.iter().zip(normals).zip(lambda) {
            out[a] += n * l;
            out[b] -= n * l;
        }
    };
    let unit = (edges.iter())
        .map(|&[a, b]| (vertices[a] - vertices[b]).norm())
        .sum::<f64>()
        / edges.len().max(1) as f64;
    let tolerance = WALL_ROUNDOFF * unit;
    let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(a, b)| a * b).sum::<f64>();
    let mut residual = Vec::with_capacity(edges.len());
    rows(vertices, &mut residual);
    let mut lambda = vec![0.0; edges.len()];
    let mut direction = residual.clone();
    let mut rr = dot(&residual, &residual);
    let (mut moved, mut product) = (Vec::new(), Vec::new());
    for _ in 0..edges.len().min(MAX_PROJECTION_STEPS) {
        if residual.iter().all(|r| r.abs() <= tolerance) {
            break;
        }
        spread(&direction, &mut moved);
        rows(&moved, &mut product);
        let curvature = dot(&direction, &product);
        if curvature <= 0.0 {
            break;
        }
        let step = rr / curvature;
        for k in 0..edges.len() {
            lambda[k] += step * direction[k];
            residual[k] -= step * product[k];
        }
        let rr_next = dot(&residual, &residual);
        let keep = rr_next / rr;
        rr = rr_next;
        for (d, r) in direction.iter_mut().zip(&residual) {
            *d = r + keep * *d;
        }
    }
    spread(&lambda, &mut moved);
    (vertices.iter().zip(&moved))
        .map(|(v, m)| *v - *m)
        .collect()
}

/// The families every kept-walls solve has over the vertices of `normalized` (the first
/// unknowns, as `layout` reads them): the kept walls (`normals`, one per edge of `conn`),
/// closeness to `surface` at a weight (firming up vertex by vertex past a bound: see
/// `BoundedCloseness`) and the hold along S at weight `hold`.
pub(crate) fn kept_wall_families<'a>(
    layout: Layout,
    normalized: &PolyMesh,
    (conn, normals): (&Connectivity, &[Vec3]),
    surface: &'a Surface,
    (closeness, bound): (f64, f64),
    hold: f64,
) -> Vec<Box<dyn Constraint + 'a>> {
    let walls = (conn.edges.iter().zip(normals))
        .map(|(&[a, b], &normal)| FixedNormalRow { normal, a, b })
        .collect();
    let closeness = BoundedCloseness::new(Closeness::new(layout, surface, closeness), bound);
    vec![
        Box::new(FixedNormals {
            name: "kept_walls",
            layout,
            rows: walls,
            weight: KEPT_WALLS_WEIGHT,
            role: Role::Condition,
        }),
        Box::new(closeness),
        Box::new(TangentialHold::new(
            layout,
            &normalized.vertices,
            |p| surface.normal_at(p),
            hold,
        )),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::Shape;
    use crate::structure::{measure, node_axes};
    use crate::tests::default_honeycomb;

    /// Vertices knocked off their walls come back onto them exactly (the walls' own rows and
    /// the node angles measured from the realized walls both to roundoff), by a move no longer
    /// than the knock: the nearest such vertices, where the honeycomb's own are one choice.
    #[test]
    fn knocked_vertices_come_back_onto_their_walls() {
        let (surface, h, conn) = default_honeycomb(Shape::Wave, 300);
        let normals = realized_normals(&h, &conn);
        let unit = h.base.mean_edge_length();
        // A deterministic knock of about a thousandth of an edge per coordinate.
        let knock = |i: usize| ((i as f64 * 12.9898).sin() * 43758.5453).fract() * 1e-3 * unit;
        let knocked: Vec<Vec3> = (h.base.vertices.iter().enumerate())
            .map(|(v, p)| *p + Vec3::new(knock(3 * v), knock(3 * v + 1), knock(3 * v + 2)))
            .collect();
        let off = |v: &[Vec3]| {
            (conn.edges.iter().zip(&normals))
                .map(|(&[a, b], n)| n.dot(v[a] - v[b]).abs())
                .fold(0.0, f64::max)
        };
        assert!(off(&knocked) > 1e-4 * unit, "the knock left the walls");
        let back = onto_kept_walls(&knocked, &conn.edges, &normals);
        assert!(off(&back) <= 1e-12 * unit, "{}", off(&back) / unit);
        let distance = |x: &[Vec3], y: &[Vec3]| {
            x.iter()
                .zip(y)
                .map(|(p, q)| (*p - *q).norm_squared())
                .sum::<f64>()
        };
        assert!(distance(&back, &knocked) <= distance(&h.base.vertices, &knocked));
        let axes = node_axes(&conn, &normals, |v| h.axes[v]);
        let realized = Honeycomb::new(
            PolyMesh::new(back, h.base.faces.clone()),
            &conn,
            axes,
            h.thickness,
        );
        let m = measure(&realized, &surface);
        assert!(m.omega_max_deg < 1e-6 && m.delta_max < 1e-10, "{m:?}");
    }
}
