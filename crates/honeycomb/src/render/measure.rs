//! What a walls picture can colour by: each measure's name, unit, tolerance and value per wall.

use crate::analysis::spherical_image;
use crate::mesh::Connectivity;
use crate::reciprocal::ON_S;
use crate::report::Report;
use crate::structure::{per_wall_worse_end, Honeycomb, Measures};
use std::str::FromStr;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WallMeasure {
    Omega,
    Delta,
    Closeness,
    Axis,
    Area,
    Length,
}

impl FromStr for WallMeasure {
    type Err = String;
    fn from_str(s: &str) -> Result<WallMeasure, String> {
        Ok(match s {
            "omega" => WallMeasure::Omega,
            "delta" => WallMeasure::Delta,
            "closeness" => WallMeasure::Closeness,
            "axis" => WallMeasure::Axis,
            "area" => WallMeasure::Area,
            "length" => WallMeasure::Length,
            _ => {
                return Err(format!(
                    "--color {s}: expected omega, delta, closeness, axis, area or length"
                ))
            }
        })
    }
}

impl WallMeasure {
    pub fn name(self) -> &'static str {
        match self {
            WallMeasure::Omega => "omega",
            WallMeasure::Delta => "delta",
            WallMeasure::Closeness => "closeness",
            WallMeasure::Axis => "axis",
            WallMeasure::Area => "area",
            WallMeasure::Length => "length",
        }
    }

    /// What the value of a wall is, in words.
    pub fn meaning(self) -> &'static str {
        match self {
            WallMeasure::Omega => "worst node angle off 120 deg at either end",
            WallMeasure::Delta => "wall planarity: diagonals' distance / mean side",
            WallMeasure::Closeness => "distance of its ends from S",
            WallMeasure::Axis => "larger angle of its node axes to S's normal",
            WallMeasure::Area => "larger |spherical area| of its two cells",
            WallMeasure::Length => "its edge over the mean edge length",
        }
    }

    pub fn unit(self) -> &'static str {
        match self {
            WallMeasure::Omega | WallMeasure::Axis => "deg",
            WallMeasure::Delta => "",
            WallMeasure::Closeness => "edge lengths",
            WallMeasure::Length => "",
            WallMeasure::Area => "sr",
        }
    }

    /// Where a wall stops being good: the honeycomb's tolerances, and the pipeline's bound for
    /// a vertex on S. Axis, area and length have none: they describe a design, they do not
    /// judge it.
    pub fn tolerance(self) -> Option<f64> {
        match self {
            WallMeasure::Omega => Some(Report::OMEGA_TOLERANCE_DEG),
            WallMeasure::Delta => Some(Report::DELTA_TOLERANCE),
            WallMeasure::Closeness => Some(ON_S),
            WallMeasure::Axis | WallMeasure::Area | WallMeasure::Length => None,
        }
    }

    /// Closeness and axis are measured against the design surface S.
    pub fn needs_surface(self) -> bool {
        matches!(self, WallMeasure::Closeness | WallMeasure::Axis)
    }

    /// One value per wall of `h`, from its measures (taken against S where the measure needs
    /// it) and, for area, the spherical image at `tolerance`.
    pub fn per_wall(
        self,
        h: &Honeycomb,
        m: &Measures,
        conn: &Connectivity,
        tolerance: f64,
    ) -> Vec<f64> {
        let larger = |per_node: &[f64]| per_wall_worse_end(&h.edges, per_node);
        match self {
            WallMeasure::Delta => m.delta_per_wall.clone(),
            WallMeasure::Omega => larger(&m.omega_per_node),
            WallMeasure::Closeness => larger(&m.closeness_per_vertex),
            WallMeasure::Axis => larger(&m.axis_normal_per_node),
            WallMeasure::Length => h
                .edges
                .iter()
                .map(|&[a, b]| {
                    (h.base.vertices[a] - h.base.vertices[b]).norm()
                        / m.mean_edge_length.max(1e-300)
                })
                .collect(),
            WallMeasure::Area => {
                let image = spherical_image(&h.base.faces, &h.axes, tolerance);
                conn.edge_faces
                    .iter()
                    .map(|fs| {
                        fs.iter()
                            .flatten()
                            .map(|&f| image.per_cell[f].area.abs())
                            .fold(0.0, f64::max)
                    })
                    .collect()
            }
        }
    }
}
