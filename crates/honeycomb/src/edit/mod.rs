//! Edits of a realized honeycomb that keep it a honeycomb (paper section 4).

mod resize;
mod translate;

pub use resize::resize_cell;
pub use translate::translate_walls;
