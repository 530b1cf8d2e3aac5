//! The constraint families of a honeycomb (DESIGN.md section 2), one file each. Each states its
//! rows, residuals and Jacobian; the solver sees only the `Constraint` trait.

mod boundary_curve;
mod closeness;
mod closeness_bound;
mod edge_length;
mod edge_vectors;
mod firming;
mod fixed_normals;
mod held_normals;
mod layout;
mod min_edge_length;
mod node_angle;
mod node_orientation;
mod normalization;
mod opposite_walls;
mod orthogonal_difference;
mod parallel_mesh;
mod parallel_on_axes;
mod planarity_bound;
mod polyline_fairness;
mod prescribed_axes;
mod quad_planarity;
mod rigid_triangles;
mod tangential_hold;
mod targets;
mod wall_consistency;
mod wall_convexity;
mod wall_plane;

pub use boundary_curve::BoundaryCurve;
pub use closeness::Closeness;
pub use closeness_bound::BoundedCloseness;
pub use edge_length::EdgeLength;
pub use edge_vectors::EdgeVectors;
pub use fixed_normals::{FixedNormalRow, FixedNormals};
pub use held_normals::HeldNormals;
pub use layout::Layout;
pub use min_edge_length::MinEdgeLength;
pub use node_angle::{Node2, Node3};
pub use node_orientation::NodeOrientation;
pub use normalization::Normalization;
pub use opposite_walls::OppositeWalls;
pub use orthogonal_difference::OrthogonalDifference;
pub use parallel_mesh::{ConstantDepth, EdgeParallelity, OffsetBlock, OffsetOnAxis};
pub use parallel_on_axes::{AxisSlides, ParallelOnAxes, ScalarTargets};
pub use planarity_bound::BoundedPlanarity;
pub use polyline_fairness::ZigzagFairness;
pub use prescribed_axes::PrescribedAxes;
pub use quad_planarity::{QuadNormalBlock, QuadNormalization, QuadPlanarity};
pub use rigid_triangles::{RigidTriangles, SharedRotations};
pub use tangential_hold::TangentialHold;
pub use targets::{AxisTargets, SharedTargets, VertexTargets};
pub use wall_consistency::WallConsistency;
pub use wall_convexity::WallConvexity;
pub use wall_plane::WallPlane;

#[cfg(test)]
pub(crate) mod jacobian_tests;
