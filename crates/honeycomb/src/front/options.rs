//! What an optimization runs with, as plain data: the same names and defaults as the
//! command line's flags (`w_angle` is `--w-angle`), so that any front can fill it in.

use crate::error::{check_positive_length, short_number, short_vector, Error, Result};
use crate::geometry::Vec3;
use crate::mesh::PolyMesh;
use crate::optimize::{
    shading_axes, unit_light, AxesOptions, OptimizeOptions, ParallelOptions, QuadOptions,
    WallNormals, Weights,
};
use crate::pipeline::Walls;
use crate::reciprocal::{AxisTargets, Turn};
use crate::solve::SolverOptions;
use crate::structure::QuadPattern;
use crate::surface::Surface;
use serde::{Deserialize, Serialize};

/// The options of an optimization. `Options::default()` is what `honeycomb optimize` runs
/// without flags: walls across S, a plain honeycomb.
///
/// ```
/// use honeycomb::{Options, Variant};
/// let options: Options = serde_json::from_str(
///     r#"{ "walls": "uniform", "iterations": 20, "w_fair": 0 }"#,
/// ).unwrap();
/// assert_eq!(options.iterations, Some(20));
/// assert!(options.validate().is_ok());
/// // A field out of range is named, with its value.
/// let bad = Options { eps: -1.0, ..Options::default() };
/// assert!(bad.validate().unwrap_err().to_string().contains("eps -1"));
/// let parallel = Options { variant: Variant::Parallel { depth: Some(0.2), w_parallel: None, w_depth: None }, ..Options::default() };
/// assert!(parallel.validate().is_ok());
/// // A shading device needs a light only; the sun path and weight may be left out.
/// let shading: Options =
///     serde_json::from_str(r#"{ "variant": { "kind": "shading", "light": [0.5, 0, -0.87] } }"#)
///         .unwrap();
/// assert!(matches!(shading.variant, Variant::Shading { ref sun_path, .. } if sun_path.is_empty()));
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Options {
    /// How the walls stand on S (a plain honeycomb only).
    pub walls: Walls,
    /// The paper's variants: parallel meshes, quads, prescribed axes, shading.
    pub variant: Variant,
    /// Guided-projection iterations at most; `None`: 10, 20 for shading and quads.
    pub iterations: Option<usize>,
    /// Initial regularization (in the frame where the mean edge is 1); it shrinks as steps
    /// succeed.
    pub eps: f64,
    /// A solve has converged when every condition's residual is below this (in the frame
    /// where the mean edge is 1); 0 runs every iteration (benchmarks).
    pub tolerance: f64,
    /// Distance between M and M' along the node axes (model units); `None`: 0.3 mean edge
    /// lengths.
    pub thickness: Option<f64>,
    /// Every edge at least this long (model units); shading defaults to 0.3 mean edge lengths.
    pub min_edge: Option<f64>,
    /// Weight of the 120-degree node condition.
    pub w_angle: f64,
    /// Weight of each wall containing its edge.
    pub w_cons: f64,
    /// Weight of unit normals; `None`: 0.3 with cell points, 10 with normals per edge.
    pub w_norm: Option<f64>,
    /// Weight of closeness to S.
    pub w_close: f64,
    /// Weight of boundary vertices on S's boundary.
    pub w_boundary: f64,
    /// Weight of opposite-wall fairness; `None`: 3, and the pipeline may try 0 next.
    pub w_fair: Option<f64>,
    /// Weight of the node axes along S's normals in the first iterations (fading).
    pub w_guide: f64,
    /// The solver's unknowns for the walls.
    pub wall_normals: WallNormals,
}

impl Default for Options {
    fn default() -> Self {
        let w = Weights::default();
        Options {
            walls: Walls::Across,
            variant: Variant::Plain,
            iterations: None,
            eps: SolverOptions::default().eps,
            tolerance: SolverOptions::default().tolerance,
            thickness: None,
            min_edge: None,
            w_angle: w.angle,
            w_cons: w.consistency,
            w_norm: None,
            w_close: w.closeness,
            w_boundary: w.boundary,
            w_fair: None,
            w_guide: w.guide,
            wall_normals: WallNormals::Auto,
        }
    }
}

/// The paper's variants (section 4). Each solves the base mesh as given by the guided
/// projection, with one normal per edge.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Variant {
    /// A honeycomb, nothing more.
    #[default]
    Plain,
    /// Parallel meshes M, M' (Fig. 9): M' solved too, its edges parallel to M's.
    Parallel {
        /// A soft constant depth |v - v'| (model units).
        depth: Option<f64>,
        /// Weight of edge parallelity (default 1).
        w_parallel: Option<f64>,
        /// Weight of the constant depth (default 0.1).
        w_depth: Option<f64>,
    },
    /// Every hexagon capped by two planar quads (Figs. 1, 11, 17).
    Quads {
        pattern: QuadPattern,
        /// The straight polylines follow the lattice direction closest to this.
        quad_direction: Option<Vec3>,
        /// Weight of quad planarity (default 1).
        w_cons_faces: Option<f64>,
        /// Weight of zigzag fairness (default 0.01).
        w_fair_zig: Option<f64>,
        /// Weight of straight-polyline fairness (default 0.01).
        w_fair_str: Option<f64>,
        /// The edge-length cv the cells may re-shape to for flatter quads (default: none, the
        /// cells keep their shape).
        quads_reshape: Option<f64>,
        /// Every hexagon split as the pattern says (default false: where the pattern's quads
        /// stay short of the floors, the least planar cells take their own diagonal).
        #[serde(default)]
        quads_whole_pattern: bool,
    },
    /// Prescribed node axes (Fig. 10): one direction per base-mesh vertex (zero: free).
    Axes {
        axes: Vec<Vec3>,
        /// Weight of the prescribed axes (default 0.1).
        w_axes: Option<f64>,
    },
    /// Shading (Fig. 18): node axes across the direction the light travels in, so that the
    /// walls block it; `sun_path` adds directions whose light share is reported too.
    Shading {
        light: Vec3,
        /// More directions (none when left out).
        #[serde(default)]
        sun_path: Vec<Vec3>,
        /// Weight of the axes across the light (default 0.03).
        w_axes: Option<f64>,
    },
}

impl Variant {
    /// What the variant is called, for labels; `None` for a plain honeycomb.
    pub fn name(&self) -> Option<String> {
        match self {
            Variant::Plain => None,
            Variant::Parallel { .. } => Some("parallel meshes".into()),
            Variant::Quads { pattern, .. } => Some(format!("quads {}", pattern.label())),
            Variant::Axes { .. } => Some("prescribed axes".into()),
            Variant::Shading { light, .. } => Some(format!(
                "shading, light {}",
                crate::error::short_vector(*light)
            )),
        }
    }
}

impl Variant {
    pub fn is_plain(&self) -> bool {
        *self == Variant::Plain
    }

    /// The variant's weights as a solve takes them, by field: the ones given, else the
    /// defaults.
    pub fn weights(&self) -> Vec<(&'static str, f64)> {
        if let Some(p) = self.parallel_options() {
            return vec![("w_parallel", p.weight), ("w_depth", p.depth_weight)];
        }
        if let Some(q) = self.quad_options() {
            return vec![
                ("w_cons_faces", q.w_cons_faces),
                ("w_fair_zig", q.w_fair_zigzag),
                ("w_fair_str", q.w_fair_straight),
            ];
        }
        self.axes_weight()
            .map(|w| vec![("w_axes", w)])
            .unwrap_or_default()
    }

    /// Parallel meshes as the solver takes them, the defaults filled in (not checked).
    fn parallel_options(&self) -> Option<ParallelOptions> {
        let Variant::Parallel {
            depth,
            w_parallel,
            w_depth,
        } = *self
        else {
            return None;
        };
        let defaults = ParallelOptions::default();
        Some(ParallelOptions {
            depth,
            weight: w_parallel.unwrap_or(defaults.weight),
            depth_weight: w_depth.unwrap_or(defaults.depth_weight),
        })
    }

    /// Quads as the solver takes them, the defaults filled in (not checked).
    fn quad_options(&self) -> Option<QuadOptions> {
        let Variant::Quads {
            pattern,
            quad_direction,
            w_cons_faces,
            w_fair_zig,
            w_fair_str,
            quads_reshape,
            quads_whole_pattern,
        } = *self
        else {
            return None;
        };
        let defaults = QuadOptions::default();
        Some(QuadOptions {
            pattern,
            direction: quad_direction,
            w_cons_faces: w_cons_faces.unwrap_or(defaults.w_cons_faces),
            w_fair_zigzag: w_fair_zig.unwrap_or(defaults.w_fair_zigzag),
            w_fair_straight: w_fair_str.unwrap_or(defaults.w_fair_straight),
            reshape: quads_reshape,
            whole_pattern: quads_whole_pattern,
        })
    }

    /// The prescribed axes' weight, given or the default of prescribed axes or of shading.
    fn axes_weight(&self) -> Option<f64> {
        match *self {
            Variant::Axes { w_axes, .. } => Some(w_axes.unwrap_or(AxesOptions::DEFAULT_WEIGHT)),
            Variant::Shading { w_axes, .. } => Some(w_axes.unwrap_or(AxesOptions::SHADING_WEIGHT)),
            _ => None,
        }
    }
}

/// Iterations beyond this are refused as a typo.
const MAX_ITERATIONS: usize = 10_000;

impl Options {
    /// The iterations asked for, or the default.
    pub fn max_iterations(&self) -> usize {
        self.iterations.unwrap_or(match self.variant {
            Variant::Shading { .. } => 20,
            // Re-shaping the cells is a slide after the held tries, which takes long.
            Variant::Quads {
                quads_reshape: Some(_),
                ..
            } => 60,
            Variant::Quads { .. } => 20,
            _ => 10,
        })
    }

    /// Checks what does not depend on the meshes, naming an offending field and its value
    /// ([`Error::Option`]).
    pub fn validate(&self) -> Result<()> {
        let iterations = self.max_iterations();
        if iterations == 0 || iterations > MAX_ITERATIONS {
            return Err(Error::option(
                "iterations",
                iterations,
                format!("expected 1 to {MAX_ITERATIONS}"),
            ));
        }
        // Below 1e-12 the regularization is lost in roundoff against unit weights.
        if !self.eps.is_finite() || !(1e-12..=1e3).contains(&self.eps) {
            return Err(Error::option(
                "eps",
                short_number(self.eps),
                "expected a number from 1e-12 to 1e3, typically 1e-3",
            ));
        }
        if !self.tolerance.is_finite() || !(0.0..=1.0).contains(&self.tolerance) {
            return Err(Error::option(
                "tolerance",
                short_number(self.tolerance),
                "expected a residual from 0 to 1",
            ));
        }
        if let Some(t) = self.thickness {
            check_positive_length("thickness", t)?;
        }
        if let Some(l) = self.min_edge {
            check_positive_length("min_edge", l)?;
        }
        self.weights().validate()?;
        // Quads cap the plain honeycomb, and the pipeline pairs parallel meshes on its walls
        // across S (free walls: parallel meshes solved with the walls, the paper's way); the
        // other variants solve the base mesh as given.
        let caps = matches!(self.variant, Variant::Plain | Variant::Quads { .. });
        let pairs = matches!(self.variant, Variant::Parallel { .. })
            && matches!(self.walls, Walls::Across | Walls::Free);
        if !caps && !pairs && self.walls != Walls::Across {
            return Err(Error::option(
                "walls",
                self.walls.label(),
                "the walls shape the plain honeycomb (and the one quads cap); parallel meshes \
                 stand on walls across S or free ones, and prescribed axes solve the base mesh \
                 as given",
            ));
        }
        if !caps && self.wall_normals == WallNormals::CellPoints {
            return Err(Error::option(
                "wall_normals",
                "cell_points",
                "only for the plain honeycomb and the one quads cap (parallel meshes and \
                 prescribed axes constrain the normals one by one)",
            ));
        }
        match &self.variant {
            Variant::Plain => Ok(()),
            Variant::Parallel { .. } => self.parallel().map(|_| ()),
            Variant::Quads { .. } => self.quads().map(|_| ()),
            Variant::Axes { axes, .. } => {
                if let Some(v) = axes.iter().position(|a| !a.is_finite()) {
                    return Err(Error::option(
                        "axes",
                        format!("[{v}] {}", short_vector(axes[v])),
                        "expected finite directions",
                    ));
                }
                self.check_axes_weight()
            }
            Variant::Shading {
                light, sun_path, ..
            } => {
                for (field, d) in std::iter::once(("light", light))
                    .chain(sun_path.iter().map(|d| ("sun_path", d)))
                {
                    unit_light(*d).map_err(|_| {
                        Error::option(field, short_vector(*d), "expected a non-zero direction")
                    })?;
                }
                self.check_axes_weight()
            }
        }
    }

    /// The prescribed axes' weight, given or the variant's default.
    fn check_axes_weight(&self) -> Result<()> {
        let w = self
            .variant
            .axes_weight()
            .unwrap_or(AxesOptions::DEFAULT_WEIGHT);
        crate::optimize::check_weight("w_axes", w, false)
    }

    /// The weights as the solver takes them.
    pub(crate) fn weights(&self) -> Weights {
        Weights {
            angle: self.w_angle,
            consistency: self.w_cons,
            normalization: self.w_norm,
            closeness: self.w_close,
            boundary: self.w_boundary,
            fairness: self.w_fair.unwrap_or(Weights::default().fairness),
            guide: self.w_guide,
            evenness: 0.0,
            held_walls: 0.0,
        }
    }

    /// Shading, as the pipeline and `optimize` make it: the light (unit), the sun path and
    /// the depth asked.
    pub(crate) fn shading(&self) -> Result<Option<Shading>> {
        let Variant::Shading {
            light, sun_path, ..
        } = &self.variant
        else {
            return Ok(None);
        };
        self.validate()?;
        Ok(Some(Shading {
            light: unit_light(*light)?,
            sun_path: sun_path.clone(),
            depth: self.thickness,
        }))
    }

    /// Parallel meshes the pipeline pairs on the walls of its honeycomb (walls across S)
    /// rather than solves with them (free walls).
    pub(crate) fn paired_parallel(&self) -> Result<Option<ParallelOptions>> {
        Ok(self.parallel()?.filter(|_| self.walls != Walls::Free))
    }

    fn parallel(&self) -> Result<Option<ParallelOptions>> {
        let p = self.variant.parallel_options();
        p.as_ref().map(ParallelOptions::validate).transpose()?;
        Ok(p)
    }

    pub(crate) fn quads(&self) -> Result<Option<QuadOptions>> {
        let q = self.variant.quad_options();
        q.as_ref().map(QuadOptions::validate).transpose()?;
        Ok(q)
    }

    /// The solver's options for what does not depend on the meshes (no prescribed axes yet).
    pub(crate) fn optimize_options(&self) -> Result<OptimizeOptions> {
        self.validate()?;
        Ok(OptimizeOptions {
            weights: self.weights(),
            solver: SolverOptions {
                max_iterations: self.max_iterations(),
                eps: self.eps,
                tolerance: self.tolerance,
                ..SolverOptions::default()
            },
            thickness: self.thickness,
            min_edge: self.min_edge,
            parallel: self.parallel()?,
            quads: self.quads()?,
            wall_normals: self.wall_normals,
            ..OptimizeOptions::default()
        })
    }

    /// The solver's options for `base` on `surface`: with prescribed axes (given, or across
    /// the light on S) and the minimum edge that shading needs; checked against the base.
    pub(crate) fn optimize_options_for(
        &self,
        base: &PolyMesh,
        surface: &Surface,
    ) -> Result<OptimizeOptions> {
        let mut options = self.optimize_options()?;
        let weight = self
            .variant
            .axes_weight()
            .unwrap_or(AxesOptions::DEFAULT_WEIGHT);
        let axes = match &self.variant {
            Variant::Axes { axes, .. } => Some(AxesOptions {
                targets: axes.clone(),
                weight,
            }),
            Variant::Shading { light, .. } => {
                // Walls tilted far from the normals collapse boundary edges without it.
                options
                    .min_edge
                    .get_or_insert(SHADING_MIN_EDGE * base.mean_edge_length());
                Some(AxesOptions {
                    targets: shading_axes(surface, &base.vertices, *light)?,
                    weight,
                })
            }
            _ => None,
        };
        if let Some(a) = &axes {
            a.validate(base.vertices.len())?;
        }
        options.axes = axes;
        options.validate(base)?;
        Ok(options)
    }
}

/// A shading device asked for (see [`Options::shading`]).
#[derive(Clone, Debug)]
pub(crate) struct Shading {
    pub light: Vec3,
    pub sun_path: Vec<Vec3>,
    /// The walls' depth (model units); `None`: [`crate::analysis::SHADING_DEPTH`] mean edge
    /// lengths.
    pub depth: Option<f64>,
}

impl Shading {
    /// What the node axes are fitted to: S's normals turned across the light and the sun
    /// path as `turn` says (a steady turn leaning the way S's mean normal turns).
    pub fn targets(&self, turn: Turn, surface: &Surface) -> AxisTargets {
        let path: Vec<Vec3> = self.sun_path.iter().map(|d| d.normalized()).collect();
        AxisTargets::across_light(self.light, &path, turn, surface.mean_normal())
    }
}

/// Shading's minimum edge length, in mean edge lengths of the base mesh.
const SHADING_MIN_EDGE: f64 = 0.3;
