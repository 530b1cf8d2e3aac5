//! Quadrangulation (paper section 4, Figs. 1, 11, 17): honeycombs capped by planar quads.

use crate::generate::roof;
use crate::optimize::{optimize, OptimizeOptions, Optimized, QuadOptions, QuadPattern};
use crate::solve::SolverOptions;
use crate::structure::{face_measures, measure, FaceMeasures, Measures};
use crate::surface::Surface;
use crate::Vec3;
use std::time::Instant;

struct Run {
    opt: Optimized,
    honeycomb: Measures,
    faces: FaceMeasures,
    initial_faces: FaceMeasures,
    /// The plain honeycomb the quads capped.
    plain: Optimized,
}

/// Optimizes the roof into a honeycomb and caps it by quads (the honeycomb's 10 iterations,
/// then the capping's 20), and measures the realized quads on the honeycomb and after.
fn run(amplitude: f64, quads: QuadOptions) -> Run {
    let (base, surface) = roof(3500, amplitude);
    let options = OptimizeOptions {
        solver: SolverOptions {
            max_iterations: 20,
            ..SolverOptions::default()
        },
        quads: Some(quads.clone()),
        ..OptimizeOptions::default()
    };
    let start = Instant::now();
    let opt = optimize(&base, Some(&surface), &options, &mut |_| {}).expect("optimize");
    let seconds = start.elapsed().as_secs_f64();
    let plain = OptimizeOptions {
        quads: None,
        ..options
    };
    let plain = optimize(&base, Some(&surface), &plain, &mut |_| {}).expect("optimize");
    let honeycomb = measure(&opt.honeycomb, &Surface::from_mesh(&surface).unwrap());
    let cover = opt.quad_cover.as_ref().expect("quad cover");
    let quad_mesh = opt.quads.as_ref().expect("quad mesh");
    // The quad mesh is M itself, its split quads first.
    assert_eq!(quad_mesh.vertices, opt.honeycomb.base.vertices);
    for (f, q) in quad_mesh.faces.iter().zip(&cover.quads) {
        assert_eq!(f.as_slice(), q.as_slice());
    }
    let faces = face_measures(&quad_mesh.vertices, &cover.quads);
    let initial_faces = face_measures(&plain.honeycomb.base.vertices, &cover.quads);
    println!(
        "{:?} |V|={} it={} T={seconds:.3}s | delta_face {:.2e}/{:.2e} (honeycomb {:.2e}/{:.2e}) \
         | omega {:.2e}/{:.2e} deg | delta {:.2e}/{:.2e} | closeness {:.2e}/{:.2e}",
        quads.pattern,
        base.vertices.len(),
        opt.solve.iterations,
        faces.delta_face_max,
        faces.delta_face_avg,
        initial_faces.delta_face_max,
        initial_faces.delta_face_avg,
        honeycomb.omega_max_deg,
        honeycomb.omega_avg_deg,
        honeycomb.delta_max,
        honeycomb.delta_avg,
        honeycomb.closeness_max,
        honeycomb.closeness_avg,
    );
    Run {
        opt,
        honeycomb,
        faces,
        initial_faces,
        plain,
    }
}

/// The capping keeps the honeycomb's walls: every node axis stays as the plain honeycomb had
/// it, the node angles and the walls' planarity as exact.
fn assert_walls_kept(r: &Run) {
    assert!(
        r.honeycomb.omega_max_deg < 1e-3,
        "{}",
        r.honeycomb.omega_max_deg
    );
    assert!(r.honeycomb.delta_max < 1e-6, "{}", r.honeycomb.delta_max);
    let turned = (r.opt.honeycomb.axes.iter().zip(&r.plain.honeycomb.axes))
        .map(|(a, b)| a.dot(*b).clamp(-1.0, 1.0).acos().to_degrees())
        .fold(0.0, f64::max);
    assert!(turned < 1e-4, "an axis turned by {turned} degrees");
}

/// Every hexagon is split into two quads that share its diagonal; other cells stay whole.
fn assert_every_hexagon_split(opt: &Optimized) {
    let cover = opt.quad_cover.as_ref().unwrap();
    let base = &opt.honeycomb.base;
    let hexagons = base.faces.iter().filter(|f| f.len() == 6).count();
    assert_eq!(cover.quads.len(), 2 * hexagons);
    assert_eq!(cover.unsplit.len(), base.faces.len() - hexagons);
    for (f, quads) in cover.cell_quads.iter().enumerate() {
        let Some([a, b]) = *quads else {
            assert_ne!(base.faces[f].len(), 6);
            continue;
        };
        let [p, q] = cover.diagonals[f].unwrap();
        for quad in [cover.quads[a], cover.quads[b]] {
            assert!(quad.contains(&p) && quad.contains(&q), "cell {f}: {quad:?}");
            assert!(quad.iter().all(|v| base.faces[f].contains(v)));
        }
    }
}

/// Figure 11 on a gently curved roof: the quads come out a little flatter than on the honeycomb
/// (a zigzag cover gains least: see `pipeline_caps_its_honeycomb_on_generated_surfaces`),
/// within the paper's .007 / .003, the vertices within 0.1 mean edge lengths of S, and the
/// walls kept.
#[test]
fn zigzag_quads_on_a_roof() {
    let r = run(0.08, QuadOptions::default());
    assert_every_hexagon_split(&r.opt);
    assert_walls_kept(&r);
    assert!(r.faces.delta_face_max < 0.007, "{:?}", r.faces);
    assert!(r.faces.delta_face_avg < 0.003, "{:?}", r.faces);
    assert!(
        r.faces.delta_face_avg < 0.95 * r.initial_faces.delta_face_avg,
        "{:?} {:?}",
        r.faces,
        r.initial_faces
    );
    assert!(
        r.honeycomb.closeness_max <= 0.1,
        "{}",
        r.honeycomb.closeness_max
    );
}

/// Figure 17's herringbone on the more curved roof: its quads lean opposite ways in
/// neighbouring strips, and come out much flatter than they started.
#[test]
fn alternating_quads_on_a_curved_roof() {
    let quads = QuadOptions {
        pattern: QuadPattern::Alternating,
        ..QuadOptions::default()
    };
    let r = run(0.12, quads);
    assert_every_hexagon_split(&r.opt);
    assert_walls_kept(&r);
    assert!(
        r.faces.delta_face_avg < 0.6 * r.initial_faces.delta_face_avg,
        "{:?} {:?}",
        r.faces,
        r.initial_faces
    );
    assert!(r.faces.delta_face_max < 0.01, "{:?}", r.faces);
    assert!(
        r.honeycomb.closeness_max <= 0.1,
        "{}",
        r.honeycomb.closeness_max
    );
}

/// `pipeline --quads` on the generated surfaces: the default honeycomb (walls across S) capped,
/// every figure from the written meshes. The capping keeps omega and delta at the honeycomb's,
/// every vertex within 0.1 mean edge lengths of S and no wall crossed; the quads come out no
/// less planar than on the honeycomb, within 0.01 (max) and 0.004 (mean), in at most 20
/// capping iterations. On the wave, whose principal directions turn so that one lattice
/// direction follows them only on average, the zigzag and alternating covers whole stay short
/// of the floors with the cells kept even, and meet them with a few cells off the pattern (see
/// `a_pattern_short_of_the_floors_gives_way_where_its_quads_stay_least_planar`).
/// The zigzag on the saddle is flat because
/// its lattice follows S's principal directions (see
/// `zigzag_quads_follow_the_principal_directions`), and so is the flattest cover on it.
#[test]
fn pipeline_caps_its_honeycomb_on_generated_surfaces() {
    use crate::generate::{design_surface, Shape};
    use crate::{pipeline, PipelineOptions, Progress};
    let cases = [
        (Shape::Dome, QuadPattern::Zigzag, true),
        (Shape::Cylinder, QuadPattern::Alternating, true),
        (Shape::Saddle, QuadPattern::Alternating, true),
        (Shape::Saddle, QuadPattern::Zigzag, true),
        (Shape::Wave, QuadPattern::Alternating, true),
        (Shape::Wave, QuadPattern::Zigzag, true),
        (Shape::Wave, QuadPattern::Flattest, true),
        (Shape::Saddle, QuadPattern::Flattest, true),
    ];
    for (shape, pattern, floors) in cases {
        let surface = Surface::new(design_surface(shape)).unwrap();
        let mut options = PipelineOptions::new(750);
        options.options.variant = quads_variant(pattern);
        let out = pipeline(&surface, &options, &mut Progress::silent()).unwrap();
        let m = measure(&out.honeycomb, &surface);
        let quads = out.report.quads.as_ref().expect("quads reported");
        let capping = quads.capping.as_ref().expect("capping reported");
        let faces = written_quads(&out);
        println!(
            "{shape:?} {pattern:?}: delta_face {:.4}/{:.4} (before {:.4}/{:.4}), omega {:.1e}, \
             delta {:.1e}, closeness {:.3}, {} iterations",
            faces.delta_face_max,
            faces.delta_face_avg,
            capping.delta_face_max_before,
            capping.delta_face_avg_before,
            m.omega_max_deg,
            m.delta_max,
            m.closeness_max,
            out.report.iterations_total
        );
        assert!(out.is_honeycomb(), "{shape:?} {pattern:?}");
        // The kept walls hold exactly: the node angles are the honeycomb's, far inside the
        // 0.05 degrees and 1e-5 asked.
        assert!(m.omega_max_deg < 1e-5 && m.delta_max < 1e-10, "{m:?}");
        assert_eq!(m.nonconvex_walls, 0);
        assert!(m.closeness_max <= 0.1 + 1e-9, "{}", m.closeness_max);
        assert!(faces.delta_face_max <= capping.delta_face_max_before + 1e-9);
        assert!(faces.delta_face_avg < capping.delta_face_avg_before);
        // All the capping's tries share the default budget of 20 iterations.
        assert!(capping.iterations <= 20, "{capping:?}");
        assert_eq!(capping.reshape, None);
        // A pattern is broken only where that meets the floors, and only in a few cells.
        let off = capping.cells_off_pattern;
        assert_eq!(off > 0, capping.whole_pattern.is_some(), "{capping:?}");
        assert!(off == 0 || faces.meet_floors(), "{capping:?}");
        assert!(5 * off <= faces.quads / 2, "{off} of {}", faces.quads / 2);
        if floors {
            assert!(faces.delta_face_max <= 0.01, "{faces:?}");
            assert!(faces.delta_face_avg <= 0.004, "{faces:?}");
        }
        // The cells re-shape no further than a honeycomb is asked to be even.
        assert!(m.edge_length_cv <= 0.12, "{}", m.edge_length_cv);
        // A patterned cover short of the floors points to the flattest one.
        let hint = (out.report.notes.iter()).any(|n| n.contains("--quads flattest"));
        let short = faces.delta_face_max > 0.01 || faces.delta_face_avg > 0.004;
        assert_eq!(
            hint,
            short && pattern != QuadPattern::Flattest,
            "{:?}",
            out.report.notes
        );
        // Walls across S: the capped honeycomb's axes lean from S's normals as the plain one's.
        assert!(
            m.axis_normal_deg.mean < m.parallel_baseline_deg.mean,
            "{m:?}"
        );
    }
}

/// A zigzag cover's quads are planar to second order where their long diagonals follow a
/// principal direction of S. `pipeline --quads zigzag` turns its lattice so (the saddle's
/// principal directions agree everywhere); the lattice along the boundary instead leaves the
/// quads of the honeycomb several times less planar, which capping with the walls kept cannot
/// undo (each column of cells would pass its twist on to the next). An alternating cover,
/// which caps well either way, keeps the boundary.
#[test]
fn zigzag_quads_follow_the_principal_directions() {
    use crate::generate::{design_surface, Shape};
    use crate::init::{Align, LatticeFollows};
    let surface = Surface::new(design_surface(Shape::Saddle)).unwrap();
    let run = |pattern, align| {
        let (out, faces, follows) = piped_quads(&surface, pattern, align);
        let capping = out.report.quads.as_ref().unwrap().capping.clone().unwrap();
        (follows, capping, faces)
    };
    let (follows, along, faces) = run(QuadPattern::Zigzag, None);
    assert_eq!(follows, LatticeFollows::Curvature);
    assert!(
        faces.delta_face_max <= 0.01 && faces.delta_face_avg <= 0.004,
        "{faces:?}"
    );
    let (follows, across, _) = run(QuadPattern::Zigzag, Some(Align::Boundary));
    assert_eq!(follows, LatticeFollows::Boundary);
    assert!(
        across.delta_face_avg_before > 3.0 * along.delta_face_avg_before,
        "{across:?} {along:?}"
    );
    let (follows, _, _) = run(QuadPattern::Alternating, None);
    assert_eq!(follows, LatticeFollows::Boundary);
}

/// Where the grid along S's principal directions leaves a quad less flat than 0.01, the
/// pipeline lays the boundary's grid too and keeps the zigzag cover whose worst quad is
/// flatter, saying which; where it does not, that grid is kept alone. On the wave, whose
/// principal directions turn, at 750 and 1500 cells.
#[test]
fn a_zigzag_cover_keeps_the_grid_with_the_flatter_worst_quad() {
    use crate::generate::{design_surface, Shape};
    use crate::init::{Align, LatticeFollows};
    let surface = Surface::new(design_surface(Shape::Wave)).unwrap();
    for cells in [750, 1500] {
        let run = |align| {
            let (out, faces, follows) = piped_quads_at(&surface, QuadPattern::Zigzag, align, cells);
            (faces, follows, out.report.notes.clone())
        };
        let (chosen, follows, notes) = run(None);
        let (along, along_follows, _) = run(Some(Align::Curvature));
        assert_eq!(along_follows, LatticeFollows::Curvature);
        let second_grid = (notes.iter()).any(|n| n.starts_with("zigzag quads: this is the grid"));
        println!("{cells}: chosen {chosen:?}, along {along:?}, {notes:?}");
        if along.delta_face_max <= 0.01 {
            assert_eq!(follows, LatticeFollows::Curvature);
            assert!((chosen.delta_face_max - along.delta_face_max).abs() < 1e-12);
            assert!(!second_grid, "{notes:?}");
            continue;
        }
        let (across, _, _) = run(Some(Align::Boundary));
        let best = along.delta_face_max.min(across.delta_face_max);
        assert!((chosen.delta_face_max - best).abs() < 1e-12, "{chosen:?}");
        let kept = if across.delta_face_max < along.delta_face_max {
            LatticeFollows::Boundary
        } else {
            LatticeFollows::Curvature
        };
        assert_eq!(follows, kept);
        assert!(second_grid, "{notes:?}");
    }
}

/// A folded plate (a roof of flat strips meeting at straight creases): a cell that straddles a
/// crease finds no flat diagonal of its own, while the zigzag's straight polylines along the
/// creases cap flat. The flattest cover meets the floors all the same: where its worst quad
/// stays above them, it is set against the zigzag cover, and the flatter kept.
#[test]
fn a_flattest_cover_is_as_flat_as_the_zigzag_on_a_folded_plate() {
    let (mut vertices, triangles) = crate::init::lifted_grid(80, |_, _| 0.0);
    let crease = |x: f64| 2.5 * (((x + 20.0) / 5.0).rem_euclid(2.0) - 1.0).abs();
    for p in &mut vertices {
        let (x, y) = (20.0 * p.x - 10.0, 20.0 * p.y - 10.0);
        *p = Vec3::new(x, y, crease(x));
    }
    let faces = triangles.iter().map(|t| t.to_vec()).collect();
    let surface = Surface::new(crate::mesh::PolyMesh::new(vertices, faces)).unwrap();
    let (flattest, faces, _) = piped_quads(&surface, QuadPattern::Flattest, None);
    let (_, zigzag, _) = piped_quads(&surface, QuadPattern::Zigzag, None);
    println!("flattest {faces:?}, zigzag {zigzag:?}");
    assert!(faces.delta_face_max <= 0.01 && faces.delta_face_avg <= 0.004);
    assert!(zigzag.delta_face_max <= 0.01 && zigzag.delta_face_avg <= 0.004);
    let capping = flattest
        .report
        .quads
        .as_ref()
        .unwrap()
        .capping
        .clone()
        .unwrap();
    // Each cell's own diagonal, on the honeycomb as it stands, is far from flat at a crease.
    assert!(capping.delta_face_max_before > 0.02, "{capping:?}");
}

/// `pipeline --quads PATTERN` at 750 cells, its grid along `align` if given (else the
/// pipeline's choice): the outcome, its quads' planarity read off quads.obj's vertices, and
/// what its grid follows.
fn piped_quads(
    surface: &Surface,
    pattern: QuadPattern,
    align: Option<crate::init::Align>,
) -> (crate::Outcome, FaceMeasures, crate::init::LatticeFollows) {
    piped_quads_at(surface, pattern, align, 750)
}

/// [`piped_quads`] at `cells` cells.
fn piped_quads_at(
    surface: &Surface,
    pattern: QuadPattern,
    align: Option<crate::init::Align>,
    cells: usize,
) -> (crate::Outcome, FaceMeasures, crate::init::LatticeFollows) {
    let mut options = crate::PipelineOptions::new(cells);
    options.options.variant = quads_variant(pattern);
    if let Some(align) = align {
        options.init.align = align;
        options.align_chosen = true;
    }
    let out = crate::pipeline(surface, &options, &mut crate::Progress::silent()).unwrap();
    assert!(out.is_honeycomb());
    let faces = written_quads(&out);
    let grid = out.initialized.as_ref().unwrap().flat.as_ref().unwrap();
    let follows = grid.lattice_follows;
    (out, faces, follows)
}

/// The planarity of the quads a `pipeline --quads` run writes (quads.obj: its four-sided
/// faces, the split quads).
fn written_quads(out: &crate::Outcome) -> FaceMeasures {
    let mesh = out.quads.as_ref().expect("quads.obj");
    let split = mesh.faces.iter().filter(|f| f.len() == 4).count();
    crate::structure::quad_mesh_measures(mesh, split)
}

/// `pipeline --quads PATTERN` with the default weights, the cells kept.
fn quads_variant(pattern: QuadPattern) -> crate::Variant {
    whole_quads_variant(pattern, None, false)
}

/// `pipeline --quads PATTERN [--quads-reshape CV] [--quads-whole-pattern]` with the default
/// weights.
fn whole_quads_variant(pattern: QuadPattern, reshape: Option<f64>, whole: bool) -> crate::Variant {
    crate::Variant::Quads {
        pattern,
        quad_direction: None,
        w_cons_faces: None,
        w_fair_zig: None,
        w_fair_str: None,
        quads_reshape: reshape,
        quads_whole_pattern: whole,
    }
}

/// Where a pattern's quads stay short of the floors, the cells whose quads stay least planar
/// take their own flattest diagonal, and the rest cap flat: the built-in wave's zigzag and
/// alternating covers at 750 cells meet both floors with at most a fifth of the cells off the
/// pattern, within the 20 capping iterations, the walls exact and the vertices within 0.1 of
/// S; the report counts those cells and gives the pattern whole's quads, which miss the
/// floors; `--quads-whole-pattern` keeps every cell on the pattern, short of them.
#[test]
fn a_pattern_short_of_the_floors_gives_way_where_its_quads_stay_least_planar() {
    use crate::generate::{design_surface, Shape};
    let surface = Surface::new(design_surface(Shape::Wave)).unwrap();
    for pattern in [QuadPattern::Zigzag, QuadPattern::Alternating] {
        let capped = |whole: bool| {
            let mut options = crate::PipelineOptions::new(750);
            options.options.variant = whole_quads_variant(pattern, None, whole);
            let out = crate::pipeline(&surface, &options, &mut crate::Progress::silent()).unwrap();
            let m = measure(&out.honeycomb, &surface);
            assert!(out.is_honeycomb());
            assert!(m.omega_max_deg < 1e-5 && m.delta_max < 1e-10, "{m:?}");
            assert!(m.closeness_max <= 0.1 + 1e-9, "{}", m.closeness_max);
            assert!(m.edge_length_cv <= 0.12, "{}", m.edge_length_cv);
            assert_eq!(m.nonconvex_walls, 0);
            let faces = written_quads(&out);
            let hexagons = (out.honeycomb.base.faces.iter()).filter(|f| f.len() == 6);
            assert_eq!(faces.quads, 2 * hexagons.count());
            let capping = (out.report.quads.as_ref())
                .and_then(|q| q.capping.clone())
                .expect("capping reported");
            assert!(capping.iterations <= 20, "{capping:?}");
            (faces, capping, out.report.notes)
        };
        let (whole, capping, notes) = capped(true);
        println!("{pattern:?} whole: {whole:?}");
        assert!(!whole.meet_floors(), "{whole:?}");
        assert_eq!(capping.cells_off_pattern, 0);
        assert!(capping.whole_pattern.is_none());
        let (broken, capping, notes_broken) = capped(false);
        println!("{pattern:?} broken: {broken:?} {capping:?}");
        assert!(broken.meet_floors(), "{broken:?}");
        let off = capping.cells_off_pattern;
        assert!(off > 0 && 5 * off <= broken.quads / 2, "{off}");
        let whole_there = capping.whole_pattern.expect("the pattern whole reported");
        assert!(!whole_there.meet_floors(), "{whole_there:?}");
        let says = |notes: &[String]| notes.iter().any(|n| n.contains("--quads-whole-pattern"));
        assert!(says(&notes_broken) && !says(&notes), "{notes_broken:?}");
    }
}

/// `--quads-reshape`: on the wave, whose zigzag cover's quads stay short of the floors with the
/// cells kept and the pattern whole, the vertices slide along S within their walls for flatter quads, the cells
/// re-shaped no further than the edge-length cv allowed: allowed far enough, the quads meet
/// the floors; held to a little, the slide is kept only as far as the cells stay that even. The
/// walls stay exact, the vertices within 0.1 mean edge lengths of S, and the trade is stated.
#[test]
fn a_capping_may_reshape_the_cells_for_flatter_quads() {
    use crate::generate::{design_surface, Shape};
    let surface = Surface::new(design_surface(Shape::Wave)).unwrap();
    let capped = |reshape: Option<f64>| {
        let mut options = crate::PipelineOptions::new(750);
        options.options.variant = whole_quads_variant(QuadPattern::Zigzag, reshape, true);
        let out = crate::pipeline(&surface, &options, &mut crate::Progress::silent()).unwrap();
        let m = measure(&out.honeycomb, &surface);
        let faces = written_quads(&out);
        let quads = out.report.quads.as_ref().expect("quads reported");
        let capping = quads.capping.clone().expect("capping reported");
        println!(
            "reshape {reshape:?}: delta_face {:.4}/{:.4}, edge cv {:.3} -> {:.3}, along S {:.2}, \
             closeness {:.3}, {} iterations",
            faces.delta_face_max,
            faces.delta_face_avg,
            capping.edge_length_cv_before,
            m.edge_length_cv,
            capping.along_s_max,
            m.closeness_max,
            capping.iterations
        );
        assert!(out.is_honeycomb());
        assert!(m.omega_max_deg < 1e-5 && m.delta_max < 1e-10, "{m:?}");
        assert_eq!(m.nonconvex_walls, 0);
        assert!(m.closeness_max <= 0.1 + 1e-9, "{}", m.closeness_max);
        assert_eq!(capping.reshape, reshape);
        assert!(
            m.edge_length_cv <= reshape.unwrap_or(0.12),
            "{}",
            m.edge_length_cv
        );
        (faces, capping, out.report.notes)
    };
    let (held, held_capping, notes) = capped(None);
    assert!(held.delta_face_max > 0.01, "{held:?}");
    assert!(held_capping.iterations <= 20, "{held_capping:?}");
    // Short of the floors with the cells kept, the note points to re-shaping them.
    let hint = |notes: &[String]| notes.iter().any(|n| n.contains("--quads-reshape"));
    assert!(hint(&notes), "{notes:?}");
    assert!(notes.iter().all(|n| !n.contains("  ")), "{notes:?}");
    let (little, _, notes) = capped(Some(0.3));
    assert!(little.delta_face_max <= held.delta_face_max, "{little:?}");
    assert!(!hint(&notes), "{notes:?}");
    let (slid, slid_capping, notes) = capped(Some(1.0));
    assert!(
        slid.delta_face_max <= 0.01 && slid.delta_face_avg <= 0.004,
        "{slid:?}"
    );
    // The cells moved along S, by edge lengths where the held ones barely moved.
    assert!(slid_capping.along_s_max > 1.0, "{slid_capping:?}");
    assert!(held_capping.along_s_max < 0.1, "{held_capping:?}");
    // It stops where the floors are met, short of the budget: the cells re-shape no further.
    assert!(slid_capping.iterations < 60, "{slid_capping:?}");
    let trade = notes.iter().find(|n| n.contains("the edge cv")).cloned();
    assert!(trade.is_some(), "{notes:?}");
}
