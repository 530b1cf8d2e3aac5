//! Planarity of the capping quads (DESIGN.md section 3, `delta_face`), from realized vertices.

use super::quad_planarity;
use crate::geometry::Vec3;
use crate::mesh::PolyMesh;
use serde::Serialize;

/// A quad whose diagonals pass within this share of its mean edge length of each other is flat
/// (the floor asked of a cover's worst quad).
pub const FLAT_QUAD: f64 = 0.01;
/// The floor asked of a cover's mean quad, in the same measure.
pub const FLAT_QUAD_MEAN: f64 = 0.004;

#[derive(Clone, Debug, Serialize)]
pub struct FaceMeasures {
    /// Distance between a quad's diagonals over its mean edge length.
    pub delta_face_max: f64,
    pub delta_face_avg: f64,
    /// How many quads were measured.
    pub quads: usize,
}

impl FaceMeasures {
    /// Whether these quads meet both floors a glazed cover asks.
    pub fn meet_floors(&self) -> bool {
        meet_quad_floors(self.delta_face_max, self.delta_face_avg)
    }
}

/// Whether quads whose worst and mean planarity are `max` and `avg` meet both floors a glazed
/// cover asks ([`FLAT_QUAD`], [`FLAT_QUAD_MEAN`]).
pub fn meet_quad_floors(max: f64, avg: f64) -> bool {
    max <= FLAT_QUAD && avg <= FLAT_QUAD_MEAN
}

/// Each quad's planarity on `vertices`.
pub fn quad_planarities(vertices: &[Vec3], quads: &[[usize; 4]]) -> Vec<f64> {
    quads
        .iter()
        .map(|q| quad_planarity(q.map(|v| vertices[v])))
        .collect()
}

/// The four-sided ones of `faces`, as corner indices.
pub fn four_sided(faces: &[Vec<usize>]) -> Vec<[usize; 4]> {
    faces
        .iter()
        .filter_map(|f| <[usize; 4]>::try_from(f.as_slice()).ok())
        .collect()
}

/// Planarity of the given quads (e.g. `QuadCover::quads`) on `vertices`.
pub fn face_measures(vertices: &[Vec3], quads: &[[usize; 4]]) -> FaceMeasures {
    let deltas = quad_planarities(vertices, quads);
    FaceMeasures {
        delta_face_max: deltas.iter().copied().fold(0.0, f64::max),
        delta_face_avg: deltas.iter().sum::<f64>() / deltas.len().max(1) as f64,
        quads: deltas.len(),
    }
}

/// Planarity of the first `split` faces of a quad-cover mesh (`QuadCover::mesh` lists the split
/// quads first; the unsplit cells after them are not required to be planar).
pub fn quad_mesh_measures(mesh: &PolyMesh, split: usize) -> FaceMeasures {
    face_measures(
        &mesh.vertices,
        &four_sided(&mesh.faces[..split.min(mesh.faces.len())]),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_planar_quad_measures_zero_and_a_twisted_one_does_not() {
        let p = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.1),
        ];
        let m = face_measures(&p, &[[0, 1, 2, 3], [0, 1, 2, 4]]);
        assert_eq!(m.quads, 2);
        // Diagonals (1, 1, 0) and (-1, 1, 0.1) through the origin and (1, 0, 0).
        let distance = 0.1 / 4.02f64.sqrt();
        let mean_edge = (2.0 + 2.0 * 1.01f64.sqrt()) / 4.0;
        assert!((m.delta_face_max - distance / mean_edge).abs() < 1e-12);
        assert!((m.delta_face_avg - m.delta_face_max / 2.0).abs() < 1e-12);
        let mesh = PolyMesh::new(p, vec![vec![0, 1, 2, 3], vec![0, 1, 2, 4]]);
        assert_eq!(quad_mesh_measures(&mesh, 1).delta_face_max, 0.0);
    }
}
