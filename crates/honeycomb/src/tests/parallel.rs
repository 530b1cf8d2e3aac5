//! Parallel meshes M, M' (paper section 4, Fig. 9) that the pipeline pairs on the walls of its
//! honeycomb across S.

use crate::generate::{design_surface, hex_disk, Shape};
use crate::mesh::Connectivity;
use crate::optimize::{pair, realized_normals, ParallelOptions};
use crate::solve::SolverOptions;
use crate::structure::{betas_deg, measure, Honeycomb};
use crate::surface::Surface;
use crate::{pipeline, PipelineOptions, Progress, Variant, Vec3, Walls};

fn parallel() -> Variant {
    Variant::Parallel {
        depth: None,
        w_parallel: None,
        w_depth: None,
    }
}

/// The angle of every edge of M to its twin in M' (degrees), from the meshes.
fn betas(h: &Honeycomb) -> Vec<f64> {
    betas_deg(&h.base.vertices, &h.offset.vertices, &h.edges).collect()
}

/// On every generated surface the pipeline's parallel meshes stand on walls across S: the
/// honeycomb exact, every wall a planar quad between an edge and its twin, the twins parallel
/// to their edges within half a degree, M on S.
#[test]
fn pipeline_pairs_parallel_meshes_on_walls_across() {
    for shape in [Shape::Dome, Shape::Saddle, Shape::Wave, Shape::Cylinder] {
        let surface = Surface::new(design_surface(shape)).unwrap();
        let mut options = PipelineOptions::new(750);
        options.options.variant = parallel();
        let out = pipeline(&surface, &options, &mut Progress::silent()).unwrap();
        let h = &out.honeycomb;
        let m = measure(h, &surface);
        let betas = betas(h);
        let beta_max = betas.iter().copied().fold(0.0, f64::max);
        let beta_avg = betas.iter().sum::<f64>() / betas.len() as f64;
        let depths: Vec<f64> = h.depths().collect();
        let (shallowest, deepest) = depths.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &d| {
            (lo.min(d), hi.max(d))
        });
        println!(
            "{shape:?}: beta {beta_max:.3}/{beta_avg:.4} deg, omega {:.1e}, delta {:.1e}, \
             closeness {:.4}, depth {shallowest:.3}..{deepest:.3} (thickness {:.3}), axes \
             {:.2} against {:.2} deg, {} iterations",
            m.omega_max_deg,
            m.delta_max,
            m.closeness_max,
            h.thickness,
            m.axis_normal_deg.mean,
            m.parallel_baseline_deg.mean,
            out.report.iterations_total
        );
        assert!(out.is_honeycomb(), "{shape:?}");
        assert_eq!(out.report.walls, Walls::Across);
        assert!(m.omega_max_deg < 0.05 && m.delta_max < 1e-5, "{m:?}");
        assert_eq!(m.nonconvex_walls, 0);
        assert!(beta_max <= 0.5, "{shape:?}: beta_max {beta_max}");
        assert!(beta_avg <= 0.05, "{shape:?}: beta_avg {beta_avg}");
        let reported = out.report.parallel.as_ref().expect("beta reported");
        assert!((reported.beta_max_deg - beta_max).abs() < 1e-9);
        assert!(m.closeness_max <= 0.1, "{shape:?}: {}", m.closeness_max);
        assert!(shallowest > 0.5 * h.thickness && deepest < 2.0 * h.thickness);
        assert!(
            m.axis_normal_deg.mean < 0.7 * m.parallel_baseline_deg.mean,
            "{m:?}"
        );
    }
}

/// Node axes all parallel (vertical walls on a flat grid) pair exactly: M' is M moved along
/// the axes by the depth asked, and M stays where it was.
#[test]
fn parallel_axes_pair_as_a_translation() {
    let mut base = hex_disk(6.0);
    for p in &mut base.vertices {
        // A gentle tilt, so that the axes are not the grid's normals.
        p.z = 0.1 * p.x;
    }
    let conn = Connectivity::build(&base).unwrap();
    let up = Vec3::new(0.0, 0.0, 1.0);
    let honeycomb = Honeycomb::new(base.clone(), &conn, vec![up; base.vertices.len()], 0.4);
    let options = ParallelOptions {
        depth: Some(0.7),
        ..ParallelOptions::default()
    };
    let normals = realized_normals(&honeycomb, &conn);
    let solver = SolverOptions::default();
    let out = pair(&honeycomb, &conn, &normals, &options, &solver, &mut |_| {}).unwrap();
    for (v, (&p, &q)) in out.vertices.iter().zip(&out.offset).enumerate() {
        assert!((p - base.vertices[v]).norm() < 1e-9, "vertex {v} moved");
        assert!((q - (p + up * 0.7)).norm() < 1e-9, "twin {v} off");
    }
    let m = crate::mesh::PolyMesh::new(out.vertices, base.faces.clone());
    let h = Honeycomb::with_offset(m, &conn, out.offset);
    assert!(betas(&h).iter().all(|&b| b < 1e-6));
}
