//! End to end: hex meshes lifted onto analytic surfaces become honeycombs.

use honeycomb::generate::{lifted_hex_patch, Shape};
use honeycomb::optimize::{optimize, OptimizeOptions};
use honeycomb::solve::SolverOptions;
use honeycomb::structure::{measure, quad_planarity, Measures};
use honeycomb::surface::Surface;

fn run(shape: Shape, vertices: usize) -> (Measures, usize) {
    let (base, surface) = lifted_hex_patch(shape, vertices);
    let options = OptimizeOptions {
        solver: SolverOptions {
            max_iterations: 10,
            ..SolverOptions::default()
        },
        ..OptimizeOptions::default()
    };
    let opt = optimize(&base, Some(&surface), &options, &mut |_| {}).expect("optimize");
    let m = measure(&opt.honeycomb, &Surface::from_mesh(&surface).unwrap());
    println!(
        "{shape:?} |V|={} it={} omega {:.2e}/{:.2e} delta {:.2e}/{:.2e} closeness {:.2e}",
        opt.honeycomb.base.vertices.len(),
        opt.solve.iterations,
        m.omega_max_deg,
        m.omega_avg_deg,
        m.delta_max,
        m.delta_avg,
        m.closeness_max
    );
    (m, opt.honeycomb.base.vertices.len())
}

fn assert_honeycomb(shape: Shape) {
    let (m, nv) = run(shape, 1500);
    assert!((1300..1800).contains(&nv), "{nv} vertices");
    assert!(
        m.omega_max_deg < 0.01,
        "{shape:?}: omega_max {} deg",
        m.omega_max_deg
    );
    assert!(m.delta_max < 1e-6, "{shape:?}: delta_max {}", m.delta_max);
    assert!(
        m.closeness_max < 0.05,
        "{shape:?}: closeness_max {}",
        m.closeness_max
    );
    assert_eq!(
        m.valence_histogram.keys().copied().collect::<Vec<_>>(),
        vec![2, 3]
    );
}

#[test]
fn saddle_becomes_a_honeycomb_in_ten_iterations() {
    assert_honeycomb(Shape::Saddle);
}

#[test]
fn dome_becomes_a_honeycomb_in_ten_iterations() {
    assert_honeycomb(Shape::Dome);
}

#[test]
fn cylinder_becomes_a_honeycomb_in_ten_iterations() {
    assert_honeycomb(Shape::Cylinder);
}

#[test]
fn the_initial_mesh_is_far_from_a_honeycomb() {
    // Guards the tests above against measuring nothing: before optimization a lifted hex grid
    // on a dome has visibly non-120-degree nodes and non-planar walls.
    let (base, surface) = lifted_hex_patch(Shape::Dome, 1500);
    let options = OptimizeOptions {
        solver: SolverOptions {
            max_iterations: 1,
            eps: 1e3,
            ..SolverOptions::default()
        },
        ..OptimizeOptions::default()
    };
    let opt = optimize(&base, Some(&surface), &options, &mut |_| {}).unwrap();
    let m = measure(&opt.honeycomb, &Surface::from_mesh(&surface).unwrap());
    assert!(m.delta_max > 1e-3 || m.omega_max_deg > 0.1, "{m:?}");
}

#[test]
fn planarity_measures_the_distance_of_the_diagonals() {
    use honeycomb::geometry::Vec3;
    let quad = [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(0.0, 0.1, 1.0),
    ];
    // The diagonals' lines are 0.1 / |(-0.1, -2, 0.1)| = 0.04994 apart; mean edge 1.0025.
    let d = quad_planarity(quad);
    assert!((d - 0.04994 / 1.0025).abs() < 1e-4, "{d}");
}
