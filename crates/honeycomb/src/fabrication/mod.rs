//! What a fabricator needs from a honeycomb: the walls unrolled flat as panels with their end
//! cuts, the panels laid out on sheets, and the tables of walls, nodes and materials.

mod layout;
mod panel;
mod tables;

pub use layout::{lay_out, Layout, Placed, Sheet};
pub use panel::{side, unroll, EndCut, Panel, Point};
pub use tables::{bill_of_materials, node_rows, wall_rows, Bom, NodeRow, WallRow};
