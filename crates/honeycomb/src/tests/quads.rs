//! Quadrangulation (paper section 4, Figs. 1, 11, 17): honeycombs capped by planar quads.

use crate::generate::roof;
use crate::optimize::{optimize, OptimizeOptions, Optimized, QuadOptions, QuadPattern, Weights};
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
}

/// Optimizes the roof capped by quads for 5 iterations (the paper's Figure 16 row) and measures
/// the realized quads, before and after.
fn run(amplitude: f64, quads: QuadOptions, closeness: f64) -> Run {
    let (base, surface) = roof(3500, amplitude);
    let options = OptimizeOptions {
        solver: SolverOptions {
            max_iterations: 5,
            ..SolverOptions::default()
        },
        quads: Some(quads.clone()),
        weights: Weights {
            closeness,
            ..Weights::default()
        },
        ..OptimizeOptions::default()
    };
    let start = Instant::now();
    let opt = optimize(&base, Some(&surface), &options, &mut |_| {}).expect("optimize");
    let seconds = start.elapsed().as_secs_f64();
    let honeycomb = measure(&opt.honeycomb, &Surface::from_mesh(&surface).unwrap());
    let cover = opt.quad_cover.as_ref().expect("quad cover");
    let quad_mesh = opt.quads.as_ref().expect("quad mesh");
    // The quad mesh is M itself, its split quads first.
    assert_eq!(quad_mesh.vertices, opt.honeycomb.base.vertices);
    for (f, q) in quad_mesh.faces.iter().zip(&cover.quads) {
        assert_eq!(f.as_slice(), q.as_slice());
    }
    let faces = face_measures(&quad_mesh.vertices, &cover.quads);
    let initial_faces = face_measures(&base.vertices, &cover.quads);
    println!(
        "{:?} |V|={} it={} T={seconds:.3}s | delta_face {:.2e}/{:.2e} (initially {:.2e}/{:.2e}) \
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
    }
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

/// Figure 11 with the paper's weights (w_cons^faces 0.1, fairness 0.01, 5 iterations), closeness
/// loosened to 0.1 as the quads need the vertices to leave S a little: a honeycomb whose quads
/// are flatter than the ones it started with, within the paper's .007 / .003. The gain is small
/// (about 4%): a honeycomb hugging S has about one degree of freedom per cell left and planar
/// quads ask for two, so flatter quads need the vertices to leave S or the cells to change
/// shape across the whole roof, and the paper's small weights do neither in 5 iterations.
#[test]
fn zigzag_quads_on_a_roof() {
    let r = run(0.08, QuadOptions::default(), 0.1);
    assert_every_hexagon_split(&r.opt);
    assert!(
        r.honeycomb.omega_max_deg < 0.1,
        "{}",
        r.honeycomb.omega_max_deg
    );
    assert!(r.honeycomb.delta_max < 1e-5, "{}", r.honeycomb.delta_max);
    assert!(r.faces.delta_face_max < 0.01, "{:?}", r.faces);
    assert!(r.faces.delta_face_avg < 0.003, "{:?}", r.faces);
    assert!(
        r.faces.delta_face_avg < 0.97 * r.initial_faces.delta_face_avg,
        "{:?} {:?}",
        r.faces,
        r.initial_faces
    );
    assert!(
        r.honeycomb.closeness_max < 0.05,
        "{}",
        r.honeycomb.closeness_max
    );
}

/// Figure 17's herringbone on the more curved roof, planarity weighted 0.3: its quads lean
/// opposite ways in neighbouring strips, and come out twice as flat as they started.
#[test]
fn alternating_quads_on_a_curved_roof() {
    let quads = QuadOptions {
        pattern: QuadPattern::Alternating,
        w_cons_faces: 0.3,
        ..QuadOptions::default()
    };
    let r = run(0.12, quads, 0.1);
    assert_every_hexagon_split(&r.opt);
    assert!(
        r.honeycomb.omega_max_deg < 0.1,
        "{}",
        r.honeycomb.omega_max_deg
    );
    assert!(
        r.faces.delta_face_avg < 0.6 * r.initial_faces.delta_face_avg,
        "{:?} {:?}",
        r.faces,
        r.initial_faces
    );
    assert!(r.faces.delta_face_max < 0.01, "{:?}", r.faces);
}

/// A prescribed direction picks the straight class: the diagonals of a zigzag cover run along
/// it, whichever of the three lattice directions is asked for.
#[test]
fn the_straight_direction_follows_the_request() {
    let (base, surface) = roof(600, 0.08);
    for degrees in [30.0f64, 90.0, 150.0, 0.0] {
        let t = degrees.to_radians();
        let direction = Vec3::new(t.cos(), t.sin(), 0.0);
        let options = OptimizeOptions {
            solver: SolverOptions {
                max_iterations: 1,
                ..SolverOptions::default()
            },
            quads: Some(QuadOptions {
                direction: Some(direction),
                ..QuadOptions::default()
            }),
            ..OptimizeOptions::default()
        };
        let opt = optimize(&base, Some(&surface), &options, &mut |_| {}).unwrap();
        let cover = opt.quad_cover.unwrap();
        // The lattice's edge directions are 30, 90 and 150 degrees (hex_disk, pointy side up):
        // the diagonals are parallel to the class closest to the request (0 is 30 degrees from
        // two of them).
        let mut cosines = Vec::new();
        for [p, q] in cover.diagonals.iter().flatten() {
            let d = (base.vertices[*q] - base.vertices[*p]).normalized();
            cosines.push(d.dot(direction).abs());
        }
        let mean = cosines.iter().sum::<f64>() / cosines.len() as f64;
        let expected = if degrees == 0.0 { 0.85 } else { 0.97 };
        assert!(mean > expected, "{degrees}: mean |cos| {mean}");
    }
}
