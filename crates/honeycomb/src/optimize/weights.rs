//! Weights of the constraint families (defaults: the paper's Figure 16).

use super::WallNormals;
use crate::error::{Error, Result};
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

    /// The weights with the labels to name them by, in the order angle, consistency,
    /// normalization, closeness, boundary, fairness, guide. The first three are the honeycomb
    /// conditions and must be positive; the others may be 0 (off).
    fn labelled<'a>(&self, labels: [&'a str; 7]) -> [(&'a str, f64, bool); 7] {
        let w = [
            self.angle,
            self.consistency,
            self.normalization(),
            self.closeness,
            self.boundary,
            self.fairness,
            self.guide,
        ];
        std::array::from_fn(|k| (labels[k], w[k], k < 3))
    }

    /// Checks every weight, naming an offender by its label in `labels` (see `labelled`).
    pub fn validate_as(&self, labels: [&str; 7]) -> Result<()> {
        for (label, w, required) in self.labelled(labels) {
            if !w.is_finite() || !(0.0..=1e6).contains(&w) || (required && w == 0.0) {
                let range = if required { "above 0" } else { "from 0" };
                return Err(Error::Parameter(format!(
                    "{label} {}: expected a weight {range} up to 1e6",
                    crate::error::rounded(w, 6)
                )));
            }
        }
        Ok(())
    }

    pub fn validate(&self) -> Result<()> {
        self.validate_as([
            "weight angle",
            "weight consistency",
            "weight normalization",
            "weight closeness",
            "weight boundary",
            "weight fairness",
            "weight guide",
        ])
    }
}
