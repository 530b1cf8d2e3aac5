//! What the sheet's node axes are fitted to: S's normals (walls across S), or S's normals
//! turned across the light (a shading system, the paper's Figure 18).

use crate::geometry::rotation::{apply, Matrix3};
use crate::geometry::Vec3;

/// How far shading turns a node axis from S's normal at most (radians), in the order tried:
/// first so far that the walls lean no more than they stand; then less, where the sheet
/// cannot follow so far on a doubly curved S; then further, twice, where a high sun's plane
/// across the light lies beyond the first turn, or S's steep parts turn it further, and the
/// walls block too little; then the turns between, where the sheet follows one turn but not
/// the next and the share let through does not fall with the turn.
const SHADING_TILTS: [f64; 6] = [
    std::f64::consts::FRAC_PI_4,
    std::f64::consts::FRAC_PI_6,
    std::f64::consts::FRAC_PI_3,
    5.0 * std::f64::consts::PI / 12.0,
    5.0 * std::f64::consts::PI / 24.0,
    7.0 * std::f64::consts::PI / 24.0,
];

/// How a shading device turns S's normals across the light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Turn {
    /// At most this far (radians).
    pub max_tilt: f64,
    /// Every turn leaning one way (see [`AxisTargets::AcrossLight`]), or each the shortest
    /// way to the plane across the light.
    pub steady: bool,
}

/// The turns shading tries, in order: the shortest turn of the first tilt, which leans the
/// walls least; then every tilt with the turns leaning one way, which the sheet follows
/// where S faces the light; then the shortest turns of the next two tilts, for a surface
/// that faces the light nowhere.
pub const SHADING_TURNS: [Turn; 9] = [
    shortest(0),
    steady(0),
    steady(1),
    steady(2),
    steady(3),
    steady(4),
    steady(5),
    shortest(1),
    shortest(2),
];

const fn shortest(k: usize) -> Turn {
    Turn {
        max_tilt: SHADING_TILTS[k],
        steady: false,
    }
}

const fn steady(k: usize) -> Turn {
    Turn {
        max_tilt: SHADING_TILTS[k],
        steady: true,
    }
}

/// How much the steady lean weighs against the turn across the light, whose weight is the
/// sine of the light's angle to the normal: as much as a normal 30 degrees from the light.
/// The one spot where the leaning turns part ways is then 30 degrees from the light the
/// other way, on slopes steeper than the sun is low, which roofs seldom have.
const STEADY_LEAN: f64 = 0.5;

/// The axis each node is fitted to, from S's unit normal where it stands.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum AxisTargets {
    /// S's normal.
    #[default]
    Normals,
    /// S's normal turned towards `across` applied to it, by at most `max_tilt` radians.
    /// `across` is `I - L / |L|` for the light's second moment `L = sum l l^T` over its unit
    /// directions: for one light the projection onto the plane across it, where no ray runs
    /// the length of a cell; for several, what is least lit by them all. The turn is bounded
    /// where S faces the light, whose plane across it lies in S.
    ///
    /// A steady turn also leans towards `steady` (unit, across the light; zero for the
    /// shortest turn): where S's normal nearly runs along the light, `across` leaves it all
    /// but unchanged and the way it turns swings all round that spot, which no folded sheet
    /// follows (its walls cross); one way across the light for all keeps neighbouring turns
    /// alike.
    AcrossLight {
        across: Matrix3,
        max_tilt: f64,
        /// Weighed by its length.
        steady: Vec3,
        /// S's mean normal: the side of S from which `steady` is seen.
        up: Vec3,
    },
}

impl AxisTargets {
    /// S's normals turned across the light `light` and the directions `more` (a sun path),
    /// each alike, as `turn` says, on a surface whose mean normal is `mean_normal` (a steady
    /// turn leans towards its part across the light). Directions are unit.
    pub fn across_light(light: Vec3, more: &[Vec3], turn: Turn, mean_normal: Vec3) -> AxisTargets {
        let mut moment = second_moment(light, 1.0);
        for &l in more {
            let m = second_moment(l, 1.0);
            for (row, m_row) in moment.iter_mut().zip(m) {
                for (x, y) in row.iter_mut().zip(m_row) {
                    *x += y;
                }
            }
        }
        let largest = largest_eigenvalue(&moment);
        let across = std::array::from_fn(|i| {
            std::array::from_fn(|j| f64::from(u8::from(i == j)) - moment[i][j] / largest)
        });
        // Where the light runs along the mean normal any way across it will do.
        let steady = [
            mean_normal,
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ]
        .map(|d| apply(&across, d))
        .into_iter()
        .find(|d| d.norm() > 1e-6)
        .filter(|_| turn.steady)
        .map_or(Vec3::ZERO, |d| d.normalized() * STEADY_LEAN);
        AxisTargets::AcrossLight {
            across,
            max_tilt: turn.max_tilt,
            steady,
            up: mean_normal,
        }
    }

    /// The target axis where S's unit normal is `normal` (on the same side of S).
    pub fn at(&self, normal: Vec3) -> Vec3 {
        match *self {
            AxisTargets::Normals => normal,
            AxisTargets::AcrossLight {
                across,
                max_tilt,
                steady,
                up,
            } => {
                let want = apply(&across, normal);
                // How far from across the light: the angle to `want` (for one light, to the
                // plane across it; a right angle where the normal runs along the light).
                let full = if want.norm() < 1e-12 {
                    std::f64::consts::FRAC_PI_2
                } else {
                    (want - normal * want.dot(normal))
                        .norm()
                        .atan2(want.dot(normal))
                };
                // The way to turn: `want`'s part across the normal, leaning towards `steady`
                // seen from the same side of S.
                let side = if normal.dot(up) < 0.0 { -1.0 } else { 1.0 };
                let lean = want + steady * side;
                let away = lean - normal * lean.dot(normal);
                if away.norm() < 1e-12 {
                    return normal;
                }
                let tilt = full.min(max_tilt);
                normal * tilt.cos() + away.normalized() * tilt.sin()
            }
        }
    }
}

/// `weight l l^T`.
fn second_moment(l: Vec3, weight: f64) -> Matrix3 {
    let l = l.to_array();
    std::array::from_fn(|i| std::array::from_fn(|j| weight * l[i] * l[j]))
}

/// The largest eigenvalue of a symmetric positive semidefinite matrix (power iteration from
/// each axis in turn, which one of them does not miss), at least the smallest positive
/// number.
fn largest_eigenvalue(m: &Matrix3) -> f64 {
    let mut largest = f64::MIN_POSITIVE;
    for k in 0..3 {
        let mut v = Vec3::from_slice(&std::array::from_fn::<f64, 3, _>(|i| {
            f64::from(u8::from(i == k))
        }));
        for _ in 0..100 {
            let next = apply(m, v);
            if next.norm() == 0.0 {
                break;
            }
            v = next.normalized();
        }
        largest = largest.max(apply(m, v).dot(v));
    }
    largest
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_4;

    #[test]
    fn the_normal_turns_across_the_light_up_to_the_bound() {
        let n = Vec3::new(0.0, 0.0, 1.0);
        // The sun 60 degrees high: the plane across the light is 60 degrees from n.
        let light = Vec3::new(1.0, 0.0, -3f64.sqrt()).normalized();
        let free = AxisTargets::across_light(light, &[], turn(1.5, false), n);
        let a = free.at(n);
        assert!(a.dot(light).abs() < 1e-12, "across the light: {a:?}");
        assert!((a.dot(n).acos().to_degrees() - 60.0).abs() < 1e-9);
        assert!(a.x > 0.0, "turned the way the light travels");
        let b = b_at(light, n);
        assert!((b.dot(n).acos().to_degrees() - 45.0).abs() < 1e-9);
        assert!((b.norm() - 1.0).abs() < 1e-12 && b.y.abs() < 1e-12 && b.x > 0.0);
        assert_eq!(AxisTargets::Normals.at(n), n);
        // The same line either side of S.
        assert!((b_at(light, -n) + b).norm() < 1e-12);
    }

    /// Where S's normal runs along the light (the sun 60 degrees high over a slope facing
    /// it), the plane across the light is S's tangent plane and the shortest way to it is
    /// away from that spot: normals 5 degrees round it turned so spread over more than 90
    /// degrees. Leaning one way they all turn towards the mean normal's part across the
    /// light, by the bound, and stay within 25 degrees of each other.
    #[test]
    fn normals_along_the_light_turn_one_way() {
        let up = Vec3::new(0.0, 0.0, 1.0);
        let light = Vec3::new(1.0, 0.0, -3f64.sqrt()).normalized();
        let steady = (up - light * up.dot(light)).normalized();
        let spread = 5f64.to_radians();
        let (e1, e2) = (
            light.cross(Vec3::new(0.0, 1.0, 0.0)),
            Vec3::new(0.0, 1.0, 0.0),
        );
        let normals: Vec<Vec3> = (0..8)
            .map(|k| {
                let phi = k as f64 * std::f64::consts::FRAC_PI_4;
                let offset = (e1 * phi.cos() + e2 * phi.sin()) * spread.sin();
                (-light * spread.cos() + offset).normalized()
            })
            .collect();
        let widest = |leaning: bool| {
            let targets = AxisTargets::across_light(light, &[], turn(FRAC_PI_4, leaning), up);
            let turned: Vec<Vec3> = normals.iter().map(|&n| targets.at(n)).collect();
            for (&n, &a) in normals.iter().zip(&turned) {
                assert!((a.norm() - 1.0).abs() < 1e-12);
                let tilt = a.dot(n).acos();
                assert!((tilt - FRAC_PI_4).abs() < 1e-9, "turned by the bound");
                if leaning {
                    assert!((a - n).dot(steady) > 0.0, "{n:?} turned to {a:?}");
                }
            }
            (turned
                .iter()
                .flat_map(|a| turned.iter().map(|b| a.dot(*b).min(1.0).acos())))
            .fold(0.0, f64::max)
            .to_degrees()
        };
        assert!(widest(false) > 90.0, "{}", widest(false));
        assert!(widest(true) < 25.0, "{}", widest(true));
        let centre = AxisTargets::across_light(light, &[], turn(FRAC_PI_4, true), up).at(-light);
        assert!((centre.dot(-light).acos() - FRAC_PI_4).abs() < 1e-9);
        assert!(centre.dot(steady) > 0.0, "{centre:?}");
    }

    fn b_at(light: Vec3, normal: Vec3) -> Vec3 {
        let up = Vec3::new(0.0, 0.0, 1.0);
        AxisTargets::across_light(light, &[], turn(FRAC_PI_4, false), up).at(normal)
    }

    fn turn(max_tilt: f64, steady: bool) -> Turn {
        Turn { max_tilt, steady }
    }

    /// A sun path from east to west over the south: the axes turn towards the north-south
    /// line, which the morning and evening light cross too, not only across the noon light.
    #[test]
    fn a_sun_path_turns_the_axes_across_the_whole_day() {
        let n = Vec3::new(0.0, 0.0, 1.0);
        let sun = |azimuth: f64| {
            let (e, a) = (40f64.to_radians(), azimuth.to_radians());
            -Vec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin())
        };
        let path: Vec<Vec3> = [0.0, 45.0, 90.0, 135.0, 180.0].map(sun).to_vec();
        let noon = sun(90.0);
        let day = AxisTargets::across_light(noon, &path, turn(FRAC_PI_4, false), n).at(n);
        let noon_only = AxisTargets::across_light(noon, &[], turn(FRAC_PI_4, false), n).at(n);
        let lit = |a: Vec3| path.iter().map(|l| a.dot(*l).powi(2)).sum::<f64>();
        assert!(lit(day) < lit(noon_only), "{day:?} vs {noon_only:?}");
        assert!((day.norm() - 1.0).abs() < 1e-12);
        assert!(
            day.dot(n) >= FRAC_PI_4.cos() - 1e-12,
            "turned at most the bound"
        );
    }
}
