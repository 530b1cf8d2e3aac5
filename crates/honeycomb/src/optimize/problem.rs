//! Builds the honeycomb's constraint families over a base mesh and a reference surface, both
//! in the normalized frame.

use super::Weights;
use crate::constraints::{
    BoundaryCurve, Closeness, Layout, MinEdgeLength, Node2, Node3, Normalization, OppositeWalls,
    PrescribedAxes, WallConsistency, WallPlane,
};
use crate::geometry::Vec3;
use crate::mesh::{Connectivity, PolyMesh};
use crate::solve::{Constraint, Role};
use crate::surface::Surface;

/// Boundary vertices closer than this (normalized units) to S's boundary are kept on it.
const ON_BOUNDARY: f64 = 0.25;

/// Initial wall normals: each edge direction rotated by -90 degrees about the surface normal at
/// its midpoint, `n_ab = (v_a - v_b)/|v_a - v_b| x N`. At a regular node they sum to zero.
pub fn initial_normals(mesh: &PolyMesh, conn: &Connectivity, surface: &Surface) -> Vec<Vec3> {
    conn.edges
        .iter()
        .map(|&[a, b]| {
            let (pa, pb) = (mesh.vertices[a], mesh.vertices[b]);
            let n = surface.normal_at((pa + pb) * 0.5);
            (pa - pb).normalized().cross(n).normalized()
        })
        .collect()
}

/// Where each block of three unknowns sits, for the solver's ordering: a vertex at its
/// position, a wall normal at its edge's midpoint; blocks appended by variants are unplaced.
pub fn block_positions(mesh: &PolyMesh, conn: &Connectivity, unknowns: usize) -> Vec<Option<Vec3>> {
    let vertices = mesh.vertices.iter().map(|&p| Some(p));
    let midpoints = conn
        .edges
        .iter()
        .map(|&[a, b]| Some((mesh.vertices[a] + mesh.vertices[b]) * 0.5));
    let mut positions: Vec<Option<Vec3>> = vertices.chain(midpoints).collect();
    positions.resize(unknowns.div_ceil(3).max(positions.len()), None);
    positions
}

/// Vertices of the base mesh's boundary that start on S's boundary.
pub fn boundary_vertices_on_surface_boundary(
    mesh: &PolyMesh,
    conn: &Connectivity,
    surface: &Surface,
) -> Vec<usize> {
    (0..mesh.vertices.len())
        .filter(|&v| conn.is_boundary_vertex[v])
        .filter(|&v| {
            surface
                .closest_boundary_point(mesh.vertices[v])
                .is_some_and(|b| b.distance < ON_BOUNDARY)
        })
        .collect()
}

/// Pairs of opposite walls of every hexagonal cell, with the sign of each wall normal as seen
/// from the cell's orientation.
fn opposite_wall_pairs(mesh: &PolyMesh, conn: &Connectivity) -> Vec<[(usize, f64); 2]> {
    let mut pairs = Vec::new();
    for (f, face) in mesh.faces.iter().enumerate() {
        if face.len() != 6 {
            continue;
        }
        let m = |k: usize| {
            let e = conn.face_edges[f][k];
            (e, conn.edge_sign(e, face[k]))
        };
        for k in 0..3 {
            pairs.push([m(k), m(k + 3)]);
        }
    }
    pairs
}

/// The minimum-edge-length family for `length` (normalized units), with its dummies placed
/// right after the honeycomb's unknowns.
pub fn min_edge_family(mesh: &PolyMesh, conn: &Connectivity, length: f64) -> MinEdgeLength {
    let layout = Layout::new(mesh.vertices.len(), conn.num_edges());
    MinEdgeLength::new(layout, conn.edges.clone(), length, layout.len(), 1.0)
}

/// Puts every edge's wall plane with an offset of its own ([`WallPlane`]) among `families` in
/// place of the wall consistency: both ends on the wall's plane instead of the edge in it, so
/// that no row couples two vertices and the solver can eliminate the vertices before it
/// factors. The offsets, one unknown per edge measured from the edge's midpoint in `x` (laid
/// out as [`Layout`] first), are appended to `x`.
pub(crate) fn use_wall_planes<'a>(
    families: &mut Vec<Box<dyn Constraint + 'a>>,
    mesh: &PolyMesh,
    conn: &Connectivity,
    x: &mut Vec<f64>,
    weight: f64,
) {
    families.retain(|f| f.name() != WallConsistency::NAME);
    families.push(Box::new(wall_planes(mesh, conn, x, weight)));
}

fn wall_planes(mesh: &PolyMesh, conn: &Connectivity, x: &mut Vec<f64>, weight: f64) -> WallPlane {
    let layout = Layout::new(mesh.vertices.len(), conn.num_edges());
    let anchors = conn
        .edges
        .iter()
        .map(|&[a, b]| (layout.vertex_at(x, a) + layout.vertex_at(x, b)) * 0.5)
        .collect();
    let planes = WallPlane {
        layout,
        edges: conn.edges.clone(),
        offsets: (x.len()..x.len() + conn.num_edges()).collect(),
        anchors,
        weight,
    };
    // Each wall starts through its edge's midpoint, which is its anchor: offset 0.
    x.resize(x.len() + conn.num_edges(), 0.0);
    planes
}

/// The walls (edge, sign seen from the node) at every node of valence 3 and of valence 2.
#[allow(clippy::type_complexity)]
pub fn node_walls(conn: &Connectivity) -> (Vec<[(usize, f64); 3]>, Vec<[(usize, f64); 2]>) {
    let mut node3 = Vec::new();
    let mut node2 = Vec::new();
    for (v, edges) in conn.vertex_edges.iter().enumerate() {
        let walls: Vec<(usize, f64)> = edges.iter().map(|&e| (e, conn.edge_sign(e, v))).collect();
        match walls.len() {
            3 => node3.push([walls[0], walls[1], walls[2]]),
            2 => node2.push([walls[0], walls[1]]),
            _ => {} // rejected by validation before we get here
        }
    }
    (node3, node2)
}

pub fn families<'a>(
    mesh: &PolyMesh,
    conn: &Connectivity,
    surface: &'a Surface,
    weights: &Weights,
) -> Vec<Box<dyn Constraint + 'a>> {
    let layout = Layout::new(mesh.vertices.len(), conn.num_edges());
    let (node3, node2) = node_walls(conn);
    let mut families: Vec<Box<dyn Constraint + 'a>> = vec![
        Box::new(Normalization {
            layout,
            weight: weights.normalization(),
        }),
        Box::new(WallConsistency {
            layout,
            edges: conn.edges.clone(),
            weight: weights.consistency,
        }),
        Box::new(Node3 {
            layout,
            nodes: node3,
            weight: weights.angle,
        }),
        Box::new(Node2 {
            layout,
            nodes: node2,
            weight: weights.angle,
        }),
    ];
    if weights.closeness > 0.0 {
        families.push(Box::new(Closeness::new(layout, surface, weights.closeness)));
    }
    let on_boundary = boundary_vertices_on_surface_boundary(mesh, conn, surface);
    if weights.boundary > 0.0 && !on_boundary.is_empty() {
        families.push(Box::new(BoundaryCurve::new(
            layout,
            surface,
            weights.boundary,
            on_boundary,
        )));
    }
    if weights.fairness > 0.0 {
        families.push(Box::new(OppositeWalls {
            layout,
            pairs: opposite_wall_pairs(mesh, conn),
            weight: weights.fairness,
        }));
    }
    if weights.guide > 0.0 {
        let ends = (0..mesh.vertices.len())
            .flat_map(|v| {
                let a = surface.normal_at(mesh.vertices[v]);
                conn.vertex_edges[v]
                    .iter()
                    .map(move |&e| (e, conn.edge_sign(e, v), a))
            })
            .collect();
        families.push(Box::new(PrescribedAxes {
            layout,
            ends,
            weight: weights.guide,
            role: Role::Guide,
        }));
    }
    families.retain(|c| c.num_rows() > 0);
    families
}
