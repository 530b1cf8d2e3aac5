//! Triangles of points that are copies of one rigid triangle: each triangle `t` has a rotation
//! `R_t` (a base rotation held outside the unknowns, times `exp(w_t)` of a rotation vector
//! among them) and its sides are the rotated sides of the reference triangle,
//! `p_(k+1) - p_k - R_t u_k = 0`, three rows per side. Unlike `|p_a - p_b|^2 = 1`, a step may
//! turn a triangle far without stretching it: the rows measure only how far neighbouring
//! triangles disagree about their shared points. The solver rebases: after a step the caller
//! folds `exp(w_t)` into the base and sets `w_t` back to zero (see [`SharedRotations`]).

use super::layout::{put, triple};
use crate::geometry::rotation::{apply, apply_derivative, exp, multiply, right_jacobian, Matrix3};
use crate::geometry::Vec3;
use crate::solve::Constraint;
use std::sync::{Arc, RwLock};

/// The base rotations, shared between the families that read them and the caller that
/// rebases them.
#[derive(Clone, Default)]
pub struct SharedRotations(Arc<RwLock<Vec<Matrix3>>>);

impl SharedRotations {
    pub fn new(bases: Vec<Matrix3>) -> SharedRotations {
        SharedRotations(Arc::new(RwLock::new(bases)))
    }

    pub fn get(&self, t: usize) -> Matrix3 {
        self.0.read().unwrap_or_else(|e| e.into_inner())[t]
    }

    /// Sets the base rotation of triangle `t`.
    pub fn set(&self, t: usize, base: Matrix3) {
        self.0.write().unwrap_or_else(|e| e.into_inner())[t] = base;
    }

    /// Folds each rotation vector `w[t]` into its base rotation.
    pub fn rebase(&self, w: &[Vec3]) {
        let mut bases = self.0.write().unwrap_or_else(|e| e.into_inner());
        for (base, &wt) in bases.iter_mut().zip(w) {
            *base = multiply(&exp(wt), base);
        }
    }
}

fn vector(x: &[f64], block: usize) -> Vec3 {
    Vec3::from_slice(&x[3 * block..])
}

pub struct RigidTriangles {
    /// The points of each triangle (point `k` is unknowns `3k..3k + 3`).
    pub triangles: Vec<[usize; 3]>,
    /// Triangle `t`'s rotation vector is the block `rotations + t` of three unknowns.
    pub rotations: usize,
    pub bases: SharedRotations,
    /// The sides `u_k` of the reference triangle (from its point k to point k + 1).
    pub sides: [Vec3; 3],
    pub weight: f64,
}

impl Constraint for RigidTriangles {
    fn name(&self) -> &str {
        "rigid_triangles"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        9 * self.triangles.len()
    }
    fn arity(&self) -> usize {
        5
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        let (t, k, d) = (row / 9, row % 9 / 3, row % 3);
        let p = self.triangles[t];
        vars[0] = 3 * p[(k + 1) % 3] + d;
        vars[1] = 3 * p[k] + d;
        triple(&mut vars[2..], 3 * (self.rotations + t));
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (t, p) in self.triangles.iter().enumerate() {
            let w = vector(x, self.rotations + t);
            let base = self.bases.get(t);
            // One rotation turns the triangle's three sides.
            let (r, jr) = (exp(w), right_jacobian(w));
            for k in 0..3 {
                let u = apply(&base, self.sides[k]);
                let side = vector(x, p[(k + 1) % 3]) - vector(x, p[k]) - apply(&r, u);
                let dw = apply_derivative(&r, &jr, u);
                for (d, r) in side.to_array().into_iter().enumerate() {
                    let row = 9 * t + 3 * k + d;
                    res[row] = r;
                    let j = &mut jac[5 * row..5 * row + 5];
                    j[0] = 1.0;
                    j[1] = -1.0;
                    put(&mut j[2..], -Vec3::new(dw[d][0], dw[d][1], dw[d][2]));
                }
            }
        }
    }
}
