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
    /// The caller stopped the work ([`crate::Progress`]'s cancel handle); nothing was made.
    #[error("cancelled")]
    Cancelled,
    /// An option of the library's front door outside its range: the field as named in
    /// [`crate::Options`] or [`crate::PipelineOptions`], its value and what it should be. A
    /// front names it its own way (the CLI by its flag).
    #[error("invalid option {field} {value}: {expected}")]
    Option {
        field: &'static str,
        value: String,
        expected: String,
    },
}

pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    /// The error with the file it is about in front, where the message is about a mesh's
    /// content and does not name it yet.
    pub fn about_file(self, path: &std::path::Path) -> Error {
        match self {
            Error::Mesh(m) => Error::Mesh(format!("{}: {m}", path.display())),
            Error::Unsuited(m) => Error::Unsuited(format!("{}: {m}", path.display())),
            e => e,
        }
    }

    /// A field of the front door's options outside its range.
    pub fn option(
        field: &'static str,
        value: impl std::fmt::Display,
        expected: impl Into<String>,
    ) -> Error {
        Error::Option {
            field,
            value: value.to_string(),
            expected: expected.into(),
        }
    }
}

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
    short_number(significant(x, digits))
}

/// `x` to `digits` significant digits, as a number.
fn significant(x: f64, digits: usize) -> f64 {
    format!("{x:.*e}", digits.max(1) - 1).parse().unwrap_or(x)
}

/// `x` rounded down to `digits` significant digits: the largest number of that many digits
/// (as [`rounded`] shows it) that is at most `x`, for a bound a message offers as one that holds.
pub fn rounded_down(x: f64, digits: usize) -> f64 {
    let r = significant(x, digits);
    if !x.is_finite() || r <= x {
        return r;
    }
    // Rounded up: one unit of the last digit less.
    let unit = 10f64.powi(x.abs().log10().floor() as i32 + 1 - digits.max(1) as i32);
    significant(r - unit, digits).min(x)
}

/// An estimated count as a message shows it: `about 384900 cells`, `about 1.5e12 cells`, and
/// for one too large for a number (it overflowed) `more cells than can be counted`.
pub fn about(count: f64, things: &str) -> String {
    if !count.is_finite() {
        format!("more {things} than can be counted")
    } else if count < 1e9 {
        format!("about {count:.0} {things}")
    } else {
        // `{:e}`: `{:?}` writes out every digit below 1e16.
        let three_digits = significant(count, 3);
        format!("about {three_digits:e} {things}")
    }
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

/// `length`, which `label` names (a flag or a word), must be a finite positive length.
pub fn check_positive_length(field: &'static str, length: f64) -> Result<()> {
    if !length.is_finite() || length <= 0.0 {
        return Err(Error::option(
            field,
            rounded(length, 6),
            "expected a positive length in model units",
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{about, rounded, rounded_down, short_number};

    #[test]
    fn short_numbers() {
        let shown = [0.5, 100.0, -1.0, 1e308, -1e308, 1e-320, f64::NAN].map(short_number);
        assert_eq!(
            shown,
            ["0.5", "100", "-1", "1e308", "-1e308", "1e-320", "NaN"]
        );
        let shown = [0.339_78, 339.78, 3.3978e-7, 1.0, f64::INFINITY].map(|x| rounded(x, 4));
        assert_eq!(shown, ["0.3398", "339.8", "3.398e-7", "1", "inf"]);
        let down = [7.38299, 7.38251, 7.3825, 99.99, 1e-300 * 4.56789].map(|x| rounded_down(x, 4));
        assert_eq!(down, [7.382, 7.382, 7.382, 99.99, 4.567e-300]);
        for x in [7.38299, 0.0104407, 32.0767, 1e300 / 3.0, 2.0f64.sqrt()] {
            let r = rounded_down(x, 4);
            assert!(r <= x && r > x * (1.0 - 1e-3), "{x} {r}");
            assert_eq!(rounded(r, 4).parse::<f64>().unwrap(), r, "{x}");
        }
        let counts = [384_900.4, 1.5e12, f64::INFINITY].map(|c| about(c, "cells"));
        assert_eq!(
            counts,
            [
                "about 384900 cells",
                "about 1.5e12 cells",
                "more cells than can be counted"
            ]
        );
    }
}
