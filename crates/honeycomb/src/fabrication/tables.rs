//! The tables a fabricator and an estimator read: one row per wall, one per node, and the bill
//! of materials. Every figure is computed from the realized meshes M and M'.

use crate::geometry::Vec3;
use crate::mesh::Connectivity;
use crate::structure::{line_angle_deg, quad_planarity, Honeycomb, Measures};
use crate::surface::Surface;
use serde::Serialize;
use std::collections::BTreeSet;

#[derive(Clone, Debug, Serialize)]
pub struct WallRow {
    /// The wall's id: its edge's index (`W<wall>` in the other files).
    pub wall: usize,
    /// Its edge (i, j) of M.
    pub i: usize,
    pub j: usize,
    /// The cells on either side (faces of M; none on the boundary).
    pub cell_left: Option<usize>,
    pub cell_right: Option<usize>,
    /// |v_j - v_i| along M and |v'_j - v'_i| along M'.
    pub length: f64,
    pub length_offset: f64,
    /// The node axis lengths at i and j.
    pub height_i: f64,
    pub height_j: f64,
    /// In the wall's plane: the angle between the edge of M and the node axis, at i and at j.
    pub end_angle_i_deg: f64,
    pub end_angle_j_deg: f64,
    /// The angle between the wall and S's tangent plane at its edge's midpoint (90: the wall
    /// stands square on the cladding).
    pub surface_angle_deg: f64,
    pub area: f64,
    /// Planarity: distance of the quad's diagonals over its mean side.
    pub delta: f64,
}

#[derive(Clone, Debug, Serialize)]
pub struct NodeRow {
    pub node: usize,
    pub position: [f64; 3],
    /// Unit direction of the node axis, from M to M'.
    pub axis: [f64; 3],
    pub axis_length: f64,
    /// The walls at the node (two on the boundary), and the unit direction in which each leaves
    /// the axis (square to it).
    pub walls: Vec<usize>,
    pub wall_directions: Vec<[f64; 3]>,
    /// The node's largest deviation from 120 degrees between neighbouring walls: how far it is
    /// from the one node design.
    pub omega_deg: f64,
}

#[derive(Clone, Debug, Serialize)]
pub struct Bom {
    pub units: &'static str,
    pub walls: usize,
    pub nodes: usize,
    pub cells: usize,
    pub total_wall_area: f64,
    /// The length of all edges of M.
    pub total_edge_length: f64,
    /// How many different wall lengths (along M) there are, each rounded to 1 mm.
    pub distinct_wall_lengths: usize,
    /// Node types: one, as every node meets at 120 degrees (the worst by `omega_max_deg`).
    pub node_types: usize,
    pub omega_max_deg: f64,
}

pub fn wall_rows(h: &Honeycomb, conn: &Connectivity, surface: &Surface) -> Vec<WallRow> {
    let (m, o) = (&h.base.vertices, &h.offset.vertices);
    (0..h.edges.len())
        .map(|e| {
            let [i, j] = h.edges[e];
            let corner = |p: Vec3, along: Vec3, axis: Vec3| {
                let (u, v) = (along - p, axis - p);
                u.cross(v).norm().atan2(u.dot(v)).to_degrees()
            };
            let wall = h.wall(e);
            let normal = h.wall_normal(e);
            let middle = (m[i] + m[j]) * 0.5;
            let [left, right] = conn.edge_faces[e];
            WallRow {
                wall: e,
                i,
                j,
                cell_left: left,
                cell_right: right,
                length: (m[j] - m[i]).norm(),
                length_offset: (o[j] - o[i]).norm(),
                height_i: (o[i] - m[i]).norm(),
                height_j: (o[j] - m[j]).norm(),
                end_angle_i_deg: corner(m[i], m[j], o[i]),
                end_angle_j_deg: corner(m[j], m[i], o[j]),
                surface_angle_deg: line_angle_deg(normal, surface.normal_at(middle)),
                area: 0.5 * (wall[2] - wall[0]).cross(wall[3] - wall[1]).norm(),
                delta: quad_planarity(wall),
            }
        })
        .collect()
}

pub fn node_rows(h: &Honeycomb, conn: &Connectivity, measures: &Measures) -> Vec<NodeRow> {
    let (m, o) = (&h.base.vertices, &h.offset.vertices);
    (0..m.len())
        .map(|v| {
            let axis = (o[v] - m[v]).normalized();
            let walls = conn.vertex_edges[v].clone();
            let wall_directions = walls
                .iter()
                .map(|&e| {
                    let d = m[conn.other_end(e, v)] - m[v];
                    (d - axis * d.dot(axis)).normalized().to_array()
                })
                .collect();
            NodeRow {
                node: v,
                position: m[v].to_array(),
                axis: axis.to_array(),
                axis_length: (o[v] - m[v]).norm(),
                walls,
                wall_directions,
                omega_deg: measures.omega_per_node[v],
            }
        })
        .collect()
}

/// `millimetre`: one millimetre in model units, the resolution at which lengths are told apart.
pub fn bill_of_materials(
    h: &Honeycomb,
    walls: &[WallRow],
    measures: &Measures,
    units: &'static str,
    millimetre: f64,
) -> Bom {
    let lengths: BTreeSet<i64> = walls
        .iter()
        .map(|w| (w.length / millimetre).round() as i64)
        .collect();
    Bom {
        units,
        walls: walls.len(),
        nodes: h.base.vertices.len(),
        cells: h.base.faces.len(),
        total_wall_area: walls.iter().map(|w| w.area).sum(),
        total_edge_length: walls.iter().map(|w| w.length).sum(),
        distinct_wall_lengths: lengths.len(),
        node_types: 1,
        omega_max_deg: measures.omega_max_deg,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::upright_hex_disk;
    use crate::structure::measure;

    #[test]
    fn vertical_walls_on_a_flat_disk_stand_square_with_square_ends() {
        let (h, conn) = upright_hex_disk(2.0, 0.3);
        let surface = Surface::from_mesh(&h.base).unwrap();
        let rows = wall_rows(&h, &conn, &surface);
        for r in &rows {
            assert!((r.surface_angle_deg - 90.0).abs() < 1e-9, "{r:?}");
            assert!(
                (r.end_angle_i_deg - 90.0).abs() < 1e-9 && (r.end_angle_j_deg - 90.0).abs() < 1e-9
            );
            assert!((r.area - r.length * 0.3).abs() < 1e-12);
            assert!((r.height_i - 0.3).abs() < 1e-12);
            assert!(r.cell_left.is_some() || r.cell_right.is_some());
        }
        let measures = measure(&h, &surface);
        let nodes = node_rows(&h, &conn, &measures);
        for n in &nodes {
            assert!(n.walls.len() >= 2);
            for d in &n.wall_directions {
                assert!(Vec3::from_slice(d).dot(Vec3::from_slice(&n.axis)).abs() < 1e-12);
            }
        }
        // A regular hexagonal disk: one wall length.
        let bom = bill_of_materials(&h, &rows, &measures, "m", 0.001);
        assert_eq!(bom.distinct_wall_lengths, 1);
        assert_eq!(bom.walls, h.edges.len());
    }
}
