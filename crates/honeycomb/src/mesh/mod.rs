//! Polygon meshes: storage, adjacency, validation and file formats.

mod connectivity;
mod polymesh;

pub use connectivity::Connectivity;
pub use polymesh::PolyMesh;
