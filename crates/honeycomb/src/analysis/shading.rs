//! The shading system's report (paper Fig. 18): the light share of the optimized honeycomb
//! against that of its own cells extruded along the surface normals to the same depth, for the
//! design light direction and for any number of others (a day's sun path), and whether it
//! blocks enough: at most [`SHADING_GOAL`] of the reference's share, for the design light and
//! for the sun path's mean.

use super::light::{light_share, DEFAULT_LIGHT_SAMPLES};
use crate::error::rounded;
use crate::geometry::Vec3;
use crate::mesh::{Connectivity, PolyMesh};
use crate::structure::Honeycomb;
use crate::surface::Surface;
use serde::Serialize;

/// The unshaded reference: the base mesh as given, each vertex extruded along S's normal.
pub fn extruded_along_normals(
    base: &PolyMesh,
    conn: &Connectivity,
    surface: &Surface,
    thickness: f64,
) -> Honeycomb {
    let axes = base
        .vertices
        .iter()
        .map(|&v| surface.normal_at(v))
        .collect();
    Honeycomb::new(base.clone(), conn, axes, thickness)
}

#[derive(Clone, Debug, Serialize)]
pub struct LightComparison {
    pub direction: [f64; 3],
    /// Share of the light that passes through the reference (before) and the result (after).
    pub before: f64,
    pub after: f64,
}

/// A shading honeycomb's walls are this deep by default (mean edge lengths): a ray across a
/// cell then meets a wall unless the light nearly runs along the node axes.
pub const SHADING_DEPTH: f64 = 1.5;

/// A shading honeycomb lets through at most this share of the light its cells would let
/// through extruded along S's normals.
pub const SHADING_GOAL: f64 = 0.5;

#[derive(Clone, Debug, Serialize)]
pub struct Shares {
    pub before: f64,
    pub after: f64,
}

/// Shares below this are no light: about the accuracy of [`light_share`] over a honeycomb.
const NO_LIGHT: f64 = 0.005;

impl Shares {
    /// Whether `after` is at most [`SHADING_GOAL`] of `before`, or no light.
    fn met(&self) -> bool {
        self.after <= SHADING_GOAL * self.before || self.after < NO_LIGHT
    }
}

#[derive(Clone, Debug, Serialize)]
pub struct ShadingReport {
    /// What "before" is.
    pub reference: &'static str,
    pub samples_per_cell: usize,
    /// The depth asked of the walls (model units): every wall is this deep, but for the ends of
    /// those that would otherwise cross themselves.
    pub depth: f64,
    /// The design light direction.
    pub light: LightComparison,
    /// Every direction of a sun path, in its order (empty without one).
    pub sun_path: Vec<LightComparison>,
    /// The sun path's mean shares, before and after.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sun_path_mean: Option<Shares>,
    /// What is asked: "after" at most this share of "before", for the light and the path's
    /// mean.
    pub goal: f64,
    pub met: bool,
}

impl LightComparison {
    fn shares(&self) -> Shares {
        Shares {
            before: self.before,
            after: self.after,
        }
    }
}

impl ShadingReport {
    /// What falls short of the goal, in one sentence; `None` when it is met.
    pub fn shortfall(&self) -> Option<String> {
        let l = &self.light;
        let mut short = Vec::new();
        if !l.shares().met() {
            short.push(format!(
                "light {}: the cells let through {} of the direct light, against {} for the \
                 same cells along S's normals",
                crate::error::short_vector(Vec3::from_slice(&l.direction)),
                rounded(l.after, 3),
                rounded(l.before, 3)
            ));
        }
        if let Some(mean) = self.sun_path_mean.as_ref().filter(|m| !m.met()) {
            short.push(format!(
                "over the sun path they let through {} on average, against {}",
                rounded(mean.after, 3),
                rounded(mean.before, 3)
            ));
        }
        (!short.is_empty()).then(|| {
            format!(
                "{} (at most {SHADING_GOAL} of it asked, at walls {} deep; deeper walls block \
                 more: --thickness)",
                short.join("; "),
                rounded(self.depth, 4)
            )
        })
    }
}

/// The shares of `h` (whose cells are `conn`'s) against its own cells extruded along the
/// normals of S (`surface`) to `depth`: the shading's judgement.
pub fn shading_against_normals(
    h: &Honeycomb,
    conn: &Connectivity,
    surface: &Surface,
    depth: f64,
    light: Vec3,
    sun_path: &[Vec3],
) -> ShadingReport {
    let before = extruded_along_normals(&h.base, conn, surface, depth);
    shading_report(&before, h, depth, light, sun_path)
}

/// The shares of `after` against `before` (walls `depth` deep) for `light` and `sun_path`.
pub fn shading_report(
    before: &Honeycomb,
    after: &Honeycomb,
    depth: f64,
    light: Vec3,
    sun_path: &[Vec3],
) -> ShadingReport {
    let compare = |d: Vec3| LightComparison {
        direction: d.to_array(),
        before: light_share(before, d, DEFAULT_LIGHT_SAMPLES).share,
        after: light_share(after, d, DEFAULT_LIGHT_SAMPLES).share,
    };
    let light = compare(light);
    let sun_path: Vec<LightComparison> = sun_path.iter().map(|&d| compare(d)).collect();
    let mean = |share: fn(&LightComparison) -> f64| {
        sun_path.iter().map(share).sum::<f64>() / sun_path.len() as f64
    };
    let sun_path_mean = (!sun_path.is_empty()).then(|| Shares {
        before: mean(|c| c.before),
        after: mean(|c| c.after),
    });
    let met = light.shares().met() && sun_path_mean.as_ref().is_none_or(Shares::met);
    ShadingReport {
        reference: "the same cells of M, extruded along the surface normals to the same depth",
        samples_per_cell: DEFAULT_LIGHT_SAMPLES,
        depth,
        light,
        sun_path,
        sun_path_mean,
        goal: SHADING_GOAL,
        met,
    }
}
