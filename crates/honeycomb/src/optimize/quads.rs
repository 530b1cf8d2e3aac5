//! Quadrangulation (paper section 4, Figs. 1, 11, 17) as an option of `optimize`: every
//! hexagon of M is split into two quads that must be planar, with soft fairness of the zigzag
//! and straight polylines. Adds one unit normal per quad after the unknowns already there.

pub use crate::structure::QuadPattern;

use super::problem::ProblemBuilder;
use super::variants::check_weight;
use crate::constraints::{
    LateralRun, QuadNormalBlock, QuadNormalization, QuadPlanarity, StraightFairness, ZigzagFairness,
};
use crate::error::{Error, Result};
use crate::geometry::{smallest_eigenvector, sum_of_outer_products, Vec3};
use crate::mesh::{Connectivity, PolyMesh};
use crate::solve::Role;
use crate::structure::QuadCover;
use crate::surface::Surface;

#[derive(Clone, Debug)]
pub struct QuadOptions {
    pub pattern: QuadPattern,
    /// The straight polylines run along the lattice direction closest to this (model
    /// coordinates); `None`: the direction whose quads start closest to planar.
    pub direction: Option<Vec3>,
    /// Weight of the quad planarity rows (the paper's w_cons^faces, 0.1).
    pub w_cons_faces: f64,
    /// Weight of zigzag fairness (the paper's w_fair^zig, 0.01).
    pub w_fair_zigzag: f64,
    /// Weight of straight-polyline fairness (the paper's w_fair^str, 0.01).
    pub w_fair_straight: f64,
}

impl Default for QuadOptions {
    fn default() -> Self {
        QuadOptions {
            pattern: QuadPattern::Zigzag,
            direction: None,
            w_cons_faces: 0.1,
            w_fair_zigzag: 0.01,
            w_fair_straight: 0.01,
        }
    }
}

impl QuadOptions {
    pub fn validate(&self) -> Result<()> {
        if let Some(d) = self.direction {
            if !d.is_finite() || d.norm() < 1e-12 {
                return Err(Error::option(
                    "quad_direction",
                    crate::error::short_vector(d),
                    "expected a non-zero finite vector",
                ));
            }
        }
        check_weight("w_cons_faces", self.w_cons_faces, false)?;
        check_weight("w_fair_zig", self.w_fair_zigzag, true)?;
        check_weight("w_fair_str", self.w_fair_straight, true)
    }
}

/// The polyline fairness keeps its small weight to the end instead of fading with the
/// regularization: it is what holds the vertices in place along the surface, which the quad
/// planarity pulls at and nothing else resists. Faded, a twisted roof (tests/quads.rs) came
/// out with zigzags irregular by 1.6 edge lengths and an iteration that swung back and forth.
const FAIRNESS_ROLE: Role = Role::Condition;

/// Which sides of a quad get a planarity row: all four (see `QuadPlanarity::sides`).
const SIDES: [usize; 4] = [0, 1, 2, 3];

/// Splits the cells of `mesh` (normalized frame), allocates one unit normal per quad and
/// pushes the planarity and fairness families. The quad normals start as each quad's best-fit
/// plane normal, turned to the side of S's normal.
pub(crate) fn add_quads(
    mesh: &PolyMesh,
    conn: &Connectivity,
    surface: &Surface,
    options: &QuadOptions,
    normalization_weight: f64,
    problem: &mut ProblemBuilder<'_, '_>,
) -> QuadCover {
    let cover = QuadCover::new(mesh, conn, options.pattern, options.direction);
    let normals = (0..cover.quads.len())
        .flat_map(|q| best_fit_normal(cover.corners(&mesh.vertices, q), surface).to_array());
    let block = QuadNormalBlock {
        start: problem.allocate("quad_normals", normals).start,
    };
    if cover.quads.is_empty() {
        return cover;
    }
    let layout = problem.layout();
    problem.push(QuadNormalization {
        block,
        num_quads: cover.quads.len(),
        weight: normalization_weight,
    });
    problem.push(QuadPlanarity {
        layout,
        block,
        quads: cover.quads.clone(),
        sides: SIDES.to_vec(),
        weight: options.w_cons_faces,
    });
    if options.w_fair_zigzag > 0.0 && !cover.zigzag_runs.is_empty() {
        problem.push(ZigzagFairness {
            layout,
            runs: cover.zigzag_runs.clone(),
            weight: options.w_fair_zigzag,
            role: FAIRNESS_ROLE,
        });
    }
    if options.w_fair_straight > 0.0 && !cover.straight_runs.is_empty() {
        let runs = cover
            .straight_runs
            .iter()
            .map(|r| LateralRun {
                edge: r.edge,
                sign: conn.edge_sign(r.edge, r.i),
                j: r.j,
                k: r.k,
            })
            .collect();
        problem.push(StraightFairness {
            layout,
            runs,
            weight: options.w_fair_straight,
            role: FAIRNESS_ROLE,
        });
    }
    cover
}

/// The normal of the plane through the quad's centroid that is closest to its corners (least
/// squares), on the side of S's normal there.
fn best_fit_normal(corners: [Vec3; 4], surface: &Surface) -> Vec3 {
    let c = corners.iter().fold(Vec3::ZERO, |s, &p| s + p) / 4.0;
    let n = smallest_eigenvector(sum_of_outer_products(corners.map(|p| p - c)));
    if n.dot(surface.normal_at(c)) < 0.0 {
        -n
    } else {
        n
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_options_are_named() {
        let bad = [
            QuadOptions {
                direction: Some(Vec3::ZERO),
                ..QuadOptions::default()
            },
            QuadOptions {
                direction: Some(Vec3::new(f64::NAN, 0.0, 1.0)),
                ..QuadOptions::default()
            },
            QuadOptions {
                w_cons_faces: 0.0,
                ..QuadOptions::default()
            },
            QuadOptions {
                w_fair_zigzag: -1.0,
                ..QuadOptions::default()
            },
            QuadOptions {
                w_fair_straight: f64::INFINITY,
                ..QuadOptions::default()
            },
        ];
        let words = [
            "quad_direction",
            "quad_direction",
            "w_cons_faces",
            "w_fair_zig",
            "w_fair_str",
        ];
        for (o, word) in bad.iter().zip(words) {
            let e = o.validate().unwrap_err().to_string();
            assert!(e.contains(word), "{e}");
        }
        QuadOptions::default().validate().unwrap();
    }
}
