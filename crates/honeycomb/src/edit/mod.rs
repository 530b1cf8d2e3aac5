//! Edits of a realized honeycomb that keep it a honeycomb (paper section 4).

mod cell_walls;
mod reciprocal;
mod resize;
mod subdivide;
mod translate;

pub use reciprocal::{reciprocal, reciprocal_range, Reciprocal, ReciprocalRange};
pub use resize::resize_cell;
pub use subdivide::subdivide;
pub use translate::translate_walls;

use crate::error::{Error, Result};
use crate::mesh::{validate_base_mesh, Connectivity, PolyMesh};

/// The smallest share of a cell's size an edit makes a new feature: a cell shrunk further, or
/// a gap narrower, is a point in all but name.
const FINEST: f64 = 1e-6;

/// An edit's new mesh, checked as `read_structure` will check it: amounts at the very end of an
/// edit's range can still bring two vertices within roundoff of each other.
fn validated(edit: &str, base: &PolyMesh) -> Result<Connectivity> {
    validate_base_mesh(base).map_err(|e| match e {
        Error::Mesh(message) => {
            Error::Parameter(format!("{edit} leaves no valid structure: {message}"))
        }
        other => other,
    })
}
