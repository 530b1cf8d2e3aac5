//! The reference surface S that a honeycomb is fitted to: a consistently oriented triangle
//! mesh with vertex normals, fast exact closest-point queries and its boundary polylines.

mod boundary;
mod bvh;
mod closest;
mod curvature;
pub(crate) mod normals;
mod orient;
#[cfg(test)]
mod tests;

pub use boundary::BoundaryPoint;
pub(crate) use bvh::Bvh;
#[cfg(test)]
pub(crate) use closest::closest_point_on_segment;
pub(crate) use closest::closest_point_on_triangle;
pub use curvature::CurvatureUnits;

use crate::error::{Error, Result};
use crate::geometry::Vec3;
use crate::mesh::PolyMesh;
use boundary::Boundary;

/// The point of S closest to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClosestPoint {
    pub point: Vec3,
    /// Unit normal at `point`: the vertex normals blended with barycentric weights, on the
    /// side of the (consistently oriented) face normals.
    pub normal: Vec3,
    /// Distance from the query point to `point`.
    pub distance: f64,
    /// Index of the triangle containing `point` (see [`Surface::triangles`]).
    pub triangle: usize,
    /// `point` lies on S's boundary (an edge or corner of a triangle that borders nothing):
    /// the query point may then be beyond S's edge rather than above it.
    pub on_boundary: bool,
}

/// From this many points on, closest points are found on two threads (a query takes about a
/// microsecond, starting a thread some tens).
pub const PARALLEL_QUERIES_FROM: usize = 1000;

/// A triangulated, consistently oriented reference surface with its acceleration structures.
#[derive(Clone, Debug)]
pub struct Surface {
    vertices: Vec<Vec3>,
    /// Triangles, all oriented like their neighbours, in BVH order.
    triangles: Vec<[usize; 3]>,
    /// The corner positions of each triangle, stored next to each other for fast queries.
    corners: Vec<[Vec3; 3]>,
    /// Unit normal per triangle (zero-area triangles borrow their vertices' normals).
    face_normals: Vec<Vec3>,
    /// Unit angle-weighted normal per vertex (zero for vertices without proper faces).
    vertex_normals: Vec<Vec3>,
    /// Per triangle, whether its edge k (from corner k to corner k + 1) is on the boundary.
    boundary_sides: Vec<[bool; 3]>,
    /// Per vertex, whether it is on the boundary.
    boundary_vertex: Vec<bool>,
    bvh: Bvh,
    boundary: Boundary,
    /// The mesh S was made from, as given (a solve works on a copy in its own frame).
    source: PolyMesh,
    /// S is the base mesh itself (no design surface given): its zigzag boundary is not S's.
    of_base: bool,
}

impl Surface {
    /// Triangulates polygons (`PolyMesh::star_triangulated`), orients triangles consistently (flips spread over shared
    /// edges; each connected piece keeps its majority orientation), computes normals, boundary
    /// loops and the BVH.
    ///
    /// Fails (`Error::Mesh`) on a mesh without faces, faces with fewer than 3 vertices,
    /// out-of-range indices, non-finite vertices, edges shared by more than two faces and
    /// non-orientable surfaces.
    pub fn from_mesh(mesh: &PolyMesh) -> Result<Surface> {
        validate(mesh)?;
        let (vertices, mut triangles) = mesh.star_triangulated();
        // The tree needs only the triangles' boxes, which orienting (a change of winding)
        // keeps: it is built beside the orientation, over triangle indices.
        let unoriented = triangles.clone();
        let ((bvh, order), oriented) = crate::parallel::both(
            || {
                let mut order: Vec<usize> = (0..unoriented.len()).collect();
                let bvh = Bvh::build(&mut order, |&t| {
                    let [a, b, c] = unoriented[t].map(|v| vertices[v]);
                    (a.min(b).min(c), a.max(b).max(c))
                });
                (bvh, order)
            },
            || orient::orient(&mut triangles),
        );
        let boundary_edges = oriented?;
        let triangles: Vec<[usize; 3]> = order.iter().map(|&t| triangles[t]).collect();
        let corners = triangles.iter().map(|t| t.map(|v| vertices[v])).collect();
        let mut face_normals = normals::face_normals(&vertices, &triangles);
        let vertex_normals = normals::vertex_normals(&vertices, &triangles, &face_normals);
        normals::fill_degenerate(&mut face_normals, &triangles, &vertex_normals);
        let boundary = Boundary::new(&vertices, &boundary_edges);
        let on_boundary: std::collections::HashSet<(usize, usize)> = boundary_edges
            .iter()
            .map(|&[a, b]| (a.min(b), a.max(b)))
            .collect();
        let boundary_sides = triangles
            .iter()
            .map(|t| {
                std::array::from_fn(|k| {
                    let (a, b) = (t[k], t[(k + 1) % 3]);
                    on_boundary.contains(&(a.min(b), a.max(b)))
                })
            })
            .collect();
        let mut boundary_vertex = vec![false; vertices.len()];
        for &[a, b] in &boundary_edges {
            boundary_vertex[a] = true;
            boundary_vertex[b] = true;
        }
        Ok(Surface {
            vertices,
            triangles,
            corners,
            face_normals,
            vertex_normals,
            boundary_sides,
            boundary_vertex,
            bvh,
            boundary,
            source: mesh.clone(),
            of_base: false,
        })
    }

    /// Reads a design surface (OBJ, OFF or PLY: triangles, quads or polygons), checked for what
    /// S must be (finite, manifold, orientable, no zero-area faces), once repaired
    /// ([`crate::mesh::repair_surface_mesh`]); errors name the file. Warnings of the reader
    /// (skipped lines, repairs, ...) are left out: read with [`crate::mesh::read_surface`] to
    /// see them.
    pub fn read(path: impl AsRef<std::path::Path>) -> Result<Surface> {
        let path = path.as_ref();
        let mesh = crate::mesh::read_surface(path)?.mesh;
        Surface::new(mesh).map_err(|e| e.about_file(path))
    }

    /// A design surface from a polygon mesh, repaired and checked as [`Surface::read`] does.
    ///
    /// ```
    /// use honeycomb::mesh::PolyMesh;
    /// use honeycomb::{Surface, Vec3};
    /// let square = PolyMesh::new(
    ///     vec![Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 0.0), Vec3::new(0.0, 1.0, 0.0)],
    ///     vec![vec![0, 1, 2, 3]],
    /// );
    /// let s = Surface::new(square)?;
    /// assert!((s.closest_point(Vec3::new(0.5, 0.5, 2.0)).distance - 2.0).abs() < 1e-12);
    /// // A face with an index beyond the vertices is refused.
    /// assert!(Surface::new(PolyMesh::new(vec![Vec3::ZERO; 3], vec![vec![0, 1, 5]])).is_err());
    /// # Ok::<(), honeycomb::Error>(())
    /// ```
    pub fn new(mut mesh: PolyMesh) -> Result<Surface> {
        crate::mesh::validate_repaired_surface(&mut mesh)?;
        Surface::from_mesh(&mesh)
    }

    /// The base mesh itself as S, where no design surface is given: a solve keeps the
    /// vertices close to it but not its zigzag boundary on S's boundary.
    pub fn of_base(base: &crate::BaseMesh) -> Result<Surface> {
        Ok(Surface::from_mesh(base.mesh())?.marked_as_base())
    }

    /// This surface marked as a base mesh itself.
    pub(crate) fn marked_as_base(mut self) -> Surface {
        self.of_base = true;
        self
    }

    /// The mesh S was made from.
    pub fn source_mesh(&self) -> &PolyMesh {
        &self.source
    }

    /// S is a base mesh itself ([`Surface::of_base`]).
    pub fn is_base(&self) -> bool {
        self.of_base
    }

    /// The design surface's mesh to solve on: `None` where S is the base mesh itself.
    pub fn design_mesh(&self) -> Option<&PolyMesh> {
        (!self.of_base).then_some(&self.source)
    }

    /// The exact closest point of S to `p`.
    pub fn closest_point(&self, p: Vec3) -> ClosestPoint {
        let eval = |t: usize| {
            let [a, b, c] = self.corners[t];
            let (q, w) = closest_point_on_triangle(p, a, b, c);
            ((p - q).norm_squared(), (t, q, w))
        };
        // Only a non-finite query escapes every box; answer it (with NaNs) from triangle 0.
        let (d2, (triangle, point, weights)) =
            self.bvh.nearest(p, &eval).unwrap_or_else(|| eval(0));
        ClosestPoint {
            point,
            normal: self.interpolated_normal(triangle, weights),
            distance: d2.sqrt(),
            triangle,
            on_boundary: self.on_boundary(triangle, weights),
        }
    }

    /// Whether the point of `triangle` with barycentric `weights` is on S's boundary: on an
    /// edge (the opposite corner's weight is zero) or at a corner that borders nothing.
    fn on_boundary(&self, triangle: usize, weights: [f64; 3]) -> bool {
        let zeros = weights.iter().filter(|&&w| w == 0.0).count();
        let first = |zero: bool| (0..3).find(|&k| (weights[k] == 0.0) == zero).unwrap_or(0);
        match zeros {
            // The side opposite corner k runs from corner k + 1 to k + 2.
            1 => self.boundary_sides[triangle][(first(true) + 1) % 3],
            2 => self.boundary_vertex[self.triangles[triangle][first(false)]],
            _ => false,
        }
    }

    /// [`Surface::closest_point`] for each point.
    pub fn closest_points(&self, ps: &[Vec3]) -> Vec<ClosestPoint> {
        ps.iter().map(|&p| self.closest_point(p)).collect()
    }

    /// The closest point on the boundary of S; `None` if S has no boundary.
    pub fn closest_boundary_point(&self, p: Vec3) -> Option<BoundaryPoint> {
        self.boundary.closest(p)
    }

    /// The surface normal at the point of S closest to `p`.
    pub fn normal_at(&self, p: Vec3) -> Vec3 {
        self.closest_point(p).normal
    }

    /// S's area-weighted mean normal (unit): the direction of the sum of its oriented
    /// triangles' areas. Zero for a closed surface, whose areas cancel.
    pub fn mean_normal(&self) -> Vec3 {
        let sum = self
            .corners
            .iter()
            .fold(Vec3::ZERO, |s, &[a, b, c]| s + (b - a).cross(c - a));
        if sum.norm() > 0.0 {
            sum.normalized()
        } else {
            sum
        }
    }

    pub fn has_boundary(&self) -> bool {
        !self.boundary.loops().is_empty()
    }

    /// Boundary loops as closed polylines (the last point connects to the first), running with
    /// the surface on their left seen from the normal side.
    pub fn boundary_loops(&self) -> &[Vec<Vec3>] {
        self.boundary.loops()
    }

    pub fn num_triangles(&self) -> usize {
        self.triangles.len()
    }

    /// The consistently oriented triangles, as indices into [`Surface::vertices`]. Their order
    /// is that of the BVH (spatially coherent), not that of the input faces.
    pub fn triangles(&self) -> &[[usize; 3]] {
        &self.triangles
    }

    /// The vertices of the input mesh.
    pub fn vertices(&self) -> &[Vec3] {
        &self.vertices
    }

    /// Unit angle-weighted vertex normals (zero for vertices outside any proper triangle).
    pub fn vertex_normals(&self) -> &[Vec3] {
        &self.vertex_normals
    }

    /// The axis-aligned bounding box `(min, max)` of the triangles.
    pub fn bbox(&self) -> (Vec3, Vec3) {
        self.bvh
            .bounds()
            .expect("a surface has at least one triangle")
    }

    /// The oriented triangles as a polygon mesh over the input vertices.
    pub fn mesh_for_export(&self) -> PolyMesh {
        PolyMesh::new(
            self.vertices.clone(),
            self.triangles.iter().map(|t| t.to_vec()).collect(),
        )
    }

    /// Blend of the corner normals with barycentric weights `w`. Vertex normals average all
    /// faces around a corner, so at a sharp fold the blend can tip past this face's tangent
    /// plane (or cancel out); then the face normal is the honest answer.
    fn interpolated_normal(&self, triangle: usize, w: [f64; 3]) -> Vec3 {
        let [a, b, c] = self.triangles[triangle];
        let face = self.face_normals[triangle];
        let n = (self.vertex_normals[a] * w[0]
            + self.vertex_normals[b] * w[1]
            + self.vertex_normals[c] * w[2])
            .normalized();
        if n.dot(face) > 0.0 {
            n
        } else {
            face
        }
    }
}

/// Rejects what the triangulation and orientation cannot work with.
fn validate(mesh: &PolyMesh) -> Result<()> {
    if mesh.faces.is_empty() {
        return Err(Error::Mesh("the surface has no faces".into()));
    }
    let nv = mesh.vertices.len();
    for (fi, f) in mesh.faces.iter().enumerate() {
        if f.len() < 3 {
            return Err(Error::Mesh(format!(
                "face {fi} has {} vertices; a face needs at least 3",
                f.len()
            )));
        }
        for &v in f {
            if v >= nv {
                return Err(Error::Mesh(format!(
                    "face {fi} refers to vertex {v}, but the mesh has {nv} vertices"
                )));
            }
            if !mesh.vertices[v].is_finite() {
                return Err(Error::Mesh(format!(
                    "vertex {v} (of face {fi}) has a non-finite coordinate"
                )));
            }
        }
    }
    Ok(())
}
