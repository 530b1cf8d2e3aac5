//! A perceptually ordered colour map (dark blue, teal, green, yellow), the calm ramp for values
//! within a tolerance, and round ticks and lengths for legends.

/// Colour at `t` in [0, 1] as (r, g, b).
pub fn color(t: f64) -> (u8, u8, u8) {
    const STOPS: [(f64, f64, f64); 5] = [
        (68.0, 1.0, 84.0),
        (59.0, 82.0, 139.0),
        (33.0, 145.0, 140.0),
        (94.0, 201.0, 98.0),
        (253.0, 231.0, 37.0),
    ];
    let x = unit(t) * (STOPS.len() - 1) as f64;
    let k = (x.floor() as usize).min(STOPS.len() - 2);
    mix(STOPS[k], STOPS[k + 1], x - k as f64)
}

/// `t` within [0, 1]; a value that is no number counts as 0.
fn unit(t: f64) -> f64 {
    if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// The colour a share `f` of the way from `a` to `b`.
fn mix(a: (f64, f64, f64), b: (f64, f64, f64), f: f64) -> (u8, u8, u8) {
    let channel = |p: f64, q: f64| (p + (q - p) * f).round() as u8;
    (channel(a.0, b.0), channel(a.1, b.1), channel(a.2, b.2))
}

/// The calm ramp for values within a tolerance (pale grey-blue at 0 to a steady blue at the
/// tolerance): a good result reads as one quiet colour, whatever its round-off.
pub fn calm(t: f64) -> (u8, u8, u8) {
    mix((226.0, 232.0, 238.0), (49.0, 104.0, 166.0), unit(t))
}

/// Over the tolerance.
pub const OVER: (u8, u8, u8) = (214, 39, 40);

/// Round tick values from 0 to at least `max`: steps of 1, 2 or 5 times a power of ten, about
/// four of them.
pub fn nice_ticks(max: f64) -> Vec<f64> {
    if !(max.is_finite() && max > 0.0) {
        return vec![0.0, 1.0];
    }
    let raw = max / 4.0;
    let power = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * power)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * power);
    let n = (max / step - 1e-9).ceil() as usize;
    (0..=n).map(|k| k as f64 * step).collect()
}

/// A round length near `about`: 1, 2 or 5 times a power of ten.
pub fn nice_length(about: f64) -> f64 {
    if !(about.is_finite() && about > 0.0) {
        return 1.0;
    }
    let power = 10f64.powf(about.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * power)
        .find(|l| *l <= about)
        .unwrap_or(power)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_and_cover_the_range() {
        assert_eq!(nice_ticks(17.3), vec![0.0, 5.0, 10.0, 15.0, 20.0]);
        assert_eq!(nice_ticks(1e-3), vec![0.0, 0.0005, 0.001]);
        assert_eq!(nice_length(7.3), 5.0);
        assert_eq!(nice_length(0.031), 0.02);
    }
}
