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
use crate::error::{Error, Result};
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

pub fn reciprocal(h: &Honeycomb, conn: &Connectivity, t: f64) -> Result<Reciprocal> {
    if !t.is_finite() || t <= 0.0 {
        return Err(Error::Parameter(format!(
            "reciprocal by {t}: expected a positive distance"
        )));
    }
    let black = colour_nodes(h, conn)?;
    let p = &h.base.vertices;
    let faces = &h.base.faces;
    let normals: Vec<Vec3> = (0..h.edges.len()).map(|e| h.wall_normal(e)).collect();
    // Each wall's translation along its normal n_e (as seen from its first vertex).
    let lambda: Vec<f64> = h
        .edges
        .iter()
        .enumerate()
        .map(|(e, &[a, b])| {
            let (from, to) = if black[a] { (a, b) } else { (b, a) };
            let left = h.axes[from].cross(p[to] - p[from]);
            t * normals[e].dot(left).signum()
        })
        .collect();
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
    // Where walls e and f of node v meet now: on a line parallel to v's axis, closest to v.
    let mut corner = |v: usize, e: usize, f: usize| -> usize {
        let key = (v, e.min(f), e.max(f));
        *index.entry(key).or_insert_with(|| {
            let walls: Vec<(Vec3, f64)> = [e, f]
                .iter()
                .map(|&w| {
                    let s = conn.edge_sign(w, v);
                    (normals[w] * s, lambda[w] * s)
                })
                .collect();
            vertices.push(p[v] + axis_plane_shift(h.axes[v], &walls));
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
    let connectivity = Connectivity::build(&base)
        .map_err(|e| Error::Parameter(format!("the reciprocal structure failed: {e}")))?;
    Ok(Reciprocal {
        honeycomb: Honeycomb::new(base, &connectivity, axes, h.thickness),
        connectivity,
        t_junctions,
    })
}
