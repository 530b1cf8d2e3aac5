//! Analytic design surfaces given as height fields z = f(x, y) over a disk of radius `d`:
//! the saddle (negative curvature), the dome (positive), the cylinder and the cone
//! (developable), the wave (both kinds), the ring (a developable round a hole, over an annulus)
//! and the roof (both kinds, over a rectangle; see `roof`).

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
    /// A stadium's bowl: a cone's flank round a hole, rising outwards at `RING_SLOPE`, so that
    /// the hole holds a sixth of a turn of curvature: a lattice closes round it only turning
    /// by 60 degrees (see `init::seam`).
    Ring,
}

/// The ring's slope: cos(a) = 5/6 for its angle a, so that its border round the hole turns by
/// a sixth of a turn less than a circle in the plane.
pub const RING_SLOPE: f64 = 0.663_324_958_071_079_9;

/// The ring's hole, as a share of the patch's radius.
const RING_HOLE: f64 = 0.4;

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
            "ring" => Ok(Shape::Ring),
            _ => Err(format!(
                "unknown surface '{s}': expected saddle, dome, cylinder, cone, wave, ring or roof"
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
            Shape::Ring => RING_SLOPE * ((x * x + y * y).sqrt() - d),
        }
    }

    /// The radius of the hole in the patch (the ring's), or 0.
    pub fn hole(&self) -> f64 {
        match self.shape {
            Shape::Ring => RING_HOLE * self.d,
            _ => 0.0,
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
        if self.shape == Shape::Ring {
            return self.triangulate_ring(n);
        }
        square_height_field(1.2 * self.d, n, |x, y| self.height(x, y))
    }

    /// The ring over the annulus from its hole to 1.2 d, in `n` / 3 rings of 2 `n` triangle
    /// pairs (about as many triangles as the square grid of `n`, as long as they are wide),
    /// counter-clockwise seen from +z.
    fn triangulate_ring(&self, n: usize) -> PolyMesh {
        let (inner, outer) = (self.hole(), 1.2 * self.d);
        let (around, n) = (2 * n, n.div_ceil(3));
        let mut vertices = Vec::with_capacity((n + 1) * around);
        for j in 0..=n {
            let r = inner + (outer - inner) * j as f64 / n as f64;
            for i in 0..around {
                let t = std::f64::consts::TAU * i as f64 / around as f64;
                let (x, y) = (r * t.cos(), r * t.sin());
                vertices.push(Vec3::new(x, y, self.height(x, y)));
            }
        }
        let id = |i: usize, j: usize| j * around + i % around;
        let mut faces = Vec::with_capacity(2 * n * around);
        for j in 0..n {
            for i in 0..around {
                faces.push(vec![id(i, j), id(i + 1, j + 1), id(i + 1, j)]);
                faces.push(vec![id(i, j), id(i, j + 1), id(i + 1, j + 1)]);
            }
        }
        PolyMesh::new(vertices, faces)
    }
}

/// `z = height(x, y)` over the square `[-half, half]^2`: `n` x `n` squares of two triangles,
/// counter-clockwise seen from +z.
pub fn square_height_field(half: f64, n: usize, height: impl Fn(f64, f64) -> f64) -> PolyMesh {
    let step = 2.0 * half / n as f64;
    let mut vertices = Vec::with_capacity((n + 1) * (n + 1));
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (-half + step * i as f64, -half + step * j as f64);
            vertices.push(Vec3::new(x, y, height(x, y)));
        }
    }
    PolyMesh::new(vertices, super::split_quads(n, n, n + 1))
}
