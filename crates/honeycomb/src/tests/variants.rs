//! The paper's variants end to end on generated surfaces: parallel meshes (Fig. 9) and
//! prescribed node axes (Fig. 10, 18), measured on the realized meshes.

use crate::analysis::{extruded_along_normals, shading_report};
use crate::generate::{lifted_hex_patch, Shape};
use crate::mesh::PolyMesh;
use crate::optimize::{optimize, shading_axes, AxesOptions, OptimizeOptions, ParallelOptions};
use crate::solve::SolverOptions;
use crate::structure::{axes_measures, measure, parallel_measures, AxesMeasures};
use crate::surface::Surface;
use crate::Vec3;
use std::time::Instant;

fn options(iterations: usize) -> OptimizeOptions {
    OptimizeOptions {
        solver: SolverOptions {
            max_iterations: iterations,
            ..SolverOptions::default()
        },
        ..OptimizeOptions::default()
    }
}

/// The paper's Figure 9 row: 6144 vertices, omega_max .073, delta_max 1.3e-5, 4 s.
#[test]
fn parallel_meshes_on_a_dome() {
    let (base, surface) = lifted_hex_patch(Shape::Dome, 6000);
    let opts = OptimizeOptions {
        parallel: Some(ParallelOptions::default()),
        ..options(10)
    };
    let start = Instant::now();
    let opt = optimize(&base, Some(&surface), &opts, &mut |_| {}).expect("optimize");
    let seconds = start.elapsed().as_secs_f64();
    let m = measure(&opt.honeycomb, &Surface::from_mesh(&surface).unwrap());
    let p = parallel_measures(&opt.honeycomb);
    println!(
        "parallel |V|={} it={} omega {:.2e}/{:.2e} delta {:.2e}/{:.2e} beta {:.2e}/{:.2e} depth {:.3}..{:.3} {:.2}s",
        opt.honeycomb.base.vertices.len(),
        opt.solve.iterations,
        m.omega_max_deg,
        m.omega_avg_deg,
        m.delta_max,
        m.delta_avg,
        p.beta_max_deg,
        p.beta_avg_deg,
        p.depth_min,
        p.depth_max,
        seconds
    );
    assert!((5500..6600).contains(&opt.honeycomb.base.vertices.len()));
    assert!(m.omega_max_deg < 0.05, "omega_max {}", m.omega_max_deg);
    assert!(m.delta_max < 1e-5, "delta_max {}", m.delta_max);
    assert!(p.beta_max_deg < 0.1, "beta_max {}", p.beta_max_deg);
    assert!(p.depth_min > 0.0);
}

/// Parallel meshes whose axes are not all parallel: on a cylinder with the axes guided towards
/// the normals, M' is a genuinely different (smaller or larger) cylinder mesh, not a translate.
#[test]
fn parallel_meshes_with_axes_across_a_vault() {
    let (base, surface) = lifted_hex_patch(Shape::Cylinder, 1500);
    let mut opts = OptimizeOptions {
        parallel: Some(ParallelOptions::default()),
        ..options(20)
    };
    opts.weights.guide = 3.0;
    opts.weights.fairness = 0.0;
    let opt = optimize(&base, Some(&surface), &opts, &mut |_| {}).expect("optimize");
    let m = measure(&opt.honeycomb, &Surface::from_mesh(&surface).unwrap());
    let p = parallel_measures(&opt.honeycomb);
    let axes = &opt.honeycomb.axes;
    let spread = axes
        .iter()
        .map(|a| crate::structure::angle_deg(*a, axes[0]))
        .fold(0.0, f64::max);
    println!(
        "parallel cylinder it={} omega {:.2e} delta {:.2e} beta {:.2e}/{:.2e} depth {:.3}..{:.3} axis spread {spread:.1} deg",
        opt.solve.iterations, m.omega_max_deg, m.delta_max, p.beta_max_deg, p.beta_avg_deg, p.depth_min, p.depth_max
    );
    assert!(spread > 20.0, "axes spread only {spread} deg: a translate");
    assert!(m.omega_max_deg < 0.05, "omega_max {}", m.omega_max_deg);
    assert!(m.delta_max < 1e-5, "delta_max {}", m.delta_max);
    assert!(p.beta_max_deg < 0.1, "beta_max {}", p.beta_max_deg);
}

#[test]
fn a_soft_constant_depth_is_reached() {
    let (base, surface) = lifted_hex_patch(Shape::Saddle, 1500);
    let opts = OptimizeOptions {
        parallel: Some(ParallelOptions {
            depth: Some(0.5),
            ..ParallelOptions::default()
        }),
        ..options(10)
    };
    let opt = optimize(&base, Some(&surface), &opts, &mut |_| {}).expect("optimize");
    let p = parallel_measures(&opt.honeycomb);
    println!(
        "depth {:.4}..{:.4} (wanted 0.5, mean edge {:.3})",
        p.depth_min, p.depth_max, opt.frame.unit
    );
    assert!((p.depth_min - 0.5).abs() < 1e-3 && (p.depth_max - 0.5).abs() < 1e-3);
    assert!(p.beta_max_deg < 0.1, "beta_max {}", p.beta_max_deg);
}

/// A uniform tilted axis field is reachable exactly (a hex grid that is regular seen along the
/// axis), so the soft prescribed-axes rows must bring every realized axis onto it.
#[test]
fn prescribed_axes_are_followed() {
    let (base, surface) = lifted_hex_patch(Shape::Dome, 1500);
    let target = Vec3::new(0.3, 0.0, 1.0);
    let plain = optimize(&base, Some(&surface), &options(10), &mut |_| {}).expect("optimize");
    let targets = vec![target; base.vertices.len()];
    let opts = OptimizeOptions {
        axes: Some(AxesOptions {
            targets: targets.clone(),
            weight: AxesOptions::DEFAULT_WEIGHT,
        }),
        ..options(10)
    };
    let opt = optimize(&base, Some(&surface), &opts, &mut |_| {}).expect("optimize");
    let before = axes_measures(&plain.honeycomb, &targets);
    let after = axes_measures(&opt.honeycomb, &targets);
    let m = measure(&opt.honeycomb, &Surface::from_mesh(&surface).unwrap());
    println!(
        "axes angle: plain {:.2}/{:.2} deg, prescribed {:.2e}/{:.2e} deg; omega {:.2e} delta {:.2e} closeness {:.2e}",
        before.axes_angle_max_deg, before.axes_angle_avg_deg, after.axes_angle_max_deg,
        after.axes_angle_avg_deg, m.omega_max_deg, m.delta_max, m.closeness_max
    );
    assert!(before.axes_angle_avg_deg > 10.0);
    assert!(after.axes_angle_max_deg < 0.5, "{after:?}");
    assert!(m.omega_max_deg < 0.01 && m.delta_max < 1e-6);
    assert_eq!(after.axes_prescribed, base.vertices.len());
}

/// The shading system (Fig. 18) on a 3.3k-vertex dome roof, sun 35 degrees above the horizon,
/// cells 1.2 edges deep: axes across the light cut the light that passes by more than half, and
/// the result stays a honeycomb. The axis field tilts the walls by up to 55 degrees from the
/// normals. Measured: it needs the minimum edge length (boundary cells collapse edges without
/// it), the lower axes weight 0.03 (the paper's 0.1 leaves delta_max 1.2e-3) and 15-20
/// iterations; a sun at 45 degrees still collapses boundary edges.
/// Shading (Fig. 18) on `subject`: the sun 35 degrees high along +x, cells 1.2 edge lengths
/// deep, axes prescribed across the light at the shading weight, 20 iterations.
fn shade(subject: (PolyMesh, PolyMesh), what: &str) -> AxesMeasures {
    let (base, surface) = subject;
    let s = Surface::from_mesh(&surface).unwrap();
    let elevation = 35f64.to_radians();
    let light = Vec3::new(elevation.cos(), 0.0, -elevation.sin());
    let targets = shading_axes(&s, &base.vertices, light).unwrap();
    let unit = base.mean_edge_length();
    let opts = OptimizeOptions {
        axes: Some(AxesOptions {
            targets: targets.clone(),
            weight: AxesOptions::SHADING_WEIGHT,
        }),
        min_edge: Some(0.3 * unit),
        thickness: Some(1.2 * unit),
        ..options(20)
    };
    let start = Instant::now();
    let opt = optimize(&base, Some(&surface), &opts, &mut |_| {}).expect("optimize");
    let seconds = start.elapsed().as_secs_f64();
    let m = measure(&opt.honeycomb, &s);
    let a = axes_measures(&opt.honeycomb, &targets);
    let before = extruded_along_normals(&base, &opt.connectivity, &s, opt.honeycomb.thickness);
    let noon = Vec3::new(0.0, 0.0, -1.0);
    let depth = opt.honeycomb.thickness;
    let report = shading_report(&before, &opt.honeycomb, depth, light, &[noon]);
    println!(
        "shading {what} |V|={} it={} omega {:.2e}/{:.2e} delta {:.2e}/{:.2e} axes {:.2}/{:.2} deg min edge {:.3} light {:.3} -> {:.3}, noon {:.3} -> {:.3}, {seconds:.2}s",
        base.vertices.len(), opt.solve.iterations, m.omega_max_deg, m.omega_avg_deg, m.delta_max,
        m.delta_avg, a.axes_angle_max_deg, a.axes_angle_avg_deg, m.min_edge_length / unit,
        report.light.before, report.light.after, report.sun_path[0].before, report.sun_path[0].after
    );
    assert!(m.omega_max_deg < 0.5, "omega_max {}", m.omega_max_deg);
    assert!(m.delta_max < 1e-3, "delta_max {}", m.delta_max);
    assert!(
        report.light.after < 0.5 * report.light.before,
        "light share {} -> {}",
        report.light.before,
        report.light.after
    );
    assert!(m.min_edge_length >= 0.3 * unit * (1.0 - 1e-6));
    a
}

#[test]
fn shading_blocks_the_design_light() {
    let a = shade(lifted_hex_patch(Shape::Dome, 3300), "dome");
    assert!(a.axes_angle_avg_deg < 2.0, "{a:?}");
}

/// The subject: a 3.3k-vertex roof (generate::roof, amplitude 0.08). Nearly level, its
/// cells already block much of a low sun when merely extruded; the prescribed axes cut what
/// passes by more than half again, and follow their targets less closely than on the dome.
#[test]
fn shading_on_a_roof() {
    let a = shade(crate::generate::roof(3300, 0.08), "roof");
    assert!(a.axes_angle_avg_deg < 5.0, "{a:?}");
}
