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
pub const SHADING_TILTS: [f64; 6] = [
    std::f64::consts::FRAC_PI_4,
    std::f64::consts::FRAC_PI_6,
    std::f64::consts::FRAC_PI_3,
    5.0 * std::f64::consts::PI / 12.0,
    5.0 * std::f64::consts::PI / 24.0,
    7.0 * std::f64::consts::PI / 24.0,
];

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
    AcrossLight { across: Matrix3, max_tilt: f64 },
}

impl AxisTargets {
    /// S's normals turned across the light `light` and the directions `more` (a sun path),
    /// each alike, by at most `max_tilt` radians. Directions are unit.
    pub fn across_light(light: Vec3, more: &[Vec3], max_tilt: f64) -> AxisTargets {
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
        AxisTargets::AcrossLight { across, max_tilt }
    }

    /// The target axis where S's unit normal is `normal` (on the same side of S).
    pub fn at(&self, normal: Vec3) -> Vec3 {
        match *self {
            AxisTargets::Normals => normal,
            AxisTargets::AcrossLight { across, max_tilt } => {
                let want = apply(&across, normal);
                // The way to turn: `want`'s part across the normal.
                let away = want - normal * want.dot(normal);
                if away.norm() < 1e-12 {
                    return normal;
                }
                let full = away.norm().atan2(want.dot(normal));
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
        let AxisTargets::AcrossLight { across, .. } =
            AxisTargets::across_light(light, &[], FRAC_PI_4)
        else {
            unreachable!()
        };
        let free = AxisTargets::AcrossLight {
            across,
            max_tilt: 1.5,
        };
        let a = free.at(n);
        assert!(a.dot(light).abs() < 1e-12, "across the light: {a:?}");
        assert!((a.dot(n).acos().to_degrees() - 60.0).abs() < 1e-9);
        assert!(a.x > 0.0, "turned the way the light travels");
        let b = AxisTargets::across_light(light, &[], FRAC_PI_4).at(n);
        assert!((b.dot(n).acos().to_degrees() - 45.0).abs() < 1e-9);
        assert!((b.norm() - 1.0).abs() < 1e-12 && b.y.abs() < 1e-12 && b.x > 0.0);
        // Light along the normal: any turn would do; the normal stays.
        assert_eq!(b_at(light, -light), -light);
        assert_eq!(AxisTargets::Normals.at(n), n);
        // The same line either side of S.
        assert!((AxisTargets::across_light(light, &[], FRAC_PI_4).at(-n) + b).norm() < 1e-12);
    }

    fn b_at(light: Vec3, normal: Vec3) -> Vec3 {
        AxisTargets::across_light(light, &[], FRAC_PI_4).at(normal)
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
        let day = AxisTargets::across_light(noon, &path, FRAC_PI_4).at(n);
        let noon_only = AxisTargets::across_light(noon, &[], FRAC_PI_4).at(n);
        let lit = |a: Vec3| path.iter().map(|l| a.dot(*l).powi(2)).sum::<f64>();
        assert!(lit(day) < lit(noon_only), "{day:?} vs {noon_only:?}");
        assert!((day.norm() - 1.0).abs() < 1e-12);
        assert!(
            day.dot(n) >= FRAC_PI_4.cos() - 1e-12,
            "turned at most the bound"
        );
    }
}
