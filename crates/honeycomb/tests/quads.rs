//! Quadrangulation (paper section 4, Figs. 1, 11, 17): honeycombs capped by planar quads.

use honeycomb::generate::{hex_disk, lifted_hex_patch, Shape};
use honeycomb::mesh::PolyMesh;
use honeycomb::optimize::{optimize, OptimizeOptions, Optimized, QuadOptions, QuadPattern};
use honeycomb::solve::SolverOptions;
use honeycomb::structure::{face_measures, measure, FaceMeasures, Measures, QuadCover};
use honeycomb::surface::Surface;
use honeycomb::Vec3;
use std::time::Instant;

/// The "roof": an undulating rectangular sheet, twice as long as wide, in the spirit of the
/// Cour Visconti roof (Fig. 1): one and a half waves along its length, a half wave across, so
/// that it has both dome-like and saddle-like regions (|V| about `vertices`, edge length 1,
/// curvature radii down to about 25 edge lengths).
fn roof(vertices: usize) -> (PolyMesh, PolyMesh) {
    // A hexagon of edge 1 has area 3 sqrt(3) / 2 and about two vertices.
    let area = vertices as f64 / 2.0 * 1.5 * 3f64.sqrt();
    let (a, b) = ((area / 2.0).sqrt(), (area / 8.0).sqrt());
    let height = |x: f64, y: f64| {
        let (u, v) = (x / a, y / b);
        0.12 * a * (1.5 * std::f64::consts::PI * u).sin() * (0.5 * std::f64::consts::PI * v).cos()
            - 0.05 * a * u * v
    };
    let disk = hex_disk(1.05 * (a * a + b * b).sqrt());
    let inside = |f: &Vec<usize>| {
        let c = f.iter().fold(Vec3::ZERO, |s, &v| s + disk.vertices[v]) / f.len() as f64;
        c.x.abs() <= a && c.y.abs() <= b
    };
    let mut index = vec![usize::MAX; disk.vertices.len()];
    let mut vs = Vec::new();
    let mut faces = Vec::new();
    for f in disk.faces.iter().filter(|f| inside(f)) {
        faces.push(
            f.iter()
                .map(|&v| {
                    if index[v] == usize::MAX {
                        index[v] = vs.len();
                        let p = disk.vertices[v];
                        vs.push(Vec3::new(p.x, p.y, height(p.x, p.y)));
                    }
                    index[v]
                })
                .collect(),
        );
    }
    // The design surface: a fine grid over the sheet with a margin, counter-clockwise from +z.
    let n = 200;
    let (ha, hb) = (1.1 * a + 2.0, 1.1 * b + 2.0);
    let mut sv = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let x = -ha + 2.0 * ha * i as f64 / n as f64;
            let y = -hb + 2.0 * hb * j as f64 / n as f64;
            sv.push(Vec3::new(x, y, height(x, y)));
        }
    }
    let id = |i: usize, j: usize| j * (n + 1) + i;
    let mut tris = Vec::new();
    for j in 0..n {
        for i in 0..n {
            tris.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            tris.push(vec![id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    (PolyMesh::new(vs, faces), PolyMesh::new(sv, tris))
}

struct Run {
    opt: Optimized,
    honeycomb: Measures,
    faces: FaceMeasures,
    initial_faces: FaceMeasures,
    seconds: f64,
}

#[derive(Clone, Copy, Debug)]
enum Subject {
    Patch(Shape),
    Roof,
}

fn run(subject: Subject, vertices: usize, iterations: usize, quads: QuadOptions) -> Run {
    run_with(subject, vertices, iterations, quads, 1.0)
}

fn run_with(
    subject: Subject,
    vertices: usize,
    iterations: usize,
    quads: QuadOptions,
    closeness: f64,
) -> Run {
    let (base, surface) = match subject {
        Subject::Patch(shape) => lifted_hex_patch(shape, vertices),
        Subject::Roof => roof(vertices),
    };
    let options = OptimizeOptions {
        solver: SolverOptions {
            max_iterations: iterations,
            eps: env("EPS", 1e-3),
            ..SolverOptions::default()
        },
        quads: Some(quads.clone()),
        weights: honeycomb::optimize::Weights {
            closeness,
            fairness: env("FW", 3.0),
            ..Default::default()
        },
        ..OptimizeOptions::default()
    };
    let start = Instant::now();
    let opt = optimize(&base, Some(&surface), &options, &mut |_| {}).expect("optimize");
    let seconds = start.elapsed().as_secs_f64();
    let honeycomb = measure(&opt.honeycomb, &Surface::from_mesh(&surface).unwrap());
    let cover = opt.quad_cover.as_ref().expect("quad cover");
    let quad_mesh = opt.quads.as_ref().expect("quad mesh");
    assert_eq!(quad_mesh.vertices, opt.honeycomb.base.vertices);
    for (f, q) in quad_mesh.faces.iter().zip(&cover.quads) {
        assert_eq!(f.as_slice(), q.as_slice());
    }
    let faces = face_measures(&quad_mesh.vertices, &cover.quads);
    let initial_faces = face_measures(&base.vertices, &cover.quads);
    println!(
        "{subject:?} {:?} |V|={} it={} T={seconds:.3}s | delta_face {:.2e}/{:.2e} (initially \
         {:.2e}/{:.2e}) | omega {:.2e}/{:.2e} deg | delta {:.2e}/{:.2e} | closeness {:.2e}/{:.2e}",
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
    if std::env::var("VERBOSE").is_ok() {
        for h in &opt.solve.history {
            println!("  {h:?}");
        }
        for f in &opt.solve.families {
            println!("  {f:?}");
        }
    }
    Run {
        opt,
        honeycomb,
        faces,
        initial_faces,
        seconds,
    }
}

#[test]
#[ignore]
fn explore_plain() {
    let (base, surface) = roof(3500);
    let no_fair = QuadOptions {
        w_fair_zigzag: 0.0,
        w_fair_straight: 0.0,
        ..QuadOptions::default()
    };
    let no_zig = QuadOptions {
        w_fair_zigzag: 0.0,
        ..QuadOptions::default()
    };
    let no_str = QuadOptions {
        w_fair_straight: 0.0,
        ..QuadOptions::default()
    };
    for quads in [
        None,
        Some(QuadOptions::default()),
        Some(no_fair),
        Some(no_zig),
        Some(no_str),
    ] {
        let options = OptimizeOptions {
            solver: SolverOptions {
                max_iterations: 5,
                ..SolverOptions::default()
            },
            quads,
            ..OptimizeOptions::default()
        };
        let start = Instant::now();
        let opt = optimize(&base, Some(&surface), &options, &mut |_| {}).expect("optimize");
        let s = &opt.solve;
        println!(
            "T={:.3} symbolic {:.3} assembly {:.3} factor {:.3} other {:.3} unknowns {} nnz {} factor_nnz {}",
            start.elapsed().as_secs_f64(),
            s.seconds_symbolic,
            s.seconds_assembly,
            s.seconds_factorization,
            s.seconds_other,
            s.unknowns,
            s.matrix_nnz,
            s.factor_nnz
        );
        for h in &s.history {
            println!("  {h:?}");
        }
        if std::env::var("ONE").is_ok() {
            break;
        }
    }
}

fn env(name: &str, default: f64) -> f64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

#[test]
#[ignore]
fn explore() {
    let subject = match std::env::var("SUBJ").as_deref() {
        Ok("dome") => Subject::Patch(Shape::Dome),
        Ok("saddle") => Subject::Patch(Shape::Saddle),
        _ => Subject::Roof,
    };
    let pattern = match std::env::var("PAT").as_deref() {
        Ok("alt") => QuadPattern::Alternating,
        _ => QuadPattern::Zigzag,
    };
    let its: Vec<usize> = std::env::var("IT")
        .map(|v| v.split(',').filter_map(|t| t.parse().ok()).collect())
        .unwrap_or(vec![5, 10]);
    for it in its {
        run_with(
            subject,
            3500,
            it,
            QuadOptions {
                pattern,
                w_cons_faces: env("QW", 0.1),
                w_fair_zigzag: env("ZW", 0.01),
                w_fair_straight: env("SW", 0.01),
                direction: std::env::var("DIR").ok().map(|_| {
                    let t = env("DIR", 0.0).to_radians();
                    Vec3::new(t.cos(), t.sin(), 0.0)
                }),
                ..QuadOptions::default()
            },
            env("CW", 1.0),
        );
    }
}
