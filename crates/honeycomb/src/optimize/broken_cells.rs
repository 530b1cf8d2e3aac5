//! Boundary cells that a solve breaks, and a solve that drops them.
//!
//! A boundary cell is held by fewer walls than an interior one. At a node of valence 2 the
//! 120-degree condition fixes one angle only, so a cap (a boundary edge between two such nodes)
//! can slide freely: where S shears a boundary cell, the solve moves the cap's wall onto the
//! line where its neighbours meet, the cap shrinks to nothing and the walls at its ends settle
//! mirrored (60 instead of 120 degrees). A minimum edge length cannot hold it, since the
//! linearized length loses its gradient as the edge vanishes. Likewise the axis of a valence-2
//! node is just the cross product of its two walls and may swing far from its neighbours', so
//! that a wall quad crosses itself. Such cells belong to no honeycomb near the start: they are
//! dropped and the solve starts again from the base mesh without them.

use std::cmp::Reverse;

use super::{optimize, OptimizeOptions, Optimized};
use crate::error::Result;
use crate::mesh::{Connectivity, PolyMesh};
use crate::solve::IterationInfo;
use crate::structure::{measure, Honeycomb, Measures};
use crate::surface::Surface;

/// A cap shorter than this share of the mean edge length has collapsed.
pub const COLLAPSED_CAP: f64 = 0.1;
/// A node this far from 120 degrees (degrees) is broken, not merely unconverged.
pub const BROKEN_NODE_DEG: f64 = 5.0;
/// A wall quad this far from planar (diagonal distance over mean edge) crosses itself.
pub const BROKEN_WALL: f64 = 0.02;

/// Cells are dropped this many times at most.
const MAX_DROPS: usize = 16;
/// Iterations of a probe solve.
const PROBE_ITERATIONS: usize = 20;
/// At most this share of the cells is dropped: beyond it the mesh would be eaten away from its
/// boundary rather than trimmed, and the solve is not the one to keep.
pub const MAX_DROPPED_SHARE: f64 = 0.03;

/// The cells with a boundary edge that hold a collapsed cap, a broken node or a broken wall
/// (far from planar, or not convex), or that border an inner cell holding one (sorted). Inner
/// cells are never listed: dropping them would open holes; nor is a cell whose loss would cut
/// a lobe off the rest (a neck one cell wide), while the few cells of a peninsula it would cut
/// off are listed with it.
pub fn broken_boundary_cells(h: &Honeycomb, conn: &Connectivity, m: &Measures) -> Vec<usize> {
    let limit = COLLAPSED_CAP * m.mean_edge_length;
    let length = |e: usize| {
        let [a, b] = conn.edges[e];
        (h.base.vertices[a] - h.base.vertices[b]).norm()
    };
    let broken_edge = |e: usize| {
        let [a, b] = conn.edges[e];
        let cap = conn.is_boundary_edge(e) && conn.valence(a) == 2 && conn.valence(b) == 2;
        (cap && length(e) < limit)
            || m.delta_per_wall[e] > BROKEN_WALL
            || !m.convex_per_wall[e]
            || m.omega_per_node[a] > BROKEN_NODE_DEG
            || m.omega_per_node[b] > BROKEN_NODE_DEG
    };
    let holds_broken = |f: usize| conn.face_edges[f].iter().any(|&e| broken_edge(e));
    let mut broken = vec![false; h.base.faces.len()];
    for f in 0..h.base.faces.len() {
        if !holds_broken(f) {
            continue;
        }
        if conn.is_boundary_face(f) {
            broken[f] = true;
        } else {
            // An inner cell next to the boundary is broken by its boundary neighbours'
            // twist (walls crossed where the axes lean together): they go instead.
            for &e in &conn.face_edges[f] {
                for g in conn.edge_faces[e].iter().flatten().copied() {
                    if conn.is_boundary_face(g) {
                        broken[g] = true;
                    }
                }
            }
        }
    }
    let candidates: Vec<usize> = (0..h.base.faces.len()).filter(|&f| broken[f]).collect();
    keeping_one_piece(conn, h.base.faces.len(), &candidates)
}

/// At most this share of the cells may be cut off with a broken cell (a peninsula at the
/// boundary, not a lobe of the structure); they go with it. The tip of a thin spike of S is
/// such a peninsula: where the cell at its root breaks, keeping it would keep that cell, and
/// the whole grid would be given up for one crossed wall.
const CUT_OFF_SHARE: f64 = 0.02;

/// Of `candidates` (sorted), those that can go in turn while the rest of the cells stays one
/// piece (cells joined through shared edges), with the few cells a candidate would cut off
/// (sorted).
pub fn keeping_one_piece(conn: &Connectivity, cells: usize, candidates: &[usize]) -> Vec<usize> {
    let cut_off_limit = (CUT_OFF_SHARE * cells as f64).floor() as usize;
    let mut gone = vec![false; cells];
    for &f in candidates {
        if gone[f] {
            continue;
        }
        gone[f] = true;
        let mut pieces = conn.pieces(&gone);
        // The largest piece stays (the first of equals); the others are cut off.
        let largest = (0..pieces.len()).max_by_key(|&k| (pieces[k].len(), Reverse(k)));
        if let Some(k) = largest {
            pieces.swap_remove(k);
        }
        let cut_off: Vec<usize> = pieces.into_iter().flatten().collect();
        if cut_off.len() <= cut_off_limit {
            for g in cut_off {
                gone[g] = true;
            }
        } else {
            gone[f] = false;
        }
    }
    (0..cells).filter(|&f| gone[f]).collect()
}

/// The vertices of `mesh` that some face outside `drop` (sorted) uses, in order: vertex `k` of
/// [`without_cells`] is `kept_vertices(..)[k]`.
pub fn kept_vertices(mesh: &PolyMesh, drop: &[usize]) -> Vec<usize> {
    let mut used = vec![false; mesh.vertices.len()];
    for (f, face) in mesh.faces.iter().enumerate() {
        if drop.binary_search(&f).is_err() {
            for &v in face {
                used[v] = true;
            }
        }
    }
    (0..mesh.vertices.len()).filter(|&v| used[v]).collect()
}

/// `mesh` without the faces `drop` (sorted) and the vertices no other face uses; the order of
/// the rest is kept. In a trivalent mesh every remaining vertex keeps valence 2 or 3.
pub fn without_cells(mesh: &PolyMesh, drop: &[usize]) -> PolyMesh {
    let kept = kept_vertices(mesh, drop);
    let mut index = vec![usize::MAX; mesh.vertices.len()];
    for (k, &v) in kept.iter().enumerate() {
        index[v] = k;
    }
    let vertices = kept.iter().map(|&v| mesh.vertices[v]).collect();
    let faces = (0..mesh.faces.len())
        .filter(|f| drop.binary_search(f).is_err())
        .map(|f| mesh.faces[f].iter().map(|&v| index[v]).collect())
        .collect();
    PolyMesh::new(vertices, faces)
}

/// What [`optimize_dropping_broken_cells`] gives: the last solve, the base mesh it started
/// from, its measures, and how many cells were dropped in how many solves.
pub struct Settled {
    pub optimized: Optimized,
    pub base: PolyMesh,
    pub measures: Measures,
    pub dropped_cells: usize,
    pub solves: usize,
}

/// [`optimize`], and while the result has broken boundary cells (at most sixteen times, and
/// while at most 3% of the cells are gone): the same from `base` without them. Meant for base
/// meshes the program made itself (`pipeline`), whose boundary cells are a choice of the
/// trimming, not the designer's. `progress` sees the solve's number (from 1) with every
/// iteration.
pub fn optimize_dropping_broken_cells(
    base: &PolyMesh,
    surface: &PolyMesh,
    options: &OptimizeOptions,
    progress: &mut dyn FnMut(usize, &IterationInfo),
) -> Result<Settled> {
    let model_surface = Surface::from_mesh(surface)?;
    let allowed = (MAX_DROPPED_SHARE * base.faces.len() as f64).floor() as usize;
    let mut probe = options.clone();
    probe.solver.max_iterations = options.solver.max_iterations.min(PROBE_ITERATIONS);
    let mut base = base.clone();
    let (mut dropped_cells, mut drops) = (0, 0);
    // Cells break in the first few steps: a short probe finds them without paying for a whole
    // solve; the whole solve follows once a probe is clean (and can still break some).
    let probes = probe.solver.max_iterations < options.solver.max_iterations;
    let mut probing = probes;
    for solve in 1.. {
        let this = if probing { &probe } else { options };
        let optimized = optimize(&base, Some(surface), this, &mut |i| progress(solve, i))?;
        let measures = measure(&optimized.honeycomb, &model_surface);
        let broken =
            broken_boundary_cells(&optimized.honeycomb, &optimized.connectivity, &measures);
        let finished = !probing || optimized.solve.converged;
        let out_of_drops = drops == MAX_DROPS || dropped_cells + broken.len() > allowed;
        if broken.is_empty() || out_of_drops {
            if !finished {
                // A clean probe, or nothing more to drop: the whole solve on this mesh.
                probing = false;
                continue;
            }
            return Ok(Settled {
                optimized,
                base,
                measures,
                dropped_cells,
                solves: solve,
            });
        }
        dropped_cells += broken.len();
        drops += 1;
        // From the start again: a solve that broke some cells has bent their neighbours too
        // (starting from where it ended breaks more cells in every round).
        base = without_cells(&base, &broken);
        probing = probes;
    }
    unreachable!("the loop returns")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::hex_disk;
    use crate::geometry::Vec3;
    use crate::mesh::validate_base_mesh;

    /// A plane hex mesh with vertical axes (a honeycomb wherever its cells are regular), its
    /// adjacency and measures.
    fn measured(mesh: &PolyMesh) -> (Honeycomb, Connectivity, Measures) {
        let conn = validate_base_mesh(mesh).unwrap();
        let axes = vec![Vec3::new(0.0, 0.0, 1.0); mesh.vertices.len()];
        let h = Honeycomb::new(mesh.clone(), &conn, axes, 0.3);
        let m = measure(&h, &Surface::from_mesh(mesh).unwrap());
        (h, conn, m)
    }

    fn caps(conn: &Connectivity) -> Vec<usize> {
        (0..conn.num_edges())
            .filter(|&e| {
                let [a, b] = conn.edges[e];
                conn.is_boundary_edge(e) && conn.valence(a) == 2 && conn.valence(b) == 2
            })
            .collect()
    }

    #[test]
    fn a_regular_hex_disk_has_no_broken_cells() {
        let mesh = hex_disk(5.0);
        let (h, conn, m) = measured(&mesh);
        assert!(m.omega_max_deg < 1e-9, "{}", m.omega_max_deg);
        assert!(!caps(&conn).is_empty(), "the disk should have caps to test");
        assert!(broken_boundary_cells(&h, &conn, &m).is_empty());
    }

    #[test]
    fn a_collapsed_cap_breaks_its_boundary_cell_and_no_interior_one() {
        let mut mesh = hex_disk(5.0);
        let conn = validate_base_mesh(&mesh).unwrap();
        let cap = caps(&conn)[0];
        let [a, b] = conn.edges[cap];
        let middle = (mesh.vertices[a] + mesh.vertices[b]) * 0.5;
        let along = (mesh.vertices[b] - mesh.vertices[a]) * 0.01;
        mesh.vertices[a] = middle - along;
        mesh.vertices[b] = middle + along;
        let (h, conn, m) = measured(&mesh);
        let broken = broken_boundary_cells(&h, &conn, &m);
        let cell = conn.edge_faces[cap][0].unwrap();
        assert!(broken.contains(&cell), "{broken:?} lacks cell {cell}");
        for &f in &broken {
            assert!(conn.is_boundary_face(f), "interior cell {f} listed");
        }
        assert!(broken.len() < 4, "{broken:?}");
    }

    #[test]
    fn dropping_boundary_cells_leaves_a_valid_base_mesh() {
        let mesh = hex_disk(5.0);
        let conn = validate_base_mesh(&mesh).unwrap();
        let mut drop: Vec<usize> = caps(&conn)
            .iter()
            .filter_map(|&e| conn.edge_faces[e][0])
            .collect();
        drop.sort_unstable();
        drop.dedup();
        let rest = without_cells(&mesh, &drop);
        assert_eq!(rest.faces.len(), mesh.faces.len() - drop.len());
        let rest_conn = validate_base_mesh(&rest).unwrap();
        // Every vertex still lies in a kept cell and keeps valence 2 or 3.
        assert!((0..rest.vertices.len()).all(|v| (2..=3).contains(&rest_conn.valence(v))));
        assert!(rest.vertices.len() < mesh.vertices.len());
        // The kept cells are the same polygons.
        let (_, _, m) = measured(&rest);
        assert!(m.omega_max_deg < 1e-9);
    }

    /// Two halves of a disk joined by one cell: that cell may not go, others may.
    #[test]
    fn a_drop_never_cuts_the_mesh_in_pieces() {
        let disk = hex_disk(4.0);
        let centre = |m: &PolyMesh, f: usize| m.face_centroid(f);
        // Without the column of cells across x = 0, but its middle cell.
        let cut: Vec<usize> = (0..disk.faces.len())
            .filter(|&f| centre(&disk, f).x.abs() < 1.0 && centre(&disk, f).norm() > 0.5)
            .collect();
        let halves = without_cells(&disk, &cut);
        let conn = Connectivity::build(&halves).unwrap();
        let cells = halves.faces.len();
        assert_eq!(conn.pieces(&vec![false; cells]).len(), 1);
        let bridge = (0..cells)
            .find(|&f| centre(&halves, f).norm() < 0.5)
            .unwrap();
        let far = (0..cells)
            .max_by(|&a, &b| centre(&halves, a).x.total_cmp(&centre(&halves, b).x))
            .unwrap();
        let mut candidates = vec![bridge, far];
        candidates.sort();
        assert_eq!(keeping_one_piece(&conn, cells, &candidates), vec![far]);
    }

    /// A boundary cell held by one neighbour only: that neighbour goes, and the cell with it.
    #[test]
    fn a_peninsula_goes_with_its_neck() {
        let disk = hex_disk(12.0);
        let conn = Connectivity::build(&disk).unwrap();
        let neighbours = |f: usize| -> Vec<usize> {
            let mut n: Vec<usize> = conn.face_edges[f]
                .iter()
                .flat_map(|&e| conn.edge_faces[e].iter().flatten().copied())
                .filter(|&g| g != f)
                .collect();
            n.sort();
            n.dedup();
            n
        };
        let tip = (0..disk.faces.len())
            .max_by(|&a, &b| disk.face_centroid(a).x.total_cmp(&disk.face_centroid(b).x))
            .unwrap();
        let around = neighbours(tip);
        let (neck, moat) = (around[0], &around[1..]);
        let island = without_cells(&disk, moat);
        let conn = Connectivity::build(&island).unwrap();
        let cells = island.faces.len();
        assert!(cells >= 100, "{cells} cells: 1% of them must hold the tip");
        assert_eq!(conn.pieces(&vec![false; cells]).len(), 1);
        // Indices of the island: cells after a dropped one shift down.
        let index = |f: usize| f - moat.iter().filter(|&&g| g < f).count();
        let mut expected = vec![index(neck), index(tip)];
        expected.sort();
        assert_eq!(keeping_one_piece(&conn, cells, &[index(neck)]), expected);
    }

    /// A broken cell at the root of a peninsula goes with the peninsula while that is at most
    /// 2% of the cells (the tip of a thin spike), and stays when the peninsula is larger (a
    /// lobe of the structure).
    #[test]
    fn a_spike_goes_with_its_root_a_lobe_does_not() {
        let disk = hex_disk(14.0);
        let cells = |m: &PolyMesh| m.faces.len();
        let tip = disk.face_centroid(
            (0..cells(&disk))
                .max_by(|&a, &b| disk.face_centroid(a).x.total_cmp(&disk.face_centroid(b).x))
                .unwrap(),
        );
        // The cells within `reach` of the tip make the peninsula; every cell around it goes
        // but the root, the one nearest the disk's centre.
        let peninsula = |reach: f64| {
            let near: Vec<usize> = (0..cells(&disk))
                .filter(|&f| (disk.face_centroid(f) - tip).norm() < reach)
                .collect();
            let conn = Connectivity::build(&disk).unwrap();
            let mut around: Vec<usize> = near
                .iter()
                .flat_map(|&f| conn.face_edges[f].iter())
                .flat_map(|&e| conn.edge_faces[e].iter().flatten().copied())
                .filter(|g| !near.contains(g))
                .collect();
            around.sort();
            around.dedup();
            let root = *around
                .iter()
                .min_by(|&&a, &&b| {
                    let d = |f: usize| disk.face_centroid(f).norm();
                    d(a).total_cmp(&d(b))
                })
                .unwrap();
            let moat: Vec<usize> = around.into_iter().filter(|&g| g != root).collect();
            let island = without_cells(&disk, &moat);
            let conn = Connectivity::build(&island).unwrap();
            assert_eq!(conn.pieces(&vec![false; cells(&island)]).len(), 1);
            let index = |f: usize| f - moat.iter().filter(|&&g| g < f).count();
            let mut expected: Vec<usize> = near.iter().map(|&f| index(f)).collect();
            expected.push(index(root));
            expected.sort();
            let share = near.len() as f64 / cells(&island) as f64;
            (
                keeping_one_piece(&conn, cells(&island), &[index(root)]),
                expected,
                share,
            )
        };
        let (gone, expected, share) = peninsula(2.0);
        assert!(
            share > 0.01 && share <= 0.02,
            "the spike is {share} of the cells"
        );
        assert_eq!(gone, expected);
        let (gone, _, share) = peninsula(6.0);
        assert!(share > 0.02, "the lobe is {share} of the cells");
        assert!(gone.is_empty(), "{gone:?}");
    }
}
