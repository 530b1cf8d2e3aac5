//! Weights of the constraint families (defaults: the paper's Figure 16).

use crate::error::{Error, Result};
use serde::Serialize;

#[derive(Clone, Copy, Debug, Serialize)]
pub struct Weights {
    pub angle: f64,
    pub consistency: f64,
    pub normalization: f64,
    pub closeness: f64,
    pub boundary: f64,
    /// Opposite-wall fairness at the initial regularization; it fades with `sqrt(eps)`, so it
    /// shapes the result without biasing the honeycomb conditions.
    pub fairness: f64,
}

impl Default for Weights {
    fn default() -> Self {
        Weights {
            angle: 1.0,
            consistency: 1.0,
            normalization: 10.0,
            closeness: 1.0,
            boundary: 1.0,
            fairness: 3.0,
        }
    }
}

impl Weights {
    pub fn validate(&self) -> Result<()> {
        let all = [
            ("angle", self.angle),
            ("consistency", self.consistency),
            ("normalization", self.normalization),
            ("closeness", self.closeness),
            ("boundary", self.boundary),
            ("fairness", self.fairness),
        ];
        for (name, w) in all {
            if !w.is_finite() || !(0.0..=1e6).contains(&w) {
                return Err(Error::Parameter(format!(
                    "weight {name} = {w}: a weight must be a number between 0 and 1e6"
                )));
            }
        }
        for (name, w) in &all[..3] {
            if *w == 0.0 {
                return Err(Error::Parameter(format!(
                    "weight {name} = 0: the honeycomb conditions need a positive weight"
                )));
            }
        }
        Ok(())
    }
}
