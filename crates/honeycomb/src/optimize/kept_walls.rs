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

/// The kept walls hold to roundoff: everything else gives way to them.
const KEPT_WALLS_WEIGHT: f64 = 1000.0;
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
