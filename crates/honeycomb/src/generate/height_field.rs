//! Analytic design surfaces given as height fields z = f(x, y) over a disk of radius `d`:
//! the saddle (negative curvature), the dome (positive), the cylinder and the cone
//! (developable), the wave (both kinds) and the roof (both kinds, over a rectangle; see `roof`).

use crate::geometry::Vec3;
use crate::mesh::PolyMesh;
use std::str::FromStr;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    Saddle,
    Dome,
    Cylinder,
    /// A slope on a cone whose apex lies outside the patch (developable, rulings that fan out).
    Cone,
    /// A wave along x that fades across y (domes and saddles by turns).
    Wave,
    /// An undulating sheet twice as long as wide (`roof` with amplitude `ROOF_AMPLITUDE`).
    Roof,
}

impl FromStr for Shape {
    type Err = String;
    fn from_str(s: &str) -> Result<Shape, String> {
        match s {
            "saddle" => Ok(Shape::Saddle),
            "dome" => Ok(Shape::Dome),
            "cylinder" => Ok(Shape::Cylinder),
            "cone" => Ok(Shape::Cone),
            "wave" => Ok(Shape::Wave),
            "roof" => Ok(Shape::Roof),
            _ => Err(format!(
                "unknown surface '{s}': expected saddle, dome, cylinder, cone, wave or roof"
            )),
        }
    }
}

/// A height field scaled to a patch of radius `d`: curvature radii are proportional to `d`, so
/// every size looks alike.
#[derive(Clone, Copy, Debug)]
pub struct HeightField {
    pub shape: Shape,
    pub d: f64,
}

impl HeightField {
    pub fn height(&self, x: f64, y: f64) -> f64 {
        let d = self.d;
        match self.shape {
            Shape::Saddle => (x * x - y * y) / (3.0 * d),
            Shape::Dome => {
                let r = 2.0 * d;
                (r * r - x * x - y * y).max(0.0).sqrt() - r
            }
            Shape::Cylinder => {
                let r = 1.5 * d;
                (r * r - x * x).max(0.0).sqrt() - r
            }
            Shape::Cone => {
                // Apex 2.5 d beyond the patch's edge, flanks rising at 1 in 2 towards it.
                let apex = 2.5 * d;
                0.5 * (apex - ((x + apex).powi(2) + y * y).sqrt())
            }
            Shape::Wave => {
                let pi = std::f64::consts::PI;
                0.15 * d * (pi * x / d).sin() * (0.5 * pi * y / d).cos()
            }
            Shape::Roof => super::roof::roof_height(x, y, d, super::roof::ROOF_AMPLITUDE),
        }
    }

    /// Moves every vertex vertically onto the surface.
    pub fn lift(&self, mesh: &mut PolyMesh) {
        for v in &mut mesh.vertices {
            v.z = self.height(v.x, v.y);
        }
    }

    /// A triangulated square grid of `n` x `n` cells over [-1.2 d, 1.2 d]^2, covering the patch
    /// with a margin; triangles counter-clockwise seen from +z.
    pub fn triangulate(&self, n: usize) -> PolyMesh {
        let half = 1.2 * self.d;
        let step = 2.0 * half / n as f64;
        let mut vertices = Vec::with_capacity((n + 1) * (n + 1));
        for j in 0..=n {
            for i in 0..=n {
                let (x, y) = (-half + step * i as f64, -half + step * j as f64);
                vertices.push(Vec3::new(x, y, self.height(x, y)));
            }
        }
        let id = |i: usize, j: usize| j * (n + 1) + i;
        let mut faces = Vec::with_capacity(2 * n * n);
        for j in 0..n {
            for i in 0..n {
                faces.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                faces.push(vec![id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        PolyMesh::new(vertices, faces)
    }
}
