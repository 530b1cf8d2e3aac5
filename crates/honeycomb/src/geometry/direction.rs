//! A direction as a user writes it: `DX,DY,DZ` (or space separated).

use super::Vec3;

/// The unit direction of `DX,DY,DZ`. The vector is scaled by its largest component before it
/// is normalized, so that neither 1e-320,0,0 nor 1e308,1e308,0 loses its length to roundoff.
pub fn parse_direction(text: &str) -> Result<Vec3, String> {
    let numbers: Vec<f64> = text
        .split(|c: char| c == ',' || c.is_whitespace())
        .filter(|w| !w.is_empty())
        .map(str::parse)
        .collect::<Result<_, _>>()
        .map_err(|_| format!("`{text}`: expected three numbers DX,DY,DZ"))?;
    let [x, y, z] = numbers[..] else {
        return Err(format!("`{text}`: expected three numbers DX,DY,DZ"));
    };
    if !numbers.iter().all(|v| v.is_finite()) {
        return Err(format!("`{text}`: expected three finite numbers DX,DY,DZ"));
    }
    let largest = x.abs().max(y.abs()).max(z.abs());
    if largest == 0.0 {
        return Err(format!(
            "`{text}`: the direction has no length (expected a non-zero DX,DY,DZ)"
        ));
    }
    Ok((Vec3::new(x, y, z) / largest).normalized())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directions_keep_their_length_at_any_scale() {
        for (text, expected) in [
            ("0,0,2", Vec3::new(0.0, 0.0, 1.0)),
            ("1e-320, 0, 0", Vec3::new(1.0, 0.0, 0.0)),
            ("1e308 1e308 0", Vec3::new(1.0, 1.0, 0.0).normalized()),
            ("-3,4,0", Vec3::new(-0.6, 0.8, 0.0)),
        ] {
            let d = parse_direction(text).unwrap();
            assert!((d - expected).norm() < 1e-15, "{text}: {d:?}");
        }
        for bad in ["0,0,0", "1,2", "1,2,3,4", "x,1,2", "inf,0,1", "NaN,0,1", ""] {
            assert!(parse_direction(bad).is_err(), "{bad}");
        }
        assert!(parse_direction("0,0,0").unwrap_err().contains("no length"));
    }
}
