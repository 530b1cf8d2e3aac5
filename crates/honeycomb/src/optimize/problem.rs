//! Builds a honeycomb's problem, its unknowns and constraint families, over a base mesh and a
//! reference surface, both in the normalized frame.

use super::unknowns::{Block, Unknowns};
use super::Weights;
use crate::constraints::{
    BoundaryCurve, Closeness, EdgeLength, HeldNormals, Layout, MinEdgeLength, Node2, Node3,
    Normalization, OppositeWalls, PrescribedAxes, WallConsistency, WallPlane,
};
use crate::geometry::Vec3;
use crate::mesh::{Connectivity, PolyMesh};
use crate::solve::{Constraint, Role};
use crate::surface::Surface;
use std::ops::Deref;

/// Boundary vertices closer than this (normalized units) to S's boundary are kept on it.
const ON_BOUNDARY: f64 = 0.25;

/// Initial wall normals: each edge direction rotated by -90 degrees about the surface normal at
/// its midpoint, `n_ab = (v_a - v_b)/|v_a - v_b| x N`. At a regular node they sum to zero.
pub fn initial_normals(mesh: &PolyMesh, conn: &Connectivity, surface: &Surface) -> Vec<Vec3> {
    conn.edges
        .iter()
        .map(|&[a, b]| {
            let (pa, pb) = (mesh.vertices[a], mesh.vertices[b]);
            let n = surface.normal_at((pa + pb) * 0.5);
            (pa - pb).normalized().cross(n).normalized()
        })
        .collect()
}

/// Where each block of three unknowns sits, for the solver's ordering: a vertex at its
/// position, a wall normal at its edge's midpoint; blocks appended by variants are unplaced.
pub fn block_positions(mesh: &PolyMesh, conn: &Connectivity, unknowns: usize) -> Vec<Option<Vec3>> {
    let vertices = mesh.vertices.iter().map(|&p| Some(p));
    let midpoints = conn
        .edges
        .iter()
        .map(|&[a, b]| Some((mesh.vertices[a] + mesh.vertices[b]) * 0.5));
    let mut positions: Vec<Option<Vec3>> = vertices.chain(midpoints).collect();
    positions.resize(unknowns.div_ceil(3).max(positions.len()), None);
    positions
}

/// Vertices of the base mesh's boundary that start on S's boundary.
pub fn boundary_vertices_on_surface_boundary(
    mesh: &PolyMesh,
    conn: &Connectivity,
    surface: &Surface,
) -> Vec<usize> {
    (0..mesh.vertices.len())
        .filter(|&v| conn.is_boundary_vertex[v])
        .filter(|&v| {
            surface
                .closest_boundary_point(mesh.vertices[v])
                .is_some_and(|b| b.distance < ON_BOUNDARY)
        })
        .collect()
}

/// Pairs of opposite walls of every hexagonal cell, with the sign of each wall normal as seen
/// from the cell's orientation.
fn opposite_wall_pairs(mesh: &PolyMesh, conn: &Connectivity) -> Vec<[(usize, f64); 2]> {
    let mut pairs = Vec::new();
    for (f, face) in mesh.faces.iter().enumerate() {
        if face.len() != 6 {
            continue;
        }
        let m = |k: usize| {
            let e = conn.face_edges[f][k];
            (e, conn.edge_sign(e, face[k]))
        };
        for k in 0..3 {
            pairs.push([m(k), m(k + 3)]);
        }
    }
    pairs
}

/// What keeps each edge in its wall.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WallRows {
    /// The wall plane contains the edge, `n_e . (v_a - v_b) = 0` ([`WallConsistency`]).
    Consistency,
    /// The wall plane has an offset of its own and holds both ends ([`WallPlane`]): no row
    /// couples two vertices, so the solver can eliminate the vertices before it factors.
    Planes,
}

/// A honeycomb's problem in the making: allocates the unknowns block by block ([`Unknowns`])
/// and gathers the families that read them. The families may borrow for `'a` (S, for one
/// solve) or own what they read (a session's `Arc<Surface>`).
pub struct ProblemBuilder<'m, 'a> {
    mesh: &'m PolyMesh,
    conn: &'m Connectivity,
    layout: Layout,
    walls: WallRows,
    /// The weight of the wall rows.
    consistency: f64,
    unknowns: Unknowns,
    families: Vec<Box<dyn Constraint + 'a>>,
}

impl<'m, 'a> ProblemBuilder<'m, 'a> {
    /// The honeycomb's unknowns, starting at `vertices` and wall `normals`, and its families
    /// ([`families`]) over `mesh` and `surface`, the walls as `walls` says.
    pub fn new<S>(
        mesh: &'m PolyMesh,
        conn: &'m Connectivity,
        surface: S,
        weights: &Weights,
        walls: WallRows,
        vertices: &[Vec3],
        normals: &[Vec3],
    ) -> Self
    where
        S: Deref<Target = Surface> + Clone + Send + Sync + 'a,
    {
        let layout = Layout::new(mesh.vertices.len(), conn.num_edges());
        let mut unknowns = Unknowns::new();
        // In the order `layout` reads them.
        unknowns.allocate("vertices", vertices.iter().flat_map(|p| p.to_array()));
        unknowns.allocate("wall_normals", normals.iter().flat_map(|n| n.to_array()));
        debug_assert_eq!(unknowns.len(), layout.len());
        let mut families = families(mesh, conn, surface, weights, walls);
        if weights.held_walls > 0.0 {
            families.push(Box::new(HeldNormals {
                layout,
                normals: normals.to_vec(),
                weight: weights.held_walls,
            }));
        }
        ProblemBuilder {
            mesh,
            conn,
            layout,
            walls,
            consistency: weights.consistency,
            unknowns,
            families,
        }
    }

    pub fn layout(&self) -> Layout {
        self.layout
    }

    /// The unknowns' starting values so far.
    pub fn values(&self) -> &[f64] {
        self.unknowns.values()
    }

    /// A block of unknowns of a family's own, after those already there.
    pub fn allocate(&mut self, name: &'static str, values: impl IntoIterator<Item = f64>) -> Block {
        self.unknowns.allocate(name, values)
    }

    pub fn push(&mut self, family: impl Constraint + 'a) {
        self.families.push(Box::new(family));
    }

    /// Every edge at least `length` (normalized units) long, by one dummy per edge.
    pub fn min_edge_length(&mut self, length: f64) {
        let edges = self.conn.edges.clone();
        let dummies = MinEdgeLength::initial_dummies(&edges, length, &self.mesh.vertices);
        let block = self.allocate("min_edge_dummies", dummies);
        self.push(MinEdgeLength::new(
            self.layout,
            edges,
            length,
            block.start,
            1.0,
        ));
    }

    /// The unknowns and the families. With wall planes their offsets (one per edge, measured
    /// from the edge's midpoint at the start) and rows come last, after every variant's:
    /// the order in which the solves have been tuned and checked.
    pub fn finish(mut self) -> (Unknowns, Vec<Box<dyn Constraint + 'a>>) {
        if self.walls == WallRows::Planes {
            let (layout, x) = (self.layout, self.unknowns.values());
            let anchors = (self.conn.edges.iter())
                .map(|&[a, b]| (layout.vertex_at(x, a) + layout.vertex_at(x, b)) * 0.5)
                .collect();
            // Each wall starts through its anchor: offset 0.
            let offsets = self.allocate("wall_offsets", vec![0.0; self.conn.num_edges()]);
            self.push(WallPlane {
                layout,
                edges: self.conn.edges.clone(),
                offsets: offsets.range().collect(),
                anchors,
                weight: self.consistency,
            });
        }
        (self.unknowns, self.families)
    }
}

/// The walls (edge, sign seen from the node) at every node of valence 3 and of valence 2.
#[allow(clippy::type_complexity)]
pub fn node_walls(conn: &Connectivity) -> (Vec<[(usize, f64); 3]>, Vec<[(usize, f64); 2]>) {
    let mut node3 = Vec::new();
    let mut node2 = Vec::new();
    for (v, edges) in conn.vertex_edges.iter().enumerate() {
        let walls: Vec<(usize, f64)> = edges.iter().map(|&e| (e, conn.edge_sign(e, v))).collect();
        match walls.len() {
            3 => node3.push([walls[0], walls[1], walls[2]]),
            2 => node2.push([walls[0], walls[1]]),
            _ => {} // rejected by validation before we get here
        }
    }
    (node3, node2)
}

/// The honeycomb's families over `mesh` and S (`surface`, borrowed or shared): with
/// [`WallRows::Planes`] without wall rows, which bring unknowns of their own (see
/// [`ProblemBuilder::finish`]).
pub fn families<'a, S>(
    mesh: &PolyMesh,
    conn: &Connectivity,
    surface: S,
    weights: &Weights,
    walls: WallRows,
) -> Vec<Box<dyn Constraint + 'a>>
where
    S: Deref<Target = Surface> + Clone + Send + Sync + 'a,
{
    let layout = Layout::new(mesh.vertices.len(), conn.num_edges());
    let (node3, node2) = node_walls(conn);
    let mut families: Vec<Box<dyn Constraint + 'a>> = vec![Box::new(Normalization {
        layout,
        weight: weights.normalization(),
    })];
    if walls == WallRows::Consistency {
        families.push(Box::new(WallConsistency {
            layout,
            edges: conn.edges.clone(),
            weight: weights.consistency,
        }));
    }
    families.push(Box::new(Node3 {
        layout,
        nodes: node3,
        weight: weights.angle,
    }));
    families.push(Box::new(Node2 {
        layout,
        nodes: node2,
        weight: weights.angle,
    }));
    if weights.closeness > 0.0 {
        let closeness = Closeness::new(layout, surface.clone(), weights.closeness);
        families.push(Box::new(closeness));
    }
    let on_boundary = boundary_vertices_on_surface_boundary(mesh, conn, &surface);
    if weights.boundary > 0.0 && !on_boundary.is_empty() {
        families.push(Box::new(BoundaryCurve::new(
            layout,
            surface.clone(),
            weights.boundary,
            on_boundary,
        )));
    }
    if weights.fairness > 0.0 {
        families.push(Box::new(OppositeWalls {
            layout,
            pairs: opposite_wall_pairs(mesh, conn),
            weight: weights.fairness,
        }));
    }
    if weights.guide > 0.0 {
        let ends = (0..mesh.vertices.len())
            .flat_map(|v| {
                let a = surface.normal_at(mesh.vertices[v]);
                conn.vertex_edges[v]
                    .iter()
                    .map(move |&e| (e, conn.edge_sign(e, v), a))
            })
            .collect();
        families.push(Box::new(PrescribedAxes {
            layout,
            ends,
            weight: weights.guide,
            role: Role::Guide,
        }));
    }
    if weights.evenness > 0.0 {
        // The normalized frame's unit is the mean edge length.
        families.push(Box::new(EdgeLength {
            layout,
            edges: conn.edges.clone(),
            length: 1.0,
            weight: weights.evenness,
        }));
    }
    families.retain(|c| c.num_rows() > 0);
    families
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constraints::jacobian_tests::saddle;

    use crate::optimize::{AxesOptions, OptimizeOptions, ParallelOptions, Problem};

    /// The blocks' names, after checking that they tile `0..len` in order.
    fn tiling(blocks: &[Block], len: usize) -> Vec<&'static str> {
        let mut end = 0;
        for b in blocks {
            assert_eq!(
                b.start, end,
                "{} starts off the previous block's end",
                b.name
            );
            end = b.end();
        }
        assert_eq!(end, len, "the blocks leave unknowns out");
        blocks.iter().map(|b| b.name).collect()
    }

    /// The block called `name`.
    fn block(blocks: &[Block], name: &str) -> Block {
        *blocks.iter().find(|b| b.name == name).unwrap()
    }

    /// Whether every row of family `name` reads its `k`-th unknown inside `block`.
    fn reads(problem: &Problem, name: &str, k: usize, block: Block) -> bool {
        let f = problem.families.iter().find(|f| f.name() == name).unwrap();
        let mut vars = vec![0; f.arity()];
        (0..f.num_rows()).all(|r| {
            f.row_variables(r, &mut vars);
            block.range().contains(&vars[k])
        })
    }

    /// Every variant's unknowns follow the honeycomb's (vertices, then wall normals, where
    /// `Layout` reads them), in the order the variants are added, and each family reads its
    /// own block.
    #[test]
    fn variants_get_blocks_after_the_honeycomb() {
        let (frame, mesh, surface, conn) = saddle();
        let options = OptimizeOptions {
            min_edge: Some(0.5 * frame.unit),
            parallel: Some(ParallelOptions::default()),
            axes: Some(AxesOptions {
                targets: vec![Vec3::new(0.0, 0.0, 1.0); mesh.vertices.len()],
                weight: 0.1,
            }),
            ..OptimizeOptions::default()
        }
        .resolved();
        let problem = Problem::build(&mesh, &conn, &surface, &options, &options.weights, &frame);
        let blocks = &problem.blocks;
        let names = tiling(blocks, problem.x.len());
        let expected = [
            "vertices",
            "wall_normals",
            "min_edge_dummies",
            "orientation_dummies",
            "offset_vertices",
        ];
        assert_eq!(names, expected);
        let (nv, ne) = (mesh.vertices.len(), conn.num_edges());
        // One orientation row per wall end at a node: two per edge.
        let lengths = [3 * nv, 3 * ne, ne, 2 * ne, 3 * nv];
        assert_eq!(blocks.iter().map(|b| b.len).collect::<Vec<_>>(), lengths);
        let layout = problem.layout;
        assert_eq!(layout.vertex(nv - 1) + 3, blocks[0].end());
        assert_eq!(layout.normal(0), blocks[1].start);
        assert_eq!(layout.len(), blocks[1].end());
        let offset = problem.offset.unwrap();
        assert_eq!(offset.start, block(blocks, "offset_vertices").start);
        assert!(reads(&problem, "min_edge_length", 6, blocks[2]));
        assert!(reads(&problem, "node_orientation_valence2", 9, blocks[3]));
        let names: Vec<&str> = problem.families.iter().map(|f| f.name()).collect();
        assert!(names.contains(&"wall_consistency") && !names.contains(&"wall_plane"));
    }

    /// With cell points the walls are planes from the start: no consistency rows, and the
    /// planes' offsets are the last block.
    #[test]
    fn cell_points_walls_are_planes_with_the_last_block() {
        let (frame, mesh, surface, conn) = saddle();
        let options = OptimizeOptions {
            min_edge: Some(0.5 * frame.unit),
            ..OptimizeOptions::cell_points()
        }
        .resolved();
        let problem = Problem::build(&mesh, &conn, &surface, &options, &options.weights, &frame);
        let names = tiling(&problem.blocks, problem.x.len());
        let expected = [
            "vertices",
            "wall_normals",
            "min_edge_dummies",
            "wall_offsets",
        ];
        assert_eq!(names, expected);
        let offsets = problem.blocks[3];
        assert_eq!(offsets.len, conn.num_edges());
        assert!(reads(&problem, "wall_plane", 6, offsets));
        let names: Vec<&str> = problem.families.iter().map(|f| f.name()).collect();
        assert!(!names.contains(&"wall_consistency"), "{names:?}");
        assert_eq!(names.last(), Some(&"wall_plane"));
    }
}
