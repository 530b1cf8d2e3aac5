//! Where the honeycomb's unknowns live in the solver's vector: all vertex positions first, then
//! one unit normal per edge. Extensions append their own blocks after these.

use crate::geometry::Vec3;

#[derive(Clone, Copy, Debug)]
pub struct Layout {
    pub num_vertices: usize,
    pub num_edges: usize,
}

impl Layout {
    pub fn new(num_vertices: usize, num_edges: usize) -> Layout {
        Layout {
            num_vertices,
            num_edges,
        }
    }

    pub fn len(&self) -> usize {
        3 * (self.num_vertices + self.num_edges)
    }

    /// Index of the first coordinate of vertex `v`.
    pub fn vertex(&self, v: usize) -> usize {
        3 * v
    }

    /// Index of the first coordinate of the normal of edge `e`.
    pub fn normal(&self, e: usize) -> usize {
        3 * (self.num_vertices + e)
    }

    pub fn vertex_at(&self, x: &[f64], v: usize) -> Vec3 {
        Vec3::from_slice(&x[self.vertex(v)..])
    }

    pub fn normal_at(&self, x: &[f64], e: usize) -> Vec3 {
        Vec3::from_slice(&x[self.normal(e)..])
    }

    #[cfg(test)]
    /// Packs positions and normals into a solver vector.
    pub fn pack(&self, vertices: &[Vec3], normals: &[Vec3]) -> Vec<f64> {
        let mut x = Vec::with_capacity(self.len());
        for p in vertices.iter().chain(normals) {
            x.extend_from_slice(&p.to_array());
        }
        x
    }
}

/// Writes the three indices `start, start+1, start+2` into `out`.
pub(crate) fn triple(out: &mut [usize], start: usize) {
    out[0] = start;
    out[1] = start + 1;
    out[2] = start + 2;
}

/// Writes a vector's coordinates into `out`.
pub(crate) fn put(out: &mut [f64], v: Vec3) {
    out[0] = v.x;
    out[1] = v.y;
    out[2] = v.z;
}
