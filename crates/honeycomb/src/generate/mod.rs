//! Meshes and surfaces built in code: the demo's default input and the tests' subjects.

mod height_field;
mod hex_patch;
mod roof;
mod tower;

pub use height_field::{square_height_field, HeightField, Shape, RING_SLOPE};
pub use hex_patch::{hex_disk, radius_for_vertices};
pub use roof::{roof, ROOF_AMPLITUDE};
pub use tower::{cooling_tower, tower_radius, tube};

use crate::mesh::PolyMesh;

/// A hexagonal base mesh of about `vertices` vertices lifted onto `shape`, and the design
/// surface it lies on (a triangulation reaching past the patch, with triangles of half a cell
/// edge, or coarser on large patches where the curvature radius spans hundreds of cells).
pub fn lifted_hex_patch(shape: Shape, vertices: usize) -> (PolyMesh, PolyMesh) {
    if shape == Shape::Roof {
        return roof(vertices, ROOF_AMPLITUDE);
    }
    let d = radius_for_vertices(vertices);
    let field = HeightField { shape, d };
    let mut base = without_hole(hex_disk(d), field.hole());
    field.lift(&mut base);
    let cells_across = (2.4 * d / 0.5).ceil() as usize;
    (base, field.triangulate(cells_across.clamp(32, 160)))
}

/// Two triangles per quad of a grid of `columns` x `rows` quads whose vertex (i, j) is
/// `j * stride + i % stride` (`stride` is `columns` where the grid closes on itself round a
/// tube, `columns + 1` where it does not); each quad split along its diagonal from (i, j).
pub(crate) fn split_quads(columns: usize, rows: usize, stride: usize) -> Vec<Vec<usize>> {
    let id = |i: usize, j: usize| j * stride + i % stride;
    let mut faces = Vec::with_capacity(2 * columns * rows);
    for j in 0..rows {
        for i in 0..columns {
            faces.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            faces.push(vec![id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    faces
}

/// `mesh` without the cells whose centroid lies within `radius` of the z axis.
fn without_hole(mesh: PolyMesh, radius: f64) -> PolyMesh {
    if radius <= 0.0 {
        return mesh;
    }
    let outside = |f: &Vec<usize>| {
        let c = f
            .iter()
            .fold(crate::geometry::Vec3::ZERO, |s, &v| s + mesh.vertices[v]);
        let c = c / f.len() as f64;
        c.x.hypot(c.y) >= radius
    };
    let mut index = vec![usize::MAX; mesh.vertices.len()];
    let mut vertices = Vec::new();
    let faces = mesh
        .faces
        .iter()
        .filter(|f| outside(f))
        .map(|f| {
            f.iter()
                .map(|&v| {
                    if index[v] == usize::MAX {
                        index[v] = vertices.len();
                        vertices.push(mesh.vertices[v]);
                    }
                    index[v]
                })
                .collect()
        })
        .collect();
    PolyMesh::new(vertices, faces)
}

/// A built-in design surface on its own (what `pipeline` takes): the height field over a
/// square of side 24 (triangles of 0.2), or the roof of about 3500 cells' worth.
pub fn design_surface(shape: Shape) -> PolyMesh {
    if shape == Shape::Roof {
        return roof(3500, ROOF_AMPLITUDE).1;
    }
    HeightField { shape, d: 10.0 }.triangulate(120)
}

/// `hex_disk(radius)` in z = 0 with every node axis vertical and M' at `thickness` above: an
/// exact honeycomb (upright planar walls at 120 degrees), the unit tests' smallest subject.
#[cfg(test)]
pub(crate) fn upright_hex_disk(
    radius: f64,
    thickness: f64,
) -> (crate::structure::Honeycomb, crate::mesh::Connectivity) {
    let base = hex_disk(radius);
    let conn = crate::mesh::Connectivity::build(&base).expect("a hex disk is a valid mesh");
    let axes = vec![crate::geometry::Vec3::new(0.0, 0.0, 1.0); base.vertices.len()];
    (
        crate::structure::Honeycomb::new(base, &conn, axes, thickness),
        conn,
    )
}

/// The first cell of `h` with no corner on the boundary (the middle one of a small disk).
#[cfg(test)]
pub(crate) fn inner_cell(
    h: &crate::structure::Honeycomb,
    conn: &crate::mesh::Connectivity,
) -> usize {
    (0..h.base.faces.len())
        .find(|&f| h.base.faces[f].iter().all(|&v| conn.valence(v) == 3))
        .expect("a cell with no corner on the boundary")
}
