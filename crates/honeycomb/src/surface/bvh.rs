//! A bounding-volume hierarchy over axis-aligned boxes, for nearest-primitive queries.
//!
//! The tree is binary, built by median split on the longest axis of the box centers, and
//! stored flat: a node's left child is the next node, its right child is stored by index.
//! What a primitive is (triangle, segment) is up to the caller, who supplies the exact
//! distance; the tree only prunes by box distance.

use crate::geometry::Vec3;

/// Primitives per leaf: a few exact evaluations are cheaper than more box tests.
const LEAF_SIZE: usize = 4;

/// Enough for any tree a median split builds: with fewer than 2^32 primitives its depth is
/// at most 33.
const MAX_DEPTH: usize = 64;

/// A node is 32 bytes, two per cache line: queries on large meshes are bound by memory
/// traffic, so the box is stored in f32, rounded outwards so that it still contains its
/// primitives and pruning stays exact.
#[derive(Clone, Copy, Debug)]
struct Node {
    min: [f32; 3],
    max: [f32; 3],
    /// Leaf: start of its range of primitives. Interior: index of the right child.
    index: u32,
    /// Number of primitives of a leaf; 0 marks an interior node.
    count: u32,
}

impl Node {
    /// Squared distance from `p` to the box (0 inside).
    #[inline]
    fn distance2(&self, p: Vec3) -> f64 {
        let mut d2 = 0.0;
        for (k, x) in [p.x, p.y, p.z].into_iter().enumerate() {
            let d = (self.min[k] as f64 - x)
                .max(x - self.max[k] as f64)
                .max(0.0);
            d2 += d * d;
        }
        d2
    }
}

fn round_down(v: Vec3) -> [f32; 3] {
    v.to_array().map(|x| {
        let f = x as f32;
        if f as f64 > x {
            f.next_down()
        } else {
            f
        }
    })
}

fn round_up(v: Vec3) -> [f32; 3] {
    v.to_array().map(|x| {
        let f = x as f32;
        if (f as f64) < x {
            f.next_up()
        } else {
            f
        }
    })
}

#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    /// The exact box around everything (the root's is rounded).
    bounds: Option<(Vec3, Vec3)>,
}

impl Bvh {
    /// Builds the tree over `prims` and reorders them into tree order, so that every leaf owns
    /// a contiguous range: a query then reads its candidates from consecutive memory instead
    /// of chasing indices. `bounds` gives a primitive's box `(min, max)`.
    pub fn build<T: Clone>(prims: &mut Vec<T>, bounds: impl Fn(&T) -> (Vec3, Vec3)) -> Bvh {
        assert!(
            prims.len() < u32::MAX as usize,
            "too many primitives for a BVH"
        );
        if prims.is_empty() {
            return Bvh::default();
        }
        let boxes: Vec<(Vec3, Vec3)> = prims.iter().map(bounds).collect();
        let mut items: Vec<Item> = boxes
            .iter()
            .enumerate()
            .map(|(i, &(lo, hi))| Item {
                center: ((lo + hi) * 0.5).to_array(),
                index: i as u32,
            })
            .collect();
        let mut nodes = Vec::with_capacity(2 * prims.len().div_ceil(LEAF_SIZE));
        let bounds = build_node(&boxes, &mut items, 0, &mut nodes);
        *prims = items
            .iter()
            .map(|it| prims[it.index as usize].clone())
            .collect();
        Bvh {
            nodes,
            bounds: Some(bounds),
        }
    }

    /// The box around all primitives, `None` for an empty tree.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        self.bounds
    }

    /// The primitive nearest to `p`: `eval(i)` returns the squared distance from `p` to
    /// primitive `i` (in tree order) and whatever the caller wants back from it. Returns the
    /// best pair; `None` for an empty tree (or a non-finite `p`, which no box admits).
    ///
    /// Depth first, nearer child first, so that a good candidate is found early and the
    /// far subtrees are pruned by their box distance.
    pub fn nearest<T>(&self, p: Vec3, mut eval: impl FnMut(usize) -> (f64, T)) -> Option<(f64, T)> {
        let mut best: Option<(f64, T)> = None;
        let mut best_d2 = f64::INFINITY;
        if self.nodes.is_empty() {
            return None;
        }
        // Deferred far children with their box distance, re-checked when popped because
        // the best distance may have shrunk meanwhile.
        let mut stack = [(0u32, 0.0f64); MAX_DEPTH];
        let mut len = 0;
        let mut node = 0usize;
        loop {
            let n = &self.nodes[node];
            if n.count > 0 {
                let start = n.index as usize;
                for prim in start..start + n.count as usize {
                    let (d2, value) = eval(prim);
                    if d2 < best_d2 {
                        best_d2 = d2;
                        best = Some((d2, value));
                    }
                }
            } else {
                let (left, right) = (node + 1, n.index as usize);
                let dl = self.nodes[left].distance2(p);
                let dr = self.nodes[right].distance2(p);
                let (near, dn, far, df) = if dl <= dr {
                    (left, dl, right, dr)
                } else {
                    (right, dr, left, dl)
                };
                if df < best_d2 {
                    stack[len] = (far as u32, df);
                    len += 1;
                }
                if dn < best_d2 {
                    node = near;
                    continue;
                }
            }
            loop {
                if len == 0 {
                    return best;
                }
                len -= 1;
                let (next, d2) = stack[len];
                if d2 < best_d2 {
                    node = next as usize;
                    break;
                }
            }
        }
    }
}

/// A primitive during the build. Partitioning these small records in place is faster than
/// partitioning indices that point into an array of centers.
#[derive(Clone, Copy)]
struct Item {
    center: [f64; 3],
    /// Position of the primitive in the caller's order.
    index: u32,
}

/// Appends the subtree over `items` (whose first element sits at `offset` in tree order) to
/// `nodes`; returns its exact box.
fn build_node(
    boxes: &[(Vec3, Vec3)],
    items: &mut [Item],
    offset: usize,
    nodes: &mut Vec<Node>,
) -> (Vec3, Vec3) {
    let me = nodes.len();
    nodes.push(Node {
        min: [0.0; 3],
        max: [0.0; 3],
        index: offset as u32,
        count: items.len() as u32,
    });
    let (lo, hi) = if items.len() <= LEAF_SIZE {
        let first = boxes[items[0].index as usize];
        items.iter().fold(first, |(lo, hi), it| {
            let b = boxes[it.index as usize];
            (lo.min(b.0), hi.max(b.1))
        })
    } else {
        let axis = longest_axis(items);
        // Splitting at the median by count (not by position) keeps the tree balanced, so its
        // depth stays ~log2(n) even for clustered or coincident centers.
        let mid = items.len() / 2;
        items.select_nth_unstable_by(mid, |a, b| a.center[axis].total_cmp(&b.center[axis]));
        let (left, right) = items.split_at_mut(mid);
        let (llo, lhi) = build_node(boxes, left, offset, nodes);
        let right_index = nodes.len() as u32;
        let (rlo, rhi) = build_node(boxes, right, offset + mid, nodes);
        nodes[me].index = right_index;
        nodes[me].count = 0;
        (llo.min(rlo), lhi.max(rhi))
    };
    nodes[me].min = round_down(lo);
    nodes[me].max = round_up(hi);
    (lo, hi)
}

/// The axis along which the centers spread most.
fn longest_axis(items: &[Item]) -> usize {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for it in items {
        for k in 0..3 {
            lo[k] = lo[k].min(it.center[k]);
            hi[k] = hi[k].max(it.center[k]);
        }
    }
    let extent = [0, 1, 2].map(|k| hi[k] - lo[k]);
    if extent[0] >= extent[1] && extent[0] >= extent[2] {
        0
    } else if extent[1] >= extent[2] {
        1
    } else {
        2
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_point_among_points() {
        // Primitives are points on a 3D lattice; the nearest is known by rounding.
        let mut pts = Vec::new();
        for i in 0..20 {
            for j in 0..20 {
                for k in 0..5 {
                    pts.push(Vec3::new(i as f64, j as f64, k as f64));
                }
            }
        }
        let bvh = Bvh::build(&mut pts, |&p| (p, p));
        assert_eq!(bvh.bounds(), Some((Vec3::ZERO, Vec3::new(19.0, 19.0, 4.0))));
        let mut evaluated = 0;
        let q = Vec3::new(7.2, 12.9, 3.4);
        let (d2, i) = bvh
            .nearest(q, |i| {
                evaluated += 1;
                ((pts[i] - q).norm_squared(), i)
            })
            .unwrap();
        assert_eq!(pts[i], Vec3::new(7.0, 13.0, 3.0));
        assert!((d2 - (0.04 + 0.01 + 0.16)).abs() < 1e-12);
        assert!(evaluated < 100, "pruning failed: {evaluated} evaluations");
    }

    #[test]
    fn f32_boxes_never_prune_the_answer() {
        // Far from the origin f32 resolves only whole units, far coarser than the spacing of
        // these points; outward rounding must keep the nearest point findable.
        let base = Vec3::new(1.0e7, -3.0e7, 2.0e7);
        let mut state = 1u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut pts: Vec<Vec3> = (0..2000)
            .map(|_| base + Vec3::new(next(), next(), next()) * 0.01)
            .collect();
        let bvh = Bvh::build(&mut pts, |&p| (p, p));
        for _ in 0..200 {
            let q = base + Vec3::new(next(), next(), next()) * 0.012;
            let (d2, _) = bvh
                .nearest(q, |i| ((pts[i] - q).norm_squared(), ()))
                .unwrap();
            let exact = pts
                .iter()
                .map(|&p| (p - q).norm_squared())
                .fold(f64::INFINITY, f64::min);
            assert_eq!(d2, exact);
        }
    }

    #[test]
    fn empty_and_coincident() {
        let bvh = Bvh::build(&mut Vec::<Vec3>::new(), |&p| (p, p));
        assert!(bvh.nearest(Vec3::ZERO, |_| (0.0, ())).is_none());
        // All centers equal: the median split must still terminate with a shallow tree.
        let mut pts = vec![Vec3::ZERO; 10_000];
        let bvh = Bvh::build(&mut pts, |&p| (p, p));
        let (d2, _) = bvh.nearest(Vec3::new(1.0, 0.0, 0.0), |i| (1.0, i)).unwrap();
        assert_eq!(d2, 1.0);
    }
}
