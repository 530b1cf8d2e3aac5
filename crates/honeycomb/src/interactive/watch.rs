//! A variant under editing. An edit keeps the honeycomb exact, not what its variant asked
//! (planar quads, parallel meshes, a share of the light): that is measured again from the
//! edited meshes, so that the editor shows what an edit cost.

use crate::analysis::{shading_against_normals, ShadingReport};
use crate::geometry::Vec3;
use crate::mesh::Connectivity;
use crate::structure::{
    face_measures, parallel_measures, FaceMeasures, Honeycomb, ParallelMeasures, QuadPattern,
};
use crate::surface::Surface;
use crate::{Outcome, Variant};
use serde::Serialize;

/// What a variant is judged by, on any honeycomb with the same cells.
#[derive(Clone, Debug, PartialEq)]
pub enum Watch {
    /// The quads that cap the cells, as corners of M.
    Quads {
        pattern: QuadPattern,
        quads: Vec<[usize; 4]>,
    },
    /// M and M' parallel: each edge's angle to its twin.
    Parallel,
    /// The light (and the sun path) the walls should block.
    Shading { light: Vec3, sun_path: Vec<Vec3> },
}

/// A [`Watch`] measured.
#[derive(Clone, Debug, Serialize)]
#[serde(tag = "variant", rename_all = "snake_case")]
pub enum Watched {
    Quads {
        pattern: QuadPattern,
        #[serde(flatten)]
        faces: FaceMeasures,
    },
    Parallel(ParallelMeasures),
    Shading(ShadingReport),
}

impl Watch {
    /// What `outcome`, made with `variant`, is judged by; `None` for a plain honeycomb (or
    /// prescribed axes, which an edit of the axes means to change).
    pub fn of(outcome: &Outcome, variant: &Variant) -> Option<Watch> {
        match variant {
            Variant::Quads { pattern, .. } => {
                let (mesh, report) = (outcome.quads.as_ref()?, outcome.report.quads.as_ref()?);
                // The cover lists its split quads first.
                let quads = (mesh.faces.iter().take(report.faces.quads))
                    .filter_map(|f| <[usize; 4]>::try_from(f.as_slice()).ok())
                    .collect();
                Some(Watch::Quads {
                    pattern: *pattern,
                    quads,
                })
            }
            Variant::Parallel { .. } => Some(Watch::Parallel),
            Variant::Shading {
                light, sun_path, ..
            } => Some(Watch::Shading {
                light: *light,
                sun_path: sun_path.clone(),
            }),
            Variant::Plain | Variant::Axes { .. } => None,
        }
    }

    /// What the variant is called.
    pub fn name(&self) -> String {
        match self {
            Watch::Quads { pattern, .. } => format!("quads {}", pattern.label()),
            Watch::Parallel => "parallel meshes".into(),
            Watch::Shading { .. } => "shading".into(),
        }
    }

    /// The variant's measure on `h` (whose cells are `conn`'s) over the design surface
    /// `surface` (model units): the shading against the same cells along S's normals, at
    /// `h`'s mean depth.
    pub fn measure(&self, h: &Honeycomb, conn: &Connectivity, surface: &Surface) -> Watched {
        match self {
            Watch::Quads { pattern, quads } => Watched::Quads {
                pattern: *pattern,
                faces: face_measures(&h.base.vertices, quads),
            },
            Watch::Parallel => Watched::Parallel(parallel_measures(h)),
            Watch::Shading { light, sun_path } => {
                let n = h.base.vertices.len().max(1) as f64;
                let depth = h.depths().sum::<f64>() / n;
                let shading = shading_against_normals(h, conn, surface, depth, *light, sun_path);
                Watched::Shading(shading)
            }
        }
    }
}
