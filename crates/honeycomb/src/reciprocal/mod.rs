//! The reciprocal sheet of a honeycomb, and honeycombs whose walls stand across S.
//!
//! Give every cell a point such that each wall normal is the difference of its two cells'
//! points (the reciprocal diagram; `optimize/dual_normals.rs` solves in the same unknowns).
//! In a honeycomb every wall normal is a unit vector and the three at a node add up to zero,
//! so the three cells around a node span a unit equilateral triangle whose normal is the node
//! axis: the cell points form a sheet of unit triangles, the triangular lattice folded without
//! stretching (a pentagon or heptagon is a cone point). Outside the boundary a ghost point
//! stands for each cell the boundary cut away; a node of valence 2 closes its triangle with a
//! virtual wall between its two ghosts, at unit length when its walls meet at 120 degrees.
//!
//! So the node axes can be designed first, as a folded sheet whose normals fit S's normals
//! ([`AxisFit`]), and the vertices placed afterwards on the walls that sheet fixes
//! ([`place`]), where walls are planar and angles exact by construction. S's normals are
//! the normals of a folded sheet only where S is developable (the paper's Property 3): on a
//! doubly curved S the fit is a compromise, which the sheet's folds make.

mod across;
mod axis_field;
mod ghosts;
mod placement;
mod sheet;
mod targets;
mod trim;

pub use across::{walls_across, Across, AcrossOptions, Stage, Start, PROVISIONAL_OMEGA_DEG};
pub use axis_field::{unit_gap, AxisFieldOptions, AxisFit};
pub use placement::{place, FittedSheet, PlacementOptions};
pub use sheet::Sheet;
pub use targets::{AxisTargets, Turn, SHADING_TURNS};
pub use trim::{edge_cv_without, trim_drawn_out, trim_overhang, DRAWN_OUT, ON_S};
