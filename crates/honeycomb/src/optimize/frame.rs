//! The normalized frame: centroid at the origin, mean edge length 1, so that weights and the
//! regularization are scale-free.

use crate::geometry::Vec3;
use crate::mesh::PolyMesh;

#[derive(Clone, Copy, Debug)]
pub struct Frame {
    pub center: Vec3,
    /// Model units per normalized unit (the mean edge length of the base mesh).
    pub unit: f64,
}

impl Frame {
    pub fn of(mesh: &PolyMesh) -> Frame {
        Frame {
            center: mesh.centroid(),
            unit: mesh.mean_edge_length(),
        }
    }

    pub fn to_normalized(self, mesh: &PolyMesh) -> PolyMesh {
        let mut m = mesh.clone();
        m.transform(self.center, 1.0 / self.unit);
        m
    }

    pub fn to_model(self, p: Vec3) -> Vec3 {
        p * self.unit + self.center
    }
}
