//! The library's one error type: every message names the problem and where it is.

use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum Error {
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// A file that cannot be read as the format it claims (line is 1-based; 0 = whole file,
    /// shown without a line number).
    #[error("{path}{}: {message}", line_suffix(.line))]
    Parse {
        path: PathBuf,
        line: usize,
        message: String,
    },
    /// A mesh that parses but is not acceptable (non-manifold, valence, degenerate, ...).
    #[error("invalid mesh: {0}")]
    Mesh(String),
    /// A parameter outside its meaningful range.
    #[error("invalid parameter: {0}")]
    Parameter(String),
    /// The optimization could not proceed (e.g. a singular system).
    #[error("solver: {0}")]
    Solver(String),
}

pub type Result<T> = std::result::Result<T, Error>;

/// `:12` for line 12; nothing for 0 (the whole file, or binary data).
fn line_suffix(line: &usize) -> String {
    if *line == 0 {
        String::new()
    } else {
        format!(":{line}")
    }
}

/// A number as a message shows it: plainly at everyday sizes, in exponent form far from them
/// (`1e308`, not three hundred digits).
pub fn shown(x: f64) -> String {
    if x != 0.0 && x.is_finite() && !(1e-4..1e6).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

#[cfg(test)]
mod tests {
    use super::shown;

    #[test]
    fn numbers_far_from_everyday_sizes_are_shown_with_an_exponent() {
        assert_eq!(shown(1e308), "1e308");
        assert_eq!(shown(-2.5e-9), "-2.5e-9");
        assert_eq!(shown(0.125), "0.125");
        assert_eq!(shown(-3.0), "-3");
        assert_eq!(shown(0.0), "0");
        assert_eq!(shown(f64::NAN), "NaN");
    }
}
