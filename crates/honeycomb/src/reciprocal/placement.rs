//! The base mesh placed on a fitted sheet's walls.
//!
//! With the wall normals fixed, give each point `k` of the sheet a potential `P_k` and put the
//! wall between points `l` and `r` in the plane `(p_l - p_r) . x = P_l - P_r`. The three planes
//! at a node then meet in a line along its axis, whatever the potentials (their equations add
//! up to zero), so every vertex is a point of its node's line: `x_v = A_v^+ b_v(P) + t_v a_v`,
//! linear in the potentials and in a slide `t_v` along the axis. The vertices are fitted to S
//! (closeness), to cells of one size and shape (each edge the regular cell's edge across its
//! wall) and, weakly, to where they started; walls stay planar and nodes at 120 degrees exactly.

use super::{Sheet, ON_S};
use crate::constraints::{Closeness, EdgeVectors, Layout, SharedTargets, VertexTargets};
use crate::error::Result;
use crate::geometry::Vec3;
use crate::mesh::{Connectivity, PolyMesh};
use crate::parallel::in_halves;
use crate::solve::{
    Cancel, Constraint, GuidedProjection, IterationInfo, SolveReport, SolveState, SolverOptions,
    Substitution,
};
use crate::surface::{Surface, PARALLEL_QUERIES_FROM};

/// Placement goes on while a vertex within S's border is farther than this from S (mean edge
/// lengths), or one whose axis grazes S (it cannot slide onto S) is farther than `ON_S`, off
/// S as the trim counts it: the closeness brings it in slowly, along a line S curves away
/// from...
const ON_SURFACE: f64 = 0.01;
/// ...or one beyond the border is farther than this from it. The closeness holds such a vertex
/// only while it is beyond, so it swings in and out from one iteration to the next and would
/// never come within `ON_SURFACE`. A cell that keeps a vertex off S by more than `ON_S` is
/// trimmed afterwards (`trim_overhang`), whether the swing left it a little or far beyond the
/// border; the placement goes on only for a vertex a whole edge length out or more, which the
/// next steps may still bring back.
const NEAR_BORDER: f64 = 1.0;

#[derive(Clone, Debug)]
pub struct PlacementOptions {
    pub iterations: usize,
    pub closeness: f64,
    /// Weight of edges of one length and of their walls' directions.
    pub evenness: f64,
    /// Weight of staying where the base mesh put a vertex: inner vertices, boundary ones.
    pub anchor: f64,
    pub boundary_anchor: f64,
    /// Each edge's regular direction is where its wall meets S's tangent plane, rather than
    /// across the node axes: the cell of one size on S where the axes lean far from S's
    /// normals (across a light), whose cross-section is then drawn out.
    pub edges_along_s: bool,
    pub cancel: Cancel,
}

impl Default for PlacementOptions {
    fn default() -> Self {
        PlacementOptions {
            iterations: 3,
            closeness: 100.0,
            evenness: 3.0,
            anchor: 0.05,
            boundary_anchor: 0.2,
            edges_along_s: false,
            cancel: Cancel::default(),
        }
    }
}

pub struct Placed {
    /// Vertices in the frame of the inputs.
    pub vertices: Vec<Vec3>,
    /// Unit axes, on the side of S's normal.
    pub axes: Vec<Vec3>,
    pub solve: SolveReport,
}

/// For each vertex, the line of its node: `x = C (P_a, P_b, P_c) + t a` with `C` 3 x 3 over
/// the potentials of its triangle `[a, b, c]`, and the unit axis `a`.
fn node_lines(sheet: &Sheet, points: &[Vec3]) -> Vec<([[f64; 3]; 3], Vec3)> {
    sheet
        .triangles
        .iter()
        .map(|&[a, b, c]| {
            let (w1, w2) = (points[a] - points[b], points[b] - points[c]);
            // x0 = A^T (A A^T)^-1 (P_a - P_b, P_b - P_c) for A with rows w1, w2.
            let (g11, g12, g22) = (w1.dot(w1), w1.dot(w2), w2.dot(w2));
            let det = g11 * g22 - g12 * g12;
            let inv = [[g22 / det, -g12 / det], [-g12 / det, g11 / det]];
            // Columns of A^T inv: the point's response to the two right-hand sides.
            let r1 = w1 * inv[0][0] + w2 * inv[1][0];
            let r2 = w1 * inv[0][1] + w2 * inv[1][1];
            // b = (P_a - P_b, P_b - P_c): P_a -> r1, P_b -> r2 - r1, P_c -> -r2.
            let cols = [r1, r2 - r1, -r2];
            let m = std::array::from_fn(|k| std::array::from_fn(|j| cols[j].to_array()[k]));
            (m, w1.cross(w2).normalized())
        })
        .collect()
}

/// A sheet and its points: the walls a placement puts the vertices on.
#[derive(Clone, Copy)]
pub struct FittedSheet<'a> {
    pub sheet: &'a Sheet,
    pub points: &'a [Vec3],
}

/// Places `mesh` (its start) on the walls of a fitted sheet, close to `surface`; all in one
/// frame. `from`: where a placement on the same walls put the vertices (the rest of a mesh
/// whose broken cells were dropped), to start from there rather than from `mesh`; the
/// vertices are still held close to `mesh`.
pub fn place(
    mesh: &PolyMesh,
    from: Option<&[Vec3]>,
    conn: &Connectivity,
    FittedSheet { sheet, points }: FittedSheet,
    surface: &Surface,
    options: &PlacementOptions,
    progress: &mut dyn FnMut(&IterationInfo),
) -> Result<Placed> {
    let (nv, np) = (mesh.vertices.len(), sheet.points());
    let lines = node_lines(sheet, points);
    let mut axes: Vec<Vec3> = lines.iter().map(|l| l.1).collect();
    for (v, a) in axes.iter_mut().enumerate() {
        if a.dot(surface.normal_at(mesh.vertices[v])) < 0.0 {
            *a = -*a;
        }
    }
    // Adding one number to every potential moves no wall: the first is held at zero (the
    // solver's unknowns are the other potentials, then the slides).
    let unknown = |point: usize| point.checked_sub(1);
    let per_x: Vec<Vec<(usize, f64)>> = (0..3 * nv)
        .map(|i| {
            let (v, k) = (i / 3, i % 3);
            let t = sheet.triangles[v];
            let mut terms: Vec<(usize, f64)> = (0..3)
                .filter_map(|j| unknown(t[j]).map(|y| (y, lines[v].0[k][j])))
                .collect();
            terms.push((np - 1 + v, axes[v].to_array()[k]));
            terms
        })
        .collect();
    let unknowns = np - 1 + nv;
    let substitution = Substitution::new(unknowns, &per_x);
    let layout = Layout::new(nv, 0);
    let mean_edge = mesh.mean_edge_length();
    let edge_vectors = conn
        .edges
        .iter()
        .enumerate()
        .map(|(e, &[a, b])| {
            let across = if options.edges_along_s {
                surface.normal_at((mesh.vertices[a] + mesh.vertices[b]) * 0.5)
            } else {
                axes[a] + axes[b]
            };
            let along = sheet.wall_normal(points, e).cross(across);
            let d = along.normalized() * mean_edge;
            let start = mesh.vertices[b] - mesh.vertices[a];
            ([a, b], if d.dot(start) < 0.0 { -d } else { d })
        })
        .collect();
    let anchors = |boundary: bool, at: &[Vec3]| {
        let targets = SharedTargets::new(nv);
        targets.set(
            (0..nv)
                .map(|v| (conn.is_boundary_vertex[v] == boundary).then_some(at[v]))
                .collect(),
        );
        targets
    };
    let anchor_family = |boundary: bool, weight, at: &[Vec3]| VertexTargets {
        layout,
        targets: anchors(boundary, at),
        weight,
    };
    let start_at = from.unwrap_or(&mesh.vertices);
    // The start: potentials and slides that best reproduce the base mesh, or where a placement
    // left the vertices (no closeness yet, whose tangent planes need vertices near S).
    let start_families: Vec<Box<dyn Constraint>> = vec![
        Box::new(anchor_family(false, 1.0, start_at)),
        Box::new(anchor_family(true, 1.0, start_at)),
    ];
    let mut y = vec![0.0; unknowns];
    let exact = SolverOptions {
        max_iterations: 1,
        eps: 1e-6,
        eps_min: 1e-6,
        cancel: options.cancel.clone(),
        ..SolverOptions::default()
    };
    let mut start = GuidedProjection::with_substitution(
        start_families,
        Substitution::new(unknowns, &per_x),
        None,
        &[],
    )?;
    let first = start.solve(&mut y, &exact, progress)?;
    let families: Vec<Box<dyn Constraint + '_>> = vec![
        Box::new(Closeness::new(layout, surface, options.closeness)),
        Box::new(EdgeVectors {
            layout,
            edges: edge_vectors,
            weight: options.evenness,
        }),
        Box::new(anchor_family(false, options.anchor, &mesh.vertices)),
        Box::new(anchor_family(true, options.boundary_anchor, &mesh.vertices)),
    ];
    let mut solver = GuidedProjection::with_substitution(families, substitution, None, &[])?;
    let solver_options = SolverOptions {
        max_iterations: options.iterations,
        eps: 1e-6,
        eps_min: 1e-6,
        tolerance: 0.0,
        cancel: options.cancel.clone(),
        ..SolverOptions::default()
    };
    // The iterations asked for (one from where a placement left the vertices), then more
    // while a vertex stays off S (the tangent planes of the closeness move as the vertices
    // do), up to twice as many.
    let least = if from.is_some() {
        1
    } else {
        options.iterations
    };
    let mut state = SolveState::new(solver_options.eps);
    let mut vertices = Vec::new();
    while state.iterations() < 2 * options.iterations.max(1) {
        match solver.iterate(&mut y, &mut state, &solver_options)? {
            Some(info) => progress(&info),
            None => break,
        }
        let x = solver.family_unknowns(&y);
        vertices = x.chunks(3).map(Vec3::from_slice).collect();
        let off = slide_onto(surface, &mut vertices, &axes, mean_edge);
        if state.iterations() >= least && off.settled(mean_edge) {
            break;
        }
    }
    let mut solve = solver.report(&y, state, &solver_options);
    solve.iterations += first.iterations;
    Ok(Placed {
        vertices,
        axes,
        solve,
    })
}

/// A slide this much shorter than its limit ends the Newton steps: the next would be of the
/// order of its square.
const SLID: f64 = 1e-7;
/// An axis this close to S's tangent plane (the cosine of its angle with S's normal) does not
/// slide: each step along it lands on the tangent plane, from which S curves away.
const GRAZING: f64 = 0.2;

/// How far the vertices are from S: the farthest of those whose closest point on S is inside
/// its border, and of those whose closest point is on the border (beyond it).
#[derive(Clone, Copy, Debug, Default)]
pub struct Off {
    pub within: f64,
    /// Of those within the border whose axes graze S (they do not slide).
    pub grazing: f64,
    pub beyond: f64,
}

impl Off {
    /// Whether a placement may stop: every vertex within S's border on S (one whose axis
    /// grazes S near enough to keep its cell), every one beyond it near the border (all in
    /// units of `mean_edge`).
    fn settled(&self, mean_edge: f64) -> bool {
        self.within <= ON_SURFACE * mean_edge
            && self.grazing <= ON_S * mean_edge
            && self.beyond <= NEAR_BORDER * mean_edge
    }
}

/// Moves each vertex along its axis onto `surface` (a few Newton steps on its signed distance
/// to the tangent plane at its closest point), never further than `limit` in one step; a
/// vertex beyond S's border stays, and so does one whose axis grazes S. Returns how far the
/// vertices are from S afterwards.
pub fn slide_onto(surface: &Surface, vertices: &mut [Vec3], axes: &[Vec3], limit: f64) -> Off {
    let mut moved: Vec<(Vec3, f64, Foot)> =
        vertices.iter().map(|&p| (p, 0.0, Foot::Within)).collect();
    in_halves(&mut moved, PARALLEL_QUERIES_FROM, |first, part| {
        for (k, (p, distance, foot)) in part.iter_mut().enumerate() {
            (*distance, *foot) = slid(surface, p, axes[first + k], limit);
        }
    });
    let mut off = Off::default();
    for (v, &(p, distance, foot)) in vertices.iter_mut().zip(&moved) {
        *v = p;
        let farthest = match foot {
            Foot::Within => &mut off.within,
            Foot::Grazing => &mut off.grazing,
            Foot::Beyond => &mut off.beyond,
        };
        *farthest = farthest.max(distance);
    }
    off
}

/// Where a slid vertex's closest point on S is, and whether its axis could take it there.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Foot {
    Within,
    /// Within S's border, with the axis too close to S's tangent plane to slide along.
    Grazing,
    /// On S's border (the vertex beyond it).
    Beyond,
}

/// `p` slid along `axis` onto `surface` (see [`slide_onto`]); its distance from S then (at most
/// that before a last step of less than [`SLID`] limits), and where its foot on S is.
fn slid(surface: &Surface, p: &mut Vec3, axis: Vec3, limit: f64) -> (f64, Foot) {
    let mut c = surface.closest_point(*p);
    for _ in 0..6 {
        if c.on_boundary {
            return (c.distance, Foot::Beyond);
        }
        let along = axis.dot(c.normal);
        if along.abs() < GRAZING {
            return (c.distance, Foot::Grazing);
        }
        let step = (-(*p - c.point).dot(c.normal) / along).clamp(-limit, limit);
        *p += axis * step;
        if step.abs() < SLID * limit {
            return (c.distance, Foot::Within);
        }
        c = surface.closest_point(*p);
    }
    let foot = if c.on_boundary {
        Foot::Beyond
    } else {
        Foot::Within
    };
    (c.distance, foot)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::hex_disk;
    use crate::mesh::validate_base_mesh;

    /// Placed on a plane from where an earlier placement on the same walls left the vertices,
    /// the solve starts at its end: it takes a single step besides its start (a placement from
    /// the base mesh takes its three at least) and puts every vertex where that one did.
    #[test]
    fn a_placement_goes_on_from_where_one_left_the_vertices() {
        let mesh = hex_disk(4.0);
        let conn = validate_base_mesh(&mesh).unwrap();
        let sheet = Sheet::new(&mesh, &conn).unwrap();
        // The sheet folded along x = 0, each half turned by 20 degrees: two families of axes.
        let (c, s) = (20f64.to_radians().cos(), 20f64.to_radians().sin());
        let points: Vec<Vec3> = sheet
            .initial_points(&mesh, &conn, |_| Vec3::new(0.0, 0.0, 1.0))
            .iter()
            .map(|p| Vec3::new(p.x * c, p.y, p.x.abs() * s))
            .collect();
        let plane = PolyMesh::square(20.0);
        let surface = Surface::from_mesh(&plane).unwrap();
        let options = PlacementOptions::default();
        let place_from = |from: Option<&[Vec3]>| {
            place(
                &mesh,
                from,
                &conn,
                FittedSheet {
                    sheet: &sheet,
                    points: &points,
                },
                &surface,
                &options,
                &mut |_| {},
            )
            .unwrap()
        };
        let first = place_from(None);
        assert_eq!(first.solve.iterations, 1 + options.iterations);
        let again = place_from(Some(&first.vertices));
        assert_eq!(again.solve.iterations, 2);
        for (v, (a, b)) in again.vertices.iter().zip(&first.vertices).enumerate() {
            assert!((*a - *b).norm() < 1e-6, "vertex {v}: {a:?} against {b:?}");
            assert!(a.z.abs() < 1e-9, "vertex {v} off the plane: {a:?}");
        }
    }

    /// A placement stops with every vertex within S's border on it, those whose axes graze S
    /// near enough to keep their cells, and those beyond it near the border (where a swing
    /// leaves them); not while one within is off S, one grazing would be trimmed or one
    /// beyond is far out.
    #[test]
    fn a_placement_settles_with_the_vertices_beyond_the_border_near_it() {
        let edge = 2.0;
        let off = |within: f64, grazing: f64, beyond: f64| {
            Off {
                within,
                grazing,
                beyond,
            }
            .settled(edge)
        };
        assert!(off(0.0, 0.0, 0.0));
        assert!(off(
            0.5 * ON_SURFACE * edge,
            0.9 * ON_S * edge,
            0.9 * NEAR_BORDER * edge
        ));
        assert!(!off(2.0 * ON_SURFACE * edge, 0.0, 0.0));
        assert!(!off(0.0, 1.1 * ON_S * edge, 0.0));
        assert!(!off(0.0, 0.0, 1.1 * NEAR_BORDER * edge));
    }

    /// Vertices above S slide down their axes onto it; one beyond S's border, whose foot is on
    /// the border, stays, and so does one whose axis nearly lies in S: their distances are
    /// told apart. On two threads as on one.
    #[test]
    fn vertices_slide_onto_s_along_their_axes() {
        let surface = Surface::from_mesh(&PolyMesh::unit_square()).unwrap();
        for count in [4, PARALLEL_QUERIES_FROM + 2] {
            let mut vertices: Vec<Vec3> = (0..count)
                .map(|k| Vec3::new(0.1 + 0.8 * (k % 7) as f64 / 7.0, 0.5, 0.3))
                .collect();
            let (beyond, grazing) = (count - 1, count - 2);
            vertices[beyond] = Vec3::new(1.2, 0.5, 0.0);
            vertices[grazing] = Vec3::new(0.5, 0.5, 0.04);
            let tilted = Vec3::new(0.3, 0.0, 1.0).normalized();
            let mut axes = vec![tilted; count];
            axes[beyond] = Vec3::new(0.0, 0.0, 1.0);
            axes[grazing] = Vec3::new(1.0, 0.0, 0.15).normalized();
            let start = vertices.clone();
            let off = slide_onto(&surface, &mut vertices, &axes, 1.0);
            assert!(off.within < 1e-12, "{count}: {off:?}");
            assert!((off.grazing - 0.04).abs() < 1e-12, "{count}: {off:?}");
            assert!((off.beyond - 0.2).abs() < 1e-12, "{count}: {off:?}");
            assert_eq!(vertices[beyond], start[beyond]);
            assert_eq!(vertices[grazing], start[grazing]);
            for (p, s) in vertices.iter().zip(&start).take(grazing) {
                assert!(p.z.abs() < 1e-12, "{p:?}");
                // Along the axis: down 0.3, across 0.3 * 0.3.
                assert!((p.x - (s.x - 0.09)).abs() < 1e-12, "{p:?} from {s:?}");
            }
        }
    }
}
