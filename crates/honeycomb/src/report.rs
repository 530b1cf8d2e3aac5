//! `report.json`: the Figure 16 row of a run and everything needed to judge it.

use crate::analysis::ShadingReport;
use crate::error::rounded;
use crate::optimize::{Optimized, WallNormals, Weights};
use crate::pipeline::Walls;
use crate::solve::{FamilyResidual, IterationInfo};
use crate::structure::{
    axes_measures, parallel_measures, quad_mesh_measures, AxesMeasures, FaceMeasures, Honeycomb,
    Measures, ParallelMeasures, QuadPattern,
};
use serde::Serialize;

#[derive(Clone, Debug, Serialize)]
pub struct Report {
    /// How the walls stand on S: `"across"`, `"uniform"` or a direction `[x, y, z]`.
    pub walls: Walls,
    pub vertices: usize,
    pub edges: usize,
    pub faces: usize,
    pub iterations: usize,
    /// Solver iterations of every solve and every try that led here.
    pub iterations_total: usize,
    /// Walls across S: the iterations of the node axes' fit among them.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub axis_field_iterations: Option<usize>,
    /// The solver's residuals fell below its tolerance.
    pub converged: bool,
    /// The realized structure meets the honeycomb tolerances (see `is_honeycomb`).
    pub honeycomb: bool,
    /// omega, delta, closeness and the valence histogram, as top-level keys.
    #[serde(flatten)]
    pub measures: Measures,
    pub thickness: f64,
    /// Parallel meshes: beta (edge parallelity of M and M') and depth, as top-level keys.
    #[serde(flatten)]
    pub parallel: Option<ParallelMeasures>,
    /// Prescribed axes: the angle of the realized axes to their targets, as top-level keys.
    #[serde(flatten)]
    pub axes: Option<AxesMeasures>,
    /// Quad cover: the pattern and the planarity of its quads (`delta_face_max/avg`), as
    /// top-level keys.
    #[serde(flatten)]
    pub quads: Option<QuadCoverReport>,
    /// Shading: the light share before and after, for the design light and a sun path.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shading: Option<ShadingReport>,
    /// `pipeline`: boundary cells dropped because the solve broke them or because they stood
    /// out beyond S's border (with the few cells their loss cut off), those trimmed from the
    /// finished walls across S among them, the solves of the kept try, and whether it is the
    /// second (no fairness, minimum edge length).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dropped_boundary_cells: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub trimmed_boundary_cells: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub solves: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub second_try: Option<bool>,
    /// `pipeline`: the kept try has normals per edge because cell points gave no honeycomb.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub per_edge_fallback: Option<bool>,
    /// What the run changed on the way to this result, one sentence each (the `note:` lines).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
    /// Wall time of the whole optimization (symbolic analysis included).
    pub seconds: f64,
    pub seconds_symbolic: f64,
    pub seconds_assembly: f64,
    pub seconds_factorization: f64,
    pub seconds_other: f64,
    pub unknowns: usize,
    /// Unknowns eliminated exactly before the factorization (the vertices of a cell-point
    /// solve, whose rows touch one vertex each); the factor is of the rest.
    pub eliminated_unknowns: usize,
    /// Non-zeros of the normal matrix's upper triangle and of its Cholesky factor.
    pub matrix_nnz: usize,
    pub factor_nnz: usize,
    /// Threads of the numeric factorization: 2 when it is split in halves (large systems, two
    /// cores).
    pub factor_threads: usize,
    pub factorizations: usize,
    pub weights: Weights,
    /// The solver's unknowns for the wall normals: `cell_points` or `per_edge`.
    pub wall_normals: WallNormals,
    /// Solver residuals per constraint family after the last step (normalized frame).
    pub residuals: Vec<FamilyResidual>,
    pub history: Vec<IterationInfo>,
}

/// The quads that cap the cells, measured on the realized quad mesh.
#[derive(Clone, Debug, Serialize)]
pub struct QuadCoverReport {
    pub quad_pattern: QuadPattern,
    #[serde(flatten)]
    pub faces: FaceMeasures,
    /// What capping traded: planarity gained for distance to S.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub capping: Option<Capping>,
}

/// The capping solve (see `optimize::capped`): its iterations and the quads' planarity on the
/// honeycomb before it (how far it took the vertices from S is `closeness_max`).
#[derive(Clone, Debug, Serialize)]
pub struct Capping {
    pub iterations: usize,
    pub delta_face_max_before: f64,
    pub delta_face_avg_before: f64,
    /// The largest move of a vertex along S (across S's normal where it ended), in mean edge
    /// lengths: how far the cells shifted within their walls.
    pub along_s_max: f64,
    /// The edge lengths' cv before (after is `edge_length_cv`): how the cells re-shaped.
    pub edge_length_cv_before: f64,
    /// The edge cv the cells were allowed to re-shape to (`--quads-reshape`); `None`: each
    /// vertex was held in its place along S.
    pub reshape: Option<f64>,
    /// Hexagons split along their own flattest diagonal instead of the pattern's (0 for a
    /// `flattest` cover, or one that met the floors whole).
    pub cells_off_pattern: usize,
    /// Where the pattern whole stayed short of the floors: its quads' planarity then, the
    /// other side of the trade (`None`: it met them, or it was kept whole on request).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub whole_pattern: Option<FaceMeasures>,
}

impl Capping {
    /// A note stating the trade: the quads' planarity gained for the vertices' moves off S
    /// (`closeness_max`) and along it.
    pub fn trade(&self, after: &FaceMeasures, closeness_max: f64, cv: f64) -> String {
        format!(
            "capped in {} iterations: the worst quad {} -> {} and the mean {} -> {} from \
             planar, for vertices up to {} mean edge lengths off S and moved up to {} along it \
             (within their walls), the edge cv {} -> {}",
            self.iterations,
            rounded(self.delta_face_max_before, 4),
            rounded(after.delta_face_max, 4),
            rounded(self.delta_face_avg_before, 4),
            rounded(after.delta_face_avg, 4),
            rounded(closeness_max, 3),
            rounded(self.along_s_max, 3),
            rounded(self.edge_length_cv_before, 3),
            rounded(cv, 3),
        )
    }
}

impl Report {
    pub fn new(opt: &Optimized, m: &Measures, seconds: f64) -> Report {
        let s = &opt.solve;
        let honeycomb =
            m.omega_max_deg <= Self::OMEGA_TOLERANCE_DEG && m.delta_max <= Self::DELTA_TOLERANCE;
        Report {
            walls: Walls::Free,
            honeycomb,
            vertices: opt.honeycomb.base.vertices.len(),
            edges: opt.honeycomb.edges.len(),
            faces: opt.honeycomb.base.faces.len(),
            iterations: s.iterations,
            iterations_total: s.iterations,
            axis_field_iterations: None,
            converged: s.converged,
            measures: m.clone(),
            thickness: opt.honeycomb.thickness,
            parallel: opt.parallel.then(|| parallel_measures(&opt.honeycomb)),
            axes: opt
                .prescribed_axes
                .as_ref()
                .map(|targets| axes_measures(&opt.honeycomb, targets)),
            quads: opt
                .quads
                .as_ref()
                .zip(opt.quad_cover.as_ref())
                .map(|(mesh, cover)| QuadCoverReport {
                    quad_pattern: cover.pattern,
                    // From the written quad mesh, whose split quads come first.
                    faces: quad_mesh_measures(mesh, cover.quads.len()),
                    capping: None,
                }),
            shading: None,
            dropped_boundary_cells: None,
            trimmed_boundary_cells: None,
            solves: None,
            second_try: None,
            per_edge_fallback: None,
            notes: Vec::new(),
            seconds,
            seconds_symbolic: s.seconds_symbolic,
            seconds_assembly: s.seconds_assembly,
            seconds_factorization: s.seconds_factorization,
            seconds_other: s.seconds_other,
            unknowns: s.unknowns,
            eliminated_unknowns: s.eliminated_unknowns,
            matrix_nnz: s.matrix_nnz,
            factor_nnz: s.factor_nnz,
            factor_threads: s.factor_threads,
            factorizations: s.factorizations,
            weights: opt.weights,
            wall_normals: opt.wall_normals,
            residuals: s.families.clone(),
            history: s.history.clone(),
        }
    }

    /// This report (of the honeycomb `capped` was capped from, `before` its quads' planarity
    /// then) turned into the capped one's, measured `m` from its meshes; the capping solve's
    /// iterations (`capped.solve`'s) count in.
    pub fn capped(
        &mut self,
        capped: &Optimized,
        m: &Measures,
        before: &FaceMeasures,
        (along_s_max, edge_length_cv_before, reshape): (f64, f64, Option<f64>),
    ) {
        let s = &capped.solve;
        let (Some(mesh), Some(cover)) = (&capped.quads, &capped.quad_cover) else {
            return;
        };
        self.followed_by(capped, m);
        self.quads = Some(QuadCoverReport {
            quad_pattern: cover.pattern,
            // From the written quad mesh, whose split quads come first.
            faces: quad_mesh_measures(mesh, cover.quads.len()),
            capping: Some(Capping {
                iterations: s.iterations,
                delta_face_max_before: before.delta_face_max,
                delta_face_avg_before: before.delta_face_avg,
                along_s_max,
                edge_length_cv_before,
                reshape,
                cells_off_pattern: cover.off_pattern.len(),
                whole_pattern: capped.quads_whole_pattern.clone(),
            }),
        });
    }

    /// This report (of the honeycomb `paired` was paired on) turned into the parallel
    /// meshes' one, measured `m` from their meshes; the pairing solve's iterations count in.
    pub fn paired(&mut self, paired: &Optimized, m: &Measures) {
        self.followed_by(paired, m);
        self.parallel = Some(parallel_measures(&paired.honeycomb));
    }

    /// This report turned into that of the same walls made deeper for shading (`deep`,
    /// measured `m`), with the light they let through.
    pub fn deepened(&mut self, deep: &Honeycomb, m: &Measures, shading: ShadingReport) {
        self.thickness = deep.thickness;
        self.honeycomb = Self::within_tolerances(m);
        self.measures = m.clone();
        self.shading = Some(shading);
    }

    /// This report followed by a solve on the finished honeycomb that keeps its walls
    /// (`next`, measured `m`): its iterations add up, the rest is the later solve's.
    fn followed_by(&mut self, next: &Optimized, m: &Measures) {
        let s = &next.solve;
        self.iterations += s.iterations;
        self.iterations_total += s.iterations;
        self.converged = s.converged;
        self.thickness = next.honeycomb.thickness;
        self.honeycomb = Self::within_tolerances(m);
        self.measures = m.clone();
        self.residuals = s.families.clone();
        self.history = s.history.clone();
    }

    /// Largest node-angle deviation of a structure we call a honeycomb (degrees).
    pub const OMEGA_TOLERANCE_DEG: f64 = 0.1;
    /// Largest wall non-planarity of a structure we call a honeycomb.
    pub const DELTA_TOLERANCE: f64 = 1e-3;

    /// Whether measures meet the honeycomb tolerances.
    pub fn within_tolerances(m: &Measures) -> bool {
        m.omega_max_deg <= Self::OMEGA_TOLERANCE_DEG && m.delta_max <= Self::DELTA_TOLERANCE
    }

    /// "omega_max 3.100 deg (tolerance 0.1 deg), delta_max 2.0e-2 (tolerance 1e-3)", or delta
    /// alone where T-junctions make the angles 180/120/60 degrees by construction.
    pub fn tolerance_summary(m: &Measures, walls_only: bool) -> String {
        let delta = format!(
            "delta_max {:.1e} (tolerance {:.0e})",
            m.delta_max,
            Self::DELTA_TOLERANCE
        );
        if walls_only {
            return delta;
        }
        format!(
            "omega_max {:.3} deg (tolerance {} deg), {delta}",
            m.omega_max_deg,
            Self::OMEGA_TOLERANCE_DEG
        )
    }

    pub const FIGURE16_HEADER: &'static str =
        "   |V|    |E|  w_ang w_con w_nrm  #It  omega_max  omega_avg  delta_max  delta_avg   T (s)  axis";

    /// One row in the layout of the paper's Figure 16, and how the walls stand on S: the mean
    /// angle of the node axes to S's normals (degrees).
    pub fn figure16_row(&self) -> String {
        format!(
            "{:>6} {:>6} {:>6} {:>5} {:>5} {:>4} {:>10.2e} {:>10.2e} {:>10.2e} {:>10.2e} {:>7.3} {:>5.1}",
            self.vertices,
            self.edges,
            self.weights.angle,
            self.weights.consistency,
            self.weights.normalization(),
            self.iterations,
            self.measures.omega_max_deg,
            self.measures.omega_avg_deg,
            self.measures.delta_max,
            self.measures.delta_avg,
            self.seconds,
            self.measures.axis_normal_deg.mean
        )
    }
}

/// `report.json` of an edited structure.
#[derive(Clone, Debug, Serialize)]
pub struct EditReport {
    pub operation: String,
    pub vertices: usize,
    pub edges: usize,
    pub faces: usize,
    /// The realized structure meets the honeycomb tolerances (with T-junctions: its walls are
    /// planar; the angles at a T-junction are 180/120/60 degrees by construction).
    pub honeycomb: bool,
    /// Vertices where one wall ends on another (reciprocal structures).
    pub t_junctions: usize,
    /// omega, delta and closeness (to the structure before the edit) as top-level keys.
    #[serde(flatten)]
    pub measures: Measures,
    pub thickness: f64,
}

impl EditReport {
    pub fn new(
        h: &Honeycomb,
        measures: Measures,
        operation: String,
        t_junctions: usize,
    ) -> EditReport {
        let honeycomb = if t_junctions == 0 {
            Report::within_tolerances(&measures)
        } else {
            measures.delta_max <= Report::DELTA_TOLERANCE
        };
        EditReport {
            operation,
            vertices: h.base.vertices.len(),
            edges: h.edges.len(),
            faces: h.base.faces.len(),
            honeycomb,
            t_junctions,
            measures,
            thickness: h.thickness,
        }
    }
}
