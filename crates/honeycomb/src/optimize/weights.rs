//! Weights of the constraint families (defaults: the paper's Figure 16).

use super::WallNormals;
use crate::error::Result;
use serde::Serialize;

#[derive(Clone, Copy, Debug, Serialize)]
pub struct Weights {
    pub angle: f64,
    pub consistency: f64,
    /// `None`: the wall normals' own (see [`WallNormals::normalization`]); `optimize` reports
    /// the weight it used.
    pub normalization: Option<f64>,
    pub closeness: f64,
    pub boundary: f64,
    /// Opposite-wall fairness at the initial regularization; it fades with the square root of
    /// the regularization's schedule (which, unlike eps, has no floor), so it shapes the result
    /// without biasing the honeycomb conditions.
    pub fairness: f64,
    /// Guide of the node axes towards the surface normals (walls across the surface) for the
    /// first iterations; it fades by 0.3 per iteration. Off (0) by default: with it, the
    /// opposite-wall fairness (which favours parallel walls) is best turned off.
    pub guide: f64,
    /// Every edge the mean length, fading like the fairness: cells of one size. Off (0) by
    /// default; the pipeline evens uneven cells of walls across S with it.
    pub evenness: f64,
    /// Every wall normal held where it starts, fading like the fairness: with the evenness,
    /// so that evening the cells does not turn the node axes away from where a fit put them.
    pub held_walls: f64,
}

impl Default for Weights {
    fn default() -> Self {
        Weights {
            angle: 1.0,
            consistency: 1.0,
            normalization: None,
            closeness: 1.0,
            boundary: 1.0,
            fairness: 3.0,
            guide: 0.0,
            evenness: 0.0,
            held_walls: 0.0,
        }
    }
}

impl Weights {
    /// The normalization weight; unset: the one of normals per edge (which the families of
    /// [`super::families`] are).
    pub fn normalization(&self) -> f64 {
        self.normalization
            .unwrap_or(WallNormals::PerEdge.normalization())
    }

    /// These weights with the normalization weight set for `normals` unless it is set.
    pub fn resolved(mut self, normals: WallNormals) -> Weights {
        self.normalization.get_or_insert(normals.normalization());
        self
    }

    /// Checks every weight, naming an offender by its field in [`crate::Options`]. The first
    /// three are the honeycomb conditions and must be positive; the others may be 0 (off).
    pub fn validate(&self) -> Result<()> {
        let weights = [
            ("w_angle", self.angle, true),
            ("w_cons", self.consistency, true),
            ("w_norm", self.normalization(), true),
            ("w_close", self.closeness, false),
            ("w_boundary", self.boundary, false),
            ("w_fair", self.fairness, false),
            ("w_guide", self.guide, false),
        ];
        for (field, w, required) in weights {
            super::variants::check_weight(field, w, !required)?;
        }
        Ok(())
    }
}
