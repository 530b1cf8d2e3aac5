//! Measures of the paper's variants, from the realized meshes M and M' only.

use super::Honeycomb;
use crate::geometry::Vec3;
use serde::Serialize;

/// Parallel meshes (Fig. 9): how parallel corresponding edges of M and M' are, and how deep.
#[derive(Clone, Debug, Serialize)]
pub struct ParallelMeasures {
    /// Angle between edge `v_a v_b` of M and `v'_a v'_b` of M' (degrees).
    pub beta_max_deg: f64,
    pub beta_avg_deg: f64,
    /// Distance |v'_i - v_i| (model units).
    pub depth_min: f64,
    pub depth_max: f64,
}

pub fn parallel_measures(h: &Honeycomb) -> ParallelMeasures {
    let betas: Vec<f64> = betas_deg(&h.base.vertices, &h.offset.vertices, &h.edges).collect();
    let (depth_min, depth_max) = h.depths().fold((f64::INFINITY, 0.0f64), |(lo, hi), d| {
        (lo.min(d), hi.max(d))
    });
    ParallelMeasures {
        beta_max_deg: betas.iter().copied().fold(0.0, f64::max),
        beta_avg_deg: betas.iter().sum::<f64>() / betas.len().max(1) as f64,
        depth_min,
        depth_max,
    }
}

/// The angle between each edge `m_a m_b` of M and its twin `o_a o_b` in M' (degrees).
pub(crate) fn betas_deg<'a>(
    m: &'a [Vec3],
    o: &'a [Vec3],
    edges: &'a [[usize; 2]],
) -> impl Iterator<Item = f64> + 'a {
    (edges.iter()).map(|&[a, b]| angle_deg(m[a] - m[b], o[a] - o[b]))
}

/// Prescribed axes: the angle between each realized node axis (the line `v_i v'_i`) and its
/// target line, over the vertices that have a target (zero targets are skipped).
#[derive(Clone, Debug, Serialize)]
pub struct AxesMeasures {
    pub axes_angle_max_deg: f64,
    pub axes_angle_avg_deg: f64,
    pub axes_prescribed: usize,
}

pub fn axes_measures(h: &Honeycomb, targets: &[Vec3]) -> AxesMeasures {
    let angles: Vec<f64> = h
        .base
        .vertices
        .iter()
        .zip(&h.offset.vertices)
        .zip(targets)
        .filter(|(_, a)| a.norm() > 0.0)
        .map(|((&v, &w), &a)| {
            // Lines, not vectors: a target and its opposite prescribe the same walls.
            let angle = angle_deg(w - v, a);
            angle.min(180.0 - angle)
        })
        .collect();
    AxesMeasures {
        axes_angle_max_deg: angles.iter().copied().fold(0.0, f64::max),
        axes_angle_avg_deg: angles.iter().sum::<f64>() / angles.len().max(1) as f64,
        axes_prescribed: angles.len(),
    }
}

/// The angle between two vectors in degrees, accurate for small angles (atan2 of |u x w|, u.w).
pub fn angle_deg(u: Vec3, w: Vec3) -> f64 {
    u.cross(w).norm().atan2(u.dot(w)).to_degrees()
}
