//! From solver variables to the realized structure (node axes, M', walls) and its measures.

mod axes;
mod honeycomb;
mod measures;
mod quad_cover;
mod quad_measures;
mod variant_measures;

pub use axes::node_axes;
pub use honeycomb::{Honeycomb, StructureJson};
pub use measures::{
    line_angle_deg, measure, node_angles, per_wall_worse_end, quad_planarity, thickest_uncrossed,
    Measures, Spread,
};
pub use quad_cover::{EdgeClasses, QuadCover, QuadPattern, StraightRun, ZigzagRun};
pub use quad_measures::{face_measures, quad_mesh_measures, FaceMeasures};
pub use variant_measures::{
    angle_deg, axes_measures, parallel_measures, AxesMeasures, ParallelMeasures,
};
