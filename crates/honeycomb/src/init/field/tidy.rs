//! Clean-up of the lattice mesh before it is dualized. Small holes (a triangle or a few that
//! the extraction missed, each of which would cost three or more cells) are filled. Edge
//! flips then bring inner lattice
//! vertices closer to six neighbours: where the position field left two dislocations (a
//! 5-7 pair each) side by side, a flip annihilates them, and every vertex of valence 6 is a
//! hexagon of the result. Then a little tangential smoothing evens out what the field's
//! rounding and the flips left uneven.

use super::extract::LatticeMesh;
use super::tangent::tangential;
use crate::geometry::Vec3;
use std::collections::HashMap;

/// Flip passes over all edges (each pass only flips what lowers the valence deviation).
const FLIP_PASSES: usize = 8;
/// Rounds of greedy flips and dislocation glides.
const GLIDE_ROUNDS: usize = 4;
/// The longest glide path tried, in lattice steps.
const LONGEST_GLIDE: usize = 8;
/// Smoothing steps, each moving a vertex this share of the way to its neighbours' mean.
const SMOOTHING_STEPS: usize = 12;
const SMOOTHING_RATE: f64 = 0.5;
/// A flipped triangle's shortest edge must be at least this share of its longest.
const MIN_EDGE_RATIO: f64 = 0.4;

/// Holes with at most this many sides are filled.
const LARGEST_HOLE: usize = 6;

pub fn tidy(lattice: &mut LatticeMesh, spacing: f64) {
    fill_small_holes(lattice, spacing);
    flip_towards_valence_six(lattice);
    smooth(lattice);
}

/// Fans of triangles over the lattice mesh's short border loops (at most [`LARGEST_HOLE`]
/// edges, each at most 1.5 spacings: S's own boundary is far longer), where the fan keeps the
/// mesh manifold and its triangles fair.
fn fill_small_holes(lattice: &mut LatticeMesh, spacing: f64) {
    let mut edges: HashMap<(usize, usize), ()> =
        HashMap::with_capacity(3 * lattice.triangles.len());
    for t in &lattice.triangles {
        for k in 0..3 {
            edges.insert((t[k], t[(k + 1) % 3]), ());
        }
    }
    // Border edges run along their triangle; a vertex with two leaving it is pinched, and
    // loops through it are left alone.
    let mut next: HashMap<usize, Option<usize>> = HashMap::new();
    let mut border: Vec<(usize, usize)> = edges
        .keys()
        .copied()
        .filter(|&(a, b)| !edges.contains_key(&(b, a)))
        .collect();
    border.sort_unstable();
    for &(a, b) in &border {
        next.entry(a).and_modify(|n| *n = None).or_insert(Some(b));
    }
    let mut seen: HashMap<usize, ()> = HashMap::new();
    for &(start, _) in &border {
        if seen.contains_key(&start) {
            continue;
        }
        let mut hole = vec![start];
        let mut v = start;
        let closed = loop {
            seen.insert(v, ());
            match next.get(&v).copied().flatten() {
                Some(w) if w == start => break true,
                Some(w) if hole.len() < LARGEST_HOLE && !seen.contains_key(&w) => {
                    hole.push(w);
                    v = w;
                }
                _ => break false,
            }
        };
        let short = (0..hole.len()).all(|k| {
            let (a, b) = (hole[k], hole[(k + 1) % hole.len()]);
            (lattice.points[a] - lattice.points[b]).norm() <= 1.5 * spacing
        });
        if !closed || !short {
            continue;
        }
        // The hole runs the other way round from its border.
        hole.reverse();
        if let Some(fan) = best_fan(lattice, &hole, &edges) {
            for t in fan {
                for k in 0..3 {
                    edges.insert((t[k], t[(k + 1) % 3]), ());
                }
                lattice.triangles.push(t);
            }
        }
    }
}

/// The fan over a loop (counter-clockwise) from the corner that gives the fairest triangles,
/// if one gives only fair triangles and no edge the mesh already has.
fn best_fan(
    lattice: &LatticeMesh,
    hole: &[usize],
    edges: &HashMap<(usize, usize), ()>,
) -> Option<Vec<[usize; 3]>> {
    let k = hole.len();
    let mut best: Option<(f64, Vec<[usize; 3]>)> = None;
    for s in 0..k {
        let r: Vec<usize> = (0..k).map(|i| hole[(s + i) % k]).collect();
        let fan: Vec<[usize; 3]> = (1..k - 1).map(|i| [r[0], r[i], r[i + 1]]).collect();
        let diagonals_new = (2..k - 1)
            .all(|i| !edges.contains_key(&(r[0], r[i])) && !edges.contains_key(&(r[i], r[0])));
        if !diagonals_new
            || !fan
                .iter()
                .all(|&t| fair(&lattice.points, &lattice.normals, t))
        {
            continue;
        }
        let worst = fan
            .iter()
            .map(|t| edge_ratio(&lattice.points, *t))
            .fold(f64::INFINITY, f64::min);
        if best.as_ref().is_none_or(|(b, _)| worst > *b) {
            best = Some((worst, fan));
        }
    }
    best.map(|(_, fan)| fan)
}

fn edge_ratio(points: &[Vec3], [a, b, c]: [usize; 3]) -> f64 {
    let (pa, pb, pc) = (points[a], points[b], points[c]);
    let lengths = [(pb - pa).norm(), (pc - pb).norm(), (pa - pc).norm()];
    let shortest = lengths.iter().copied().fold(f64::INFINITY, f64::min);
    let longest = lengths.iter().copied().fold(0.0, f64::max);
    shortest / longest
}

/// Greedy flips of interior edges that lower the sum over inner vertices of (valence - 6)^2,
/// then dislocations glided towards partners or the border (see [`Flipper::glide`]), in
/// rounds until nothing changes.
fn flip_towards_valence_six(lattice: &mut LatticeMesh) {
    let LatticeMesh {
        points,
        normals,
        triangles,
    } = lattice;
    let mut flipper = Flipper::new(points, normals, triangles);
    for _ in 0..GLIDE_ROUNDS {
        flipper.greedy();
        if flipper.glide() == 0 {
            break;
        }
    }
    flipper.greedy();
}

/// One edge flip: edge (a, b) of triangles t1 = (a, b, c) and t2 = (b, a, d) becomes (c, d).
#[derive(Clone, Copy, Debug)]
struct Flip {
    a: usize,
    b: usize,
    c: usize,
    d: usize,
    t1: usize,
    t2: usize,
}

/// The lattice triangles with what edge flips need: the triangle of each directed edge, and
/// each vertex's valence and whether it is inner.
struct Flipper<'a> {
    points: &'a [Vec3],
    normals: &'a [Vec3],
    triangles: &'a mut Vec<[usize; 3]>,
    owner: HashMap<(usize, usize), usize>,
    valence: Vec<i64>,
    inner: Vec<bool>,
}

impl<'a> Flipper<'a> {
    fn new(
        points: &'a [Vec3],
        normals: &'a [Vec3],
        triangles: &'a mut Vec<[usize; 3]>,
    ) -> Flipper<'a> {
        let mut owner: HashMap<(usize, usize), usize> = HashMap::with_capacity(3 * triangles.len());
        for (t, tri) in triangles.iter().enumerate() {
            for k in 0..3 {
                owner.insert((tri[k], tri[(k + 1) % 3]), t);
            }
        }
        let count = points.len();
        let mut valence = vec![0i64; count];
        let mut inner = vec![true; count];
        for &(a, b) in owner.keys() {
            // Each undirected edge is counted from both sides when it is interior.
            valence[a] += 1;
            if !owner.contains_key(&(b, a)) {
                valence[b] += 1;
                inner[a] = false;
                inner[b] = false;
            }
        }
        Flipper {
            points,
            normals,
            triangles,
            owner,
            valence,
            inner,
        }
    }

    fn deviation(&self, v: usize, valence: i64) -> i64 {
        if self.inner[v] {
            (valence - 6) * (valence - 6)
        } else {
            0
        }
    }

    /// The flip of edge (a, b) and the change in the valence deviation it makes, if the edge
    /// is interior, the flip keeps the mesh a manifold with fair triangles and no vertex of
    /// valence below 3.
    fn candidate(&self, a: usize, b: usize) -> Option<(i64, Flip)> {
        let (&t1, &t2) = (self.owner.get(&(a, b))?, self.owner.get(&(b, a))?);
        let c = third(self.triangles[t1], a, b);
        let d = third(self.triangles[t2], b, a);
        if c == d || self.owner.contains_key(&(c, d)) || self.owner.contains_key(&(d, c)) {
            return None;
        }
        let v = &self.valence;
        if v[a] <= 3 || v[b] <= 3 {
            return None;
        }
        let before = self.deviation(a, v[a])
            + self.deviation(b, v[b])
            + self.deviation(c, v[c])
            + self.deviation(d, v[d]);
        let after = self.deviation(a, v[a] - 1)
            + self.deviation(b, v[b] - 1)
            + self.deviation(c, v[c] + 1)
            + self.deviation(d, v[d] + 1);
        let flip = Flip { a, b, c, d, t1, t2 };
        let fine = fair(self.points, self.normals, [c, a, d])
            && fair(self.points, self.normals, [d, b, c]);
        fine.then_some((after - before, flip))
    }

    fn apply(&mut self, f: Flip) {
        let Flip { a, b, c, d, t1, t2 } = f;
        self.triangles[t1] = [c, a, d];
        self.triangles[t2] = [d, b, c];
        self.owner.remove(&(a, b));
        self.owner.remove(&(b, a));
        self.owner.insert((b, c), t2);
        self.owner.insert((a, d), t1);
        self.owner.insert((c, d), t2);
        self.owner.insert((d, c), t1);
        self.valence[a] -= 1;
        self.valence[b] -= 1;
        self.valence[c] += 1;
        self.valence[d] += 1;
    }

    fn revert(&mut self, f: Flip) {
        let Flip { a, b, c, d, t1, t2 } = f;
        self.triangles[t1] = [a, b, c];
        self.triangles[t2] = [b, a, d];
        self.owner.remove(&(c, d));
        self.owner.remove(&(d, c));
        self.owner.insert((a, b), t1);
        self.owner.insert((b, c), t1);
        self.owner.insert((c, a), t1);
        self.owner.insert((b, a), t2);
        self.owner.insert((a, d), t2);
        self.owner.insert((d, b), t2);
        self.valence[a] += 1;
        self.valence[b] += 1;
        self.valence[c] -= 1;
        self.valence[d] -= 1;
    }

    /// Passes of every flip that lowers the deviation.
    fn greedy(&mut self) {
        for _ in 0..FLIP_PASSES {
            let mut edges: Vec<(usize, usize)> = self
                .owner
                .keys()
                .copied()
                .filter(|&(a, b)| a < b && self.owner.contains_key(&(b, a)))
                .collect();
            edges.sort_unstable();
            let mut flipped = 0;
            for (a, b) in edges {
                if let Some((change, flip)) = self.candidate(a, b) {
                    if change < 0 {
                        self.apply(flip);
                        flipped += 1;
                    }
                }
            }
            if flipped == 0 {
                break;
            }
        }
    }

    /// Moves dislocations (an inner vertex of valence 7 next to one of valence 5) along their
    /// glide lines: flipping the edge from the 7 to a vertex x the 7 and the 5 share turns the
    /// 7 and the 5 into sixes and x and the vertex across into a new 5 and 7, one step along.
    /// Steps cost nothing while they meet sixes; a path is kept when within
    /// [`LONGEST_GLIDE`] steps it meets another defect or the border and lowers the
    /// deviation, and undone otherwise. The number of paths kept.
    fn glide(&mut self) -> usize {
        let mut kept = 0;
        let sevens: Vec<usize> = (0..self.valence.len())
            .filter(|&v| self.inner[v] && self.valence[v] == 7)
            .collect();
        for seven in sevens {
            'pairs: for five in self.fives_next_to(seven) {
                for side in [(seven, five), (five, seven)] {
                    if self.valence[seven] != 7 || self.valence[five] != 5 {
                        continue 'pairs;
                    }
                    let Some(&t) = self.owner.get(&side) else {
                        continue;
                    };
                    let pivot = third(self.triangles[t], side.0, side.1);
                    if self.glide_from(seven, five, pivot) {
                        kept += 1;
                        continue 'pairs;
                    }
                }
            }
        }
        kept
    }

    fn fives_next_to(&self, v: usize) -> Vec<usize> {
        let mut fives: Vec<usize> = self
            .owner
            .keys()
            .filter(|&&(a, b)| a == v && self.inner[b] && self.valence[b] == 5)
            .map(|&(_, b)| b)
            .collect();
        fives.sort_unstable();
        fives
    }

    /// Glides the dislocation (7 at `seven`, 5 at `five`) over `pivot`, a vertex both share,
    /// and on in that direction; true when kept.
    fn glide_from(&mut self, mut seven: usize, mut five: usize, mut pivot: usize) -> bool {
        let mut path = Vec::new();
        for _ in 0..LONGEST_GLIDE {
            let Some((change, flip)) = self.candidate(seven, pivot) else {
                break;
            };
            // The flip's far corner is the 5 (on the side the pivot was taken from) or
            // the vertex beyond.
            let beyond = if flip.c == five {
                flip.d
            } else if flip.d == five {
                flip.c
            } else {
                break;
            };
            if change > 0 {
                break;
            }
            self.apply(flip);
            path.push(flip);
            if change < 0 {
                return true;
            }
            // Now `beyond` is the 7 and `pivot` the 5; the next pivot is across the edge
            // (pivot, beyond) from the old 5.
            let (new_seven, new_five) = (beyond, pivot);
            let next = [(new_five, new_seven), (new_seven, new_five)]
                .into_iter()
                .filter_map(|e| {
                    self.owner
                        .get(&e)
                        .map(|&t| third(self.triangles[t], e.0, e.1))
                })
                .find(|&x| x != five);
            let Some(next) = next else { break };
            (seven, five, pivot) = (new_seven, new_five, next);
        }
        while let Some(flip) = path.pop() {
            self.revert(flip);
        }
        false
    }
}

/// The corner of `t` that is neither a nor b.
fn third(t: [usize; 3], a: usize, b: usize) -> usize {
    t.into_iter().find(|&v| v != a && v != b).unwrap_or(a)
}

/// Facing along the normals and not a sliver.
fn fair(points: &[Vec3], normals: &[Vec3], [a, b, c]: [usize; 3]) -> bool {
    let (pa, pb, pc) = (points[a], points[b], points[c]);
    let n = (pb - pa).cross(pc - pa);
    let facing = n.dot(normals[a] + normals[b] + normals[c]);
    edge_ratio(points, [a, b, c]) >= MIN_EDGE_RATIO && facing > 1.5 * n.norm()
}

/// Moves inner vertices (those with a closed ring of neighbours) towards their neighbours'
/// mean, within their tangent planes.
fn smooth(lattice: &mut LatticeMesh) {
    let count = lattice.points.len();
    let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); count];
    let mut out = vec![0i64; count];
    for t in &lattice.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            neighbours[a].push(b);
            neighbours[b].push(a);
            out[a] += 1;
            out[b] -= 1;
        }
    }
    // A vertex is inner when each of its edges appears in two triangles, both ways.
    let inner: Vec<bool> = neighbours
        .iter_mut()
        .enumerate()
        .map(|(v, list)| {
            let uses = list.len();
            list.sort_unstable();
            list.dedup();
            out[v] == 0 && uses == 2 * list.len() && !list.is_empty()
        })
        .collect();
    for _ in 0..SMOOTHING_STEPS {
        let moved: Vec<Vec3> = (0..count)
            .map(|v| {
                let p = lattice.points[v];
                if !inner[v] {
                    return p;
                }
                let list = &neighbours[v];
                let mean =
                    list.iter().fold(Vec3::ZERO, |s, &w| s + lattice.points[w]) / list.len() as f64;
                p + tangential(mean - p, lattice.normals[v]) * SMOOTHING_RATE
            })
            .collect();
        lattice.points = moved;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::init::field::extract::flat_lattice_patch;

    #[test]
    fn a_flip_turns_two_sevens_and_two_fives_into_sixes() {
        // A regular triangular patch with one edge flipped: its ends drop to valence 5 and
        // the two opposite corners rise to 7; flipping back restores the lattice.
        let (mut lattice, index) = flat_lattice_patch(4);
        // Flip the edge (0,0)-(1,0): its triangles are (0,0),(1,0),(0,1) and (0,0),(1,-1),(1,0).
        let (o, e, n, s) = (
            index[&(0, 0)],
            index[&(1, 0)],
            index[&(0, 1)],
            index[&(1, -1)],
        );
        let triangles = &mut lattice.triangles;
        let t1 = triangles.iter().position(|t| *t == [o, e, n]).unwrap();
        let t2 = triangles.iter().position(|t| *t == [o, s, e]).unwrap();
        triangles[t1] = [n, o, s];
        triangles[t2] = [s, e, n];
        flip_towards_valence_six(&mut lattice);
        let has = |t: [usize; 3]| {
            lattice
                .triangles
                .iter()
                .any(|x| (0..3).any(|k| [x[k], x[(k + 1) % 3], x[(k + 2) % 3]] == t))
        };
        assert!(has([o, e, n]) && has([o, s, e]));
    }
}
