//! The regular hexagonal lattice of the plane: cells of edge length L, pointy side up before
//! the lattice's rotation. Cell (i, j) has its center at i a1 + j a2 with a1 = (sqrt 3 L, 0),
//! a2 = (sqrt 3 / 2 L, 3/2 L). Every corner is the top corner of one cell and the bottom corner
//! of another, so a corner is named by (i, j, top or bottom) without any search.

use super::flatten::Point2;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Corner {
    pub i: i64,
    pub j: i64,
    pub top: bool,
}

#[derive(Clone, Copy, Debug)]
pub struct Lattice {
    pub edge: f64,
    /// Rotation of the lattice (radians).
    pub angle: f64,
    pub offset: Point2,
}

const SQRT3: f64 = 1.732_050_807_568_877_2;

impl Lattice {
    fn to_plane(self, local: Point2) -> Point2 {
        let (s, c) = self.angle.sin_cos();
        [
            self.offset[0] + c * local[0] - s * local[1],
            self.offset[1] + s * local[0] + c * local[1],
        ]
    }

    fn to_local(self, p: Point2) -> Point2 {
        let (s, c) = self.angle.sin_cos();
        let (x, y) = (p[0] - self.offset[0], p[1] - self.offset[1]);
        [c * x + s * y, -s * x + c * y]
    }

    fn local_center(&self, i: i64, j: i64) -> Point2 {
        let l = self.edge;
        [(i as f64 + 0.5 * j as f64) * SQRT3 * l, 1.5 * j as f64 * l]
    }

    pub fn center(&self, (i, j): (i64, i64)) -> Point2 {
        self.to_plane(self.local_center(i, j))
    }

    pub fn corner(&self, c: Corner) -> Point2 {
        let m = self.local_center(c.i, c.j);
        let dy = if c.top { self.edge } else { -self.edge };
        self.to_plane([m[0], m[1] + dy])
    }

    /// The six corners of cell (i, j), counter-clockwise from the top one.
    pub fn cell_corners((i, j): (i64, i64)) -> [Corner; 6] {
        let top = |i, j| Corner { i, j, top: true };
        let bottom = |i, j| Corner { i, j, top: false };
        [
            top(i, j),
            bottom(i - 1, j + 1),
            top(i, j - 1),
            bottom(i, j),
            top(i + 1, j - 1),
            bottom(i, j + 1),
        ]
    }

    /// The cell containing `p` (hexagonal rounding of its fractional cell coordinates).
    pub fn cell_containing(&self, p: Point2) -> (i64, i64) {
        let l = self.to_local(p);
        let r = l[1] / (1.5 * self.edge);
        let q = l[0] / (SQRT3 * self.edge) - 0.5 * r;
        // Round the cube coordinates (q, r, -q-r), fixing the one that moved most.
        let s = -q - r;
        let (mut rq, mut rr, rs) = (q.round(), r.round(), s.round());
        let (dq, dr, ds) = ((rq - q).abs(), (rr - r).abs(), (rs - s).abs());
        if dq > dr && dq > ds {
            rq = -rr - rs;
        } else if dr > ds {
            rr = -rq - rs;
        }
        (rq as i64, rr as i64)
    }

    /// This lattice turned and scaled the least so that `shift` is the step between two cells'
    /// centers; None where `shift` is shorter than half a step.
    pub fn with_step(self, shift: Point2) -> Option<Lattice> {
        let at_origin = Lattice {
            offset: [0.0, 0.0],
            ..self
        };
        let (i, j) = at_origin.cell_containing(shift);
        if (i, j) == (0, 0) {
            return None;
        }
        let unit = Lattice {
            edge: 1.0,
            angle: 0.0,
            offset: [0.0, 0.0],
        }
        .local_center(i, j);
        Some(Lattice {
            edge: shift[0].hypot(shift[1]) / unit[0].hypot(unit[1]),
            angle: shift[1].atan2(shift[0]) - unit[1].atan2(unit[0]),
            ..self
        })
    }

    /// The corner nearest `p`.
    pub fn corner_near(&self, p: Point2) -> Corner {
        let distance = |c: &Corner| {
            let q = self.corner(*c);
            (q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2)
        };
        Lattice::cell_corners(self.cell_containing(p))
            .into_iter()
            .min_by(|a, b| distance(a).total_cmp(&distance(b)))
            .expect("six corners")
    }

    /// Every cell whose center lies within two edge lengths of the box [lo, hi].
    pub fn cells_covering(&self, lo: Point2, hi: Point2) -> Vec<(i64, i64)> {
        let pad = 2.0 * self.edge;
        let box_corners = [
            [lo[0] - pad, lo[1] - pad],
            [hi[0] + pad, lo[1] - pad],
            [hi[0] + pad, hi[1] + pad],
            [lo[0] - pad, hi[1] + pad],
        ]
        .map(|p| self.to_local(p));
        let (mut min, mut max) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in box_corners {
            for c in 0..2 {
                min[c] = min[c].min(p[c]);
                max[c] = max[c].max(p[c]);
            }
        }
        let l = self.edge;
        let (j0, j1) = (
            (min[1] / (1.5 * l)).floor() as i64,
            (max[1] / (1.5 * l)).ceil() as i64,
        );
        let mut cells = Vec::new();
        for j in j0..=j1 {
            let shift = 0.5 * j as f64;
            let i0 = (min[0] / (SQRT3 * l) - shift).floor() as i64;
            let i1 = (max[0] / (SQRT3 * l) - shift).ceil() as i64;
            for i in i0..=i1 {
                let m = self.local_center(i, j);
                if (min[0]..=max[0]).contains(&m[0]) && (min[1]..=max[1]).contains(&m[1]) {
                    cells.push((i, j));
                }
            }
        }
        cells
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    #[test]
    fn corners_are_shared_by_three_cells_and_edges_have_the_lattice_length() {
        let lattice = Lattice {
            edge: 0.7,
            angle: 0.3,
            offset: [0.2, -0.1],
        };
        let cells = lattice.cells_covering([-5.0, -5.0], [5.0, 5.0]);
        let mut cells_at: HashMap<Corner, usize> = HashMap::new();
        for &cell in &cells {
            let corners = Lattice::cell_corners(cell);
            let center = lattice.center(cell);
            for k in 0..6 {
                *cells_at.entry(corners[k]).or_default() += 1;
                let (p, q) = (
                    lattice.corner(corners[k]),
                    lattice.corner(corners[(k + 1) % 6]),
                );
                let length = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt();
                assert!((length - 0.7).abs() < 1e-12);
                let radius = ((p[0] - center[0]).powi(2) + (p[1] - center[1]).powi(2)).sqrt();
                assert!((radius - 0.7).abs() < 1e-12);
                // Counter-clockwise: each corner turns left around the center.
                let cross = (p[0] - center[0]) * (q[1] - center[1])
                    - (p[1] - center[1]) * (q[0] - center[0]);
                assert!(cross > 0.0);
            }
        }
        // Corners near the middle belong to exactly three cells.
        let middle = cells_at
            .iter()
            .filter(|(c, _)| {
                let p = lattice.corner(**c);
                p[0].abs() < 3.0 && p[1].abs() < 3.0
            })
            .collect::<Vec<_>>();
        assert!(middle.len() > 20);
        assert!(middle.iter().all(|(_, &n)| n == 3));
        // A point near a center, or inside near a corner, lies in that cell.
        for &cell in cells.iter().take(50) {
            let c = lattice.center(cell);
            for k in 0..6 {
                let corner = lattice.corner(Lattice::cell_corners(cell)[k]);
                let p = [
                    c[0] + 0.95 * (corner[0] - c[0]),
                    c[1] + 0.95 * (corner[1] - c[1]),
                ];
                assert_eq!(lattice.cell_containing(p), cell);
            }
            assert_eq!(lattice.cell_containing(c), cell);
        }
    }
}
