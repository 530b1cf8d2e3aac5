//! From solver variables to the realized structure (node axes, M', walls) and its measures.

mod axes;
mod honeycomb;
mod measures;
mod quad_cover;
mod quad_measures;
mod variant_measures;

pub(crate) use axes::node_axes;
pub use honeycomb::{Honeycomb, StructureJson};
pub use measures::{edge_length_cv, largest_move_along, measure, quad_planarity, Measures, Spread};
pub(crate) use measures::{is_convex, line_angle_deg, per_wall_worse_end, thickest_uncrossed};
pub(crate) use quad_cover::QuadCover;
pub use quad_cover::QuadPattern;
pub(crate) use quad_measures::quad_mesh_measures;
pub(crate) use quad_measures::{face_measures, four_sided, quad_planarities};
pub use quad_measures::{meet_quad_floors, FaceMeasures, FLAT_QUAD, FLAT_QUAD_MEAN};
#[cfg(test)]
pub(crate) use variant_measures::angle_deg;
pub(crate) use variant_measures::betas_deg;
pub(crate) use variant_measures::{axes_measures, parallel_measures};
pub use variant_measures::{AxesMeasures, ParallelMeasures};
