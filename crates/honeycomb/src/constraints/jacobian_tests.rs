//! Every family's analytic Jacobian against central finite differences, at a perturbed (not
//! converged) iterate so that no term vanishes by accident.

use super::*;
use crate::generate::{lifted_hex_patch, Shape};
use crate::geometry::Vec3;
use crate::mesh::Connectivity;
use crate::mesh::PolyMesh;
use crate::optimize::{
    initial_normals, AxesOptions, CappingProblem, CappingTry, Frame, OptimizeOptions,
    PairingProblem, ParallelOptions, Problem, ProblemBuilder, QuadOptions, QuadPattern, WallRows,
    Weights,
};
use crate::solve::{jacobian_fd_error, Constraint};
use crate::structure::QuadCover;
use crate::surface::Surface;

/// A deterministic pseudo-random perturbation in [-1, 1].
fn jitter(i: usize) -> f64 {
    let h = (i as u64)
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    ((h >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
}

/// A small saddle patch in the normalized frame, as `optimize` sees it.
pub(crate) fn saddle() -> (Frame, PolyMesh, Surface, Connectivity) {
    let (base, surface) = lifted_hex_patch(Shape::Saddle, 200);
    let frame = Frame::of(&base);
    let mesh = frame.to_normalized(&base);
    let surface = Surface::from_mesh(&frame.to_normalized(&surface)).unwrap();
    let conn = Connectivity::build(&mesh).unwrap();
    (frame, mesh, surface, conn)
}

/// Every `expected` family is present, and every family's Jacobian at `x` matches central
/// differences.
fn assert_families_match(families: &mut [Box<dyn Constraint + '_>], x: &[f64], expected: &[&str]) {
    let names: Vec<&str> = families.iter().map(|c| c.name()).collect();
    for e in expected {
        assert!(names.contains(e), "family {e} missing: {names:?}");
    }
    for c in families {
        c.refresh(x);
        let err = jacobian_fd_error(c.as_ref(), x, 1e-6);
        assert!(
            err < 1e-7,
            "{}: Jacobian deviates from finite differences by {err}",
            c.name()
        );
    }
}

#[test]
fn every_family_matches_finite_differences() {
    let (_, mesh, surface, conn) = saddle();
    let normals = initial_normals(&mesh, &conn, &surface);
    let weights = Weights {
        guide: 1.0,
        evenness: 0.3,
        held_walls: 0.1,
        ..Weights::default()
    };
    let walls = WallRows::Consistency;
    let mut problem = ProblemBuilder::new(
        &mesh,
        &conn,
        &surface,
        &weights,
        walls,
        &mesh.vertices,
        &normals,
    );
    problem.min_edge_length(0.9);
    let (unknowns, mut fams) = problem.finish();
    let (mut x, _) = unknowns.into_parts();
    for (i, xi) in x.iter_mut().enumerate() {
        *xi += 0.05 * jitter(i);
    }
    let expected = [
        "normalization",
        "wall_consistency",
        "node_120_valence3",
        "node_120_valence2",
        "closeness",
        "fairness_opposite_walls",
        "guide_axes_along_normals",
        "edge_length",
        "held_normals",
        "min_edge_length",
    ];
    assert_families_match(&mut fams, &x, &expected);
}

/// The variants' families, built the way `optimize` builds them: parallel meshes with a
/// constant depth, prescribed axes, the minimum edge length and the boundary orientation guard.
#[test]
fn variant_families_match_finite_differences() {
    let (frame, mesh, surface, conn) = saddle();
    let options = OptimizeOptions {
        min_edge: Some(0.5 * frame.unit),
        parallel: Some(ParallelOptions {
            depth: Some(0.4 * frame.unit),
            ..ParallelOptions::default()
        }),
        axes: Some(AxesOptions {
            targets: (0..mesh.vertices.len())
                .map(|v| Vec3::new(jitter(3 * v), jitter(3 * v + 1), 2.0))
                .collect(),
            weight: 0.1,
        }),
        ..OptimizeOptions::default()
    };
    let mut problem = Problem::build(&mesh, &conn, &surface, &options, &options.weights, &frame);
    for (i, xi) in problem.x.iter_mut().enumerate() {
        *xi += 0.05 * jitter(i + 11);
    }
    let expected = [
        "offset_on_axis",
        "edge_parallelity",
        "constant_depth",
        "prescribed_axes",
        "node_orientation_valence2",
        "min_edge_length",
    ];
    assert_families_match(&mut problem.families, &problem.x, &expected);
}

/// A cell-point solve's families, as `optimize` builds them: the wall planes with offsets
/// instead of the wall consistency. Their offsets start on the walls through the edges'
/// midpoints, so the rows start at zero.
#[test]
fn wall_plane_families_match_finite_differences() {
    let (frame, mesh, surface, conn) = saddle();
    let options = OptimizeOptions::cell_points().resolved();
    let mut problem = Problem::build(&mesh, &conn, &surface, &options, &options.weights, &frame);
    let names: Vec<&str> = problem.families.iter().map(|c| c.name()).collect();
    assert!(!names.contains(&"wall_consistency"), "{names:?}");
    let planes = problem.families.iter().find(|c| c.name() == "wall_plane");
    let planes = planes.expect("wall planes");
    let mut res = vec![0.0; planes.num_rows()];
    let mut jac = vec![0.0; planes.num_rows() * planes.arity()];
    planes.evaluate(&problem.x, &mut res, &mut jac);
    // At the start each plane holds its edge's midpoint; the ends are off only as far as
    // the initial normal is off perpendicular to the edge (it is exactly perpendicular).
    let off = res.iter().fold(0.0f64, |m, r| m.max(r.abs()));
    assert!(off < 1e-12, "wall planes start {off} off their edges");
    for (i, xi) in problem.x.iter_mut().enumerate() {
        *xi += 0.05 * jitter(i + 5);
    }
    let expected = [
        "normalization",
        "wall_plane",
        "node_120_valence3",
        "closeness",
    ];
    assert_families_match(&mut problem.families, &problem.x, &expected);
}

/// The quad cover's families (every pattern): normals, planarity, polyline fairness, and the
/// closeness that firms up where a vertex strays (as the jittered ones do).
#[test]
fn capping_families_match_finite_differences() {
    for pattern in [
        QuadPattern::Zigzag,
        QuadPattern::Alternating,
        QuadPattern::Flattest,
    ] {
        let (_, mesh, surface, conn) = saddle();
        let normals = initial_normals(&mesh, &conn, &surface);
        let options = QuadOptions {
            pattern,
            ..QuadOptions::default()
        };
        let axes: Vec<Vec3> = (mesh.vertices.iter())
            .map(|&p| surface.normal_at(p))
            .collect();
        let walls = (normals.as_slice(), axes.as_slice(), 1.0);
        let sliding = CappingTry {
            closeness: 0.3,
            sliding: true,
        };
        let cover = QuadCover::new(&mesh, &conn, pattern, None);
        let mut problem =
            CappingProblem::build(&mesh, &conn, walls, (&surface, cover), &options, sliding);
        let cover = &problem.cover;
        assert_eq!(cover.quads.len(), 2 * mesh.faces.len());
        // The vertices, one unit normal per quad on S's side, one dummy per edge.
        let start = 3 * mesh.vertices.len();
        assert_eq!(
            problem.x.len(),
            start + 3 * cover.quads.len() + conn.num_edges()
        );
        for (q, corners) in cover.quads.iter().enumerate() {
            let n = Vec3::from_slice(&problem.x[start + 3 * q..]);
            let c = corners
                .iter()
                .fold(Vec3::ZERO, |s, &v| s + mesh.vertices[v])
                / 4.0;
            assert!((n.norm() - 1.0).abs() < 1e-12 && n.dot(surface.normal_at(c)) > 0.9);
        }
        for (i, xi) in problem.x.iter_mut().enumerate() {
            *xi += 0.05 * jitter(i);
        }
        let expected = [
            "kept_walls",
            "closeness",
            "tangential_hold",
            "min_edge_length",
            "quad_normalization",
            "quad_planarity",
            "fairness_zigzag",
            "fairness_straight",
            "wall_convexity",
        ];
        // Twice, so that the bounded closeness scales its far vertices by 4 (and the bounded
        // planarity its bent quads).
        for family in problem.families.iter_mut() {
            family.refresh(&problem.x);
        }
        assert_families_match(&mut problem.families, &problem.x, &expected);
    }
}

/// The pairing of parallel meshes on a honeycomb's walls: the bilinear parallelity of each
/// edge and its twin, the holds on S and at the nominal depth, off any solution.
#[test]
fn pairing_families_match_finite_differences() {
    let (frame, mesh, surface, conn) = saddle();
    let normals = initial_normals(&mesh, &conn, &surface);
    let axes: Vec<Vec3> = (0..mesh.vertices.len())
        .map(|v| surface.normal_at(mesh.vertices[v]) + Vec3::new(0.1 * jitter(v), 0.0, 0.0))
        .map(Vec3::normalized)
        .collect();
    let model = PolyMesh::new(
        mesh.vertices.iter().map(|&p| frame.to_model(p)).collect(),
        mesh.faces.clone(),
    );
    let honeycomb = crate::structure::Honeycomb::new(model, &conn, axes, 0.3 * frame.unit);
    let options = ParallelOptions::default();
    let mut problem = PairingProblem::build(
        &honeycomb,
        &Frame::of(&honeycomb.base),
        &conn,
        &normals,
        0.3,
        &options,
        0.3,
    );
    assert_eq!(problem.x.len(), 2 * mesh.vertices.len());
    for (i, xi) in problem.x.iter_mut().enumerate() {
        *xi += 0.05 * jitter(i + 11);
    }
    let expected = ["parallel_on_axes", "on_s", "depth"];
    assert_families_match(&mut problem.families, &problem.x, &expected);
}

#[test]
fn boundary_curve_matches_finite_differences() {
    // S is the base mesh itself, so every boundary vertex starts on S's boundary.
    let (base, _) = lifted_hex_patch(Shape::Dome, 200);
    let surface = Surface::from_mesh(&base).unwrap();
    let conn = Connectivity::build(&base).unwrap();
    let layout = Layout::new(base.vertices.len(), conn.num_edges());
    let vertices = crate::optimize::boundary_vertices_on_surface_boundary(&base, &conn, &surface);
    assert!(
        vertices.len() > 20,
        "only {} boundary vertices on S's boundary",
        vertices.len()
    );
    let mut c = BoundaryCurve::new(layout, &surface, 1.0, vertices);
    let normals = initial_normals(&base, &conn, &surface);
    let mut x = layout.pack(&base.vertices, &normals);
    for (i, xi) in x.iter_mut().enumerate() {
        *xi += 0.02 * jitter(i + 7);
    }
    c.refresh(&x);
    let err = jacobian_fd_error(&c, &x, 1e-6);
    assert!(err < 1e-7, "boundary_curve: {err}");
    // The residual is the distance to the tangent line: it is zero on the boundary itself.
    let mut res = vec![0.0; c.num_rows()];
    let mut jac = vec![0.0; c.num_rows() * 3];
    let x0 = layout.pack(&base.vertices, &normals);
    c.refresh(&x0);
    c.evaluate(&x0, &mut res, &mut jac);
    assert!(
        res.iter().all(|r| r.abs() < 1e-9),
        "boundary vertices should have zero residual"
    );
}

/// The editor's target families, with targets on some vertices and none on others.
#[test]
fn target_families_match_finite_differences() {
    let (_, mesh, surface, conn) = saddle();
    let layout = Layout::new(mesh.vertices.len(), conn.num_edges());
    let normals = initial_normals(&mesh, &conn, &surface);
    let mut x = layout.pack(&mesh.vertices, &normals);
    for (i, xi) in x.iter_mut().enumerate() {
        *xi += 0.05 * jitter(i + 3);
    }
    let positions = SharedTargets::new(mesh.vertices.len());
    let axes = SharedTargets::new(mesh.vertices.len());
    for v in (0..mesh.vertices.len()).step_by(7) {
        positions.set_one(v, Some(mesh.vertices[v] + Vec3::new(0.3, -0.2, 0.1)));
        axes.set_one(v, Some(Vec3::new(jitter(v), 0.2, 1.0).normalized()));
    }
    let mut fams: Vec<Box<dyn Constraint>> = vec![
        Box::new(VertexTargets {
            layout,
            targets: positions.clone(),
            weight: 1.0,
        }),
        Box::new(AxisTargets::new(layout, &conn.edges, axes.clone(), 0.1)),
    ];
    assert_families_match(&mut fams, &x, &["vertex_targets", "axis_targets"]);
    // A vertex without a target contributes nothing; one with a target its offset.
    let mut res = vec![0.0; fams[0].num_rows()];
    let mut jac = vec![0.0; fams[0].num_rows()];
    fams[0].evaluate(&x, &mut res, &mut jac);
    assert_eq!(&res[3..6], &[0.0, 0.0, 0.0]);
    let expected = layout.vertex_at(&x, 0) - positions.get()[0].unwrap();
    assert!((Vec3::from_slice(&res[0..3]) - expected).norm() < 1e-15);
}

/// The reciprocal sheet's families (rigid triangles with their turns, differences orthogonal
/// to a direction) and the placement's edge vectors, at points and turns off any solution.
#[test]
fn sheet_families_match_finite_differences() {
    let (_, mesh, surface, conn) = saddle();
    let sheet = crate::reciprocal::Sheet::new(&mesh, &conn).unwrap();
    let points = sheet.initial_points(&mesh, &conn, |p| surface.normal_at(p));
    let (np, nt) = (points.len(), sheet.triangles.len());
    let mut x: Vec<f64> = points.iter().flat_map(|p| p.to_array()).collect();
    // Turns of up to 0.3 radians: the exponential map's derivative is checked away from 0.
    x.extend((0..3 * nt).map(|i| 0.3 * jitter(i + 11)));
    for (i, xi) in x.iter_mut().enumerate().take(3 * np) {
        *xi += 0.05 * jitter(i + 5);
    }
    let s = 3f64.sqrt().recip();
    let corner = |k: f64| {
        let a = std::f64::consts::FRAC_PI_2 + 2.0 * std::f64::consts::FRAC_PI_3 * k;
        Vec3::new(a.cos(), a.sin(), 0.0) * s
    };
    let sides = [0.0, 1.0, 2.0].map(|k| corner(k + 1.0) - corner(k));
    let bases = SharedRotations::new(
        (0..nt)
            .map(|t| crate::geometry::rotation::exp(Vec3::new(jitter(t), jitter(t + 1), 0.5)))
            .collect(),
    );
    let directions = |offset: usize| {
        sheet
            .sides
            .iter()
            .enumerate()
            .map(|(e, &pair)| {
                let d = Vec3::new(jitter(e + offset), jitter(e + offset + 1), 1.0);
                (pair, d.normalized())
            })
            .collect::<Vec<_>>()
    };
    let layout = Layout::new(np, 0);
    let edges = directions(40)
        .into_iter()
        .filter(|&([a, b], _)| a != b)
        .map(|(pair, d)| (pair, d * 1.3))
        .collect();
    let mut fams: Vec<Box<dyn Constraint>> = vec![
        Box::new(RigidTriangles {
            triangles: sheet.triangles.clone(),
            rotations: np,
            bases,
            sides,
            weight: 10.0,
        }),
        Box::new(OrthogonalDifference {
            name: "orthogonal_difference",
            rows: directions(7),
            value: 0.5,
            weight: 1.0,
            role: crate::solve::Role::Guide,
            fade: 0.5,
        }),
        Box::new(EdgeVectors {
            layout,
            edges,
            weight: 3.0,
        }),
    ];
    assert_families_match(
        &mut fams,
        &x,
        &["rigid_triangles", "orthogonal_difference", "edge_vectors"],
    );
}
