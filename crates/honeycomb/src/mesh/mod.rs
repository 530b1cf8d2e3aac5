//! Polygon meshes: storage, adjacency, validation and file formats.

mod coincident;
mod connectivity;
mod convexity;
pub mod io;
mod orientation;
mod polymesh;
mod validate;

pub use connectivity::Connectivity;
pub use convexity::nonconvex_faces;
pub use io::{
    read_base, read_mesh, read_surface, replace_folder, write_atomically, write_mesh,
    write_output_dir, LoadedMesh, OutputDir, Outputs, Previous, Verdict,
};
pub(crate) use orientation::orientation_flips;
pub use polymesh::PolyMesh;
pub use validate::{
    check_base_near_surface, repair_base_mesh, repair_surface_mesh, validate_base_mesh,
    validate_repaired_surface, validate_surface_mesh,
};
