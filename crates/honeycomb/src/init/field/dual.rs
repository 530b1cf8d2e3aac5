//! The hexagonal mesh is the lattice mesh's dual: one vertex per lattice triangle (its
//! centroid, moved to the closest point of S), one cell per lattice vertex whose triangles
//! close around it. Lattice vertices on the lattice mesh's border have open fans and give no
//! cell (the cells S's boundary cuts are trimmed), nor do those whose cell would have a
//! corner beyond S's boundary. Of what remains, the largest piece joined through shared
//! edges is kept.

use super::extract::{LatticeMesh, UnionFind};
use super::tangent::tangential;
use crate::geometry::Vec3;
use crate::mesh::PolyMesh;
use crate::surface::Surface;
use std::collections::HashMap;

/// A corner whose centroid lies farther than this many edge lengths beside S (beyond its
/// boundary, measured in S's tangent plane) drops its cells.
const MAX_LATERAL: f64 = 0.2;

/// The dual cells, every vertex on S; empty when no lattice vertex has a closed fan.
pub fn hex_mesh(lattice: &LatticeMesh, surface: &Surface, edge: f64) -> PolyMesh {
    let triangles = &lattice.triangles;
    let mut fans: Vec<Vec<usize>> = vec![Vec::new(); lattice.points.len()];
    let mut owner: HashMap<(usize, usize), usize> = HashMap::with_capacity(3 * triangles.len());
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            fans[tri[k]].push(t);
            owner.insert((tri[k], tri[(k + 1) % 3]), t);
        }
    }
    let corners: Vec<Corner> = triangles
        .iter()
        .map(|tri| {
            let centroid = tri.iter().fold(Vec3::ZERO, |s, &v| s + lattice.points[v]) / 3.0;
            let closest = surface.closest_point(centroid);
            let beside = tangential(centroid - closest.point, closest.normal).norm();
            Corner {
                point: closest.point,
                normal: closest.normal,
                on_s: beside <= MAX_LATERAL * edge,
            }
        })
        .collect();
    let cells: Vec<Option<Vec<usize>>> = (0..lattice.points.len())
        .map(|v| closed_fan(v, &fans[v], triangles, &owner))
        .map(|fan| {
            fan.filter(|f| f.iter().all(|&t| corners[t].on_s) && faces_like_s(f, &corners, surface))
        })
        .collect();
    let Some(piece) = largest_piece(&cells, triangles) else {
        return PolyMesh::default();
    };
    let mut index = vec![usize::MAX; triangles.len()];
    let corners: Vec<(Vec3, bool)> = corners.iter().map(|c| (c.point, c.on_s)).collect();
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for (v, cell) in cells.iter().enumerate() {
        let Some(fan) = cell else { continue };
        if !piece[v] {
            continue;
        }
        let face = fan
            .iter()
            .map(|&t| {
                if index[t] == usize::MAX {
                    index[t] = vertices.len();
                    vertices.push(corners[t].0);
                }
                index[t]
            })
            .collect();
        faces.push(face);
    }
    PolyMesh::new(vertices, faces)
}

/// A hex vertex: a lattice triangle's centroid moved onto S.
struct Corner {
    point: Vec3,
    normal: Vec3,
    /// False when the centroid lies beside S (beyond its boundary).
    on_s: bool,
}

/// Whether the cell's polygon turns counter-clockwise about S's normals at its corners and at
/// its centre (on a sharp fold of S the projected corners can turn it over).
fn faces_like_s(fan: &[usize], corners: &[Corner], surface: &Surface) -> bool {
    let c = fan.iter().fold(Vec3::ZERO, |s, &t| s + corners[t].point) / fan.len() as f64;
    let mut area = Vec3::ZERO;
    let mut normal = Vec3::ZERO;
    for k in 0..fan.len() {
        let (a, b) = (
            corners[fan[k]].point,
            corners[fan[(k + 1) % fan.len()]].point,
        );
        area += (a - c).cross(b - c);
        normal += corners[fan[k]].normal;
    }
    // And about S's normal at the centre (on strongly curved S the two can disagree).
    area.dot(normal) > 0.0 && area.dot(surface.normal_at(c)) > 0.0
}

/// The triangles around `v` counter-clockwise, if they close into one fan.
fn closed_fan(
    v: usize,
    around: &[usize],
    triangles: &[[usize; 3]],
    owner: &HashMap<(usize, usize), usize>,
) -> Option<Vec<usize>> {
    let &start = around.first()?;
    let mut fan = vec![start];
    let mut t = start;
    loop {
        let tri = triangles[t];
        let k = tri.iter().position(|&x| x == v)?;
        // The next triangle counter-clockwise shares the edge from v to the corner before it.
        let before = tri[(k + 2) % 3];
        t = *owner.get(&(v, before))?;
        if t == start {
            break;
        }
        fan.push(t);
        if fan.len() > around.len() {
            return None;
        }
    }
    (fan.len() == around.len() && fan.len() >= 3).then_some(fan)
}

/// Which lattice vertices' cells form the largest piece joined through shared edges (ties go
/// to the piece with the lowest vertex); None without cells.
fn largest_piece(cells: &[Option<Vec<usize>>], triangles: &[[usize; 3]]) -> Option<Vec<bool>> {
    let mut sets = UnionFind::new(cells.len());
    for (v, cell) in cells.iter().enumerate() {
        let Some(fan) = cell else { continue };
        for &t in fan {
            for &w in &triangles[t] {
                if w != v && cells[w].is_some() {
                    sets.union(v, w);
                }
            }
        }
    }
    let mut sizes: HashMap<usize, (usize, usize)> = HashMap::new();
    for (v, cell) in cells.iter().enumerate() {
        if cell.is_some() {
            let entry = sizes.entry(sets.find(v)).or_insert((0, v));
            entry.0 += 1;
        }
    }
    let (&root, _) = sizes
        .iter()
        .max_by(|a, b| a.1 .0.cmp(&b.1 .0).then(b.1 .1.cmp(&a.1 .1)))?;
    Some(
        (0..cells.len())
            .map(|v| cells[v].is_some() && sets.find(v) == root)
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::init::field::extract::flat_lattice_patch;
    use crate::mesh::validate_base_mesh;

    #[test]
    fn a_lattice_patch_becomes_hexagons_of_the_right_size() {
        let (lattice, _) = flat_lattice_patch(4);
        let plane = PolyMesh::new(
            vec![
                Vec3::new(-10.0, -10.0, 0.0),
                Vec3::new(10.0, -10.0, 0.0),
                Vec3::new(10.0, 10.0, 0.0),
                Vec3::new(-10.0, 10.0, 0.0),
            ],
            vec![vec![0, 1, 2, 3]],
        );
        let surface = Surface::from_mesh(&plane).unwrap();
        let edge = 1.0 / 3f64.sqrt();
        let hex = hex_mesh(&lattice, &surface, edge);
        // The interior vertices of a 4-ring hexagon: 1 + 6 (1 + 2 + 3) = 37 cells.
        assert_eq!(hex.faces.len(), 37);
        assert!(hex.faces.iter().all(|f| f.len() == 6));
        validate_base_mesh(&hex).unwrap();
        for f in &hex.faces {
            for k in 0..6 {
                let (a, b) = (hex.vertices[f[k]], hex.vertices[f[(k + 1) % 6]]);
                assert!(((a - b).norm() - edge).abs() < 1e-9);
            }
            // Counter-clockwise seen from +z, like the lattice.
            let c = f.iter().fold(Vec3::ZERO, |s, &v| s + hex.vertices[v]) / 6.0;
            let (a, b) = (hex.vertices[f[0]], hex.vertices[f[1]]);
            assert!((a - c).cross(b - c).z > 0.0);
        }
        // A plane too small: corners beyond its boundary drop their cells.
        let small = PolyMesh::new(
            vec![
                Vec3::new(-1.0, -1.0, 0.0),
                Vec3::new(1.0, -1.0, 0.0),
                Vec3::new(1.0, 1.0, 0.0),
                Vec3::new(-1.0, 1.0, 0.0),
            ],
            vec![vec![0, 1, 2, 3]],
        );
        let hex = hex_mesh(&lattice, &Surface::from_mesh(&small).unwrap(), edge);
        assert!(hex.faces.len() < 37 && !hex.faces.is_empty());
        validate_base_mesh(&hex).unwrap();
    }
}
