//! The multiresolution hierarchy the fields are solved on: each coarser level pairs
//! neighbouring vertices of the finer one (a matching that prefers small pairs whose normals
//! agree), so that a few sweeps per level carry the low-frequency part of a field across the
//! whole surface, which sweeps on the finest level alone would take thousands of steps to do.

use super::tangent::usable_normal;
use crate::geometry::Vec3;

/// Levels stop when this few vertices remain.
const COARSEST: usize = 16;

/// One level: a graph of vertices with positions, normals and areas.
pub struct Level {
    pub points: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    pub areas: Vec<f64>,
    /// Neighbours of vertex i: `neighbours[offsets[i]..offsets[i + 1]]`, sorted.
    offsets: Vec<usize>,
    neighbours: Vec<u32>,
    /// The vertex of the next coarser level that each vertex was merged into (empty on the
    /// coarsest level).
    pub parent: Vec<u32>,
}

impl Level {
    pub fn len(&self) -> usize {
        self.points.len()
    }

    pub fn neighbours(&self, i: usize) -> &[u32] {
        &self.neighbours[self.offsets[i]..self.offsets[i + 1]]
    }

    /// Every edge once, as (i, j) with i < j.
    pub fn edges(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        (0..self.len()).flat_map(move |i| {
            self.neighbours(i)
                .iter()
                .map(|&j| j as usize)
                .filter(move |&j| j > i)
                .map(move |j| (i, j))
        })
    }

    /// The finest level: the samples and the edges of their triangles.
    pub fn from_triangles(
        points: Vec<Vec3>,
        normals: Vec<Vec3>,
        areas: Vec<f64>,
        triangles: &[[u32; 3]],
    ) -> Level {
        let mut lists: Vec<Vec<u32>> = vec![Vec::new(); points.len()];
        for t in triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                lists[a as usize].push(b);
                lists[b as usize].push(a);
            }
        }
        let (offsets, neighbours) = compress(lists);
        Level {
            points,
            normals,
            areas,
            offsets,
            neighbours,
            parent: Vec::new(),
        }
    }

    /// Pairs neighbours into the next coarser level, recording each vertex's parent; `None`
    /// when pairing no longer shrinks the graph.
    fn coarsen(&mut self) -> Option<Level> {
        let n = self.len();
        let mut candidates: Vec<(f64, u32, u32)> = self
            .edges()
            .map(|(i, j)| {
                let agree = self.normals[i].dot(self.normals[j]);
                let size = (self.areas[i] + self.areas[j]).max(1e-300);
                (agree / size, i as u32, j as u32)
            })
            .collect();
        // Highest score first; ties by index, so one input gives one hierarchy.
        candidates
            .sort_unstable_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
        let mut partner = vec![u32::MAX; n];
        for &(_, i, j) in &candidates {
            if partner[i as usize] == u32::MAX && partner[j as usize] == u32::MAX {
                partner[i as usize] = j;
                partner[j as usize] = i;
            }
        }
        let mut parent = vec![u32::MAX; n];
        let mut coarse = 0u32;
        for i in 0..n {
            if parent[i] != u32::MAX {
                continue;
            }
            parent[i] = coarse;
            if partner[i] != u32::MAX {
                parent[partner[i] as usize] = coarse;
            }
            coarse += 1;
        }
        let m = coarse as usize;
        if m as f64 > 0.9 * n as f64 {
            return None;
        }
        let mut points = vec![Vec3::ZERO; m];
        let mut normals = vec![Vec3::ZERO; m];
        let mut areas = vec![0.0; m];
        // Plain sums too, for children without area.
        let mut plain = vec![(Vec3::ZERO, 0.0); m];
        for (i, &c) in parent.iter().enumerate() {
            let c = c as usize;
            let w = self.areas[i];
            points[c] += self.points[i] * w;
            normals[c] += self.normals[i] * w;
            areas[c] += w;
            plain[c].0 += self.points[i];
            plain[c].1 += 1.0;
        }
        for c in 0..m {
            points[c] = if areas[c] > 0.0 {
                points[c] / areas[c]
            } else {
                plain[c].0 / plain[c].1
            };
        }
        // Children whose normals cancel out: the parent takes a child's.
        for (i, &c) in parent.iter().enumerate() {
            let c = c as usize;
            let cancelled = normals[c].norm_squared() <= 0.0 || !normals[c].is_finite();
            if cancelled {
                normals[c] = self.normals[i];
            }
        }
        for nc in &mut normals {
            *nc = usable_normal(*nc);
        }
        let mut lists: Vec<Vec<u32>> = vec![Vec::new(); m];
        for i in 0..n {
            let pi = parent[i];
            for &j in self.neighbours(i) {
                let pj = parent[j as usize];
                if pi != pj {
                    lists[pi as usize].push(pj);
                }
            }
        }
        let (offsets, neighbours) = compress(lists);
        self.parent = parent;
        Some(Level {
            points,
            normals,
            areas,
            offsets,
            neighbours,
            parent: Vec::new(),
        })
    }
}

/// Sorted, duplicate-free neighbour lists packed into one array.
fn compress(mut lists: Vec<Vec<u32>>) -> (Vec<usize>, Vec<u32>) {
    let mut offsets = Vec::with_capacity(lists.len() + 1);
    let mut neighbours = Vec::new();
    offsets.push(0);
    for list in &mut lists {
        list.sort_unstable();
        list.dedup();
        neighbours.extend_from_slice(list);
        offsets.push(neighbours.len());
    }
    (offsets, neighbours)
}

/// The levels from the finest (index 0) to the coarsest.
pub fn build(finest: Level) -> Vec<Level> {
    let mut levels = vec![finest];
    while levels.last().is_some_and(|l| l.len() > COARSEST) && levels.len() < 64 {
        let last = levels.len() - 1;
        match levels[last].coarsen() {
            Some(coarser) => levels.push(coarser),
            None => break,
        }
    }
    levels
}

/// A flat n x n grid of unit squares, each split into two triangles, normals up (a fixture
/// for the fields' tests).
#[cfg(test)]
pub fn flat_grid(n: usize) -> Level {
    let mut points = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            points.push(Vec3::new(i as f64, j as f64, 0.0));
        }
    }
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let count = points.len();
    Level::from_triangles(
        points,
        vec![Vec3::new(0.0, 0.0, 1.0); count],
        vec![1.0; count],
        &triangles,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_halve_and_keep_area_and_connectivity() {
        let levels = build(flat_grid(30));
        assert!(levels.len() >= 5, "{} levels", levels.len());
        for pair in levels.windows(2) {
            let (fine, coarse) = (&pair[0], &pair[1]);
            assert!(coarse.len() <= (0.9 * fine.len() as f64) as usize);
            assert!(coarse.len() * 2 >= fine.len());
            let total = |l: &Level| l.areas.iter().sum::<f64>();
            assert!((total(fine) - total(coarse)).abs() < 1e-9);
            // Every fine edge maps to a coarse edge or inside one vertex.
            for (i, j) in fine.edges() {
                let (a, b) = (fine.parent[i], fine.parent[j]);
                assert!(a == b || coarse.neighbours(a as usize).contains(&b));
            }
        }
        assert!(levels.last().unwrap().len() <= COARSEST * 2);
        // Neighbour lists are symmetric.
        for level in &levels {
            for (i, j) in level.edges() {
                assert!(level.neighbours(j).contains(&(i as u32)));
            }
        }
    }
}
