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
    /// A sound surface that the structure asked for does not suit (too curved for cells of
    /// one size, say).
    #[error("unsuited surface: {0}")]
    Unsuited(String),
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

/// A number as a message shows it: `0.5`, `100`, `1e308`, `1e-320` (`{}` writes out every one
/// of 1e308's 309 digits).
pub fn short_number(x: f64) -> String {
    let debug = format!("{x:?}");
    match debug.strip_suffix(".0") {
        Some(whole) => whole.to_string(),
        None => debug,
    }
}

/// `x` rounded to `digits` significant digits, shown as [`short_number`] shows it: 0.3398,
/// 339.8, 3.398e-7.
pub fn rounded(x: f64, digits: usize) -> String {
    let text = format!("{x:.*e}", digits.max(1) - 1);
    short_number(text.parse().unwrap_or(x))
}

/// A direction as a message shows it: `0,0,1`, each coordinate to 4 significant digits.
pub fn short_vector(v: crate::Vec3) -> String {
    coordinates(v, 4, ",")
}

/// A point as a message shows it: `(0.5, 1e-300, NaN)`, each coordinate to 6 significant
/// digits.
pub fn short_point(p: crate::Vec3) -> String {
    format!("({})", coordinates(p, 6, ", "))
}

fn coordinates(v: crate::Vec3, digits: usize, separator: &str) -> String {
    v.to_array().map(|c| rounded(c, digits)).join(separator)
}

#[cfg(test)]
mod tests {
    use super::{rounded, short_number};

    #[test]
    fn short_numbers() {
        let shown = [0.5, 100.0, -1.0, 1e308, -1e308, 1e-320, f64::NAN].map(short_number);
        assert_eq!(
            shown,
            ["0.5", "100", "-1", "1e308", "-1e308", "1e-320", "NaN"]
        );
        let shown = [0.339_78, 339.78, 3.3978e-7, 1.0, f64::INFINITY].map(|x| rounded(x, 4));
        assert_eq!(shown, ["0.3398", "339.8", "3.398e-7", "1", "inf"]);
    }
}
