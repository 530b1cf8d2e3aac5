//! Guided projection (Tang et al. 2014): a regularized Gauss-Newton method for systems of
//! linear and quadratic constraints, on a sparsity pattern that is fixed for the whole solve.

mod cancel;
mod cholesky;
mod columns;
mod condensation;
mod constraint;
mod dissection;
mod lists;
mod normal_matrix;
mod ordering;
mod solver;
mod split;
mod substitution;

pub use cancel::Cancel;
#[cfg(test)]
pub use constraint::jacobian_fd_error;
pub use constraint::{Constraint, Role};
pub use solver::{
    FamilyResidual, GuidedProjection, IterationInfo, SolveReport, SolveState, SolverOptions,
};
pub use substitution::Substitution;
