//! Capping a honeycomb with quads (paper section 4, Figs. 1, 11 and 17): every hexagonal cell of
//! M is split by one of its three long diagonals into two quads, which the optimization then
//! makes planar. Cells that are not hexagons stay whole.
//!
//! Edge classes. Around a hexagon of a hexagonal lattice the edge direction turns by 60 degrees
//! per step, so opposite edges are parallel and the edges fall into three direction classes:
//! edge k of a cell has class `(offset + k) mod 3`. Two cells agree on their shared edge (a
//! consistently oriented neighbour runs it backwards, which is the same line), which fixes the
//! neighbour's offset; a breadth-first search over the hexagons labels a whole patch. At a
//! trivalent node the three edges get three classes. Around a lattice defect (a non-hexagonal
//! cell) the labels need not close up: an edge keeps the first label it gets, every cell splits
//! by its own offset, and the disagreements are only counted.
//!
//! The long diagonal `face[k-1] face[k+2]` of a hexagon is parallel to its edges k and k+3; it
//! has their class. Classes are renumbered per patch so that class 0 is the *straight* class.
//! - `Zigzag` (Figs. 1, 11): every cell splits along its class-0 diagonal. Class-0 edges and
//!   diagonals form straight polylines; edges of classes 1 and 2 alternate along zigzags.
//! - `Alternating` (Fig. 17): strips of cells joined across class-0 edges are numbered by
//!   parity (crossing a class-0 edge keeps it, crossing a class-1 or -2 edge flips it; the three
//!   cells at a trivalent node cross one edge of each class, so the parity closes up around
//!   every node). Even strips split along their class-1 diagonal, odd strips along class 2: the
//!   quads of neighbouring strips lean opposite ways (a herringbone). The diagonals no longer
//!   line up across cells, but each is still continued at both ends by the edge beyond it.
//! - `Flattest`: every cell splits along whichever diagonal leaves its two quads flattest as
//!   the honeycomb stands. No polyline runs straight for long, but where S twists along every
//!   lattice direction in turn (most freeform roofs) the quads start flatter than any one
//!   pattern's, and the capping, no longer fighting a twist passed along columns of cells,
//!   takes them much further.

use super::quad_planarity;
use crate::geometry::Vec3;
use crate::mesh::{Connectivity, PolyMesh};
use std::collections::VecDeque;
use std::str::FromStr;

/// Which long diagonal splits each hexagon.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum QuadPattern {
    /// Every cell along the straight class (Figs. 1, 11).
    #[default]
    Zigzag,
    /// Strips along the straight class, split along the other two classes by turns (Fig. 17).
    Alternating,
    /// Each cell along whichever of its diagonals leaves its two quads flattest.
    Flattest,
}

impl QuadPattern {
    /// `zigzag` or `alternating`, as the option is written.
    pub fn label(self) -> &'static str {
        match self {
            QuadPattern::Zigzag => "zigzag",
            QuadPattern::Alternating => "alternating",
            QuadPattern::Flattest => "flattest",
        }
    }
}

impl FromStr for QuadPattern {
    type Err = String;
    fn from_str(s: &str) -> Result<QuadPattern, String> {
        match s {
            "zigzag" => Ok(QuadPattern::Zigzag),
            "alternating" => Ok(QuadPattern::Alternating),
            "flattest" => Ok(QuadPattern::Flattest),
            _ => Err(format!(
                "unknown quad pattern '{s}': expected zigzag, alternating or flattest"
            )),
        }
    }
}

/// The three lattice directions of a hex mesh, as labels 0, 1, 2 on its edges.
#[derive(Clone, Debug)]
pub struct EdgeClasses {
    /// Per edge: its class; `None` for an edge of no hexagon.
    pub edge: Vec<Option<u8>>,
    /// Per face: the class of its edge 0 (edge k has class `(offset + k) % 3`); `None` for a
    /// cell that is not a hexagon.
    pub cell_offset: Vec<Option<u8>>,
    /// Per face: the patch (connected set of hexagons) it belongs to.
    pub patch: Vec<Option<usize>>,
    pub num_patches: usize,
    /// Edges whose two hexagons disagree on the class (0 on a defect-free patch).
    pub conflicts: usize,
}

impl EdgeClasses {
    /// Labels the edges of every patch of hexagons, starting each patch at its lowest face.
    pub fn of(mesh: &PolyMesh, conn: &Connectivity) -> EdgeClasses {
        let nf = mesh.faces.len();
        let is_hex = |f: usize| mesh.faces[f].len() == 6;
        let mut classes = EdgeClasses {
            edge: vec![None; conn.num_edges()],
            cell_offset: vec![None; nf],
            patch: vec![None; nf],
            num_patches: 0,
            conflicts: 0,
        };
        let mut queue = VecDeque::new();
        for root in 0..nf {
            if !is_hex(root) || classes.cell_offset[root].is_some() {
                continue;
            }
            let patch = classes.num_patches;
            classes.num_patches += 1;
            classes.cell_offset[root] = Some(0);
            classes.patch[root] = Some(patch);
            queue.push_back(root);
            while let Some(f) = queue.pop_front() {
                let offset = classes.cell_offset[f].unwrap_or(0);
                for (k, &e) in conn.face_edges[f].iter().enumerate() {
                    let class = ((offset as usize + k) % 3) as u8;
                    match classes.edge[e] {
                        None => classes.edge[e] = Some(class),
                        Some(c) if c != class => classes.conflicts += 1,
                        Some(_) => {}
                    }
                    for g in conn.edge_faces[e].into_iter().flatten() {
                        if g == f || !is_hex(g) || classes.cell_offset[g].is_some() {
                            continue;
                        }
                        let kg = conn.face_edges[g].iter().position(|&x| x == e).unwrap_or(0);
                        classes.cell_offset[g] = Some(((class as usize + 6 - kg) % 3) as u8);
                        classes.patch[g] = Some(patch);
                        queue.push_back(g);
                    }
                }
            }
        }
        classes
    }

    /// The class of edge k of cell f, as that cell sees it.
    pub fn cell_edge_class(&self, f: usize, k: usize) -> Option<u8> {
        self.cell_offset[f].map(|o| ((o as usize + k) % 3) as u8)
    }

    /// The same labels with class `zero[p]` of each patch p renamed 0 (and the others shifted
    /// along: the cyclic order of the classes is kept).
    fn renumbered(&self, conn: &Connectivity, zero: &[u8]) -> EdgeClasses {
        let shift = |patch: Option<usize>, c: u8| {
            let z = patch.map_or(0, |p| zero[p]);
            (c + 3 - z) % 3
        };
        let mut out = self.clone();
        for (f, o) in out.cell_offset.iter_mut().enumerate() {
            *o = o.map(|o| shift(self.patch[f], o));
        }
        for (e, c) in out.edge.iter_mut().enumerate() {
            // An edge takes its patch from either hexagon: both lie in the same patch.
            let patch = conn.edge_faces[e]
                .into_iter()
                .flatten()
                .find_map(|f| self.patch[f]);
            *c = c.map(|c| shift(patch, c));
        }
        out
    }

    /// The edge of class `c` at vertex `v`, when the labelled edges at `v` have distinct classes.
    fn edge_at(&self, conn: &Connectivity, v: usize, c: u8) -> Option<usize> {
        let edges = &conn.vertex_edges[v];
        let mut found = None;
        for (i, &e) in edges.iter().enumerate() {
            let ce = self.edge[e]?;
            if edges[..i].iter().any(|&o| self.edge[o] == Some(ce)) {
                return None;
            }
            if ce == c {
                found = Some(e);
            }
        }
        found
    }
}

/// Three consecutive edges of a zigzag, `v1 v2`, `v2 v3`, `v3 v4`.
pub type ZigzagRun = [usize; 4];

/// Three consecutive vertices `i, j, k` of a straight polyline: the edge `ij` (edge index
/// `edge`) continued at `j` by the diagonal `jk` of a split cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StraightRun {
    pub edge: usize,
    pub i: usize,
    pub j: usize,
    pub k: usize,
}

/// The quads that cap a hex mesh, and the polylines whose fairness the optimization watches.
#[derive(Clone, Debug)]
pub struct QuadCover {
    pub pattern: QuadPattern,
    /// Vertex indices of M, each quad oriented like its cell.
    pub quads: Vec<[usize; 4]>,
    /// The faces of M that are not split (not hexagons), in face order.
    pub unsplit: Vec<usize>,
    /// Per face of M: its two quads (indices into `quads`), or `None` when unsplit.
    pub cell_quads: Vec<Option<[usize; 2]>>,
    /// Per face of M: the endpoints of its splitting diagonal.
    pub diagonals: Vec<Option<[usize; 2]>>,
    /// Edge classes, class 0 the straight one.
    pub classes: EdgeClasses,
    /// Zigzags of edges of classes 1 and 2, by three consecutive edges.
    pub zigzag_runs: Vec<ZigzagRun>,
    /// Every diagonal continued at each end by the edge beyond it.
    pub straight_runs: Vec<StraightRun>,
    /// The hexagons split along their own flattest diagonal where the pattern's is another
    /// (see [`QuadCover::resplit`]), in face order; always empty for `Flattest`.
    pub off_pattern: Vec<usize>,
    unsplit_loops: Vec<Vec<usize>>,
}

impl QuadCover {
    /// Splits the hexagons of `mesh` by `pattern`. The straight class of each patch is the
    /// class whose edges are on average most parallel to `direction`; without a direction it
    /// is the one whose quads start closest to planar (least total `quad_planarity`): on a
    /// smooth surface a trapezoid with its parallel sides along `u` is planar to second order
    /// when `u` is conjugate to its transversal, so this picks the lattice direction closest to
    /// a principal curvature direction, and the optimization has the least to move.
    pub fn new(
        mesh: &PolyMesh,
        conn: &Connectivity,
        pattern: QuadPattern,
        direction: Option<Vec3>,
    ) -> QuadCover {
        let raw = EdgeClasses::of(mesh, conn);
        let straight = match (pattern, direction) {
            // Each cell picks its own diagonal: the classes' names do not matter.
            (QuadPattern::Flattest, _) => vec![0; raw.num_patches],
            (_, Some(d)) => most_parallel_class(mesh, conn, &raw, d),
            (_, None) => flattest_class(mesh, conn, &raw, pattern),
        };
        let classes = raw.renumbered(conn, &straight);
        QuadCover::with_classes(mesh, conn, pattern, classes, &[])
    }

    /// The same cover with the hexagons `cells` (besides those already off it) split along
    /// whichever of their diagonals leaves their quads flattest on `mesh`, the pattern's
    /// polylines broken there: where the pattern's quads stay far from planar, a few cells off
    /// it may let the rest be capped flat. A cell whose flattest diagonal is the pattern's
    /// stays on it.
    pub fn resplit(&self, mesh: &PolyMesh, conn: &Connectivity, cells: &[usize]) -> QuadCover {
        let mut off = self.off_pattern.clone();
        off.extend(cells.iter().filter(|&&f| self.cell_quads[f].is_some()));
        off.sort_unstable();
        off.dedup();
        QuadCover::with_classes(mesh, conn, self.pattern, self.classes.clone(), &off)
    }

    /// The cover with these classes; the hexagons `off` (sorted) split along their own
    /// flattest diagonal whatever the pattern.
    fn with_classes(
        mesh: &PolyMesh,
        conn: &Connectivity,
        pattern: QuadPattern,
        classes: EdgeClasses,
        off: &[usize],
    ) -> QuadCover {
        let nf = mesh.faces.len();
        let parity = match pattern {
            QuadPattern::Zigzag | QuadPattern::Flattest => vec![0; nf],
            QuadPattern::Alternating => strip_parity(mesh, conn, &classes),
        };
        let mut cover = QuadCover {
            pattern,
            quads: Vec::with_capacity(2 * nf),
            unsplit: Vec::new(),
            cell_quads: vec![None; nf],
            diagonals: vec![None; nf],
            classes,
            zigzag_runs: Vec::new(),
            straight_runs: Vec::new(),
            off_pattern: Vec::new(),
            unsplit_loops: Vec::new(),
        };
        for (f, face) in mesh.faces.iter().enumerate() {
            let Some(offset) = cover.classes.cell_offset[f] else {
                cover.unsplit.push(f);
                cover.unsplit_loops.push(face.clone());
                continue;
            };
            let class = match pattern {
                QuadPattern::Zigzag => 0,
                QuadPattern::Alternating => 1 + parity[f],
                QuadPattern::Flattest => flattest_diagonal(mesh, face, offset),
            };
            let own = (off.binary_search(&f).is_ok())
                .then(|| flattest_diagonal(mesh, face, offset))
                .filter(|&own| own != class);
            if own.is_some() {
                cover.off_pattern.push(f);
            }
            let class = own.unwrap_or(class);
            let halves = halves(face, class, offset);
            let q = cover.quads.len();
            cover.quads.extend(halves);
            cover.cell_quads[f] = Some([q, q + 1]);
            cover.diagonals[f] = Some([halves[0][0], halves[0][3]]);
        }
        cover.zigzag_runs = zigzag_runs(conn, &cover.classes);
        cover.straight_runs = straight_runs(mesh, conn, &cover.diagonals);
        cover
    }

    /// The quad mesh on `vertices` (M's, realized): the split quads first, in `quads` order,
    /// then the unsplit cells as they are.
    pub fn mesh(&self, vertices: &[Vec3]) -> PolyMesh {
        let faces = self
            .quads
            .iter()
            .map(|q| q.to_vec())
            .chain(self.unsplit_loops.iter().cloned())
            .collect();
        PolyMesh::new(vertices.to_vec(), faces)
    }

    /// The realized corners of quad `q`.
    pub fn corners(&self, vertices: &[Vec3], q: usize) -> [Vec3; 4] {
        self.quads[q].map(|v| vertices[v])
    }
}

/// The two quads hexagon `face` (its edge 0 of class `offset`) splits into along its diagonal of
/// class `class`, the diagonal from the first corner of the first quad to its last.
fn halves(face: &[usize], class: u8, offset: u8) -> [[usize; 4]; 2] {
    // Edges k0 and k0 + 3 have the diagonal's class; it runs from face[k0 - 1].
    let k0 = (class as usize + 3 - offset as usize) % 3;
    let j = (k0 + 5) % 6;
    let at = |i: usize| face[(j + i) % 6];
    [[at(0), at(1), at(2), at(3)], [at(3), at(4), at(5), at(0)]]
}

/// The class of the diagonal of hexagon `face` whose two quads are flattest (the larger of their
/// planarities least).
fn flattest_diagonal(mesh: &PolyMesh, face: &[usize], offset: u8) -> u8 {
    best(|class| {
        halves(face, class as u8, offset)
            .map(|q| quad_planarity(q.map(|v| mesh.vertices[v])))
            .into_iter()
            .fold(0.0, f64::max)
    })
}

/// Per patch, the class whose edges are on average most parallel to `d` (absolute cosine).
fn most_parallel_class(
    mesh: &PolyMesh,
    conn: &Connectivity,
    classes: &EdgeClasses,
    d: Vec3,
) -> Vec<u8> {
    let d = d.normalized();
    let mut sums = vec![[(0.0, 0usize); 3]; classes.num_patches];
    for (f, fe) in conn.face_edges.iter().enumerate() {
        let Some(p) = classes.patch[f] else { continue };
        for (k, &e) in fe.iter().enumerate() {
            let c = classes.cell_edge_class(f, k).unwrap_or(0) as usize;
            let [a, b] = conn.edges[e];
            let u = (mesh.vertices[b] - mesh.vertices[a]).normalized();
            sums[p][c].0 += u.dot(d).abs();
            sums[p][c].1 += 1;
        }
    }
    sums.iter()
        .map(|s| {
            let mean = |c: usize| s[c].0 / s[c].1.max(1) as f64;
            best(|c| -mean(c))
        })
        .collect()
}

/// Per patch, the straight class whose split starts with the least total quad non-planarity.
fn flattest_class(
    mesh: &PolyMesh,
    conn: &Connectivity,
    classes: &EdgeClasses,
    pattern: QuadPattern,
) -> Vec<u8> {
    let mut defect = vec![[0.0; 3]; classes.num_patches];
    for c in 0..3u8 {
        let zero = vec![c; classes.num_patches];
        let trial =
            QuadCover::with_classes(mesh, conn, pattern, classes.renumbered(conn, &zero), &[]);
        for (f, quads) in trial.cell_quads.iter().enumerate() {
            let (Some(p), Some(qs)) = (classes.patch[f], quads) else {
                continue;
            };
            for q in qs {
                defect[p][c as usize] += quad_planarity(trial.corners(&mesh.vertices, *q));
            }
        }
    }
    defect.iter().map(|d| best(|c| d[c])).collect()
}

/// The lowest class 0, 1 or 2 whose `cost` is within rounding of the least: symmetric shapes
/// (a dome on a hexagonally symmetric patch) tie exactly, and the choice must not then depend
/// on the frame the vertices are given in.
fn best(cost: impl Fn(usize) -> f64) -> u8 {
    let least = (0..3).map(&cost).fold(f64::INFINITY, f64::min);
    let slack = 1e-9 * least.abs() + 1e-300;
    (0..3).find(|&c| cost(c) <= least + slack).unwrap_or(0) as u8
}

/// Strip parity of the `Alternating` pattern (see the module comment), by a search per patch.
fn strip_parity(mesh: &PolyMesh, conn: &Connectivity, classes: &EdgeClasses) -> Vec<u8> {
    let nf = mesh.faces.len();
    let mut parity: Vec<Option<u8>> = vec![None; nf];
    let mut queue = VecDeque::new();
    for root in 0..nf {
        if classes.cell_offset[root].is_none() || parity[root].is_some() {
            continue;
        }
        parity[root] = Some(0);
        queue.push_back(root);
        while let Some(f) = queue.pop_front() {
            let pf = parity[f].unwrap_or(0);
            for (k, &e) in conn.face_edges[f].iter().enumerate() {
                let flip = u8::from(classes.cell_edge_class(f, k) != Some(0));
                for g in conn.edge_faces[e].into_iter().flatten() {
                    if classes.cell_offset[g].is_some() && parity[g].is_none() {
                        parity[g] = Some(pf ^ flip);
                        queue.push_back(g);
                    }
                }
            }
        }
    }
    parity.into_iter().map(|p| p.unwrap_or(0)).collect()
}

/// Every edge of class 1 or 2 with the edge of the other of these classes at each end: three
/// consecutive edges of a zigzag. Nodes whose labels repeat (at defects) are skipped.
fn zigzag_runs(conn: &Connectivity, classes: &EdgeClasses) -> Vec<ZigzagRun> {
    let mut runs = Vec::new();
    for (e, &[a, b]) in conn.edges.iter().enumerate() {
        let Some(c @ (1 | 2)) = classes.edge[e] else {
            continue;
        };
        let other = 3 - c;
        if let (Some(e1), Some(e3)) = (
            classes.edge_at(conn, a, other),
            classes.edge_at(conn, b, other),
        ) {
            runs.push([conn.other_end(e1, a), a, b, conn.other_end(e3, b)]);
        }
    }
    runs
}

/// Each splitting diagonal `jk` continued at `j` (and at `k`) by the one edge at `j` that is
/// not in the diagonal's cell.
fn straight_runs(
    mesh: &PolyMesh,
    conn: &Connectivity,
    diagonals: &[Option<[usize; 2]>],
) -> Vec<StraightRun> {
    let mut runs = Vec::new();
    for (f, d) in diagonals.iter().enumerate() {
        let Some([p, q]) = *d else { continue };
        for (j, k) in [(p, q), (q, p)] {
            let face = &mesh.faces[f];
            let n = face.len();
            let Some(pos) = face.iter().position(|&v| v == j) else {
                continue;
            };
            let in_cell = [
                conn.face_edges[f][pos],
                conn.face_edges[f][(pos + n - 1) % n],
            ];
            let mut beyond = conn.vertex_edges[j].iter().filter(|e| !in_cell.contains(e));
            if let (Some(&edge), None) = (beyond.next(), beyond.next()) {
                let i = conn.other_end(edge, j);
                runs.push(StraightRun { edge, i, j, k });
            }
        }
    }
    runs
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{hex_disk, lifted_hex_patch, Shape};

    fn cover(pattern: QuadPattern, direction: Option<Vec3>) -> (PolyMesh, Connectivity, QuadCover) {
        let mesh = hex_disk(6.0);
        let conn = Connectivity::build(&mesh).unwrap();
        let c = QuadCover::new(&mesh, &conn, pattern, direction);
        (mesh, conn, c)
    }

    #[test]
    fn classes_are_the_three_lattice_directions() {
        let (mesh, conn, c) = cover(QuadPattern::Zigzag, None);
        assert_eq!(c.classes.conflicts, 0);
        assert_eq!(c.classes.num_patches, 1);
        // Each class is one direction of the planar lattice (lines, so modulo 180 degrees).
        let mut angle: [Option<f64>; 3] = [None; 3];
        for (e, &[a, b]) in conn.edges.iter().enumerate() {
            let d = mesh.vertices[b] - mesh.vertices[a];
            let t = d.y.atan2(d.x).to_degrees().rem_euclid(180.0);
            let cls = c.classes.edge[e].unwrap() as usize;
            let t0 = *angle[cls].get_or_insert(t);
            let diff = (t - t0).rem_euclid(180.0);
            assert!(diff.min(180.0 - diff) < 1e-9, "edge {e}: {t} vs {t0}");
        }
    }

    #[test]
    fn a_user_direction_picks_the_class_along_it() {
        // Pointy-top hexagons: one class is vertical.
        let (mesh, _, c) = cover(QuadPattern::Zigzag, Some(Vec3::new(0.1, 1.0, 0.0)));
        for d in c.diagonals.iter().flatten() {
            let u = mesh.vertices[d[1]] - mesh.vertices[d[0]];
            assert!(u.x.abs() < 1e-9, "diagonal not vertical: {u:?}");
        }
    }

    #[test]
    fn alternating_strips_lean_both_ways_and_cover_every_hexagon() {
        let (mesh, _, c) = cover(QuadPattern::Alternating, Some(Vec3::new(0.0, 1.0, 0.0)));
        assert!(c.unsplit.is_empty());
        assert_eq!(c.quads.len(), 2 * mesh.faces.len());
        let mut directions = std::collections::BTreeSet::new();
        for d in c.diagonals.iter().flatten() {
            let u = mesh.vertices[d[1]] - mesh.vertices[d[0]];
            let t = u.y.atan2(u.x).to_degrees().rem_euclid(180.0).round() as i64;
            directions.insert(t % 180);
        }
        // Never along the strip class (vertical), both of the other two directions.
        assert_eq!(directions.into_iter().collect::<Vec<_>>(), vec![30, 150]);
        // Cells sharing a vertical edge lie in one strip and split alike.
        let conn = Connectivity::build(&mesh).unwrap();
        for (e, faces) in conn.edge_faces.iter().enumerate() {
            if let [Some(f), Some(g)] = *faces {
                let dir = |f: usize| {
                    let [p, q] = c.diagonals[f].unwrap();
                    let u = mesh.vertices[q] - mesh.vertices[p];
                    (u.y.atan2(u.x).to_degrees().rem_euclid(180.0).round() as i64) % 180
                };
                let vertical = c.classes.edge[e] == Some(0);
                assert_eq!(dir(f) == dir(g), vertical, "edge {e}");
            }
        }
    }

    #[test]
    fn fairness_runs_vanish_on_the_regular_lattice() {
        for pattern in [QuadPattern::Zigzag, QuadPattern::Alternating] {
            let (mesh, _, c) = cover(pattern, None);
            let p = &mesh.vertices;
            assert!(!c.zigzag_runs.is_empty() && !c.straight_runs.is_empty());
            for &[v1, v2, v3, v4] in &c.zigzag_runs {
                let r = (p[v1] - p[v2]) - (p[v3] - p[v4]);
                assert!(r.norm() < 1e-9, "{pattern:?} zigzag {v1} {v2} {v3} {v4}");
            }
            for s in &c.straight_runs {
                // The edge beyond a diagonal's end continues it.
                let (u, w) = (p[s.j] - p[s.i], p[s.k] - p[s.j]);
                assert!(
                    u.cross(w).norm() < 1e-9 && u.dot(w) > 0.0,
                    "{pattern:?} {s:?}"
                );
            }
        }
    }

    #[test]
    fn the_quad_mesh_is_a_valid_mesh_with_the_unsplit_cells() {
        let (mesh, _) = lifted_hex_patch(Shape::Dome, 60);
        let conn = Connectivity::build(&mesh).unwrap();
        let c = QuadCover::new(&mesh, &conn, QuadPattern::Zigzag, None);
        let m = c.mesh(&mesh.vertices);
        assert_eq!(m.faces.len(), c.quads.len() + c.unsplit.len());
        // Consistently oriented (Connectivity rejects flips) on M's own vertices.
        Connectivity::build(&m).unwrap();
    }

    /// A hex disk lifted onto `z = sin x cos y / 5`, whose principal directions turn: it twists
    /// along different lattice directions in different places.
    fn twisted_disk() -> (PolyMesh, Connectivity) {
        let mut mesh = hex_disk(6.0);
        for p in &mut mesh.vertices {
            p.z = (p.x.sin() * p.y.cos()) / 5.0;
        }
        let conn = Connectivity::build(&mesh).unwrap();
        (mesh, conn)
    }

    /// On a surface that twists along different lattice directions in different places (here
    /// `z = sin x cos y / 5`, whose principal directions turn), a flattest cover splits each
    /// hexagon along the long diagonal whose two quads are flattest, whichever class that is.
    #[test]
    fn a_flattest_cover_splits_each_cell_where_its_quads_are_flattest() {
        let (mesh, conn) = twisted_disk();
        let c = QuadCover::new(&mesh, &conn, QuadPattern::Flattest, None);
        let mut classes = std::collections::HashSet::new();
        for (f, face) in mesh.faces.iter().enumerate() {
            let at = |i: usize| mesh.vertices[face[i % 6]];
            let worse = |k: usize| {
                let first = quad_planarity([at(k), at(k + 1), at(k + 2), at(k + 3)]);
                first.max(quad_planarity([at(k + 3), at(k + 4), at(k + 5), at(k + 6)]))
            };
            let mut chosen = c.diagonals[f].unwrap();
            chosen.sort();
            let k = (0..3).find(|&k| chosen.contains(&face[k])).unwrap();
            let least = (0..3).map(worse).fold(f64::INFINITY, f64::min);
            // Cells placed symmetrically tie; any of the tied diagonals is right.
            assert!(worse(k) <= least * (1.0 + 1e-9), "cell {f}");
            classes.insert(c.classes.cell_edge_class(f, k + 1));
        }
        assert_eq!(classes.len(), 3, "{classes:?}");
    }

    /// A zigzag cover with some cells taken off the pattern: those cells take the flattest
    /// cover's diagonal and are named where it is not the zigzag's, every other cell keeps the
    /// zigzag's, and taking more cells off later keeps the first ones off.
    #[test]
    fn cells_taken_off_the_pattern_take_their_flattest_diagonal() {
        let (mesh, conn) = twisted_disk();
        let zigzag = QuadCover::new(&mesh, &conn, QuadPattern::Zigzag, None);
        let flattest = QuadCover::new(&mesh, &conn, QuadPattern::Flattest, None);
        assert!(zigzag.off_pattern.is_empty() && flattest.off_pattern.is_empty());
        let sorted = |d: Option<[usize; 2]>| {
            let mut d = d.unwrap();
            d.sort();
            d
        };
        let nf = mesh.faces.len();
        let first: Vec<usize> = (0..nf).step_by(3).collect();
        let once = zigzag.resplit(&mesh, &conn, &first);
        let twice = once.resplit(&mesh, &conn, &[1, 4]);
        for (cover, off) in [
            (&once, first.clone()),
            (&twice, [first, vec![1, 4]].concat()),
        ] {
            assert_eq!(cover.quads.len(), zigzag.quads.len());
            let mut named = Vec::new();
            for f in 0..nf {
                let (own, pattern) = (sorted(flattest.diagonals[f]), sorted(zigzag.diagonals[f]));
                let d = sorted(cover.diagonals[f]);
                if off.contains(&f) {
                    assert_eq!(d, own, "cell {f}");
                    if own != pattern {
                        named.push(f);
                    }
                } else {
                    assert_eq!(d, pattern, "cell {f}");
                }
            }
            assert!(!named.is_empty());
            assert_eq!(cover.off_pattern, named);
        }
    }

    /// Corannulene: a pentagon ringed by five hexagons, a lattice defect around which the
    /// classes cannot close up (each hexagon turns them by one step, five steps around).
    fn corannulene() -> PolyMesh {
        let ring = |r: f64, t: f64| Vec3::new(r * t.cos(), r * t.sin(), 0.0);
        let step = std::f64::consts::TAU / 5.0;
        let (h, s, a, b) = (
            |i: usize| i % 5,
            |i: usize| 5 + i % 5,
            |i| 10 + i,
            |i| 15 + i,
        );
        let mut vertices = Vec::new();
        vertices.extend((0..5).map(|i| ring(1.0, step * i as f64)));
        vertices.extend((0..5).map(|i| ring(2.0, step * i as f64)));
        vertices.extend((0..5).map(|i| ring(3.0, step * (i as f64 + 0.3))));
        vertices.extend((0..5).map(|i| ring(3.0, step * (i as f64 + 0.7))));
        let mut faces = vec![(0..5).collect::<Vec<_>>()];
        faces.extend((0..5).map(|i| vec![h(i + 1), h(i), s(i), a(i), b(i), s(i + 1)]));
        PolyMesh::new(vertices, faces)
    }

    #[test]
    fn a_lattice_defect_is_counted_not_fatal() {
        let mesh = corannulene();
        let conn = Connectivity::build(&mesh).unwrap();
        for pattern in [QuadPattern::Zigzag, QuadPattern::Alternating] {
            let c = QuadCover::new(&mesh, &conn, pattern, None);
            assert!(c.classes.conflicts > 0, "{pattern:?}");
            assert_eq!(c.unsplit, vec![0]);
            assert_eq!(c.quads.len(), 10);
            assert_eq!(c.mesh(&mesh.vertices).faces.len(), 11);
        }
    }
}
