//! A hexagonal base mesh, checked once.

use crate::error::Result;
use crate::geometry::Vec3;
use crate::mesh::{read_base, repair_base_mesh, validate_base_mesh, Connectivity, PolyMesh};
use std::path::Path;

/// A trivalent polygon mesh that an optimization can start from: every vertex of valence 2 or
/// 3, manifold, finite, without zero-length edges. Made only through its checks, so a
/// `BaseMesh` in hand is a valid one, with its connectivity (edges, the cells at each edge).
#[derive(Clone, Debug)]
pub struct BaseMesh {
    mesh: PolyMesh,
    connectivity: Connectivity,
}

impl BaseMesh {
    /// A base mesh from vertex positions and cells (each a list of vertex indices, in order
    /// around the cell).
    ///
    /// ```
    /// use honeycomb::{BaseMesh, Error, Vec3};
    /// // One hexagon: its six vertices are of valence 2, which a boundary node may have.
    /// let corner = |k: usize| {
    ///     let a = std::f64::consts::FRAC_PI_3 * k as f64;
    ///     Vec3::new(a.cos(), a.sin(), 0.0)
    /// };
    /// let base = BaseMesh::new((0..6).map(corner).collect(), vec![(0..6).collect()])?;
    /// assert_eq!(base.num_edges(), 6);
    /// // A vertex index beyond the vertices is refused with the cell it is in.
    /// let e = BaseMesh::new(vec![Vec3::ZERO; 3], vec![vec![0, 1, 7]]).unwrap_err();
    /// assert!(matches!(e, Error::Mesh(_)), "{e}");
    /// # Ok::<(), Error>(())
    /// ```
    pub fn new(vertices: Vec<Vec3>, cells: Vec<Vec<usize>>) -> Result<BaseMesh> {
        BaseMesh::from_mesh(PolyMesh::new(vertices, cells))
    }

    /// Checks a polygon mesh as a base mesh, its vertices at one position joined
    /// ([`crate::mesh::repair_base_mesh`]).
    pub fn from_mesh(mut mesh: PolyMesh) -> Result<BaseMesh> {
        repair_base_mesh(&mut mesh);
        let connectivity = validate_base_mesh(&mesh)?;
        Ok(BaseMesh { mesh, connectivity })
    }

    /// Reads a base mesh (OBJ, OFF or PLY); errors name the file.
    pub fn read(path: impl AsRef<Path>) -> Result<BaseMesh> {
        let path = path.as_ref();
        let mesh = read_base(path)?.mesh;
        BaseMesh::from_mesh(mesh).map_err(|e| e.about_file(path))
    }

    pub fn vertices(&self) -> &[Vec3] {
        &self.mesh.vertices
    }

    /// The cells, each as its vertex indices in order.
    pub fn cells(&self) -> &[Vec<usize>] {
        &self.mesh.faces
    }

    /// The edges as vertex index pairs, in the order of the walls of a result.
    pub fn edges(&self) -> &[[usize; 2]] {
        &self.connectivity.edges
    }

    pub fn num_edges(&self) -> usize {
        self.connectivity.num_edges()
    }

    pub fn mesh(&self) -> &PolyMesh {
        &self.mesh
    }
}
