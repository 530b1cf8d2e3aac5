//! Wall normals as differences of cell points: `n_e = c_left - c_right` for an edge between two
//! cells (the reciprocal diagram). The node condition `n_ij + n_ik + n_il = 0` then holds at
//! every inner node by construction, and the solver has one point per cell instead of one
//! normal per edge: about 1.5 V instead of 2.5 V blocks of unknowns, and a third less fill.
//! Boundary edges, and a cut of edges from each inner boundary loop to the outer one, keep
//! normals of their own: around a hole the normals need not add up to zero, which differences
//! of cell points could not express.

use crate::constraints::Layout;
use crate::error::Result;
use crate::geometry::differences::integrated;
use crate::geometry::Vec3;
use crate::mesh::{Connectivity, PolyMesh};
use crate::solve::Substitution;
use std::collections::VecDeque;

pub struct DualNormals {
    pub substitution: Substitution,
    /// The solver's unknowns: vertices, cell points (but for one per group, held at the
    /// origin), free normals, then the rest of x as is.
    pub y: Vec<f64>,
    /// A position per block of three unknowns of y (for the ordering).
    pub positions: Vec<Option<Vec3>>,
}

/// The cell on the left of each edge's stored direction (the face holding `a -> b`) and on its
/// right.
fn sides(mesh: &PolyMesh, conn: &Connectivity) -> Vec<[Option<usize>; 2]> {
    let mut sides = vec![[None, None]; conn.num_edges()];
    for (f, face) in mesh.faces.iter().enumerate() {
        for (k, &e) in conn.face_edges[f].iter().enumerate() {
            let from = face[k];
            let slot = if conn.edges[e][0] == from { 0 } else { 1 };
            sides[e][slot] = Some(f);
        }
    }
    sides
}

/// Edges that keep their own normal: the boundary, and per boundary loop after the longest a
/// shortest path of edges through the cells from that loop to the longest.
fn free_edges(mesh: &PolyMesh, conn: &Connectivity, sides: &[[Option<usize>; 2]]) -> Vec<bool> {
    let mut free: Vec<bool> = sides
        .iter()
        .map(|s| s[0].is_none() || s[1].is_none())
        .collect();
    if conn.boundary_loops.len() < 2 {
        return free;
    }
    let loop_cells = |lp: &[usize]| -> Vec<usize> {
        lp.iter()
            .flat_map(|&v| conn.vertex_edges[v].iter())
            .filter(|&&e| sides[e].contains(&None))
            .flat_map(|&e| sides[e].iter().flatten().copied())
            .collect()
    };
    let outer = (0..conn.boundary_loops.len())
        .max_by_key(|&l| conn.boundary_loops[l].len())
        .unwrap_or(0);
    let mut is_target = vec![false; mesh.faces.len()];
    for c in loop_cells(&conn.boundary_loops[outer]) {
        is_target[c] = true;
    }
    for (l, lp) in conn.boundary_loops.iter().enumerate() {
        if l == outer {
            continue;
        }
        // Breadth-first over cells through edges between two cells.
        let mut came: Vec<Option<(usize, usize)>> = vec![None; mesh.faces.len()];
        let mut seen = vec![false; mesh.faces.len()];
        let mut queue = VecDeque::new();
        for c in loop_cells(lp) {
            if !seen[c] {
                seen[c] = true;
                queue.push_back(c);
            }
        }
        let mut reached = None;
        while let Some(c) = queue.pop_front() {
            if is_target[c] {
                reached = Some(c);
                break;
            }
            for &e in &conn.face_edges[c] {
                if let [Some(a), Some(b)] = sides[e] {
                    let d = if a == c { b } else { a };
                    if !seen[d] {
                        seen[d] = true;
                        came[d] = Some((c, e));
                        queue.push_back(d);
                    }
                }
            }
        }
        let mut c = reached;
        while let Some(cell) = c {
            c = came[cell].map(|(prev, e)| {
                free[e] = true;
                prev
            });
        }
    }
    free
}

/// The substitution for the honeycomb's unknowns `x` (laid out by `layout`, followed by
/// `x.len() - layout.len()` unknowns of variants, kept as they are), and its starting point:
/// the cell points that best reproduce the normals in `x` (least squares on the cells' graph).
pub fn dual_normals(
    mesh: &PolyMesh,
    conn: &Connectivity,
    layout: Layout,
    x: &[f64],
) -> Result<DualNormals> {
    let (nv, ne, nf) = (mesh.vertices.len(), conn.num_edges(), mesh.faces.len());
    let sides = sides(mesh, conn);
    let free = free_edges(mesh, conn, &sides);
    let mut free_index = vec![usize::MAX; ne];
    let mut nfree = 0;
    for e in 0..ne {
        if free[e] {
            free_index[e] = nfree;
            nfree += 1;
        }
    }
    // Normals see only differences of cell points: one point per group of cells that the
    // differences link stays at the origin, so that the solver has no free translation left
    // (held by nothing but its tiny regularization, it made pivots vanish in roundoff).
    let group = cell_groups(conn, &sides, &free, nf);
    let pinned = |f: usize| group[f] == f;
    let mut cell_index = vec![None; nf];
    let mut ncells = 0;
    for f in (0..nf).filter(|&f| !pinned(f)) {
        cell_index[f] = Some(ncells);
        ncells += 1;
    }
    let cell = |f: usize| cell_index[f].map(|c| 3 * (nv + c));
    let own = |e: usize| 3 * (nv + ncells + free_index[e]);
    let rest = 3 * (nv + ncells + nfree);
    let extra = x.len() - layout.len();
    let y_len = rest + extra;
    let mut per_x: Vec<Vec<(usize, f64)>> = Vec::with_capacity(x.len());
    for i in 0..3 * nv {
        per_x.push(vec![(i, 1.0)]);
    }
    for e in 0..ne {
        for k in 0..3 {
            per_x.push(match sides[e] {
                [Some(l), Some(r)] if !free[e] => [(cell(l), 1.0), (cell(r), -1.0)]
                    .into_iter()
                    .filter_map(|(c, sign)| c.map(|c| (c + k, sign)))
                    .collect(),
                _ => vec![(own(e) + k, 1.0)],
            });
        }
    }
    for i in 0..extra {
        per_x.push(vec![(rest + i, 1.0)]);
    }
    let mut y = vec![0.0; y_len];
    y[..3 * nv].copy_from_slice(&x[..3 * nv]);
    for e in (0..ne).filter(|&e| free[e]) {
        y[own(e)..own(e) + 3].copy_from_slice(&x[layout.normal(e)..layout.normal(e) + 3]);
    }
    y[rest..].copy_from_slice(&x[layout.len()..]);
    let points = fit_cell_points(&sides, &free, layout, x, nf)?;
    for f in 0..nf {
        if let Some(c) = cell(f) {
            // Relative to the group's pinned point, which is the origin.
            let p = points[f] - points[group[f]];
            y[c..c + 3].copy_from_slice(&p.to_array());
        }
    }
    let mut positions: Vec<Option<Vec3>> = mesh.vertices.iter().map(|&p| Some(p)).collect();
    positions.extend(
        (0..nf)
            .filter(|&f| !pinned(f))
            .map(|f| Some(mesh.face_centroid(f))),
    );
    positions.extend((0..ne).filter(|&e| free[e]).map(|e| {
        let [a, b] = conn.edges[e];
        Some((mesh.vertices[a] + mesh.vertices[b]) * 0.5)
    }));
    positions.resize(y_len.div_ceil(3), None);
    Ok(DualNormals {
        substitution: Substitution::new(y_len, &per_x),
        y,
        positions,
    })
}

/// The cell points whose differences best reproduce the normals in `x` over the edges between
/// two cells (least squares).
fn fit_cell_points(
    sides: &[[Option<usize>; 2]],
    free: &[bool],
    layout: Layout,
    x: &[f64],
    nf: usize,
) -> Result<Vec<Vec3>> {
    let differences: Vec<(usize, usize, Vec3)> = (sides.iter().enumerate())
        .filter(|&(e, _)| !free[e])
        .filter_map(|(e, s)| match *s {
            [Some(l), Some(r)] => Some((l, r, layout.normal_at(x, e))),
            _ => None,
        })
        .collect();
    integrated(nf, &differences)
}

/// For each cell, the first cell of its group: the cells linked to it through edges whose
/// normal is a difference of cell points.
fn cell_groups(
    conn: &Connectivity,
    sides: &[[Option<usize>; 2]],
    free: &[bool],
    nf: usize,
) -> Vec<usize> {
    let mut group = vec![usize::MAX; nf];
    for start in 0..nf {
        if group[start] != usize::MAX {
            continue;
        }
        group[start] = start;
        let mut stack = vec![start];
        while let Some(c) = stack.pop() {
            for &e in &conn.face_edges[c] {
                if let [Some(a), Some(b)] = sides[e] {
                    let d = if a == c { b } else { a };
                    if !free[e] && group[d] == usize::MAX {
                        group[d] = start;
                        stack.push(d);
                    }
                }
            }
        }
    }
    group
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::hex_disk;
    use crate::optimize::{node_walls, without_cells};
    use faer::{Mat, Side};

    fn annulus() -> (PolyMesh, Connectivity) {
        let disk = hex_disk(8.0);
        let inner: Vec<usize> = (0..disk.faces.len())
            .filter(|&f| disk.face_centroid(f).norm() < 3.0)
            .collect();
        let mesh = without_cells(&disk, &inner);
        let conn = Connectivity::build(&mesh).unwrap();
        (mesh, conn)
    }

    /// For any cell points, the normals `S y` add up to zero at every node none of whose
    /// walls is free; the boundary is free, and so is a cut from the hole outwards.
    #[test]
    fn cell_points_meet_the_node_condition_and_the_hole_gets_a_cut() {
        let (mesh, conn) = annulus();
        assert_eq!(conn.boundary_loops.len(), 2);
        let sides = sides(&mesh, &conn);
        let free = free_edges(&mesh, &conn, &sides);
        let cut = (0..conn.num_edges())
            .filter(|&e| free[e] && !conn.is_boundary_edge(e))
            .count();
        assert!(cut >= 2, "{cut} inner edges free");
        assert!((0..conn.num_edges()).all(|e| !conn.is_boundary_edge(e) || free[e]));
        let layout = Layout::new(mesh.vertices.len(), conn.num_edges());
        let x0 = vec![0.0; layout.len()];
        let d = dual_normals(&mesh, &conn, layout, &x0).unwrap();
        let y: Vec<f64> = (0..d.y.len())
            .map(|i| ((i * 7919) % 1000) as f64 / 500.0 - 1.0)
            .collect();
        let mut x = vec![0.0; layout.len()];
        d.substitution.apply(&y, &mut x);
        let (node3, _) = node_walls(&conn);
        let mut checked = 0;
        for walls in &node3 {
            if walls.iter().any(|&(e, _)| free[e]) {
                continue;
            }
            let sum = walls.iter().fold(Vec3::ZERO, |s, &(e, sign)| {
                s + layout.normal_at(&x, e) * sign
            });
            assert!(sum.norm() < 1e-12, "node sum {sum:?}");
            checked += 1;
        }
        assert!(checked > 100, "{checked} nodes checked");
    }

    /// No change of the solver's unknowns leaves every wall normal and vertex as it is (S has
    /// full column rank): a translation of all cell points would, unless one is held.
    #[test]
    fn no_unknown_is_free() {
        let (mesh, conn) = annulus();
        let layout = Layout::new(mesh.vertices.len(), conn.num_edges());
        let d = dual_normals(&mesh, &conn, layout, &vec![0.0; layout.len()]).unwrap();
        let s = &d.substitution;
        let n = s.y_len();
        let mut sts = Mat::<f64>::zeros(n, n);
        for i in 0..s.x_len() {
            for &(a, u) in s.terms(i) {
                for &(b, v) in s.terms(i) {
                    sts[(a, b)] += u * v;
                }
            }
        }
        let llt = sts.llt(Side::Lower).expect("S^T S is positive definite");
        let smallest = (0..n)
            .map(|i| llt.L()[(i, i)])
            .fold(f64::INFINITY, f64::min);
        assert!(smallest > 1e-3, "smallest pivot {smallest}");
    }

    /// Normals that are differences of cell points come back exactly from the fit.
    #[test]
    fn the_fit_recovers_cell_point_normals() {
        let (mesh, conn) = annulus();
        let layout = Layout::new(mesh.vertices.len(), conn.num_edges());
        let x0 = vec![0.0; layout.len()];
        let d = dual_normals(&mesh, &conn, layout, &x0).unwrap();
        let y: Vec<f64> = (0..d.y.len())
            .map(|i| ((i * 104729) % 997) as f64 / 300.0)
            .collect();
        let mut x = vec![0.0; layout.len()];
        d.substitution.apply(&y, &mut x);
        let fitted = dual_normals(&mesh, &conn, layout, &x).unwrap();
        let mut again = vec![0.0; layout.len()];
        fitted.substitution.apply(&fitted.y, &mut again);
        let worst = x
            .iter()
            .zip(&again)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(worst < 1e-6, "normals differ by {worst}");
    }
}
