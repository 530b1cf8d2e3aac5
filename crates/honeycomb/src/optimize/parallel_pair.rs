//! Parallel meshes M, M' (paper section 4, Fig. 9) on the walls of a finished honeycomb: the
//! walls are kept, so every node keeps its 120 degrees and every wall its plane, and what is
//! solved for is where M and M' sit on the node axes (see `ParallelOnAxes`). A honeycomb on S
//! leaves about one degree of freedom per cell for this (the paper's count); the rest is
//! bought by letting the vertices slide off S along their axes, softly held, and the depth
//! vary, softly held at the nominal one.

use super::{Frame, ParallelOptions};
use crate::constraints::{AxisSlides, ParallelOnAxes, ScalarTargets};
use crate::error::Result;
use crate::geometry::Vec3;
use crate::mesh::Connectivity;
use crate::solve::{Constraint, GuidedProjection, IterationInfo, SolveReport, SolverOptions};
use crate::structure::{betas_deg, Honeycomb};

/// The hold of each vertex on S (its slide along the axis, per mean edge length), tried from
/// firm to loose until the edges of M and M' are within [`BETA_ACCEPTED_DEG`]: the freedom to
/// make them parallel lies across S, and this is what it costs.
const SHIFT_WEIGHTS: [f64; 3] = [1.0, 0.3, 0.1];
/// A try whose edges of M and M' are all this parallel (degrees) is kept.
const BETA_ACCEPTED_DEG: f64 = 0.5;
/// Iterations per try: the rows are bilinear and the solve settles in a few steps.
const ITERATIONS_PER_TRY: usize = 6;
/// A depth below this share of the nominal one, or a twin edge turned against its edge, counts
/// as collapsed (a try that makes one is not kept).
const COLLAPSED: f64 = 0.1;

/// M and M' on the kept walls, in model units.
pub struct Paired {
    pub vertices: Vec<Vec3>,
    pub offset: Vec<Vec3>,
    pub solve: SolveReport,
}

/// Places M and M' of `honeycomb` (model units; `normals` its unit wall normals, one per edge
/// of `conn`) on its node axes so that their edges are as parallel as the walls allow; the
/// nominal depth is `options.depth`, else the honeycomb's thickness.
pub(crate) fn pair(
    honeycomb: &Honeycomb,
    conn: &Connectivity,
    normals: &[Vec3],
    options: &ParallelOptions,
    solver: &SolverOptions,
    progress: &mut dyn FnMut(&IterationInfo),
) -> Result<Paired> {
    let frame = Frame::of(&honeycomb.base);
    let depth = options.depth.unwrap_or(honeycomb.thickness) / frame.unit;
    let solver = SolverOptions {
        max_iterations: ITERATIONS_PER_TRY,
        ..solver.clone()
    };
    let mut iterations = 0;
    let mut best: Option<(f64, Paired)> = None;
    let mut last_solve = None;
    for &shift_weight in &SHIFT_WEIGHTS {
        let problem = PairingProblem::build(
            honeycomb,
            &frame,
            conn,
            normals,
            depth,
            options,
            shift_weight,
        );
        let (mut x, slides, anchors) = (problem.x, problem.slides, problem.anchors);
        let mut projection = GuidedProjection::with_positions(x.len(), problem.families, None)?;
        let mut solve = projection.solve(&mut x, &solver, progress)?;
        iterations += solve.iterations;
        solve.iterations = iterations;
        let (vertices, offset): (Vec<Vec3>, Vec<Vec3>) = (anchors.iter().enumerate())
            .map(|(v, &p)| {
                let a = honeycomb.axes[v];
                let on_m = p + a * x[slides.shift(v)];
                (on_m, on_m + a * x[slides.depth(v)])
            })
            .unzip();
        let collapsed = (0..vertices.len()).any(|v| x[slides.depth(v)] < COLLAPSED * depth)
            || conn.edges.iter().any(|&[a, b]| {
                let (e, twin) = (vertices[a] - vertices[b], offset[a] - offset[b]);
                e.dot(twin) <= 0.0
            });
        if collapsed {
            last_solve = Some(solve);
            continue;
        }
        let beta = betas_deg(&vertices, &offset, &conn.edges).fold(0.0, f64::max);
        let paired = Paired {
            vertices: vertices.into_iter().map(|p| frame.to_model(p)).collect(),
            offset: offset.into_iter().map(|p| frame.to_model(p)).collect(),
            solve,
        };
        if beta <= BETA_ACCEPTED_DEG {
            return Ok(paired);
        }
        if best.as_ref().is_none_or(|(b, _)| beta < *b) {
            best = Some((beta, paired));
        }
    }
    Ok(match best {
        Some((_, mut paired)) => {
            paired.solve.iterations = iterations;
            paired
        }
        // Every try collapsed an edge: M' at the nominal depth, as the honeycomb was.
        None => Paired {
            vertices: honeycomb.base.vertices.clone(),
            offset: (honeycomb.base.vertices.iter().zip(&honeycomb.axes))
                .map(|(&p, &a)| p + a * depth * frame.unit)
                .collect(),
            solve: last_solve.expect("a try ran"),
        },
    })
}

/// The pairing solve's unknowns (each vertex's slide along its axis, then its depth, in the
/// normalized frame) and families.
pub(crate) struct PairingProblem {
    pub x: Vec<f64>,
    pub families: Vec<Box<dyn Constraint>>,
    pub slides: AxisSlides,
    /// The honeycomb's vertices, normalized: where the slides start.
    pub anchors: Vec<Vec3>,
}

impl PairingProblem {
    pub fn build(
        honeycomb: &Honeycomb,
        frame: &Frame,
        conn: &Connectivity,
        normals: &[Vec3],
        depth: f64,
        options: &ParallelOptions,
        shift_weight: f64,
    ) -> PairingProblem {
        let anchors = frame.to_normalized(&honeycomb.base).vertices;
        let n = anchors.len();
        let slides = AxisSlides {
            start: 0,
            vertices: n,
        };
        let mut x = vec![0.0; n];
        x.extend(std::iter::repeat_n(depth, n));
        let families: Vec<Box<dyn Constraint>> = vec![
            Box::new(ParallelOnAxes {
                slides,
                anchors: anchors.clone(),
                axes: honeycomb.axes.clone(),
                edges: conn.edges.clone(),
                normals: normals.to_vec(),
                depth,
                weight: options.weight,
            }),
            Box::new(ScalarTargets {
                name: "on_s",
                start: slides.shift(0),
                targets: vec![0.0; n],
                unit: 1.0,
                weight: shift_weight,
            }),
            Box::new(ScalarTargets {
                name: "depth",
                start: slides.depth(0),
                targets: vec![depth; n],
                unit: depth,
                weight: options.depth_weight,
            }),
        ];
        PairingProblem {
            x,
            families,
            slides,
            anchors,
        }
    }
}
