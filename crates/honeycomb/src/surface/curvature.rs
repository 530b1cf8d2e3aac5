//! How much S curves at the scale of a cell: its angle defects (the discrete Gauss curvature)
//! summed over boxes about two cell edges wide, in units of 60 degrees. A hexagonal lattice of
//! even spacing absorbs one unit per pentagon or heptagon, or by stretching its cells; small
//! wrinkles cancel inside a box and are not counted.

use super::Surface;
use std::collections::HashMap;
use std::f64::consts::{FRAC_PI_3, TAU};

/// S's curvature at one scale, in units of 60 degrees of angle defect.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CurvatureUnits {
    /// Sums of the boxes that curve like a dome, and of those that curve like a saddle.
    pub positive: f64,
    pub negative: f64,
}

impl Surface {
    /// S's curvature summed over boxes of side `scale` (model units).
    pub fn curvature_units(&self, scale: f64) -> CurvatureUnits {
        let mut defect = vec![TAU; self.vertices.len()];
        for t in &self.triangles {
            for k in 0..3 {
                let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                let (u, v) = (
                    self.vertices[b] - self.vertices[a],
                    self.vertices[c] - self.vertices[a],
                );
                let angle = u.cross(v).norm().atan2(u.dot(v));
                defect[a] -= angle;
            }
        }
        let used: Vec<bool> = {
            let mut used = vec![false; self.vertices.len()];
            for t in &self.triangles {
                for &v in t {
                    used[v] = true;
                }
            }
            used
        };
        let mut boxes: HashMap<[i64; 3], f64> = HashMap::new();
        for (v, &p) in self.vertices.iter().enumerate() {
            if !used[v] || self.boundary_vertex[v] {
                continue;
            }
            let key = [p.x, p.y, p.z].map(|c| (c / scale).floor() as i64);
            *boxes.entry(key).or_insert(0.0) += defect[v];
        }
        let mut units = CurvatureUnits::default();
        for &d in boxes.values() {
            if d > 0.0 {
                units.positive += d / FRAC_PI_3;
            } else {
                units.negative -= d / FRAC_PI_3;
            }
        }
        units
    }
}
