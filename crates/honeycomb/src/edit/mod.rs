//! Edits of a realized honeycomb that keep it a honeycomb (paper section 4).

mod cell_walls;
mod reciprocal;
mod resize;
mod subdivide;
mod translate;

pub use reciprocal::{reciprocal, Reciprocal};
pub use resize::resize_cell;
pub use subdivide::subdivide;
pub use translate::translate_walls;
