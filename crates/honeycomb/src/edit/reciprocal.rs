//! The reciprocal structure (paper Fig. 15): the walls of every cell move out and in by turns,
//! by `t`. Around a node the three walls then turn the same way, no longer meet in one line and
//! bound a small triangle: a triangular cell per node. Every wall ends on another one at a
//! corner of such a triangle, a T-junction, which the mesh represents explicitly as a vertex on
//! a straight side of the neighbouring cell. Walls keep their directions, so every new vertex
//! has an old node's axis.
//!
//! Turning "by turns" into a rule: colour the nodes black and white (cells with an even number
//! of sides make that possible); every wall, oriented from its black to its white end, moves to
//! its left.

use super::translate::axis_plane_shift;
use super::{validated, FINEST};
use crate::error::{rounded, short_number, Error, Result};
use crate::geometry::Vec3;
use crate::mesh::{Connectivity, PolyMesh};
use crate::structure::Honeycomb;
use std::collections::{HashMap, VecDeque};

pub struct Reciprocal {
    pub honeycomb: Honeycomb,
    pub connectivity: Connectivity,
    /// Vertices where one wall ends on another (all corners of the node triangles).
    pub t_junctions: Vec<usize>,
}

/// Two-colours the nodes, or names a cell with an odd number of sides.
fn colour_nodes(h: &Honeycomb, conn: &Connectivity) -> Result<Vec<bool>> {
    let n = h.base.vertices.len();
    let mut colour: Vec<Option<bool>> = vec![None; n];
    let mut queue = VecDeque::new();
    for start in 0..n {
        if colour[start].is_some() {
            continue;
        }
        colour[start] = Some(true);
        queue.push_back(start);
        while let Some(v) = queue.pop_front() {
            for &e in &conn.vertex_edges[v] {
                let w = conn.other_end(e, v);
                match colour[w] {
                    None => {
                        colour[w] = colour[v].map(|c| !c);
                        queue.push_back(w);
                    }
                    Some(c) if Some(c) == colour[v] => {
                        let odd = h
                            .base
                            .faces
                            .iter()
                            .position(|f| f.len() % 2 == 1)
                            .unwrap_or(0);
                        return Err(Error::Parameter(format!(
                            "a reciprocal structure needs cells with an even number of sides; \
                             cell {odd} has {}",
                            h.base.faces[odd].len()
                        )));
                    }
                    Some(_) => {}
                }
            }
        }
    }
    Ok(colour.into_iter().map(|c| c.unwrap_or(true)).collect())
}

/// The walls' moves for a unit distance. Every corner of the reciprocal structure is its node
/// plus the distance times a fixed shift, so the whole structure scales with the distance.
struct UnitMoves<'a> {
    h: &'a Honeycomb,
    conn: &'a Connectivity,
    normals: Vec<Vec3>,
    /// Each wall's translation along its normal n_e (as seen from its first vertex): +-1.
    lambda: Vec<f64>,
}

impl<'a> UnitMoves<'a> {
    fn new(h: &'a Honeycomb, conn: &'a Connectivity) -> Result<UnitMoves<'a>> {
        let black = colour_nodes(h, conn)?;
        let p = &h.base.vertices;
        let normals: Vec<Vec3> = (0..h.edges.len()).map(|e| h.wall_normal(e)).collect();
        let lambda = h
            .edges
            .iter()
            .enumerate()
            .map(|(e, &[a, b])| {
                let (from, to) = if black[a] { (a, b) } else { (b, a) };
                let left = h.axes[from].cross(p[to] - p[from]);
                normals[e].dot(left).signum()
            })
            .collect();
        Ok(UnitMoves {
            h,
            conn,
            normals,
            lambda,
        })
    }

    /// Where walls e and f of node v meet after the move, relative to v: on a line parallel to
    /// v's axis, closest to v.
    fn corner_shift(&self, v: usize, e: usize, f: usize) -> Vec3 {
        let walls = [e, f].map(|w| {
            let s = self.conn.edge_sign(w, v);
            (self.normals[w] * s, self.lambda[w] * s)
        });
        axis_plane_shift(self.h.axes[v], &walls)
    }

    /// The distances this honeycomb takes: its upper end is where, along some edge's wall, the
    /// node triangles at its two ends (growing linearly with the distance) meet.
    fn range(&self) -> ReciprocalRange {
        let p = &self.h.base.vertices;
        let mut limit = (f64::INFINITY, [0, 0]);
        for (e, &[a, b]) in self.h.edges.iter().enumerate() {
            let length = (p[b] - p[a]).norm();
            let along = (p[b] - p[a]) / length;
            // How far along the edge the corners on this wall at node v lie, per unit distance.
            let reach = |v: usize| {
                self.conn.vertex_edges[v]
                    .iter()
                    .filter(|&&f| f != e)
                    .map(move |&f| self.corner_shift(v, e, f).dot(along))
            };
            let closing =
                reach(a).fold(f64::NEG_INFINITY, f64::max) - reach(b).fold(f64::INFINITY, f64::min);
            if closing > 0.0 && length / closing < limit.0 {
                limit = (length / closing, [a, b]);
            }
        }
        ReciprocalRange {
            smallest: FINEST * limit.0.min(self.h.base.mean_edge_length()),
            limit: limit.0,
            edge: limit.1,
        }
    }
}

/// The distances `reciprocal` takes on a honeycomb: from `smallest` (a millionth of its scale:
/// the mean edge length, or `limit` where that is less) to below `limit`.
pub struct ReciprocalRange {
    pub smallest: f64,
    /// Where the node triangles at the ends of `edge` meet; infinite when no edge limits.
    pub limit: f64,
    pub edge: [usize; 2],
}

pub fn reciprocal_range(h: &Honeycomb, conn: &Connectivity) -> Result<ReciprocalRange> {
    Ok(UnitMoves::new(h, conn)?.range())
}

/// The reciprocal structure of `h` by distance `t`, which must lie in its [`reciprocal_range`].
pub fn reciprocal(h: &Honeycomb, conn: &Connectivity, t: f64) -> Result<Reciprocal> {
    let what = format!("reciprocal by {}", short_number(t));
    let moves = UnitMoves::new(h, conn)?;
    let range = moves.range();
    if !(range.smallest <= t && t < range.limit) {
        let [a, b] = range.edge;
        let upper = if range.limit.is_finite() {
            format!(
                " to below {}, where the node triangles at the ends of edge {a}-{b} ({} long) \
                 meet",
                rounded(range.limit, 4),
                rounded((h.base.vertices[b] - h.base.vertices[a]).norm(), 4)
            )
        } else {
            String::new()
        };
        return Err(Error::Parameter(format!(
            "{what}: expected a distance from {}{upper}",
            rounded(range.smallest, 4)
        )));
    }
    let p = &h.base.vertices;
    let faces = &h.base.faces;
    let (normals, lambda) = (&moves.normals, &moves.lambda);
    // The cell each wall moved into.
    let moved_into: Vec<Option<usize>> = (0..h.edges.len())
        .map(|e| {
            let [a, b] = h.edges[e];
            let mid = (p[a] + p[b]) * 0.5;
            conn.edge_faces[e]
                .iter()
                .flatten()
                .copied()
                .find(|&f| (h.base.face_centroid(f) - mid).dot(normals[e] * lambda[e]) > 0.0)
        })
        .collect();

    let mut vertices = Vec::new();
    let mut axes = Vec::new();
    let mut index: HashMap<(usize, usize, usize), usize> = HashMap::new();
    let mut corner = |v: usize, e: usize, f: usize| -> usize {
        let key = (v, e.min(f), e.max(f));
        *index.entry(key).or_insert_with(|| {
            vertices.push(p[v] + moves.corner_shift(v, e, f) * t);
            axes.push(h.axes[v]);
            vertices.len() - 1
        })
    };
    let third = |v: usize, e: usize, f: usize| {
        conn.vertex_edges[v]
            .iter()
            .copied()
            .find(|&r| r != e && r != f)
    };

    let mut new_faces: Vec<Vec<usize>> = Vec::with_capacity(faces.len() + p.len());
    let mut t_junctions = Vec::new();
    for (c, face) in faces.iter().enumerate() {
        let n = face.len();
        let mut loop_ = Vec::with_capacity(2 * n);
        for (k, &v) in face.iter().enumerate() {
            let (prev, next) = (conn.face_edges[c][(k + n - 1) % n], conn.face_edges[c][k]);
            let radial = third(v, prev, next);
            let here = corner(v, prev, next);
            // The triangle at v shows along the one of this cell's walls that moved into it.
            match radial {
                Some(r) if moved_into[prev] == Some(c) => {
                    let tj = corner(v, prev, r);
                    t_junctions.push(tj);
                    loop_.extend([tj, here]);
                }
                Some(r) if moved_into[next] == Some(c) => {
                    let tj = corner(v, next, r);
                    t_junctions.push(tj);
                    loop_.extend([here, tj]);
                }
                _ => loop_.push(here),
            }
        }
        new_faces.push(loop_);
    }
    // One triangle per trivalent node, oriented against the cells it borders.
    let mut side_direction: HashMap<(usize, usize), bool> = HashMap::new();
    for f in &new_faces {
        for k in 0..f.len() {
            side_direction.insert((f[k], f[(k + 1) % f.len()]), true);
        }
    }
    for v in 0..p.len() {
        let [e, f, g] = match conn.vertex_edges[v][..] {
            [e, f, g] => [e, f, g],
            _ => continue,
        };
        let tri = [corner(v, e, f), corner(v, f, g), corner(v, g, e)];
        let used_forward = (0..3).any(|k| side_direction.contains_key(&(tri[k], tri[(k + 1) % 3])));
        new_faces.push(if used_forward {
            vec![tri[2], tri[1], tri[0]]
        } else {
            tri.to_vec()
        });
    }
    t_junctions.sort_unstable();
    t_junctions.dedup();
    let base = PolyMesh::new(vertices, new_faces);
    let connectivity = validated(&what, &base)?;
    Ok(Reciprocal {
        honeycomb: Honeycomb::new(base, &connectivity, axes, h.thickness),
        connectivity,
        t_junctions,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::upright_hex_disk;

    fn shortest_edge(h: &Honeycomb) -> f64 {
        let p = &h.base.vertices;
        h.edges
            .iter()
            .map(|&[a, b]| (p[b] - p[a]).norm())
            .fold(f64::INFINITY, f64::min)
    }

    /// Regular hexagons of edge 1: the node triangles (side 2 sqrt(3) t) grow along every wall
    /// from both ends and meet at t = 1 / (2 sqrt(3)); the structure's sides vanish there.
    #[test]
    fn the_range_ends_where_the_node_triangles_meet() {
        let (h, conn) = upright_hex_disk(2.0, 0.3);
        let range = reciprocal_range(&h, &conn).unwrap();
        assert!(
            (range.limit - 1.0 / 12f64.sqrt()).abs() < 1e-12,
            "{}",
            range.limit
        );
        // The shortest side shrinks linearly to nothing at the limit.
        for share in [0.5, 0.9, 0.99] {
            let r = reciprocal(&h, &conn, share * range.limit).unwrap();
            let shortest = shortest_edge(&r.honeycomb);
            assert!(
                (shortest - (1.0 - share)).abs() < 1e-9,
                "{share}: {shortest}"
            );
        }
        let [a, b] = range.edge;
        for t in [1.01 * range.limit, 1e308, 1e-300, 0.0, -1.0, f64::NAN] {
            let message = reciprocal(&h, &conn, t).err().unwrap().to_string();
            let expected = format!(
                "reciprocal by {}: expected a distance from 2.887e-7 to below 0.2887, where the \
                 node triangles at the ends of edge {a}-{b} (1 long) meet",
                short_number(t)
            );
            assert!(message.contains(&expected), "{message}");
        }
    }
}
