//! What an optimization or the pipeline gives back: the honeycomb, measured and judged.

use crate::error::{rounded, Result};
use crate::export::write_structure_with;
use crate::init::InitReport;
use crate::mesh::{OutputDir, PolyMesh, Verdict as Placement};
use crate::report::Report;
use crate::structure::{thickest_uncrossed, Honeycomb, Measures};
use std::path::{Path, PathBuf};

/// A result: the structure, its measures (from its realized meshes), whether it is a
/// honeycomb and why not, and the report (`report.json`).
pub struct Outcome {
    pub honeycomb: Honeycomb,
    pub measures: Measures,
    pub verdict: Verdict,
    pub report: Report,
    /// The mesh the result started from: the base mesh given, or the one the pipeline made
    /// (without the boundary cells it dropped).
    pub base: PolyMesh,
    /// The planar quads that cap the cells ([`crate::Variant::Quads`]).
    pub quads: Option<PolyMesh>,
    /// How the pipeline made its base mesh (`init.json`).
    pub initialized: Option<InitReport>,
}

/// Whether a result is a honeycomb: every node within the 120-degree tolerance and every
/// wall planar within its tolerance ([`Report::OMEGA_TOLERANCE_DEG`],
/// [`Report::DELTA_TOLERANCE`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Verdict {
    pub honeycomb: bool,
    /// Why not, in a sentence; `None` for a honeycomb.
    pub why: Option<String>,
    /// Where wall quads cross because the axes at their ends lean together: the thickness
    /// below which none does (model units), if that is less than the structure's.
    pub uncrossed_below: Option<f64>,
    /// What the variant asked and the result falls short of, in a sentence (a shading device
    /// that lets through more than half the light: [`crate::analysis::SHADING_GOAL`]).
    pub unmet: Option<String>,
}

impl Verdict {
    pub(crate) fn of(h: &Honeycomb, report: &Report) -> Verdict {
        let m = &report.measures;
        let uncrossed_below = (m.nonconvex_walls > 0)
            .then(|| thickest_uncrossed(h))
            .filter(|&t| t < report.thickness);
        let unmet = report.shading.as_ref().and_then(|s| s.shortfall());
        if report.honeycomb {
            return Verdict {
                honeycomb: true,
                why: None,
                uncrossed_below,
                unmet,
            };
        }
        // A pipeline's last solve after its other tries: what they all took too.
        let in_all = match report.iterations_total {
            total if total > report.iterations => format!(" ({total} in all, every try counted)"),
            _ => String::new(),
        };
        let mut why = format!(
            "not a honeycomb after {} iterations{in_all}: omega_max {:.3} deg, delta_max {:.1e} \
             (tolerance {} deg, {:.0e})",
            report.iterations,
            m.omega_max_deg,
            m.delta_max,
            Report::OMEGA_TOLERANCE_DEG,
            Report::DELTA_TOLERANCE,
        );
        if m.nonconvex_walls > 0 {
            why += &format!(
                "; {} wall quads are not convex at thickness {} (the node axes at their ends \
                 lean together or apart across the wall)",
                m.nonconvex_walls,
                rounded(report.thickness, 4)
            );
        }
        Verdict {
            honeycomb: false,
            why: Some(why),
            uncrossed_below,
            unmet,
        }
    }
}

impl Outcome {
    pub fn is_honeycomb(&self) -> bool {
        self.verdict.honeycomb
    }

    /// Writes the structure files into the directory `dir` (created if needed):
    /// structure.json, base.obj, offset.obj, walls.obj, report.json, quads.obj with quads,
    /// a pipeline's init.json, and initial.obj from a pipeline or a solve that dropped
    /// boundary cells.
    pub fn write(&self, dir: &Path) -> Result<()> {
        let mut extra: Vec<(&str, &PolyMesh)> = Vec::new();
        if let Some(q) = &self.quads {
            extra.push(("quads.obj", q));
        }
        let dropped = self.report.dropped_boundary_cells.is_some_and(|d| d > 0);
        if self.initialized.is_some() || dropped {
            // The mesh the kept solve started from, so that `optimize` repeats it.
            extra.push(("initial.obj", &self.base));
        }
        write_structure_with(dir, &self.honeycomb, &extra, &self.report)?;
        if let Some(init) = &self.initialized {
            crate::export::write_json(&dir.join("init.json"), init)?;
        }
        Ok(())
    }

    /// Writes the result as a whole: into `dir` for a honeycomb, else into `dir.failed` for
    /// inspection (the other of the two is removed); nothing half-written is ever left in
    /// either. Returns where it went.
    ///
    /// ```
    /// use honeycomb::generate::{lifted_hex_patch, Shape};
    /// use honeycomb::{optimize, BaseMesh, Options, Progress, Surface};
    /// let (base, surface) = lifted_hex_patch(Shape::Saddle, 150);
    /// let (base, surface) = (BaseMesh::from_mesh(base)?, Surface::new(surface)?);
    /// let outcome = optimize(&base, &surface, &Options::default(), &mut Progress::silent())?;
    /// let dir = std::env::temp_dir().join(format!("honeycomb-doc-{}", std::process::id()));
    /// assert_eq!(outcome.save(&dir)?, dir);
    /// assert!(dir.join("report.json").is_file() && dir.join("walls.obj").is_file());
    /// # std::fs::remove_dir_all(&dir).unwrap();
    /// # Ok::<(), honeycomb::Error>(())
    /// ```
    pub fn save(&self, dir: impl AsRef<Path>) -> Result<PathBuf> {
        let out = OutputDir::begin(dir.as_ref(), &[])?;
        out.finish(self.placement(), |d| self.write(d))
    }

    /// Where the outputs of this result belong ([`OutputDir::finish`]): a honeycomb that
    /// meets what its variant asks takes `DIR`'s place, any other goes to `DIR.failed` for
    /// inspection.
    pub fn placement(&self) -> Placement {
        if self.verdict.honeycomb && self.verdict.unmet.is_none() {
            Placement::Passed
        } else {
            Placement::Failed
        }
    }
}
