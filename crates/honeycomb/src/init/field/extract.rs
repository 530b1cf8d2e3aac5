//! From the two fields to a triangle mesh of lattice points (the hex cells' centres). Each
//! sample knows the lattice point nearest to it; along every sample edge the two points are
//! compared in a frame both share: no lattice step between them means one lattice point (the
//! samples are merged), one step a lattice edge, anything else says nothing. The merged
//! groups are the lattice vertices, the edges join them, and the triangles are the 3-cycles
//! of that graph that face like S, a manifold set of them, best-shaped first.

use super::hierarchy::Level;
use super::orientation::closest_sixfold;
use super::position::{axes, nearest_step};
use super::tangent::{tangential, unit_tangent, usable_normal};
use crate::geometry::Vec3;
use std::collections::HashSet;

/// A step whose ends miss the lattice by more than this many spacings is not trusted.
const MAX_RESIDUAL: f64 = 0.3;

/// Triangles whose shortest edge is less than this share of their longest are dropped.
const MIN_EDGE_RATIO: f64 = 0.45;

pub struct LatticeMesh {
    /// Each lattice vertex at the mean of its samples' lattice points (in their tangent
    /// planes, so slightly off S where it curves).
    pub points: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    /// Counter-clockwise seen from the normals; no two share a directed edge.
    pub triangles: Vec<[usize; 3]>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Step {
    Same,
    Neighbour,
    Other,
}

/// How the lattice points of two samples relate.
fn step(level: &Level, axes: &[Vec3], origins: &[Vec3], i: usize, j: usize, spacing: f64) -> Step {
    let n = usable_normal(level.normals[i] + level.normals[j]);
    let Some(ai) = unit_tangent(axes[i], n) else {
        return Step::Other;
    };
    let aj = closest_sixfold(ai, n, axes[j]);
    let Some(axis) = unit_tangent(ai + aj, n) else {
        return Step::Other;
    };
    let d = tangential(origins[j] - origins[i], n);
    let across = n.cross(axis);
    let (step, residual) = nearest_step(d.dot(axis) / spacing, d.dot(across) / spacing);
    if residual > MAX_RESIDUAL {
        return Step::Other;
    }
    match step {
        [0, 0] => Step::Same,
        [1, 0] | [0, 1] | [-1, 1] | [-1, 0] | [0, -1] | [1, -1] => Step::Neighbour,
        _ => Step::Other,
    }
}

pub fn extract(level: &Level, orientation: &[Vec3], origins: &[Vec3], spacing: f64) -> LatticeMesh {
    let axes = axes(level, orientation);
    let n = level.len();
    let mut sets = UnionFind::new(n);
    let mut links = Vec::new();
    for (i, j) in level.edges() {
        match step(level, &axes, origins, i, j, spacing) {
            Step::Same => sets.union(i, j),
            Step::Neighbour => links.push((i, j)),
            Step::Other => {}
        }
    }
    // Lattice vertices numbered in the order of their first sample.
    let mut cluster = vec![usize::MAX; n];
    let mut count = 0;
    for i in 0..n {
        let root = sets.find(i);
        if cluster[root] == usize::MAX {
            cluster[root] = count;
            count += 1;
        }
        cluster[i] = cluster[root];
    }
    let mut points = vec![Vec3::ZERO; count];
    let mut normals = vec![Vec3::ZERO; count];
    let mut members = vec![0.0; count];
    for i in 0..n {
        let c = cluster[i];
        points[c] += origins[i];
        normals[c] += level.normals[i];
        members[c] += 1.0;
    }
    for c in 0..count {
        points[c] = points[c] / members[c];
        normals[c] = usable_normal(normals[c]);
    }
    let mut adjacent: Vec<Vec<usize>> = vec![Vec::new(); count];
    for (i, j) in links {
        let (a, b) = (cluster[i], cluster[j]);
        if a != b {
            adjacent[a].push(b);
            adjacent[b].push(a);
        }
    }
    for list in &mut adjacent {
        list.sort_unstable();
        list.dedup();
    }
    let triangles = manifold_triangles(&points, &normals, &adjacent, spacing);
    LatticeMesh {
        points,
        normals,
        triangles,
    }
}

/// The 3-cycles of the graph, turned to face along the normals, fairly shaped, chosen
/// best-shaped first so that no directed edge is used twice.
fn manifold_triangles(
    points: &[Vec3],
    normals: &[Vec3],
    adjacent: &[Vec<usize>],
    spacing: f64,
) -> Vec<[usize; 3]> {
    let mut candidates: Vec<(f64, [usize; 3])> = Vec::new();
    for a in 0..points.len() {
        for &b in adjacent[a].iter().filter(|&&b| b > a) {
            // Common neighbours beyond b (both lists are sorted).
            let (la, lb) = (&adjacent[a], &adjacent[b]);
            let (mut x, mut y) = (0, 0);
            while x < la.len() && y < lb.len() {
                match la[x].cmp(&lb[y]) {
                    std::cmp::Ordering::Less => x += 1,
                    std::cmp::Ordering::Greater => y += 1,
                    std::cmp::Ordering::Equal => {
                        let c = la[x];
                        if c > b {
                            if let Some(candidate) = shaped(points, normals, [a, b, c], spacing) {
                                candidates.push(candidate);
                            }
                        }
                        x += 1;
                        y += 1;
                    }
                }
            }
        }
    }
    candidates.sort_unstable_by(|p, q| q.0.total_cmp(&p.0).then(p.1.cmp(&q.1)));
    let mut used: HashSet<(usize, usize)> = HashSet::with_capacity(3 * candidates.len());
    let mut chosen = Vec::with_capacity(candidates.len());
    for (_, t) in candidates {
        let directed = [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])];
        if directed.iter().any(|e| used.contains(e)) {
            continue;
        }
        used.extend(directed);
        chosen.push(t);
    }
    chosen
}

/// The triangle oriented along the normals and its shape score (shortest over longest
/// edge), or None for a sliver, a triangle on edge to S, or one far off the lattice size.
fn shaped(
    points: &[Vec3],
    normals: &[Vec3],
    [a, b, c]: [usize; 3],
    spacing: f64,
) -> Option<(f64, [usize; 3])> {
    let (pa, pb, pc) = (points[a], points[b], points[c]);
    let lengths = [(pb - pa).norm(), (pc - pb).norm(), (pa - pc).norm()];
    let shortest = lengths.iter().copied().fold(f64::INFINITY, f64::min);
    let longest = lengths.iter().copied().fold(0.0, f64::max);
    // Written so that NaN lengths fail too.
    let fair = shortest >= MIN_EDGE_RATIO * longest && longest <= 1.8 * spacing;
    if !fair {
        return None;
    }
    let n = (pb - pa).cross(pc - pa);
    let facing = n.dot(normals[a] + normals[b] + normals[c]);
    // Well-shaped, so |n| is near sqrt(3)/2 longest^2 and facing near 3 |n|.
    if facing.abs() < 0.5 * n.norm() {
        return None;
    }
    let score = shortest / longest;
    Some(if facing > 0.0 {
        (score, [a, b, c])
    } else {
        (score, [a, c, b])
    })
}

/// Disjoint sets with path halving and union by size.
pub struct UnionFind {
    parent: Vec<usize>,
    size: Vec<usize>,
}

impl UnionFind {
    pub fn new(n: usize) -> UnionFind {
        UnionFind {
            parent: (0..n).collect(),
            size: vec![1; n],
        }
    }

    pub fn find(&mut self, mut x: usize) -> usize {
        while self.parent[x] != x {
            self.parent[x] = self.parent[self.parent[x]];
            x = self.parent[x];
        }
        x
    }

    /// How many members there are in all.
    pub fn members(&self) -> usize {
        self.parent.len()
    }

    /// How many members the set of `x` has.
    pub fn size_of(&mut self, x: usize) -> usize {
        let root = self.find(x);
        self.size[root]
    }

    pub fn union(&mut self, a: usize, b: usize) {
        let (mut a, mut b) = (self.find(a), self.find(b));
        if a == b {
            return;
        }
        if self.size[a] < self.size[b] || (self.size[a] == self.size[b] && a > b) {
            std::mem::swap(&mut a, &mut b);
        }
        self.parent[b] = a;
        self.size[a] += self.size[b];
    }
}

/// A flat regular triangular lattice of `rings` rings around the origin (unit spacing, normals
/// up) and the index of each lattice point (u, v): a fixture for the tests of what follows
/// extraction.
#[cfg(test)]
pub fn flat_lattice_patch(
    rings: i64,
) -> (LatticeMesh, std::collections::HashMap<(i64, i64), usize>) {
    let s3 = 3f64.sqrt() / 2.0;
    let mut index = std::collections::HashMap::new();
    let mut points = Vec::new();
    for v in -rings..=rings {
        for u in -rings..=rings {
            if (u + v).abs() <= rings {
                index.insert((u, v), points.len());
                points.push(Vec3::new(u as f64 + 0.5 * v as f64, s3 * v as f64, 0.0));
            }
        }
    }
    let mut keys: Vec<_> = index.keys().copied().collect();
    keys.sort();
    let mut triangles = Vec::new();
    for (u, v) in keys {
        let a = index[&(u, v)];
        if let (Some(&b), Some(&c)) = (index.get(&(u + 1, v)), index.get(&(u, v + 1))) {
            triangles.push([a, b, c]);
        }
        if let (Some(&b), Some(&c)) = (index.get(&(u + 1, v)), index.get(&(u + 1, v - 1))) {
            triangles.push([a, c, b]);
        }
    }
    let normals = vec![Vec3::new(0.0, 0.0, 1.0); points.len()];
    let lattice = LatticeMesh {
        points,
        normals,
        triangles,
    };
    (lattice, index)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overlapping_triangles_of_a_quad_with_both_diagonals_are_not_both_kept() {
        // A unit square with both diagonals: four 3-cycles, two of which tile it.
        let points = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ];
        let normals = vec![Vec3::new(0.0, 0.0, 1.0); 4];
        let adjacent = vec![vec![1, 2, 3], vec![0, 2, 3], vec![0, 1, 3], vec![0, 1, 2]];
        let triangles = manifold_triangles(&points, &normals, &adjacent, 1.0);
        assert_eq!(triangles.len(), 2, "{triangles:?}");
        for t in &triangles {
            let [a, b, c] = t.map(|v| points[v]);
            assert!((b - a).cross(c - a).z > 0.0, "{t:?} faces down");
        }
    }

    #[test]
    fn union_find_joins_and_separates() {
        let mut sets = UnionFind::new(6);
        sets.union(0, 1);
        sets.union(2, 3);
        sets.union(1, 3);
        assert_eq!(sets.find(0), sets.find(2));
        assert_ne!(sets.find(0), sets.find(4));
        assert_ne!(sets.find(4), sets.find(5));
    }
}
