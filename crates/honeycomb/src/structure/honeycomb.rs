//! The realized honeycomb: base mesh M, second mesh M' (same vertex order and faces, each v'_i
//! on the node axis of v_i), and one wall quad `v_a v_b v'_b v'_a` per edge.

use super::is_convex;
use crate::geometry::Vec3;
use crate::mesh::{Connectivity, PolyMesh};
use serde::{Deserialize, Serialize};

/// [`Honeycomb::deepened`] shortens the ends of a crossing wall by this factor per round, for
/// at most this many rounds.
const SHALLOWING: f64 = 0.85;
const SHALLOWING_ROUNDS: usize = 60;

#[derive(Clone, Debug)]
pub struct Honeycomb {
    pub base: PolyMesh,
    pub offset: PolyMesh,
    pub edges: Vec<[usize; 2]>,
    pub axes: Vec<Vec3>,
    /// Nominal distance between M and M' along the axes (model units): the constant offset of
    /// `new`, the mean depth of `with_offset`.
    pub thickness: f64,
}

impl Honeycomb {
    pub fn new(base: PolyMesh, conn: &Connectivity, axes: Vec<Vec3>, thickness: f64) -> Honeycomb {
        let offset_vertices = base
            .vertices
            .iter()
            .zip(&axes)
            .map(|(&v, &a)| v + a * thickness)
            .collect();
        let offset = PolyMesh::new(offset_vertices, base.faces.clone());
        Honeycomb {
            base,
            offset,
            edges: conn.edges.clone(),
            axes,
            thickness,
        }
    }

    /// A honeycomb whose second mesh M' is given vertex by vertex (parallel meshes: the depth
    /// varies); the axes are the realized directions `v'_i - v_i`.
    pub fn with_offset(
        base: PolyMesh,
        conn: &Connectivity,
        offset_vertices: Vec<Vec3>,
    ) -> Honeycomb {
        let depths: Vec<f64> = base
            .vertices
            .iter()
            .zip(&offset_vertices)
            .map(|(&v, &w)| (w - v).norm())
            .collect();
        let axes = base
            .vertices
            .iter()
            .zip(&offset_vertices)
            .map(|(&v, &w)| (w - v).normalized())
            .collect();
        let thickness = depths.iter().sum::<f64>() / depths.len().max(1) as f64;
        let offset = PolyMesh::new(offset_vertices, base.faces.clone());
        Honeycomb {
            base,
            offset,
            edges: conn.edges.clone(),
            axes,
            thickness,
        }
    }

    /// This honeycomb with its walls `depth` deep along the node axes, less (down to `least`)
    /// at the ends of a wall whose quad would cross itself where neighbouring axes lean
    /// together. The walls stay planar whatever the depths: each contains its two axes.
    pub fn deepened(&self, conn: &Connectivity, depth: f64, least: f64) -> Honeycomb {
        let m = &self.base.vertices;
        let mut depths = vec![depth; m.len()];
        let quad = |d: &[f64], [a, b]: [usize; 2]| {
            let (ta, tb) = (m[a] + self.axes[a] * d[a], m[b] + self.axes[b] * d[b]);
            [m[a], m[b], tb, ta]
        };
        for _ in 0..SHALLOWING_ROUNDS {
            let crossed: Vec<[usize; 2]> = (self.edges.iter())
                .filter(|&&e| !is_convex(quad(&depths, e)))
                .copied()
                .collect();
            if crossed.is_empty() {
                break;
            }
            for v in crossed.into_iter().flatten() {
                depths[v] = (depths[v] * SHALLOWING).max(least);
            }
        }
        let offset = (m.iter().zip(&self.axes).zip(&depths))
            .map(|((&v, &a), &d)| v + a * d)
            .collect();
        Honeycomb::with_offset(self.base.clone(), conn, offset)
    }

    /// Distance `|v'_i - v_i|` per vertex.
    pub fn depths(&self) -> impl Iterator<Item = f64> + '_ {
        self.base
            .vertices
            .iter()
            .zip(&self.offset.vertices)
            .map(|(&v, &w)| (w - v).norm())
    }

    /// The corners `v_a, v_b, v'_b, v'_a` of the wall of edge `e`.
    pub fn wall(&self, e: usize) -> [Vec3; 4] {
        let [a, b] = self.edges[e];
        let (m, o) = (&self.base.vertices, &self.offset.vertices);
        [m[a], m[b], o[b], o[a]]
    }

    /// All walls as one quad mesh over the vertices of M followed by those of M'.
    pub fn walls(&self) -> PolyMesh {
        let nv = self.base.vertices.len();
        let mut vertices = self.base.vertices.clone();
        vertices.extend_from_slice(&self.offset.vertices);
        let faces = self
            .edges
            .iter()
            .map(|&[a, b]| vec![a, b, nv + b, nv + a])
            .collect();
        PolyMesh::new(vertices, faces)
    }

    /// Unit normal of the realized wall quad of edge `e` (cross product of its diagonals),
    /// oriented like the solver's `n_e`: pointing away from the edge's first vertex side.
    pub fn wall_normal(&self, e: usize) -> Vec3 {
        let [p0, p1, p2, p3] = self.wall(e);
        let n = (p2 - p0).cross(p3 - p1).normalized();
        // Orientation: n_ab . (v_a - v_b) = 0 fixes nothing; use the edge/axis frame instead,
        // n_ab = (v_a - v_b) x axis, matching the initial rotation of the edge about N.
        let reference = (p0 - p1).cross(self.axes[self.edges[e][0]]);
        if n.dot(reference) < 0.0 {
            -n
        } else {
            n
        }
    }

    pub fn to_json(&self) -> StructureJson {
        StructureJson {
            thickness: self.thickness,
            vertices: self.base.vertices.iter().map(|v| v.to_array()).collect(),
            offset_vertices: self.offset.vertices.iter().map(|v| v.to_array()).collect(),
            faces: self.base.faces.clone(),
            edges: self.edges.clone(),
            wall_normals: (0..self.edges.len())
                .map(|e| self.wall_normal(e).to_array())
                .collect(),
            node_axes: self.axes.iter().map(|a| a.to_array()).collect(),
        }
    }
}

/// `structure.json`: the honeycomb for other tools, in model units.
#[derive(Serialize, Deserialize)]
pub struct StructureJson {
    pub thickness: f64,
    pub vertices: Vec<[f64; 3]>,
    pub offset_vertices: Vec<[f64; 3]>,
    pub faces: Vec<Vec<usize>>,
    /// Edge `e = (a, b)`; its wall normal is `wall_normals[e]` as seen from `a`.
    pub edges: Vec<[usize; 2]>,
    pub wall_normals: Vec<[f64; 3]>,
    pub node_axes: Vec<[f64; 3]>,
}
