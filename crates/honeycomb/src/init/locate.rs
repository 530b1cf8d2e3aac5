//! Which triangle of a planar triangulation contains a point: a uniform grid of buckets over
//! the triangles' bounding boxes, then barycentric coordinates.

use super::flatten::Point2;

pub struct Locator<'a> {
    points: &'a [Point2],
    triangles: &'a [[usize; 3]],
    origin: Point2,
    cell: f64,
    columns: usize,
    rows: usize,
    buckets: Vec<Vec<u32>>,
}

/// A point of a triangle: the triangle and the barycentric weights of its corners.
#[derive(Clone, Copy, Debug)]
pub struct Located {
    pub triangle: usize,
    pub weights: [f64; 3],
}

impl<'a> Locator<'a> {
    pub fn new(points: &'a [Point2], triangles: &'a [[usize; 3]]) -> Locator<'a> {
        let (lo, hi) = super::bounds(points);
        // About two triangles per bucket.
        let area = ((hi[0] - lo[0]) * (hi[1] - lo[1])).max(1e-300);
        let cell = (2.0 * area / triangles.len().max(1) as f64)
            .sqrt()
            .max(1e-12);
        let columns = (((hi[0] - lo[0]) / cell) as usize + 1).min(4096);
        let rows = (((hi[1] - lo[1]) / cell) as usize + 1).min(4096);
        let mut locator = Locator {
            points,
            triangles,
            origin: lo,
            cell: cell
                .max((hi[0] - lo[0]) / columns as f64)
                .max((hi[1] - lo[1]) / rows as f64),
            columns,
            rows,
            buckets: vec![Vec::new(); columns * rows],
        };
        for (t, tri) in triangles.iter().enumerate() {
            let (mut tlo, mut thi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            for &v in tri {
                for c in 0..2 {
                    tlo[c] = tlo[c].min(points[v][c]);
                    thi[c] = thi[c].max(points[v][c]);
                }
            }
            let (i0, j0) = locator.bucket_of(tlo);
            let (i1, j1) = locator.bucket_of(thi);
            for j in j0..=j1 {
                for i in i0..=i1 {
                    locator.buckets[j * columns + i].push(t as u32);
                }
            }
        }
        locator
    }

    pub fn triangles(&self) -> &'a [[usize; 3]] {
        self.triangles
    }

    fn bucket_of(&self, p: Point2) -> (usize, usize) {
        let clamp = |x: f64, n: usize| (x.max(0.0) as usize).min(n - 1);
        (
            clamp((p[0] - self.origin[0]) / self.cell, self.columns),
            clamp((p[1] - self.origin[1]) / self.cell, self.rows),
        )
    }

    /// The triangle containing `p` (within a relative tolerance on its edges), if any.
    pub fn locate(&self, p: Point2) -> Option<Located> {
        if !p[0].is_finite() || !p[1].is_finite() {
            return None;
        }
        let (i, j) = self.bucket_of(p);
        let inside = |x: f64, n: usize| x >= -1e-9 && x <= n as f64 + 1e-9;
        if !inside((p[0] - self.origin[0]) / self.cell, self.columns)
            || !inside((p[1] - self.origin[1]) / self.cell, self.rows)
        {
            return None;
        }
        // On a shared edge, the triangle the point is deepest in.
        let mut best: Option<(f64, Located)> = None;
        for &t in &self.buckets[j * self.columns + i] {
            let w = barycentric(self.triangles[t as usize].map(|v| self.points[v]), p);
            let depth = w[0].min(w[1]).min(w[2]);
            if depth >= -1e-9 && best.is_none_or(|(d, _)| depth > d) {
                let located = Located {
                    triangle: t as usize,
                    weights: w,
                };
                best = Some((depth, located));
            }
        }
        best.map(|(_, located)| located)
    }
}

/// Barycentric coordinates of `p` in triangle `abc` (all NaN-free for a non-degenerate one).
pub fn barycentric([a, b, c]: [Point2; 3], p: Point2) -> [f64; 3] {
    let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    if det.abs() < 1e-300 {
        return [f64::NEG_INFINITY; 3];
    }
    let wb = ((p[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (p[1] - a[1])) / det;
    let wc = ((b[0] - a[0]) * (p[1] - a[1]) - (p[0] - a[0]) * (b[1] - a[1])) / det;
    [1.0 - wb - wc, wb, wc]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_are_found_in_their_triangle_and_outside_points_are_not() {
        // Two triangles making the unit square.
        let points = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let triangles = vec![[0, 1, 2], [0, 2, 3]];
        let locator = Locator::new(&points, &triangles);
        let l = locator.locate([0.7, 0.2]).unwrap();
        assert_eq!(l.triangle, 0);
        let w = l.weights;
        let back = [
            w[0] * 0.0 + w[1] * 1.0 + w[2] * 1.0,
            w[0] * 0.0 + w[1] * 0.0 + w[2] * 1.0,
        ];
        assert!((back[0] - 0.7).abs() < 1e-12 && (back[1] - 0.2).abs() < 1e-12);
        assert_eq!(locator.locate([0.2, 0.7]).unwrap().triangle, 1);
        assert!(locator.locate([1.0, 1.0]).is_some(), "a corner is inside");
        assert!(locator.locate([1.2, 0.5]).is_none());
        assert!(locator.locate([-0.1, 0.5]).is_none());
        assert!(locator.locate([f64::NAN, 0.5]).is_none());
    }
}
