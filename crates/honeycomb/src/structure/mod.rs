//! From solver variables to the realized structure (node axes, M', walls) and its measures.

mod axes;
mod honeycomb;
mod measures;

pub use axes::node_axes;
pub use honeycomb::{Honeycomb, StructureJson};
pub use measures::{measure, node_angles, quad_planarity, Measures};
