//! Orthographic views: a rotation taking model coordinates to screen (x right, y up, z toward
//! the viewer).

use crate::geometry::Vec3;
use std::str::FromStr;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum View {
    Top,
    Front,
    Side,
    Iso,
}

impl FromStr for View {
    type Err = String;
    fn from_str(s: &str) -> Result<View, String> {
        match s {
            "top" => Ok(View::Top),
            "front" => Ok(View::Front),
            "side" => Ok(View::Side),
            "iso" => Ok(View::Iso),
            _ => Err(format!(
                "unknown view '{s}': expected top, front, side or iso"
            )),
        }
    }
}

impl View {
    /// Screen axes (right, up, toward the viewer) in model coordinates.
    fn axes(self) -> (Vec3, Vec3, Vec3) {
        let (x, y, z) = (
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
        );
        match self {
            View::Top => (x, y, z),
            View::Front => (x, z, -y),
            View::Side => (y, z, x),
            View::Iso => {
                let toward = Vec3::new(1.0, -1.0, 1.0).normalized();
                let right = z.cross(toward).normalized();
                (right, toward.cross(right), toward)
            }
        }
    }

    /// (screen x, screen y, depth toward the viewer).
    pub fn project(self, p: Vec3) -> Vec3 {
        let (r, u, t) = self.axes();
        Vec3::new(p.dot(r), p.dot(u), p.dot(t))
    }
}
