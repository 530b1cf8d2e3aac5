//! The boundary of the reference surface: closed polylines, with nearest-point queries.

use super::bvh::Bvh;
use super::closest::closest_point_on_segment;
use crate::geometry::Vec3;
use std::collections::HashMap;

/// The point of the boundary of S closest to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundaryPoint {
    pub point: Vec3,
    /// Unit direction of the boundary segment containing `point`, along the loop.
    pub tangent: Vec3,
    /// Distance from the query point to `point`.
    pub distance: f64,
    /// Which loop of [`super::Surface::boundary_loops`] the point lies on.
    pub loop_index: usize,
}

#[derive(Clone, Copy, Debug)]
struct Segment {
    a: Vec3,
    b: Vec3,
    tangent: Vec3,
    loop_index: usize,
}

#[derive(Clone, Debug, Default)]
pub(crate) struct Boundary {
    /// Closed polylines: the last point connects back to the first.
    loops: Vec<Vec<Vec3>>,
    /// All polyline segments of positive length (a zero-length one has no direction, and its
    /// point is also an end of a neighbouring segment).
    segments: Vec<Segment>,
    bvh: Bvh,
}

impl Boundary {
    /// Chains the boundary half-edges into loops. The half-edges of an oriented mesh enter and
    /// leave every vertex equally often, so walking them always closes up.
    pub fn new(vertices: &[Vec3], half_edges: &[[usize; 2]]) -> Boundary {
        let loops: Vec<Vec<Vec3>> = chain_loops(half_edges)
            .into_iter()
            .map(|lp| lp.into_iter().map(|v| vertices[v]).collect())
            .collect();
        let mut segments = Vec::new();
        for (loop_index, lp) in loops.iter().enumerate() {
            for k in 0..lp.len() {
                let (a, b) = (lp[k], lp[(k + 1) % lp.len()]);
                let tangent = (b - a).normalized();
                if tangent != Vec3::ZERO {
                    segments.push(Segment {
                        a,
                        b,
                        tangent,
                        loop_index,
                    });
                }
            }
        }
        let bvh = Bvh::build(&mut segments, |s| (s.a.min(s.b), s.a.max(s.b)));
        Boundary {
            loops,
            segments,
            bvh,
        }
    }

    pub fn loops(&self) -> &[Vec<Vec3>] {
        &self.loops
    }

    /// The closest boundary point; `None` without a boundary (of positive length).
    pub fn closest(&self, p: Vec3) -> Option<BoundaryPoint> {
        let eval = |s: usize| {
            let (q, _) = closest_point_on_segment(p, self.segments[s].a, self.segments[s].b);
            ((p - q).norm_squared(), (s, q))
        };
        // Only a non-finite query escapes every box; answer it from segment 0.
        let (d2, (s, point)) = self
            .bvh
            .nearest(p, &eval)
            .or_else(|| (!self.segments.is_empty()).then(|| eval(0)))?;
        Some(BoundaryPoint {
            point,
            tangent: self.segments[s].tangent,
            distance: d2.sqrt(),
            loop_index: self.segments[s].loop_index,
        })
    }
}

/// Walks the half-edges into closed vertex loops. Where loops touch at a vertex (two boundary
/// parts meeting at one point), any unused outgoing half-edge continues a closed walk.
fn chain_loops(half_edges: &[[usize; 2]]) -> Vec<Vec<usize>> {
    let mut outgoing: HashMap<usize, Vec<usize>> = HashMap::new();
    for (e, &[a, _]) in half_edges.iter().enumerate() {
        outgoing.entry(a).or_default().push(e);
    }
    let mut used = vec![false; half_edges.len()];
    let mut loops = Vec::new();
    for first in 0..half_edges.len() {
        if used[first] {
            continue;
        }
        let start = half_edges[first][0];
        let mut lp = Vec::new();
        let mut e = first;
        loop {
            used[e] = true;
            lp.push(half_edges[e][0]);
            let v = half_edges[e][1];
            if v == start {
                break;
            }
            let next = outgoing
                .get(&v)
                .and_then(|es| es.iter().copied().find(|&x| !used[x]));
            match next {
                Some(x) => e = x,
                None => break, // cannot happen for an oriented mesh; close the loop anyway
            }
        }
        loops.push(lp);
    }
    loops
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_loops_touching_at_a_vertex() {
        // Two triangles' boundaries sharing vertex 0 (a bow tie).
        let he = [[0, 1], [1, 2], [2, 0], [0, 3], [3, 4], [4, 0]];
        let loops = chain_loops(&he);
        assert_eq!(loops.iter().map(Vec::len).sum::<usize>(), 6);
        for lp in &loops {
            assert!(lp.len() == 3 || lp.len() == 6);
        }
    }

    #[test]
    fn zero_length_segments_are_skipped() {
        let v = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ];
        let b = Boundary::new(&v, &[[0, 1], [1, 2], [2, 3], [3, 0]]);
        assert_eq!(b.loops().len(), 1);
        assert_eq!(b.loops()[0].len(), 4);
        let q = b.closest(Vec3::new(1.5, 0.2, 0.0)).unwrap();
        assert_eq!(q.point, Vec3::new(1.0, 0.0, 0.0));
        assert!((q.tangent.norm() - 1.0).abs() < 1e-12);
    }
}
