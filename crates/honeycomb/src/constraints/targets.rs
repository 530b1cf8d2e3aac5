//! Targets an interactive editor moves between solver steps (paper section 4, "User
//! interaction"): positions for dragged vertices, `v_i - t_i = 0`, and directions for node axes,
//! `a_i . n_ij = 0` at every edge end of node `i`.
//!
//! Both families have rows for every vertex, so the sparsity pattern (and the symbolic
//! factorization) never changes while the targets do: a vertex without a target has residual 0
//! and a zero Jacobian row. The targets live behind a shared handle that the editor writes and
//! the family reads.

use super::layout::{put, triple, Layout};
use crate::geometry::Vec3;
use crate::solve::Constraint;
use std::sync::{Arc, RwLock};

/// One optional target per vertex, shared between an editor and a family.
#[derive(Clone, Default)]
pub struct SharedTargets(Arc<RwLock<Vec<Option<Vec3>>>>);

impl SharedTargets {
    pub fn new(num_vertices: usize) -> SharedTargets {
        SharedTargets(Arc::new(RwLock::new(vec![None; num_vertices])))
    }

    #[cfg(test)]
    pub fn get(&self) -> Vec<Option<Vec3>> {
        self.read().clone()
    }

    pub fn set(&self, targets: Vec<Option<Vec3>>) {
        *self.0.write().unwrap_or_else(|e| e.into_inner()) = targets;
    }

    pub fn set_one(&self, v: usize, target: Option<Vec3>) {
        self.0.write().unwrap_or_else(|e| e.into_inner())[v] = target;
    }

    fn read(&self) -> std::sync::RwLockReadGuard<'_, Vec<Option<Vec3>>> {
        self.0.read().unwrap_or_else(|e| e.into_inner())
    }
}

/// `w (v_i - t_i) = 0`: three rows per vertex, each touching one coordinate.
pub struct VertexTargets {
    pub layout: Layout,
    pub targets: SharedTargets,
    pub weight: f64,
}

impl Constraint for VertexTargets {
    fn name(&self) -> &str {
        "vertex_targets"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        3 * self.layout.num_vertices
    }
    fn arity(&self) -> usize {
        1
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        vars[0] = self.layout.vertex(row / 3) + row % 3;
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (v, target) in self.targets.read().iter().enumerate() {
            let (r, j) = (&mut res[3 * v..3 * v + 3], &mut jac[3 * v..3 * v + 3]);
            match target {
                Some(t) => {
                    put(r, self.layout.vertex_at(x, v) - *t);
                    j.fill(1.0);
                }
                None => {
                    r.fill(0.0);
                    j.fill(0.0);
                }
            }
        }
    }
}

/// `a_i . n_ij = 0` at every edge end of a node with a target axis `a_i` (unit). One row per
/// edge end, touching that edge's normal only: no fill.
pub struct AxisTargets {
    pub layout: Layout,
    /// Per edge end: (edge, node).
    pub ends: Vec<(usize, usize)>,
    pub targets: SharedTargets,
    pub weight: f64,
}

impl AxisTargets {
    pub fn new(layout: Layout, edges: &[[usize; 2]], targets: SharedTargets, weight: f64) -> Self {
        let ends = edges
            .iter()
            .enumerate()
            .flat_map(|(e, &[a, b])| [(e, a), (e, b)])
            .collect();
        AxisTargets {
            layout,
            ends,
            targets,
            weight,
        }
    }
}

impl Constraint for AxisTargets {
    fn name(&self) -> &str {
        "axis_targets"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        self.ends.len()
    }
    fn arity(&self) -> usize {
        3
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        triple(vars, self.layout.normal(self.ends[row].0));
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        let targets = self.targets.read();
        for (row, &(e, v)) in self.ends.iter().enumerate() {
            let a = targets[v].unwrap_or(Vec3::new(0.0, 0.0, 0.0));
            res[row] = a.dot(self.layout.normal_at(x, e));
            put(&mut jac[3 * row..], a);
        }
    }
}
