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
/// Smoothing steps, each moving a vertex this share of the way to its neighbours' mean.
const SMOOTHING_STEPS: usize = 3;
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

/// Greedy flips of interior edges that lower the sum over inner vertices of (valence - 6)^2.
fn flip_towards_valence_six(lattice: &mut LatticeMesh) {
    let triangles = &mut lattice.triangles;
    let mut owner: HashMap<(usize, usize), usize> = HashMap::with_capacity(3 * triangles.len());
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            owner.insert((tri[k], tri[(k + 1) % 3]), t);
        }
    }
    let count = lattice.points.len();
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
    let deviation = |v: usize, valence: i64| {
        if inner[v] {
            (valence - 6) * (valence - 6)
        } else {
            0
        }
    };
    for _ in 0..FLIP_PASSES {
        let mut edges: Vec<(usize, usize)> = owner
            .keys()
            .copied()
            .filter(|&(a, b)| a < b && owner.contains_key(&(b, a)))
            .collect();
        edges.sort_unstable();
        let mut flipped = 0;
        for (a, b) in edges {
            let (Some(&t1), Some(&t2)) = (owner.get(&(a, b)), owner.get(&(b, a))) else {
                continue;
            };
            let c = third(triangles[t1], a, b);
            let d = third(triangles[t2], b, a);
            if c == d || owner.contains_key(&(c, d)) || owner.contains_key(&(d, c)) {
                continue;
            }
            let before = deviation(a, valence[a])
                + deviation(b, valence[b])
                + deviation(c, valence[c])
                + deviation(d, valence[d]);
            let after = deviation(a, valence[a] - 1)
                + deviation(b, valence[b] - 1)
                + deviation(c, valence[c] + 1)
                + deviation(d, valence[d] + 1);
            if after >= before || valence[a] <= 3 || valence[b] <= 3 {
                continue;
            }
            let (new1, new2) = ([c, a, d], [d, b, c]);
            if !fair(&lattice.points, &lattice.normals, new1)
                || !fair(&lattice.points, &lattice.normals, new2)
            {
                continue;
            }
            triangles[t1] = new1;
            triangles[t2] = new2;
            owner.remove(&(a, b));
            owner.remove(&(b, a));
            owner.insert((b, c), t2);
            owner.insert((a, d), t1);
            owner.insert((c, d), t2);
            owner.insert((d, c), t1);
            valence[a] -= 1;
            valence[b] -= 1;
            valence[c] += 1;
            valence[d] += 1;
            flipped += 1;
        }
        if flipped == 0 {
            break;
        }
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
