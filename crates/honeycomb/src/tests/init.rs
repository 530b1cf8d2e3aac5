//! `init`: hex base meshes on design surfaces, judged on the meshes it makes.

use super::shared_data;
use crate::generate::{lifted_hex_patch, Shape};
use crate::geometry::Vec3;
use crate::init::{init, Align, BoundaryMode, CellSize, Flattener, InitOptions, Method};
use crate::mesh::{validate_base_mesh, PolyMesh};
use crate::optimize::{optimize, optimize_made_mesh, OptimizeOptions};
use crate::structure::measure;
use crate::surface::Surface;

fn options(cells: usize) -> InitOptions {
    InitOptions::new(CellSize::Cells(cells))
}

/// The design surface of a built-in shape (a triangulated height field).
fn surface(shape: Shape) -> PolyMesh {
    lifted_hex_patch(shape, 1500).1
}

/// What every base mesh must be: valid for `optimize` (manifold, valence 2 or 3), on S, with
/// nearly all interior cells hexagons of nearly one size.
fn assert_good(base: &PolyMesh, s: &PolyMesh, report: &crate::init::InitReport, what: &str) {
    validate_base_mesh(base).unwrap_or_else(|e| panic!("{what}: {e}"));
    assert!(report.interior_hexagon_share >= 0.95, "{what}: {report:?}");
    assert!(
        report.edge_length_cv <= 0.12,
        "{what}: cv {}",
        report.edge_length_cv
    );
    // Measured again here, not read from the report.
    let surface = Surface::from_mesh(s).unwrap();
    let mean = base.mean_edge_length();
    let far = base
        .vertices
        .iter()
        .map(|&p| surface.closest_point(p).distance)
        .fold(0.0, f64::max);
    assert!(far < 1e-9 * mean.max(1.0), "{what}: a vertex {far} off S");
    assert_eq!(report.vertices, base.vertices.len());
}

#[test]
fn hex_meshes_on_generated_surfaces() {
    for shape in [Shape::Saddle, Shape::Dome, Shape::Cylinder, Shape::Roof] {
        let s = surface(shape);
        let made = init(&s, &options(700)).unwrap();
        println!("{shape:?}: {:?}", made.report);
        assert_good(&made.base, &s, &made.report, &format!("{shape:?}"));
        let cells = made.base.faces.len();
        assert!(
            (500..=720).contains(&cells),
            "{shape:?}: {cells} cells for 700 asked"
        );
        assert!(made.report.flat.as_ref().unwrap().flattening.conformal_avg < 1.1);
    }
}

/// The paper's full path: a surface, a hex mesh on it, a honeycomb. On the developable
/// cylinder and the roof the ARAP grid becomes a honeycomb (omega 1e-7 degrees or better); on
/// the dome (0.3 deg) and the saddle the optimizer does not get there from it, but it does from
/// the grid laid in plan view (`Flattener::Project`: parallel node axes from the start).
#[test]
fn init_then_optimize_gives_a_honeycomb() {
    let cases = [
        (Shape::Cylinder, Flattener::Arap),
        (Shape::Roof, Flattener::Arap),
        (Shape::Dome, Flattener::Project),
        (Shape::Saddle, Flattener::Project),
    ];
    for (shape, flattener) in cases {
        let s = surface(shape);
        let made = init(
            &s,
            &InitOptions {
                flattener,
                ..options(700)
            },
        )
        .unwrap();
        assert_good(
            &made.base,
            &s,
            &made.report,
            &format!("{shape:?} {flattener:?}"),
        );
        let opt = optimize(
            &made.base,
            Some(&s),
            &OptimizeOptions::default(),
            &mut |_| {},
        )
        .unwrap();
        let m = measure(&opt.honeycomb, &Surface::from_mesh(&s).unwrap());
        println!(
            "{shape:?}: omega {:.2e} delta {:.2e} closeness {:.2e}",
            m.omega_max_deg, m.delta_max, m.closeness_max
        );
        assert!(
            m.omega_max_deg < 0.01,
            "{shape:?}: omega {}",
            m.omega_max_deg
        );
        assert!(
            m.delta_max < 1e-6 && m.closeness_max < 0.05,
            "{shape:?}: {m:?}"
        );
    }
}

#[test]
fn the_same_seed_gives_the_same_mesh_and_another_seed_another() {
    let s = surface(Shape::Dome);
    let a = init(&s, &options(300)).unwrap().base;
    let b = init(&s, &options(300)).unwrap().base;
    assert_eq!(a.vertices, b.vertices);
    assert_eq!(a.faces, b.faces);
    let c = init(
        &s,
        &InitOptions {
            seed: 7,
            ..options(300)
        },
    )
    .unwrap();
    assert_ne!(a.vertices, c.base.vertices);
    assert_good(&c.base, &s, &c.report, "seed 7");
}

#[test]
fn kept_boundary_cells_are_closed_against_the_boundary() {
    let s = surface(Shape::Roof);
    let trim = init(&s, &options(700)).unwrap();
    let keep = init(
        &s,
        &InitOptions {
            boundary: BoundaryMode::Keep,
            ..options(700)
        },
    )
    .unwrap();
    validate_base_mesh(&keep.base).unwrap();
    assert!(keep.base.faces.len() > trim.base.faces.len());
    // Some vertices now lie on S's boundary, and every vertex lies on S.
    let surface = Surface::from_mesh(&s).unwrap();
    let on_boundary = keep
        .base
        .vertices
        .iter()
        .filter(|&&p| {
            surface
                .closest_boundary_point(p)
                .is_some_and(|b| (b.point - p).norm() < 1e-9)
        })
        .count();
    assert!(on_boundary > 20, "{on_boundary} vertices on the boundary");
    assert!(keep.report.distance_to_surface_max < 1e-9);
}

#[test]
fn strokes_turn_the_grid() {
    // A flat square and one stroke at 20 degrees: a third of the edges follow it.
    let flat = lifted_hex_patch(Shape::Roof, 1500).1;
    let flat = PolyMesh::new(
        flat.vertices
            .iter()
            .map(|p| Vec3::new(p.x, p.y, 0.0))
            .collect(),
        flat.faces.clone(),
    );
    let t = 20f64.to_radians();
    let stroke = vec![Vec3::ZERO, Vec3::new(10.0 * t.cos(), 10.0 * t.sin(), 0.0)];
    let made = init(
        &flat,
        &InitOptions {
            align: Align::Strokes(vec![stroke]),
            ..options(500)
        },
    )
    .unwrap();
    let direction = Vec3::new(t.cos(), t.sin(), 0.0);
    let edges: Vec<f64> = made
        .base
        .faces
        .iter()
        .flat_map(|f| (0..6).map(move |k| (f[k], f[(k + 1) % 6])))
        .map(|(a, b)| {
            (made.base.vertices[b] - made.base.vertices[a])
                .normalized()
                .dot(direction)
                .abs()
        })
        .collect();
    let along = edges.iter().filter(|&&c| c > 0.9999).count();
    assert!(
        (along as f64 / edges.len() as f64 - 1.0 / 3.0).abs() < 0.02,
        "{along} of {}",
        edges.len()
    );
    // A flat surface is no problem for flattening: no distortion at all.
    assert!(made.report.flat.as_ref().unwrap().flattening.conformal_max < 1.0 + 1e-6);
    assert!(made.report.edge_length_cv < 1e-6);
}

#[test]
fn unusable_surfaces_and_sizes_are_named() {
    let s = surface(Shape::Dome);
    let error = |mesh: &PolyMesh, o: &InitOptions| init(mesh, o).err().unwrap().to_string();
    // A closed surface: a cube of quads.
    let cube = PolyMesh::new(
        (0..8)
            .map(|i| Vec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
            .collect(),
        vec![
            vec![0, 2, 3, 1],
            vec![4, 5, 7, 6],
            vec![0, 1, 5, 4],
            vec![2, 6, 7, 3],
            vec![0, 4, 6, 2],
            vec![1, 3, 7, 5],
        ],
    );
    assert!(error(&cube, &options(100)).contains("closed"));
    // Two pieces.
    let mut two = s.clone();
    let n = two.vertices.len();
    two.vertices
        .extend(s.vertices.iter().map(|&p| p + Vec3::new(1e3, 0.0, 0.0)));
    two.faces.extend(
        s.faces
            .iter()
            .map(|f| f.iter().map(|&v| v + n).collect::<Vec<_>>()),
    );
    assert!(error(&two, &options(100)).contains("2 separate pieces"));
    // Cells larger than the surface.
    let e = error(
        &s,
        &InitOptions {
            size: CellSize::EdgeLength(1e3),
            ..options(1)
        },
    );
    assert!(e.contains("no cell") && e.contains("smaller cells"), "{e}");
    // Nonsense sizes.
    for size in [
        CellSize::Cells(0),
        CellSize::Cells(10_000_000),
        CellSize::EdgeLength(f64::NAN),
        CellSize::EdgeLength(-1.0),
    ] {
        let e = error(&s, &InitOptions { size, ..options(1) });
        assert!(e.contains("cells") || e.contains("edge_length"), "{e}");
    }
    let e = error(
        &s,
        &InitOptions {
            size: CellSize::EdgeLength(1e-6),
            ..options(1)
        },
    );
    assert!(e.contains("at most"), "{e}");
    // The field method trims; closing cells is the flattening's.
    let e = error(
        &s,
        &InitOptions {
            method: Method::Field,
            boundary: BoundaryMode::Keep,
            ..options(100)
        },
    );
    assert!(e.contains("--boundary keep"), "{e}");
}

/// A grid of unit squares over [0, n]^2 without the squares `hole` (column, row) lists.
/// An export that gives each face corners of its own (as STL does) is the same surface: init
/// and S see the welded mesh, with the same cells.
#[test]
fn an_unwelded_surface_is_read_as_the_welded_one() {
    let s = surface(Shape::Wave);
    let mut unwelded = PolyMesh::default();
    for f in &s.faces {
        let first = unwelded.vertices.len();
        unwelded.vertices.extend(f.iter().map(|&v| s.vertices[v]));
        unwelded.faces.push((first..first + f.len()).collect());
    }
    let welded = init(&s, &options(300)).unwrap().report;
    let joined = init(&unwelded, &options(300)).unwrap().report;
    // The joined vertices come in another order, which may shift the grid a little.
    let (a, b) = (joined.cells as f64, welded.cells as f64);
    assert!((a - b).abs() <= 0.02 * b, "{a} cells joined, {b} welded");
    assert!(joined.edge_length_cv <= welded.edge_length_cv + 0.01);
    let surface = Surface::new(unwelded).unwrap();
    assert_eq!(surface.source_mesh().vertices.len(), s.vertices.len());
    // Unwelded, every edge would be S's border, an inner vertex on it.
    let middle = s.centroid();
    let inner = s
        .vertices
        .iter()
        .min_by(|a, b| (**a - middle).norm().total_cmp(&(**b - middle).norm()))
        .unwrap();
    assert!(
        !surface
            .closest_point(*inner + Vec3::new(0.0, 0.0, 0.1))
            .on_boundary
    );
}

fn square_with_holes(n: usize, hole: &[(usize, usize)]) -> PolyMesh {
    let id = |i: usize, j: usize| j * (n + 1) + i;
    let vertices = (0..=n)
        .flat_map(|j| (0..=n).map(move |i| Vec3::new(i as f64, j as f64, 0.0)))
        .collect();
    let faces = (0..n)
        .flat_map(|j| (0..n).map(move |i| (i, j)))
        .filter(|c| !hole.contains(c))
        .map(|(i, j)| vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)])
        .collect();
    PolyMesh::new(vertices, faces)
}

/// A hole smaller than a cell: the cells over it are dropped, leaving a gap of about one cell
/// (a second boundary loop), and the mesh stays valid. A surface whose pieces touch at one
/// vertex only is refused by name.
#[test]
fn small_holes_leave_a_gap_and_non_manifold_surfaces_are_refused() {
    let s = square_with_holes(20, &[(10, 10)]);
    let made = init(
        &s,
        &InitOptions {
            size: CellSize::EdgeLength(1.5),
            ..options(1)
        },
    )
    .unwrap();
    let conn = validate_base_mesh(&made.base).unwrap();
    assert_eq!(conn.boundary_loops.len(), 2, "the hole is kept as a hole");
    let full = init(
        &square_with_holes(20, &[]),
        &InitOptions {
            size: CellSize::EdgeLength(1.5),
            ..options(1)
        },
    )
    .unwrap();
    let lost = full.base.faces.len() - made.base.faces.len();
    assert!(
        (1..=3).contains(&lost),
        "{lost} cells lost to a hole of a third of a cell"
    );
    let keep = InitOptions {
        size: CellSize::EdgeLength(1.5),
        boundary: BoundaryMode::Keep,
        ..options(1)
    };
    let kept = init(&s, &keep).unwrap();
    assert_eq!(
        validate_base_mesh(&kept.base).unwrap().boundary_loops.len(),
        2
    );
    // Two squares meeting at a corner.
    let bowtie = PolyMesh::new(
        vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(2.0, 1.0, 0.0),
            Vec3::new(2.0, 2.0, 0.0),
            Vec3::new(1.0, 2.0, 0.0),
        ],
        vec![vec![0, 1, 2, 3], vec![2, 4, 5, 6]],
    );
    let e = init(&bowtie, &options(10)).err().unwrap().to_string();
    assert!(e.contains("non-manifold vertex 2"), "{e}");
}

/// A surface that folds over seen along its mean normal but not from the side: a long flat
/// plate (normal +z) that curls up and over by 170 degrees at one end. The plan view is found
/// along the direction its worst triangle faces best.
#[test]
fn projection_looks_from_where_the_whole_surface_is_seen() {
    let mut profile = Vec::new();
    for k in 0..=40 {
        profile.push((-20.0 + 0.5 * k as f64, 0.0));
    }
    for k in 1..=34 {
        // A circle of radius 2 turning left, its tangent from +x to 170 degrees.
        let t = (5.0 * k as f64).to_radians();
        profile.push((2.0 * t.sin(), 2.0 - 2.0 * t.cos()));
    }
    let width = 12;
    let mut vertices = Vec::new();
    for &(x, z) in &profile {
        for j in 0..=width {
            vertices.push(Vec3::new(x, 0.5 * j as f64, z));
        }
    }
    let id = |k: usize, j: usize| k * (width + 1) + j;
    let mut faces = Vec::new();
    for k in 0..profile.len() - 1 {
        for j in 0..width {
            // Counter-clockwise seen from +z on the plate.
            faces.push(vec![id(k, j), id(k + 1, j), id(k + 1, j + 1), id(k, j + 1)]);
        }
    }
    let curl = PolyMesh::new(vertices, faces);
    let o = InitOptions {
        flattener: Flattener::Project,
        size: CellSize::EdgeLength(0.5),
        ..options(1)
    };
    let made = init(&curl, &o).unwrap();
    validate_base_mesh(&made.base).unwrap();
    assert!(
        made.base.faces.len() > 100,
        "{} cells",
        made.base.faces.len()
    );
    assert!(made.report.distance_to_surface_max < 1e-9);
}

/// The design surfaces of ../shared/data (triangle and quad meshes) that a flattening suits.
const FLATTENABLE: [&str; 7] = [
    "inspired_mesh.obj",
    "Neumunster.ply",
    "botanic-garden-bubble.off",
    "train-station.off",
    "barrellvault10m.ply",
    "YasIsland.off",
    "free_negshell_marc_anet.obj",
];

/// The real design surfaces (triangle and quad meshes) of ../shared/data, at about 1.5k and 8k
/// vertices. camelhead (a strongly curved head) is beyond a flattening: its mesh is valid but
/// its cells vary in size (cv 0.76), which the report says.
#[test]
fn hex_meshes_on_the_shared_surfaces() {
    let Some(data) = shared_data() else {
        println!("skipping: ../shared/data not found");
        return;
    };
    for file in FLATTENABLE.into_iter().chain(["camelhead.off"]) {
        let s = crate::mesh::read_mesh(&data.join(file)).unwrap().mesh;
        for cells in [750, 4000] {
            let made = init(&s, &options(cells)).unwrap();
            let r = &made.report;
            println!(
                "{file} {cells}: {} V, {} cells, hexagons {:.3}, cv {:.3}, {:?}, {:.2} s",
                r.vertices,
                r.cells,
                r.interior_hexagon_share,
                r.edge_length_cv,
                r.flat.as_ref().map(|f| f.flattener),
                r.seconds
            );
            if file == "camelhead.off" {
                validate_base_mesh(&made.base).unwrap();
            } else {
                assert_good(&made.base, &s, r, file);
            }
        }
    }
}

/// The plan-view path on the real surfaces (`--walls uniform`): the grid seen along S's mean
/// normal (ARAP where S folds over), then the solve for a mesh the program made (broken boundary
/// cells dropped, a second try without fairness). At about 1.5k vertices all of them become
/// honeycombs (omega below 0.01 degrees, planar walls).
/// camelhead is left out: its flattened cells vary too much in size; so is Yas
/// Island, whose steep boundary cells this solve breaks where dropping them would cut the ring
/// in pieces (cells are never dropped then; walls across S, the default, make it a honeycomb:
/// tests/walls.rs).
#[test]
fn pipeline_on_the_shared_surfaces() {
    let Some(data) = shared_data() else {
        println!("skipping: ../shared/data not found");
        return;
    };
    for file in FLATTENABLE.into_iter().filter(|&f| f != "YasIsland.off") {
        let s = crate::mesh::read_mesh(&data.join(file)).unwrap().mesh;
        let cells = 750;
        let plan_view = InitOptions {
            flattener: Flattener::Project,
            ..options(cells)
        };
        let made = init(&s, &plan_view)
            .or_else(|_| init(&s, &options(cells)))
            .unwrap();
        let result = optimize_made_mesh(
            &made.base,
            &s,
            &OptimizeOptions::default(),
            true,
            &mut |_, _| {},
        )
        .unwrap();
        let settled = &result.settled;
        let m = &settled.measures;
        println!(
            "{file} {cells}: {} V, omega {:.2e}, delta {:.2e}, closeness {:.1e}, dropped {} \
                 of {} cells in {} solves, second try {}, normals per edge {}",
            settled.optimized.honeycomb.base.vertices.len(),
            m.omega_max_deg,
            m.delta_max,
            m.closeness_max,
            settled.dropped_cells,
            made.base.faces.len(),
            settled.solves,
            result.second_try,
            result.per_edge_fallback
        );
        assert!(
            settled.dropped_cells as f64 <= 0.03 * made.base.faces.len() as f64,
            "{file} {cells}"
        );
        assert!(
            m.omega_max_deg < 0.01,
            "{file} {cells}: {}",
            m.omega_max_deg
        );
        assert!(m.delta_max < 1e-3, "{file} {cells}: delta {}", m.delta_max);
        // Every vertex on S, the boundary ones too (none beyond S's edge).
        assert!(
            m.closeness_max < 1e-3,
            "{file} {cells}: closeness {}",
            m.closeness_max
        );
    }
}

/// `init` with the field method: a valid hex mesh on S with nearly all interior cells
/// hexagons of nearly one size, reported without a flattening.
#[test]
fn the_field_method_through_init() {
    for shape in [Shape::Dome, Shape::Saddle] {
        let s = surface(shape);
        let made = init(
            &s,
            &InitOptions {
                method: Method::Field,
                ..options(750)
            },
        )
        .unwrap();
        assert_good(&made.base, &s, &made.report, &format!("field {shape:?}"));
        assert!(made.report.flat.is_none());
        assert_eq!(made.report.method, Method::Field);
        let json = serde_json::to_value(&made.report).unwrap();
        assert!(json.get("flattener").is_none(), "{json}");
        let again = init(
            &s,
            &InitOptions {
                method: Method::Field,
                ..options(750)
            },
        )
        .unwrap();
        assert_eq!(again.base, made.base, "not deterministic");
        // `--align none` leaves the field free of the boundary: another mesh, as good.
        let free = init(
            &s,
            &InitOptions {
                method: Method::Field,
                align: Align::None,
                ..options(750)
            },
        )
        .unwrap();
        assert_good(
            &free.base,
            &s,
            &free.report,
            &format!("field {shape:?}, free"),
        );
        assert_ne!(free.base, made.base);
    }
}
