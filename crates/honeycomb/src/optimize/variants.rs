//! The paper's variants (section 4) as options of `optimize`: each adds its own block of
//! unknowns after the honeycomb's (at `x.len()` when it is added) and its constraint families.

use crate::error::{Error, Result};
use crate::geometry::Vec3;
use crate::surface::Surface;

/// Parallel meshes M, M' (Fig. 9): M' becomes unknowns, its vertices on the node axes and its
/// edges parallel to those of M.
#[derive(Clone, Copy, Debug)]
pub struct ParallelOptions {
    /// Soft constant depth |v_i - v'_i| = C (model units); `None`: free depth.
    pub depth: Option<f64>,
    /// Weight of edge parallelity (the paper's w_parallel, 1).
    pub weight: f64,
    /// Weight of the constant-depth rows (low: the depth is a wish, not a condition).
    pub depth_weight: f64,
}

impl Default for ParallelOptions {
    fn default() -> Self {
        ParallelOptions {
            depth: None,
            weight: 1.0,
            depth_weight: 0.1,
        }
    }
}

impl ParallelOptions {
    pub fn validate(&self) -> Result<()> {
        if let Some(c) = self.depth {
            crate::error::check_positive_length("depth", c)?;
        }
        check_weight("w_parallel", self.weight, false)?;
        check_weight("w_depth", self.depth_weight, true)
    }
}

/// Prescribed node axes (Fig. 10 mechanism, shading Fig. 18): `a_i . n_ij = 0` at every edge
/// end of a vertex with a target.
#[derive(Clone, Debug)]
pub struct AxesOptions {
    /// One target direction per base-mesh vertex (any length; zero: no target at that vertex).
    pub targets: Vec<Vec3>,
    /// The paper's w_axes (0.1): lower than the honeycomb conditions.
    pub weight: f64,
}

impl AxesOptions {
    pub const DEFAULT_WEIGHT: f64 = 0.1;
    /// For the shading field, which tilts walls far from the normals: at 0.1 the conditions give
    /// way (a 3.3k dome, sun 35 degrees up: delta_max 1.2e-3; at 0.03: 3e-4, axes within 1.1
    /// degrees on average).
    pub const SHADING_WEIGHT: f64 = 0.03;

    pub fn validate(&self, num_vertices: usize) -> Result<()> {
        if self.targets.len() != num_vertices {
            return Err(Error::Parameter(format!(
                "{} prescribed axes for a base mesh of {num_vertices} vertices: expected one per vertex",
                self.targets.len()
            )));
        }
        if let Some(v) = self.targets.iter().position(|a| !a.is_finite()) {
            return Err(Error::Parameter(format!(
                "prescribed axis of vertex {v} is not finite"
            )));
        }
        if self.targets.iter().all(|a| a.norm() == 0.0) {
            return Err(Error::Parameter(
                "every prescribed axis is zero: nothing to prescribe".into(),
            ));
        }
        check_weight("w_axes", self.weight, false)
    }

    /// The unit targets (zero where none is given).
    pub fn unit_targets(&self) -> Vec<Vec3> {
        self.targets
            .iter()
            .map(|&a| if a.norm() > 0.0 { a.normalized() } else { a })
            .collect()
    }
}

/// The shading system's axis field (Fig. 18): at each vertex the surface normal with its
/// component along the light removed, so that every wall contains a direction across the light.
/// Where the normal is (nearly) parallel to the light any axis across it would do; those
/// vertices get no target (zero).
pub fn shading_axes(surface: &Surface, vertices: &[Vec3], light: Vec3) -> Result<Vec<Vec3>> {
    let l = unit_light(light)?;
    Ok(vertices
        .iter()
        .map(|&p| {
            let n = surface.normal_at(p);
            let a = n - l * n.dot(l);
            if a.norm() < 1e-3 {
                Vec3::new(0.0, 0.0, 0.0)
            } else {
                a.normalized()
            }
        })
        .collect())
}

/// A light direction as a unit vector, or a clear error for a zero or non-finite one.
pub fn unit_light(light: Vec3) -> Result<Vec3> {
    if !light.is_finite() || light.norm() < 1e-12 {
        return Err(Error::Parameter(format!(
            "light direction {}: expected a non-zero finite vector",
            crate::error::short_point(light)
        )));
    }
    Ok(light.normalized())
}

pub(crate) fn check_weight(field: &'static str, w: f64, may_be_zero: bool) -> Result<()> {
    if !w.is_finite() || !(0.0..=1e6).contains(&w) || (!may_be_zero && w == 0.0) {
        let range = if may_be_zero { "from 0" } else { "above 0" };
        return Err(Error::option(
            field,
            crate::error::rounded(w, 6),
            format!("expected a weight {range} up to 1e6"),
        ));
    }
    Ok(())
}
