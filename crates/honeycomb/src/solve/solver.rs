//! The guided-projection iteration: linearize every family at the current iterate, solve the
//! regularized normal equations on the fixed pattern, control the step, repeat.

use super::cancel::Cancel;
use super::cholesky::Cholesky;
use super::condensation::Condensation;
use super::constraint::{Constraint, Role};
use super::normal_matrix::NormalMatrix;
use super::substitution::Substitution;
use crate::error::{Error, Result};
use crate::geometry::Vec3;
use serde::Serialize;
use std::time::{Duration, Instant};

#[derive(Clone, Debug)]
pub struct SolverOptions {
    pub max_iterations: usize,
    /// Initial regularization `eps` (normalized frame: mean edge length 1).
    pub eps: f64,
    /// The regularization shrinks towards this as steps succeed.
    pub eps_min: f64,
    /// Converged when every condition residual is below this (normalized units).
    pub tolerance: f64,
    /// Halve a step that blows up the weighted residual energy.
    pub step_control: bool,
    /// With step control: the factor a whole step may multiply the energy by.
    pub energy_growth: f64,
    /// Read before every step: once set, the solve stops with [`Error::Cancelled`].
    pub cancel: Cancel,
}

impl Default for SolverOptions {
    fn default() -> Self {
        SolverOptions {
            max_iterations: 10,
            eps: 1e-3,
            eps_min: 1e-8,
            tolerance: 1e-11,
            step_control: true,
            energy_growth: ENERGY_GROWTH_ALLOWED,
            cancel: Cancel::default(),
        }
    }
}

#[derive(Clone, Debug, Serialize)]
pub struct IterationInfo {
    pub iteration: usize,
    /// Largest absolute residual over the condition families before the step.
    pub max_residual: f64,
    /// Weighted residual energy before the step.
    pub energy: f64,
    pub eps: f64,
    /// Largest variable change of the accepted step.
    pub step: f64,
    /// How often the step was halved.
    pub halvings: usize,
}

#[derive(Clone, Debug, Serialize)]
pub struct FamilyResidual {
    pub name: String,
    pub rows: usize,
    pub weight: f64,
    pub max_abs: f64,
    pub rms: f64,
}

#[derive(Clone, Debug, Serialize)]
pub struct SolveReport {
    pub iterations: usize,
    pub converged: bool,
    pub unknowns: usize,
    /// Unknowns eliminated block by block before the sparse factorization (see
    /// `condensation.rs`); the factor is of the rest.
    pub eliminated_unknowns: usize,
    pub matrix_nnz: usize,
    pub factor_nnz: usize,
    /// Threads of the numeric factorization: 2 when it is split in halves.
    pub factor_threads: usize,
    pub factorizations: usize,
    pub seconds_symbolic: f64,
    pub seconds_assembly: f64,
    pub seconds_factorization: f64,
    pub seconds_other: f64,
    /// Residuals after the last step, per family (with the families' nominal weights).
    pub families: Vec<FamilyResidual>,
    pub history: Vec<IterationInfo>,
}

/// Regularization decay after a step that paid off (see `paid_off`): with a small eps the step
/// is close to the minimum-norm Gauss-Newton step, which converges where a fixed eps stalls on
/// the low-frequency modes (singular values below sqrt(eps)).
const EPS_DECAY: f64 = 0.1;
/// Regularization growth after a step that did not pay off (see `paid_off`).
const EPS_GROWTH: f64 = 10.0;
/// A whole step right after one that lowered the energy still pays off when it raised the
/// energy by less than this factor. In a slow phase the second-order terms of the quadratic
/// conditions lift the energy by a few percent every other step; growing eps tenfold for each
/// such step made eps swing between 1e-6 and 1e-4 for 150 iterations on Yas Island at 4000
/// cells (omega 8e-3 degrees after 200; 1e-10 with this allowance). Two rises in a row do not
/// pay off, so that a steady climb cannot drive eps down.
const PAID_OFF_GROWTH: f64 = 1.1;

/// By default step control halves a step only when it multiplies the weighted residual energy by more
/// than this: a guard against divergence. Demanding a monotone decrease stalls the iteration,
/// because the low-frequency modes a honeycomb needs pass through a transient rise of the
/// residuals of the quadratic constraints.
const ENERGY_GROWTH_ALLOWED: f64 = 100.0;

/// A solver bound to a set of constraint families over `n` unknowns.
pub struct GuidedProjection<'a> {
    families: Vec<Box<dyn Constraint + 'a>>,
    matrix: NormalMatrix,
    /// Blocks eliminated before the sparse factorization, which then factors the rest.
    condensation: Option<Condensation>,
    cholesky: Cholesky,
    residuals: Vec<Vec<f64>>,
    jacobians: Vec<Vec<f64>>,
    /// With a substitution: the families' unknowns `S y` at the last evaluation.
    substitution: Option<(Substitution, Vec<f64>)>,
    seconds_symbolic: f64,
    iteration: usize,
    /// Whether the guides weigh nothing any more ([`SolveState::release_guides`]).
    guides_released: bool,
}

impl<'a> GuidedProjection<'a> {
    #[cfg(test)]
    /// Builds the fixed pattern and its symbolic factorization.
    pub fn new(n: usize, families: Vec<Box<dyn Constraint + 'a>>) -> Result<Self> {
        Self::with_positions(n, families, None)
    }

    /// As [`GuidedProjection::new`], with a position for each block of three unknowns where
    /// one is known (a vertex, an edge's midpoint for its wall normal): large systems are then
    /// ordered by nested dissection.
    pub fn with_positions(
        n: usize,
        families: Vec<Box<dyn Constraint + 'a>>,
        positions: Option<&[Option<Vec3>]>,
    ) -> Result<Self> {
        Self::build(n, families, positions, None, &[])
    }

    /// As [`GuidedProjection::with_positions`], eliminating the blocks of three unknowns in
    /// `eliminable` that no other of them is coupled to before each factorization (see
    /// `condensation.rs`): the same step from a smaller factorization.
    pub fn eliminating(
        n: usize,
        families: Vec<Box<dyn Constraint + 'a>>,
        positions: Option<&[Option<Vec3>]>,
        eliminable: &[usize],
    ) -> Result<Self> {
        Self::build(n, families, positions, None, eliminable)
    }

    /// A solver over the unknowns y of `substitution`: the families see `S y`. `positions`
    /// are per block of three unknowns of y. The blocks of three unknowns in `eliminable`
    /// that no other of them is coupled to are eliminated exactly before each factorization
    /// (see `condensation.rs`); the step is the same, the factorization smaller.
    pub fn with_substitution(
        families: Vec<Box<dyn Constraint + 'a>>,
        substitution: Substitution,
        positions: Option<&[Option<Vec3>]>,
        eliminable: &[usize],
    ) -> Result<Self> {
        Self::build(
            substitution.y_len(),
            families,
            positions,
            Some(substitution),
            eliminable,
        )
    }

    fn build(
        n: usize,
        families: Vec<Box<dyn Constraint + 'a>>,
        positions: Option<&[Option<Vec3>]>,
        substitution: Option<Substitution>,
        eliminable: &[usize],
    ) -> Result<Self> {
        let start = Instant::now();
        let matrix = NormalMatrix::new(n, &families, substitution.as_ref());
        let condensation = Condensation::analyse(&matrix, eliminable);
        let cholesky = match &condensation {
            // The rest is ordered unknown by unknown (each at its block's position): its
            // blocks of three are not what couples it (a wall's offset is one unknown), and
            // ordered in blocks it had 1.8x the operations at 8.8k vertices.
            Some(c) => {
                let kept = positions.map(|p| {
                    let at = |i: usize| p.get(i / 3).copied().flatten();
                    c.kept().iter().map(|&i| at(i)).collect::<Vec<_>>()
                });
                Cholesky::analyse(&c.matrix, 1, kept.as_deref())?
            }
            None => Cholesky::analyse(&matrix, 3, positions)?,
        };
        let residuals = families.iter().map(|c| vec![0.0; c.num_rows()]).collect();
        let jacobians = families
            .iter()
            .map(|c| vec![0.0; c.num_rows() * c.arity()])
            .collect();
        Ok(GuidedProjection {
            families,
            matrix,
            condensation,
            cholesky,
            residuals,
            jacobians,
            substitution: substitution.map(|s| {
                let x = vec![0.0; s.x_len()];
                (s, x)
            }),
            seconds_symbolic: start.elapsed().as_secs_f64(),
            iteration: 0,
            guides_released: false,
        })
    }

    /// Effective weight of family `f` at fade `fade` (the regularization's schedule without its
    /// floor, over its start). Fairness fades with `sqrt(fade)`: early on it steers the
    /// iteration towards regular cells (and makes it converge much faster than eps alone); at
    /// the end it is gone, so that it does not hold the conditions off their zero (a fairness
    /// left at the floor's weight kept unit normals 3e-4 off on an irregular mesh with the
    /// cell points' soft normalization).
    fn weight(&self, f: usize, fade: f64) -> f64 {
        let c = &self.families[f];
        match c.role() {
            Role::Guide if self.guides_released => 0.0,
            Role::Guide => c.weight() * c.guide_fade().powi(self.iteration as i32),
            Role::Condition => c.weight(),
            Role::Fairness => c.weight() * fade.sqrt(),
        }
    }

    /// Evaluates every family at the solver's unknowns `y`; returns (weighted energy, largest
    /// condition residual).
    fn evaluate(&mut self, y: &[f64], fade: f64) -> (f64, f64) {
        let (mut energy, mut worst) = (0.0, 0.0f64);
        let x = family_point(&mut self.substitution, y);
        let values = self.residuals.iter_mut().zip(&mut self.jacobians);
        for (c, (residuals, jacobian)) in self.families.iter().zip(values) {
            c.evaluate(x, residuals, jacobian);
        }
        for f in 0..self.families.len() {
            let w = self.weight(f, fade);
            let sq: f64 = self.residuals[f].iter().map(|r| r * r).sum();
            energy += w * w * sq;
            if self.families[f].role() == Role::Condition {
                worst = self.residuals[f].iter().fold(worst, |m, r| m.max(r.abs()));
            }
        }
        (energy, worst)
    }

    /// The families' linearization data refreshed at the solver's unknowns `y`.
    fn refresh(&mut self, y: &[f64]) {
        let x = family_point(&mut self.substitution, y);
        for c in &mut self.families {
            c.refresh(x);
        }
    }

    /// The families' unknowns for the solver's unknowns `y` (`S y`, or `y` itself).
    pub fn family_unknowns(&self, y: &[f64]) -> Vec<f64> {
        match &self.substitution {
            Some((s, _)) => {
                let mut x = vec![0.0; s.x_len()];
                s.apply(y, &mut x);
                x
            }
            None => y.to_vec(),
        }
    }

    /// Runs the iteration on `x` in place; `progress` sees every iteration.
    pub fn solve(
        &mut self,
        x: &mut [f64],
        opts: &SolverOptions,
        progress: &mut dyn FnMut(&IterationInfo),
    ) -> Result<SolveReport> {
        let mut state = SolveState::new(opts.eps);
        while state.history.len() < opts.max_iterations {
            match self.iterate(x, &mut state, opts)? {
                Some(info) => progress(&info),
                None => break,
            }
        }
        Ok(self.report(x, state, opts))
    }

    /// One guided-projection step on `x` from `state` (an editor drives the solve this way,
    /// one step at a time, and can change targets between steps). `None`: the conditions are
    /// met already and nothing was done.
    pub fn iterate(
        &mut self,
        x: &mut [f64],
        state: &mut SolveState,
        opts: &SolverOptions,
    ) -> Result<Option<IterationInfo>> {
        if opts.cancel.is_cancelled() {
            return Err(Error::Cancelled);
        }
        let n = x.len();
        if let Some(i) = x.iter().position(|v| !v.is_finite()) {
            return Err(Error::Solver(format!("unknown {i} is not finite")));
        }
        state.rhs.resize(n, 0.0);
        state.trial.resize(n, 0.0);
        let (eps, fade) = (state.eps, state.relative_fade());
        self.iteration = state.history.len();
        self.guides_released = state.guides_released;
        let t = Instant::now();
        self.refresh(x);
        state.t_other += t.elapsed();

        let t = Instant::now();
        let (energy, max_residual) = self.evaluate(x, fade);
        if max_residual < opts.tolerance {
            state.converged = true;
            state.t_assembly += t.elapsed();
            return Ok(None);
        }
        let rhs = &mut state.rhs;
        self.matrix.clear(rhs);
        for f in 0..self.families.len() {
            let w = self.weight(f, fade);
            self.matrix
                .add_family(f, w, &self.residuals[f], &self.jacobians[f], rhs);
        }
        self.matrix.add_diagonal(eps);
        state.t_assembly += t.elapsed();

        let t = Instant::now();
        match &mut self.condensation {
            Some(c) => c.factorize(&self.matrix, &mut self.cholesky),
            None => self.cholesky.factorize(&self.matrix),
        }
        .map_err(|p| p.error(self.matrix.n))?;
        state.factorizations += 1;
        state.t_factor += t.elapsed();

        let t = Instant::now();
        match &mut self.condensation {
            Some(c) => c.solve_in_place(&mut self.cholesky, rhs),
            None => self.cholesky.solve_in_place(rhs),
        }
        if rhs.iter().any(|d| !d.is_finite()) {
            return Err(Error::Solver(format!(
                "iteration {}: the step is not finite (degenerate geometry?)",
                state.history.len() + 1
            )));
        }
        // Step control: halve while the step blows the energy up.
        let mut halvings = 0;
        let mut scale = 1.0;
        let trial_energy = loop {
            for ((t, &xi), &d) in state.trial.iter_mut().zip(x.iter()).zip(rhs.iter()) {
                *t = xi + scale * d;
            }
            let trial_energy = self.evaluate(&state.trial, fade).0;
            let acceptable = trial_energy <= energy * opts.energy_growth;
            if !opts.step_control || halvings == 5 || acceptable {
                break trial_energy;
            }
            scale *= 0.5;
            halvings += 1;
        };
        let step = rhs.iter().fold(0.0f64, |m, d| m.max((scale * d).abs()));
        x.copy_from_slice(&state.trial);
        let paid = paid_off(halvings, energy, trial_energy, state.last_rose);
        state.last_rose = trial_energy > energy;
        state.adapt(paid, opts.eps_min);
        state.t_other += t.elapsed();

        let info = IterationInfo {
            iteration: state.history.len() + 1,
            max_residual,
            energy,
            eps: state.eps,
            step,
            halvings,
        };
        state.history.push(info.clone());
        Ok(Some(info))
    }

    /// Residuals at `x` (linearization refreshed) and the timings of `state`.
    pub fn report(&mut self, x: &[f64], state: SolveState, opts: &SolverOptions) -> SolveReport {
        let t = Instant::now();
        self.refresh(x);
        let (_, max_residual) = self.evaluate(x, state.relative_fade());
        let converged = state.converged || max_residual < opts.tolerance;
        let families = self
            .families
            .iter()
            .zip(&self.residuals)
            .map(|(c, r)| FamilyResidual {
                name: c.name().to_string(),
                rows: r.len(),
                weight: c.weight(),
                max_abs: r.iter().fold(0.0f64, |m, v| m.max(v.abs())),
                rms: (r.iter().map(|v| v * v).sum::<f64>() / r.len().max(1) as f64).sqrt(),
            })
            .collect();
        let t_other = state.t_other + t.elapsed();

        SolveReport {
            iterations: state.history.len(),
            converged,
            unknowns: x.len(),
            eliminated_unknowns: self
                .condensation
                .as_ref()
                .map_or(0, |c| x.len() - c.kept().len()),
            matrix_nnz: self.matrix.nnz(),
            factor_nnz: self.cholesky.factor_nnz(),
            factor_threads: self.cholesky.threads(),
            factorizations: state.factorizations,
            seconds_symbolic: self.seconds_symbolic,
            seconds_assembly: state.t_assembly.as_secs_f64(),
            seconds_factorization: state.t_factor.as_secs_f64(),
            seconds_other: t_other.as_secs_f64(),
            families,
            history: state.history,
        }
    }
}

impl SolveReport {
    /// The report of a solve over `unknowns` whose start already passed its test: no
    /// iteration, nothing factorized, converged.
    pub fn untouched(unknowns: usize) -> SolveReport {
        SolveReport {
            iterations: 0,
            converged: true,
            unknowns,
            eliminated_unknowns: 0,
            matrix_nnz: 0,
            factor_nnz: 0,
            factor_threads: 0,
            factorizations: 0,
            seconds_symbolic: 0.0,
            seconds_assembly: 0.0,
            seconds_factorization: 0.0,
            seconds_other: 0.0,
            families: Vec::new(),
            history: Vec::new(),
        }
    }

    /// This report followed by `next`, a later solve of the same problem: iterations, work and
    /// time add up, the residuals and the convergence are the later solve's.
    pub fn then(mut self, next: SolveReport) -> SolveReport {
        self.iterations += next.iterations;
        self.converged = next.converged;
        self.unknowns = self.unknowns.max(next.unknowns);
        self.eliminated_unknowns = self.eliminated_unknowns.max(next.eliminated_unknowns);
        self.matrix_nnz = self.matrix_nnz.max(next.matrix_nnz);
        self.factor_nnz = self.factor_nnz.max(next.factor_nnz);
        self.factor_threads = self.factor_threads.max(next.factor_threads);
        self.factorizations += next.factorizations;
        self.seconds_symbolic += next.seconds_symbolic;
        self.seconds_assembly += next.seconds_assembly;
        self.seconds_factorization += next.seconds_factorization;
        self.seconds_other += next.seconds_other;
        self.families = next.families;
        let offset = self.history.len();
        self.history.extend(next.history.into_iter().map(|mut i| {
            i.iteration += offset;
            i
        }));
        self
    }
}

/// Whether a step earns a smaller regularization: taken whole, and the energy did not rise,
/// or rose by less than `PAID_OFF_GROWTH` right after a step that did not rise.
fn paid_off(halvings: usize, energy: f64, trial_energy: f64, last_rose: bool) -> bool {
    let allowed = if last_rose { 1.0 } else { PAID_OFF_GROWTH };
    halvings == 0 && trial_energy <= energy * allowed
}

/// The families' unknowns at the solver's unknowns `y`: `S y` (into the substitution's
/// buffer) or `y` itself.
fn family_point<'b>(
    substitution: &'b mut Option<(Substitution, Vec<f64>)>,
    y: &'b [f64],
) -> &'b [f64] {
    match substitution {
        Some((s, x)) => {
            s.apply(y, x);
            x
        }
        None => y,
    }
}

/// Where a solve stands between steps: the regularization (and the one it started from, which
/// fairness weights are scaled by), the steps taken and the time spent.
pub struct SolveState {
    pub eps: f64,
    eps0: f64,
    /// What eps would be without its floor: the fairness fades with it, so that at the floor
    /// it keeps fading and no longer pulls against the conditions.
    fade: f64,
    converged: bool,
    /// Whether the last step raised the energy.
    last_rose: bool,
    guides_released: bool,
    history: Vec<IterationInfo>,
    factorizations: usize,
    t_assembly: Duration,
    t_factor: Duration,
    t_other: Duration,
    rhs: Vec<f64>,
    trial: Vec<f64>,
}

impl SolveState {
    /// A solve starting at regularization `eps`.
    pub fn new(eps: f64) -> SolveState {
        SolveState {
            eps,
            eps0: eps,
            fade: eps,
            converged: false,
            last_rose: false,
            guides_released: false,
            history: Vec::new(),
            factorizations: 0,
            t_assembly: Duration::ZERO,
            t_factor: Duration::ZERO,
            t_other: Duration::ZERO,
            rhs: Vec::new(),
            trial: Vec::new(),
        }
    }

    /// The fairness's fade: the regularization's schedule without its floor, over its start.
    fn relative_fade(&self) -> f64 {
        self.fade / self.eps0
    }

    /// Trusts the linearization more after a step that paid off, less after one that did
    /// not: eps and the fade shrink or grow together, eps within its floor and its start, the
    /// fade within its start only.
    fn adapt(&mut self, paid_off: bool, eps_min: f64) {
        if paid_off {
            self.eps = (self.eps * EPS_DECAY).max(eps_min);
            self.fade *= EPS_DECAY;
        } else {
            self.eps = (self.eps * EPS_GROWTH).min(self.eps0);
            self.fade = (self.fade * EPS_GROWTH).min(self.eps0);
        }
    }

    /// The guides weigh nothing from the next step on. Once the conditions are nearly met,
    /// what is left of a guide only moves the unknowns along the conditions' null space, and
    /// every such step breaks the conditions again to second order.
    pub fn release_guides(&mut self) {
        self.guides_released = true;
    }

    /// Steps taken so far.
    pub fn iterations(&self) -> usize {
        self.history.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows `x_i - target` over three unknowns.
    struct Pull {
        target: f64,
        weight: f64,
        role: Role,
    }

    impl Constraint for Pull {
        fn name(&self) -> &str {
            "pull"
        }
        fn weight(&self) -> f64 {
            self.weight
        }
        fn role(&self) -> Role {
            self.role
        }
        fn num_rows(&self) -> usize {
            3
        }
        fn arity(&self) -> usize {
            1
        }
        fn row_variables(&self, row: usize, vars: &mut [usize]) {
            vars[0] = row;
        }
        fn evaluate(&self, x: &[f64], residuals: &mut [f64], jacobian: &mut [f64]) {
            for row in 0..3 {
                residuals[row] = x[row] - self.target;
                jacobian[row] = 1.0;
            }
        }
    }

    /// A whole step pays off unless it raised the energy by a tenth or more, or raised it at
    /// all right after another rise; a halved step never pays off.
    #[test]
    fn a_step_pays_off_despite_a_small_rise() {
        assert!(paid_off(0, 1.0, 0.5, false));
        assert!(paid_off(0, 1.0, 1.05, false));
        assert!(!paid_off(0, 1.0, 1.2, false));
        assert!(!paid_off(0, 1.0, 1.05, true));
        assert!(paid_off(0, 1.0, 0.5, true));
        assert!(!paid_off(1, 1.0, 0.5, false));
    }

    /// A fairness that pulls against a condition fades out: the condition ends met to
    /// roundoff. Had it stopped fading at eps's floor (1e-8 of a start at 1e-3), it would
    /// hold the unknowns 9e-5 short.
    #[test]
    fn fairness_stops_pulling_against_the_conditions() {
        let mut solver = pulled_against(Role::Fairness);
        let mut x = vec![0.0; 3];
        let opts = SolverOptions {
            max_iterations: 20,
            tolerance: 0.0,
            ..SolverOptions::default()
        };
        solver.solve(&mut x, &opts, &mut |_| {}).unwrap();
        let off = off_the_condition(&x);
        assert!(off < 1e-10, "the condition is {off} off");
    }

    /// The condition `x = 1` on three unknowns, and a family of `role` pulling them to 0.
    fn pulled_against(role: Role) -> GuidedProjection<'static> {
        let families: Vec<Box<dyn Constraint>> = vec![
            Box::new(Pull {
                target: 1.0,
                weight: 1.0,
                role: Role::Condition,
            }),
            Box::new(Pull {
                target: 0.0,
                weight: 3.0,
                role,
            }),
        ];
        GuidedProjection::new(3, families).unwrap()
    }

    /// How far `x` is from meeting the condition of [`pulled_against`].
    fn off_the_condition(x: &[f64]) -> f64 {
        x.iter().fold(0.0f64, |m, v| m.max((v - 1.0).abs()))
    }

    /// A released guide no longer pulls: the next step meets the condition it pulled against
    /// (to the regularization), where the guide kept at its faded weight holds it 0.45 short.
    #[test]
    fn a_released_guide_no_longer_pulls() {
        let after_two_steps = |release: bool| {
            let mut solver = pulled_against(Role::Guide);
            let mut x = vec![0.0; 3];
            let opts = SolverOptions {
                tolerance: 0.0,
                ..SolverOptions::default()
            };
            let mut state = SolveState::new(opts.eps);
            solver.iterate(&mut x, &mut state, &opts).unwrap();
            if release {
                state.release_guides();
            }
            solver.iterate(&mut x, &mut state, &opts).unwrap();
            off_the_condition(&x)
        };
        let (released, kept) = (after_two_steps(true), after_two_steps(false));
        assert!(released < 1e-3, "released, the condition is {released} off");
        assert!(kept > 0.4, "kept, the condition is {kept} off");
    }
}
