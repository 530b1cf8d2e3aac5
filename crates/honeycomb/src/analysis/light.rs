//! The light share of a honeycomb used as a shading device (paper section 4, Figure 18).
//!
//! Each cell is a tube: its face on M at one end, its face on M' at the other, and between them
//! the walls `v_a v_b v'_b v'_a` of its edges. For a light direction `l`, "the share of direct
//! light that passes through the cells" means, in our reports:
//!
//! - a point `p` of a cell's face on M casts the ray `p + t r` (t > 0), where `r = ±l/|l|` is
//!   the sense that enters the tube: towards the side of the face that the cell's mean axis
//!   (the mean of its realized `v'_i - v_i`) points to, the side of M';
//! - the ray passes when it hits none of the cell's wall quads (each split into two
//!   triangles); it then leaves the tube through the face on M';
//! - a cell's share is the fraction of its face's area whose rays pass, and the honeycomb's
//!   share is the mean of the cells' shares weighted by the light flux onto each face (its area
//!   times |cos| of the light to its normal: the area it presents across the light), so that it
//!   is the share of the light falling on the structure that passes (0 = all blocked, 1 = none).
//!
//! Light through a tube is reversible, so `l` and `-l` give the same share. Light parallel to a
//! face (grazing) does not enter its cell and counts as blocked; a cell of zero depth has no
//! walls and lets everything else through. Each cell is judged alone: neither walls of other
//! cells shading its opening (possible on a strongly curved honeycomb) nor light reflected off
//! the walls are counted.
//!
//! The points are deterministic: the face is cut into a fan of triangles around its centroid,
//! each triangle into `m x m` equal sub-triangles (a stratified barycentric grid, `m` chosen
//! for about `samples` points per cell), and each sub-triangle holds one point, weighted by
//! its triangle's area over `m^2`, at an offset taken from a low-discrepancy sequence.

use crate::error::{Error, Result};
use crate::geometry::{read_vectors, Vec3};
use crate::structure::Honeycomb;
use serde::Serialize;
use std::path::Path;

/// Sample points per cell (294 on a hexagon): a cell's share within about 1.5 points of the
/// exact value, the honeycomb's within about 0.3, and a 3k-vertex honeycomb in some 20 ms
/// per direction.
pub const DEFAULT_LIGHT_SAMPLES: usize = 256;

/// Below this `|cos|` between the light and a face's normal, the light grazes the face.
const GRAZING: f64 = 1e-12;

#[derive(Clone, Debug, Serialize)]
pub struct LightShare {
    /// Share of the light passing through, over all cells weighted by the flux onto their faces
    /// (0..1).
    pub share: f64,
    /// Per cell (face of the base mesh M): the share of its face whose rays pass; 0 for a
    /// degenerate face (zero area or a corner missing from M or M').
    pub per_cell: Vec<f64>,
    /// Rays cast, one per sample point (grazing ones included).
    pub rays: usize,
}

/// The share of light along `direction` (either sense; any non-zero vector) that passes
/// through the cells of `h`, from about `samples` rays per cell (at least one per fan
/// triangle). A zero or non-finite direction passes nowhere.
pub fn light_share(h: &Honeycomb, direction: Vec3, samples: usize) -> LightShare {
    let light = unit(direction);
    let (mut passed, mut flux, mut rays) = (0.0, 0.0, 0usize);
    let per_cell = (0..h.base.faces.len())
        .map(|f| {
            let Some(cell) = Cell::new(h, f) else {
                return 0.0;
            };
            let cast = cell.cast(light, samples, f);
            passed += cast.passed * cast.cos;
            flux += cast.area * cast.cos;
            rays = rays.saturating_add(cast.rays);
            if cast.area > 0.0 {
                cast.passed / cast.area
            } else {
                0.0
            }
        })
        .collect();
    LightShare {
        share: if flux > 0.0 { passed / flux } else { 0.0 },
        per_cell,
        rays,
    }
}

/// Reads a sun path: one light direction per line (see `read_vectors` for the format). The
/// directions are returned as written (not normalized). A file without directions and a zero
/// vector are errors naming the line.
pub fn read_directions(path: &Path) -> Result<Vec<Vec3>> {
    let vectors = read_vectors(path)?;
    if let Some(&(line, _)) = vectors.iter().find(|(_, d)| *d == Vec3::ZERO) {
        return Err(Error::Parse {
            path: path.to_path_buf(),
            line,
            message: "the zero vector is not a direction".to_string(),
        });
    }
    if vectors.is_empty() {
        return Err(Error::Parse {
            path: path.to_path_buf(),
            line: 0,
            message: "no directions in the file".to_string(),
        });
    }
    Ok(vectors.into_iter().map(|(_, d)| d).collect())
}

/// `d / |d|`, computed without overflow or underflow; `None` for zero or non-finite vectors.
fn unit(d: Vec3) -> Option<Vec3> {
    let largest = d.x.abs().max(d.y.abs()).max(d.z.abs());
    if !(largest > 0.0 && largest.is_finite()) {
        return None;
    }
    Some((d / largest).normalized())
}

/// One cell of the honeycomb as a tube: its corners on M and on M'.
struct Cell {
    base: Vec<Vec3>,
    top: Vec<Vec3>,
    centroid: Vec3,
    /// Unit normal of the face on M turned towards M' (for a cell of zero depth, as the face is
    /// oriented); `None` for a face of zero area.
    normal: Option<Vec3>,
    /// Mean edge length: the scale of the tolerance that keeps a ray's start from hitting.
    scale: f64,
}

/// What one cell's rays found: the face area whose rays pass, the face area, |cos| of the light
/// to the face's normal, the rays cast.
struct Cast {
    passed: f64,
    area: f64,
    cos: f64,
    rays: usize,
}

impl Cell {
    fn new(h: &Honeycomb, f: usize) -> Option<Cell> {
        let face = &h.base.faces[f];
        let (m, o) = (&h.base.vertices, &h.offset.vertices);
        if face.len() < 3 || face.iter().any(|&v| v >= m.len() || v >= o.len()) {
            return None;
        }
        let base: Vec<Vec3> = face.iter().map(|&v| m[v]).collect();
        let top: Vec<Vec3> = face.iter().map(|&v| o[v]).collect();
        let n = base.len();
        let centroid = h.base.face_centroid(f);
        let (mut area_vector, mut axis, mut perimeter) = (Vec3::ZERO, Vec3::ZERO, 0.0);
        for k in 0..n {
            let (a, b) = (base[k], base[(k + 1) % n]);
            area_vector += (a - centroid).cross(b - centroid);
            axis += top[k] - base[k];
            perimeter += (b - a).norm();
        }
        let normal = unit(area_vector).map(|u| if u.dot(axis) < 0.0 { -u } else { u });
        Some(Cell {
            base,
            top,
            centroid,
            normal,
            scale: perimeter / n as f64,
        })
    }

    /// Casts the rays of the cell numbered `index` (which picks its sample offsets).
    fn cast(&self, light: Option<Vec3>, samples: usize, index: usize) -> Cast {
        let n = self.base.len();
        // m x m points per fan triangle, n triangles: about `samples` in all.
        let m = ((samples as f64 / n as f64).sqrt().round() as usize).max(1);
        let per_triangle = m.saturating_mul(m);
        let fan = (0..n).map(|k| (self.base[k], self.base[(k + 1) % n]));
        let area: f64 = fan
            .clone()
            .map(|(a, b)| 0.5 * (a - self.centroid).cross(b - self.centroid).norm())
            .sum();
        let rays = n.saturating_mul(per_triangle);
        let cos = match (light, self.normal) {
            (Some(l), Some(normal)) => l.dot(normal).abs(),
            _ => 0.0,
        };
        let ray = match (light, self.normal) {
            (Some(l), Some(normal)) => {
                let cos = l.dot(normal);
                if cos.abs() <= GRAZING {
                    None
                } else if cos > 0.0 {
                    Some(l)
                } else {
                    Some(-l)
                }
            }
            _ => None,
        };
        let Some(ray) = ray else {
            return Cast {
                passed: 0.0,
                area,
                cos,
                rays,
            };
        };

        let walls: Vec<WallTriangle> = (0..n)
            .flat_map(|k| {
                let j = (k + 1) % n;
                let (a, b, b_top, a_top) = (self.base[k], self.base[j], self.top[j], self.top[k]);
                [(a, b, b_top), (a, b_top, a_top)]
            })
            .filter_map(|(p0, p1, p2)| WallTriangle::new(p0, p1, p2, ray))
            .collect();
        let t_min = 1e-9 * self.scale;
        let mut passed = 0.0;
        // Each cell and fan triangle takes its own stretch of one sequence of offsets.
        let mut first = index.wrapping_mul(rays);
        for (a, b) in fan {
            let weight = 0.5 * (a - self.centroid).cross(b - self.centroid).norm();
            let mut open = 0usize;
            for_each_sample(self.centroid, a, b, m, first, |p| {
                if !walls.iter().any(|w| w.blocks(p, t_min)) {
                    open += 1;
                }
            });
            passed += weight * open as f64 / per_triangle as f64;
            first = first.wrapping_add(per_triangle);
        }
        Cast {
            passed,
            area,
            cos,
            rays,
        }
    }
}

/// One point in each of the `m x m` equal sub-triangles of the triangle `c a b`, placed in its
/// stratum by the R2 sequence (golden-ratio-like steps of the plastic number) from term
/// `first` on. Centroids would line up with the cell's edges, and with the edges of the lit
/// region, which are parallel to them: a lattice then errs by whole rows at once.
fn for_each_sample(c: Vec3, a: Vec3, b: Vec3, m: usize, first: usize, mut visit: impl FnMut(Vec3)) {
    const STEP_U: f64 = 0.754_877_666_246_692_8; // 1 / g, g^3 = g + 1
    const STEP_V: f64 = 0.569_840_290_998_053_3; // 1 / g^2
    let (ea, eb) = (a - c, b - c);
    let cell = 1.0 / m as f64;
    let mut term = first;
    // Offsets (r, s) with r + s <= 1: a point of the reference triangle (0,0) (1,0) (0,1).
    let mut offset = || {
        // Terms past 2^32 would lose the fraction's digits: the sequence wraps there instead.
        let k = (term as u64 % (1 << 32)) as f64;
        term = term.wrapping_add(1);
        let (r, s) = ((0.5 + k * STEP_U).fract(), (0.5 + k * STEP_V).fract());
        if r + s > 1.0 {
            (1.0 - r, 1.0 - s)
        } else {
            (r, s)
        }
    };
    let at = |u: f64, v: f64| c + ea * (u * cell) + eb * (v * cell);
    for i in 0..m {
        for j in 0..m - i {
            // The sub-triangle pointing like `c a b`, then (if any) the one pointing back.
            let (r, s) = offset();
            visit(at(i as f64 + r, j as f64 + s));
            if i + j + 1 < m {
                let (r, s) = offset();
                visit(at((i + 1) as f64 - r, (j + 1) as f64 - s));
            }
        }
    }
}

/// A wall triangle `p0 p1 p2` set up for rays of one direction `r` (Moller-Trumbore): with the
/// direction fixed, the barycentric coordinates u, v and the ray parameter t of the crossing
/// are linear in the ray's origin, `u = (o - p0) . to_u` and so on.
struct WallTriangle {
    p0: Vec3,
    to_u: Vec3,
    to_v: Vec3,
    to_t: Vec3,
}

impl WallTriangle {
    /// `None` when the rays run parallel to the triangle (or it is degenerate): they cannot
    /// cross it.
    fn new(p0: Vec3, p1: Vec3, p2: Vec3, r: Vec3) -> Option<WallTriangle> {
        let (e1, e2) = (p1 - p0, p2 - p0);
        let p = r.cross(e2);
        let det = e1.dot(p);
        if det.is_nan() || det.abs() <= 1e-12 * e1.norm() * e2.norm() {
            return None;
        }
        let inv = 1.0 / det;
        Some(WallTriangle {
            p0,
            to_u: p * inv,
            to_v: e1.cross(r) * inv,
            to_t: e1.cross(e2) * inv,
        })
    }

    /// Whether the ray from `o` crosses the triangle (edges included) beyond `t_min`.
    fn blocks(&self, o: Vec3, t_min: f64) -> bool {
        let s = o - self.p0;
        let u = s.dot(self.to_u);
        if !(0.0..=1.0).contains(&u) {
            return false;
        }
        let v = s.dot(self.to_v);
        if v < 0.0 || u + v > 1.0 {
            return false;
        }
        s.dot(self.to_t) > t_min
    }
}

/// The direction the light of a sun `elevation` degrees above the horizon (the xy plane, z
/// up) travels in, the sun standing at `azimuth` degrees, counted from +x towards +y.
pub fn sun_light(elevation: f64, azimuth: f64) -> Vec3 {
    let (e, a) = (elevation.to_radians(), azimuth.to_radians());
    -Vec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{hex_disk, radius_for_vertices};
    use crate::mesh::Connectivity;
    use std::f64::consts::PI;

    /// Hexagons of edge 1 in z = 0, all axes `axis`, M' at `thickness` along them.
    fn extruded_disk(radius: f64, axis: Vec3, thickness: f64) -> Honeycomb {
        let base = hex_disk(radius);
        let conn = Connectivity::build(&base).expect("a hex disk is a valid mesh");
        let axes = vec![axis.normalized(); base.vertices.len()];
        Honeycomb::new(base, &conn, axes, thickness)
    }

    /// The regular hexagon of `hex_disk`, centred at the origin (pointy side up).
    fn hexagon() -> Vec<[f64; 2]> {
        (0..6)
            .map(|k| {
                let t = PI / 6.0 + PI / 3.0 * k as f64;
                [t.cos(), t.sin()]
            })
            .collect()
    }

    fn polygon_area(p: &[[f64; 2]]) -> f64 {
        let n = p.len();
        0.5 * (0..n)
            .map(|k| {
                let (a, b) = (p[k], p[(k + 1) % n]);
                a[0] * b[1] - a[1] * b[0]
            })
            .sum::<f64>()
    }

    /// `subject` clipped to the convex, counter-clockwise `clip` (one half-plane per edge).
    fn clip_convex(subject: &[[f64; 2]], clip: &[[f64; 2]]) -> Vec<[f64; 2]> {
        let mut out = subject.to_vec();
        for k in 0..clip.len() {
            let (a, b) = (clip[k], clip[(k + 1) % clip.len()]);
            // Positive on the inner (left) side of the edge a -> b.
            let side = |p: [f64; 2]| (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
            let input = std::mem::take(&mut out);
            for i in 0..input.len() {
                let (p, q) = (input[i], input[(i + 1) % input.len()]);
                let (sp, sq) = (side(p), side(q));
                if sp >= 0.0 {
                    out.push(p);
                }
                if (sp >= 0.0) != (sq >= 0.0) {
                    let t = sp / (sp - sq);
                    out.push([p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]);
                }
            }
            if out.is_empty() {
                break;
            }
        }
        out
    }

    /// The exact share of a cell of `extruded_disk(_, axis, thickness)` under light `d`: a ray
    /// from p on the face passes iff its point at the height of M' lies in the face on M', that
    /// is iff p lies in the hexagon translated by the ray's drift relative to the shear of the
    /// tube (the prism is convex). Overlap area over hexagon area.
    fn exact_share(axis: Vec3, thickness: f64, d: Vec3) -> f64 {
        let a = axis.normalized();
        let r = if d.z > 0.0 { d } else { -d };
        let height = thickness * a.z;
        let drift = [
            r.x / r.z * height - a.x * thickness,
            r.y / r.z * height - a.y * thickness,
        ];
        let hex = hexagon();
        let moved: Vec<[f64; 2]> = hex
            .iter()
            .map(|p| [p[0] + drift[0], p[1] + drift[1]])
            .collect();
        polygon_area(&clip_convex(&moved, &hex)) / polygon_area(&hex)
    }

    fn tilted(theta_deg: f64, phi_deg: f64) -> Vec3 {
        let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
        Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
    }

    #[test]
    fn the_overlap_helper_is_right() {
        // Shifting by the width across flats (w) or across corners (2) leaves nothing.
        let w = 3f64.sqrt();
        let hex = hexagon();
        let shift = |dx: f64, dy: f64| -> f64 {
            let moved: Vec<[f64; 2]> = hex.iter().map(|p| [p[0] + dx, p[1] + dy]).collect();
            polygon_area(&clip_convex(&moved, &hex)) / polygon_area(&hex)
        };
        assert!((shift(0.0, 0.0) - 1.0).abs() < 1e-12);
        assert!(shift(w, 0.0).abs() < 1e-12);
        assert!(shift(0.0, 2.0).abs() < 1e-12);
        // Shifted across its flat sides by s, the overlap's width at height y is the
        // hexagon's width there less s: integrating, 3w/2 - 2s + s^2/(2w) out of 3w/2.
        for s in [0.2, 0.7, 1.3] {
            let exact = (1.5 * w - 2.0 * s + s * s / (2.0 * w)) / (1.5 * w);
            assert!((shift(s, 0.0) - exact).abs() < 1e-12, "{s}");
        }
    }

    #[test]
    fn light_along_the_axes_passes() {
        let h = extruded_disk(4.0, Vec3::new(0.0, 0.0, 1.0), 1.0);
        for d in [Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.0, 0.0, -3.0)] {
            let s = light_share(&h, d, DEFAULT_LIGHT_SAMPLES);
            assert!(s.share > 0.999, "{}", s.share);
            assert!(s.per_cell.iter().all(|&c| c > 0.999));
        }
    }

    #[test]
    fn light_across_the_axes_is_blocked() {
        let h = extruded_disk(4.0, Vec3::new(0.0, 0.0, 1.0), 1.0);
        for d in [Vec3::new(1.0, 0.0, 0.0), Vec3::new(-1.0, 2.0, 0.0)] {
            let s = light_share(&h, d, DEFAULT_LIGHT_SAMPLES);
            assert_eq!(s.share, 0.0);
            assert!(s.per_cell.iter().all(|&c| c == 0.0));
            assert!(s.rays > 0);
        }
    }

    #[test]
    fn tilted_light_passes_the_overlap_of_the_cell_with_its_drifted_self() {
        let axis = Vec3::new(0.0, 0.0, 1.0);
        let thickness = 1.0;
        let h = extruded_disk(4.0, axis, thickness);
        // Towards a vertex (90 degrees) and towards an edge midpoint (0 degrees).
        for phi in [90.0, 0.0] {
            for theta in [15.0, 30.0, 45.0] {
                let d = tilted(theta, phi);
                let exact = exact_share(axis, thickness, d);
                let s = light_share(&h, d, DEFAULT_LIGHT_SAMPLES);
                let worst = s
                    .per_cell
                    .iter()
                    .map(|c| (c - exact).abs())
                    .fold(0.0, f64::max);
                eprintln!(
                    "theta {theta} phi {phi}: exact {exact:.4}, share {:.4}, worst cell off by {worst:.4}",
                    s.share
                );
                assert!(exact > 0.2 && exact < 0.9, "a telling case: {exact}");
                assert!(
                    (s.share - exact).abs() < 0.01 * exact,
                    "{} vs {exact}",
                    s.share
                );
                assert!(worst < 0.02, "worst cell off by {worst}");
            }
        }
    }

    #[test]
    fn light_is_reversible() {
        let h = extruded_disk(3.0, Vec3::new(0.2, -0.1, 1.0), 0.8);
        let d = Vec3::new(0.3, 0.5, 1.0);
        let (fwd, back) = (light_share(&h, d, 100), light_share(&h, -d, 100));
        assert_eq!(fwd.share, back.share);
        assert_eq!(fwd.per_cell, back.per_cell);
        assert!(fwd.share > 0.0 && fwd.share < 1.0);
    }

    #[test]
    fn sheared_cells_cast_into_the_tube() {
        // Axes leaning 45 degrees: the tube is a sheared prism.
        let axis = Vec3::new(1.0, 0.0, 1.0);
        let thickness = 0.5;
        let h = extruded_disk(3.0, axis, thickness);
        // Vertical light; light along the axes; and light that leans with the axes but falls
        // below the horizon of the face, (1, 0, -0.5): d . axis > 0 while d . normal < 0, so
        // the ray that enters the tube runs against the axis.
        for d in [
            Vec3::new(0.0, 0.0, 1.0),
            axis,
            Vec3::new(1.0, 0.0, -0.5),
            Vec3::new(0.3, 0.4, 1.0),
        ] {
            let exact = exact_share(axis, thickness, d);
            let s = light_share(&h, d, DEFAULT_LIGHT_SAMPLES);
            assert!(
                (s.share - exact).abs() < 0.01,
                "{d:?}: {} vs {exact}",
                s.share
            );
        }
    }

    #[test]
    fn rays_follow_the_samples() {
        let h = extruded_disk(3.0, Vec3::new(0.0, 0.0, 1.0), 1.0);
        let cells = h.base.faces.len();
        // 6 fan triangles of 7 x 7 points: 294 per hexagon for 256 asked.
        let s = light_share(&h, tilted(30.0, 10.0), DEFAULT_LIGHT_SAMPLES);
        assert_eq!(s.rays, cells * 294);
        assert_eq!(s.per_cell.len(), cells);
        // No samples asked still casts one ray per fan triangle.
        assert_eq!(light_share(&h, tilted(30.0, 10.0), 0).rays, cells * 6);
    }

    #[test]
    fn degenerate_directions_pass_nowhere() {
        let h = extruded_disk(2.0, Vec3::new(0.0, 0.0, 1.0), 1.0);
        for d in [
            Vec3::ZERO,
            Vec3::new(f64::NAN, 0.0, 1.0),
            Vec3::new(0.0, f64::INFINITY, 1.0),
        ] {
            assert_eq!(light_share(&h, d, 16).share, 0.0);
        }
        // Tiny and huge vectors are directions like any other.
        let up = light_share(&h, Vec3::new(0.0, 0.0, 1.0), 16).share;
        assert_eq!(light_share(&h, Vec3::new(0.0, 0.0, 1e-320), 16).share, up);
        assert_eq!(light_share(&h, Vec3::new(0.0, 0.0, 1e308), 16).share, up);
    }

    fn temp_file(name: &str, text: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("honeycomb-light-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let path = dir.join(name);
        std::fs::write(&path, text).expect("write temp file");
        path
    }

    #[test]
    fn a_sun_path_file_reads() {
        let path = temp_file(
            "good.txt",
            "# a morning\n\n0.5 0.1 1\n  -0.2,0.3,0.9  # noon-ish\n1e-3, 0 ,\t-2\n",
        );
        let d = read_directions(&path).expect("a good file");
        assert_eq!(
            d,
            vec![
                Vec3::new(0.5, 0.1, 1.0),
                Vec3::new(-0.2, 0.3, 0.9),
                Vec3::new(1e-3, 0.0, -2.0)
            ]
        );
    }

    #[test]
    fn a_bad_sun_path_file_names_the_line() {
        let cases = [
            ("empty.txt", "", 0, "no directions"),
            ("comments.txt", "# nothing\n\n   \n", 0, "no directions"),
            ("two.txt", "0 0 1\n1 2\n", 2, "3 numbers"),
            ("four.txt", "# x y z\n0 0 1\n\n1, 2, 3, 4\n", 4, "3 numbers"),
            ("word.txt", "0 0 1\n0 0 1\nup 0 1\n", 3, "not a number"),
            ("inf.txt", "inf 0 1\n", 1, "not a finite"),
            ("nan.txt", "0 0 1\n0 NaN 1\n", 2, "not a finite"),
            ("zero.txt", "0 0 1\n0, 0, -0\n", 2, "zero vector"),
        ];
        for (name, text, expected_line, words) in cases {
            let path = temp_file(name, text);
            match read_directions(&path) {
                Err(Error::Parse { line, message, .. }) => {
                    assert_eq!(line, expected_line, "{name}: {message}");
                    assert!(message.contains(words), "{name}: {message}");
                }
                other => panic!("{name}: expected a parse error, got {other:?}"),
            }
        }
        let binary = std::env::temp_dir()
            .join(format!("honeycomb-light-{}", std::process::id()))
            .join("binary.txt");
        std::fs::write(&binary, b"0 0 1\n0 \xff 1\n").expect("write");
        assert!(matches!(
            read_directions(&binary),
            Err(Error::Parse { line: 2, .. })
        ));
        let missing = binary.with_file_name("missing.txt");
        assert!(matches!(read_directions(&missing), Err(Error::Io { .. })));
    }

    #[test]
    fn timing_of_a_3k_vertex_honeycomb() {
        let h = extruded_disk(radius_for_vertices(3300), Vec3::new(0.0, 0.0, 1.0), 1.0);
        // Along the axes no wall faces the rays; tilted a little, every ray passes only after
        // being tested against all twelve wall triangles (the slowest case).
        for (label, d) in [
            ("along the axes", tilted(0.0, 0.0)),
            ("tilted 2 deg", tilted(2.0, 20.0)),
            ("tilted 30 deg", tilted(30.0, 20.0)),
        ] {
            let start = std::time::Instant::now();
            let s = light_share(&h, d, DEFAULT_LIGHT_SAMPLES);
            let elapsed = start.elapsed();
            eprintln!(
                "light share, {} vertices, {} cells, {} rays, {label}: {:.1} ms (share {:.3})",
                h.base.vertices.len(),
                h.base.faces.len(),
                s.rays,
                elapsed.as_secs_f64() * 1e3,
                s.share
            );
        }
    }
}
