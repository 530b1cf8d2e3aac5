//! Tests of the assembled surface: queries against brute force, orientation, boundary.

use super::*;

/// Deterministic pseudo-random numbers in [0, 1) (SplitMix64).
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in the box `[lo, hi]`.
    fn in_box(&mut self, lo: Vec3, hi: Vec3) -> Vec3 {
        Vec3::new(
            lo.x + (hi.x - lo.x) * self.unit(),
            lo.y + (hi.y - lo.y) * self.unit(),
            lo.z + (hi.z - lo.z) * self.unit(),
        )
    }
}

/// An `n x n` grid of quads over `[0, size]^2` with `z = height(x, y)`, faces counterclockwise
/// seen from +z. Vertex `(i, j)` is `i + (n + 1) j`.
fn grid(n: usize, size: f64, height: impl Fn(f64, f64) -> f64) -> PolyMesh {
    let mut vertices = Vec::with_capacity((n + 1) * (n + 1));
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (size * i as f64 / n as f64, size * j as f64 / n as f64);
            vertices.push(Vec3::new(x, y, height(x, y)));
        }
    }
    let id = |i: usize, j: usize| i + (n + 1) * j;
    let mut faces = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            faces.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    PolyMesh::new(vertices, faces)
}

/// The bumpy height field of the brief: 40 x 40 quads, `z = 0.3 sin(x) cos(y)`.
fn bumpy() -> PolyMesh {
    grid(40, 6.0, |x, y| 0.3 * x.sin() * y.cos())
}

/// Closest point over all triangles, the slow way.
fn brute_force(s: &Surface, p: Vec3) -> f64 {
    s.triangles()
        .iter()
        .map(|&[a, b, c]| {
            let v = s.vertices();
            let (q, _) = closest_point_on_triangle(p, v[a], v[b], v[c]);
            (p - q).norm()
        })
        .fold(f64::INFINITY, f64::min)
}

fn face_normal(s: &Surface, t: usize) -> Vec3 {
    let [a, b, c] = s.triangles()[t].map(|v| s.vertices()[v]);
    (b - a).cross(c - a).normalized()
}

fn is_unit(v: Vec3) -> bool {
    (v.norm() - 1.0).abs() < 1e-12
}

#[test]
fn closest_point_matches_brute_force() {
    let s = Surface::from_mesh(&bumpy()).unwrap();
    assert_eq!(s.num_triangles(), 2 * 40 * 40);
    let mut rng = Rng(1);
    let (lo, hi) = (Vec3::new(-1.0, -1.0, -1.5), Vec3::new(7.0, 7.0, 1.5));
    let ps: Vec<Vec3> = (0..1000).map(|_| rng.in_box(lo, hi)).collect();
    for (p, c) in ps.iter().zip(s.closest_points(&ps)) {
        let exact = brute_force(&s, *p);
        assert!(
            (c.distance - exact).abs() < 1e-12,
            "{p:?}: {} vs {exact}",
            c.distance
        );
        assert!(((*p - c.point).norm() - c.distance).abs() < 1e-12);
        // The point lies on its triangle: the triangle's own closest point to it is itself.
        let [a, b, t] = s.triangles()[c.triangle].map(|v| s.vertices()[v]);
        assert!((closest_point_on_triangle(c.point, a, b, t).0 - c.point).norm() < 1e-12);
    }
}

#[test]
fn normals_are_unit_and_on_the_face_side() {
    let s = Surface::from_mesh(&bumpy()).unwrap();
    for n in s.vertex_normals() {
        assert!(is_unit(*n) && n.z > 0.0);
    }
    let mut rng = Rng(2);
    let (lo, hi) = (Vec3::new(-1.0, -1.0, -1.5), Vec3::new(7.0, 7.0, 1.5));
    for _ in 0..1000 {
        let c = s.closest_point(rng.in_box(lo, hi));
        assert!(is_unit(c.normal));
        assert!(c.normal.dot(face_normal(&s, c.triangle)) > 0.0);
        // The input faces point up, and so must the oriented surface.
        assert!(c.normal.z > 0.0);
        assert_eq!(s.normal_at(c.point), s.closest_point(c.point).normal);
    }
}

#[test]
fn normal_is_exact_on_a_plane_and_smooth_on_a_sphere_patch() {
    let plane = Surface::from_mesh(&grid(5, 1.0, |_, _| 0.0)).unwrap();
    for p in [
        Vec3::new(0.3, 0.7, 2.0),
        Vec3::new(-1.0, 0.0, -1.0),
        Vec3::new(1.0, 0.5, 0.0),
    ] {
        assert!((plane.normal_at(p) - Vec3::new(0.0, 0.0, 1.0)).norm() < 1e-15);
    }
    // On a fine patch of a unit sphere, the blended normal approximates the radial direction.
    let center = Vec3::new(0.5, 0.5, -1.0);
    let cap = grid(20, 1.0, |x, y| {
        -1.0 + (4.0 - (x - 0.5).powi(2) - (y - 0.5).powi(2)).sqrt()
    });
    let s = Surface::from_mesh(&cap).unwrap();
    let p = Vec3::new(0.37, 0.61, 1.2);
    let c = s.closest_point(p);
    let radial = (c.point - center).normalized();
    assert!(c.normal.dot(radial) > 1.0 - 1e-4);
}

#[test]
fn inconsistent_input_orientation_is_repaired() {
    let mut mesh = bumpy();
    for f in mesh.faces.iter_mut().step_by(7) {
        f.reverse();
    }
    let s = Surface::from_mesh(&mesh).unwrap();
    for t in 0..s.num_triangles() {
        assert!(face_normal(&s, t).z > 0.0, "triangle {t} still points down");
    }
    // Every interior edge is used once in each direction.
    let exported = s.mesh_for_export();
    let mut directed = std::collections::HashSet::new();
    for f in &exported.faces {
        for k in 0..3 {
            assert!(directed.insert((f[k], f[(k + 1) % 3])));
        }
    }
    // A fully reversed input keeps its (consistent) orientation.
    let mut down = bumpy();
    down.faces.iter_mut().for_each(|f| f.reverse());
    let s = Surface::from_mesh(&down).unwrap();
    assert!(s.normal_at(Vec3::new(3.0, 3.0, 5.0)).z < 0.0);
}

#[test]
fn bad_meshes_are_rejected() {
    let mobius = {
        // A strip of quads glued to itself with a half twist.
        let n = 12;
        let mut vertices = Vec::new();
        for k in 0..n {
            let phi = std::f64::consts::TAU * k as f64 / n as f64;
            let dir = Vec3::new(phi.cos(), phi.sin(), 0.0);
            let half = phi / 2.0;
            let across = dir * (0.3 * half.cos()) + Vec3::new(0.0, 0.0, 0.3 * half.sin());
            vertices.push(dir - across);
            vertices.push(dir + across);
        }
        let faces = (0..n)
            .map(|k| {
                let (a, b) = (2 * k, 2 * k + 1);
                let (c, d) = if k + 1 < n { (a + 2, b + 2) } else { (1, 0) };
                vec![a, c, d, b]
            })
            .collect();
        PolyMesh::new(vertices, faces)
    };
    let v = vec![Vec3::ZERO; 5];
    let cases = [
        mobius,
        PolyMesh::new(v.clone(), vec![]),
        PolyMesh::new(v.clone(), vec![vec![0, 1]]),
        PolyMesh::new(v.clone(), vec![vec![0, 1, 7]]),
        PolyMesh::new(v.clone(), vec![vec![0, 1, 2], vec![1, 0, 3], vec![0, 1, 4]]),
        PolyMesh::new(
            vec![Vec3::ZERO, Vec3::new(f64::NAN, 0.0, 0.0), Vec3::ZERO],
            vec![vec![0, 1, 2]],
        ),
    ];
    for (k, mesh) in cases.iter().enumerate() {
        assert!(
            matches!(Surface::from_mesh(mesh), Err(Error::Mesh(_))),
            "case {k} accepted"
        );
    }
}

#[test]
fn square_grid_boundary_is_one_loop() {
    let n = 10;
    let s = Surface::from_mesh(&grid(n, 1.0, |_, _| 0.0)).unwrap();
    assert!(s.has_boundary());
    assert_eq!(s.boundary_loops().len(), 1);
    let lp = &s.boundary_loops()[0];
    assert_eq!(lp.len(), 4 * n);
    for p in lp {
        let on_edge = p.x == 0.0 || p.x == 1.0 || p.y == 0.0 || p.y == 1.0;
        assert!(on_edge, "{p:?} is not on the boundary");
    }
    // The loop runs counterclockwise seen from the normal (+z): positive signed area.
    let area: f64 = (0..lp.len())
        .map(|k| lp[k].cross(lp[(k + 1) % lp.len()]).z / 2.0)
        .sum();
    assert!((area - 1.0).abs() < 1e-12);

    // A point outside the left side projects onto it, with a tangent along it.
    let b = s
        .closest_boundary_point(Vec3::new(-0.5, 0.33, 0.2))
        .unwrap();
    assert!((b.point - Vec3::new(0.0, 0.33, 0.0)).norm() < 1e-12);
    assert!((b.distance - (0.25f64 + 0.04).sqrt()).abs() < 1e-12);
    assert!(is_unit(b.tangent) && b.tangent.y.abs() > 1.0 - 1e-12);
    assert_eq!(b.loop_index, 0);
    // Inside, the nearest side is found too.
    let b = s.closest_boundary_point(Vec3::new(0.6, 0.93, 0.0)).unwrap();
    assert!((b.point - Vec3::new(0.6, 1.0, 0.0)).norm() < 1e-12);
    assert!(b.tangent.x.abs() > 1.0 - 1e-12);
}

#[test]
fn boundary_point_matches_brute_force_on_two_loops() {
    // An annulus-like grid with a hole: drop the middle quads of the bumpy field.
    let mut mesh = bumpy();
    let n = 40;
    mesh.faces.retain({
        let mut k = 0;
        move |_| {
            let (i, j) = (k % n, k / n);
            k += 1;
            !((15..25).contains(&i) && (15..25).contains(&j))
        }
    });
    let s = Surface::from_mesh(&mesh).unwrap();
    assert_eq!(s.boundary_loops().len(), 2);
    let mut lens: Vec<usize> = s.boundary_loops().iter().map(Vec::len).collect();
    lens.sort();
    assert_eq!(lens, vec![40, 160]);
    let segments: Vec<(Vec3, Vec3)> = s
        .boundary_loops()
        .iter()
        .flat_map(|lp| (0..lp.len()).map(move |k| (lp[k], lp[(k + 1) % lp.len()])))
        .collect();
    let mut rng = Rng(3);
    for _ in 0..500 {
        let p = rng.in_box(Vec3::new(-1.0, -1.0, -1.0), Vec3::new(7.0, 7.0, 1.0));
        let b = s.closest_boundary_point(p).unwrap();
        let exact = segments
            .iter()
            .map(|&(a, c)| (p - closest_point_on_segment(p, a, c).0).norm())
            .fold(f64::INFINITY, f64::min);
        assert!((b.distance - exact).abs() < 1e-12);
        assert!(is_unit(b.tangent));
        // The tangent is the direction of a segment through the point.
        let along = segments.iter().any(|&(a, c)| {
            (closest_point_on_segment(b.point, a, c).0 - b.point).norm() < 1e-12
                && ((c - a).normalized() - b.tangent).norm() < 1e-12
        });
        assert!(along);
    }
}

#[test]
fn closed_surface_has_no_boundary() {
    // An octahedron, with its faces given in mixed orientation.
    let v = vec![
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(-1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::new(0.0, -1.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(0.0, 0.0, -1.0),
    ];
    let faces = vec![
        vec![0, 2, 4],
        vec![2, 1, 4],
        vec![1, 3, 4],
        vec![3, 0, 4],
        vec![2, 0, 5],
        vec![2, 1, 5], // inward
        vec![1, 5, 3],
        vec![0, 5, 3], // inward
    ];
    let s = Surface::from_mesh(&PolyMesh::new(v, faces)).unwrap();
    assert!(!s.has_boundary());
    assert!(s.closest_boundary_point(Vec3::ZERO).is_none());
    for p in [
        Vec3::new(1.0, 1.0, 1.0),
        Vec3::new(-0.1, 0.2, -0.3),
        Vec3::new(0.0, 0.0, -3.0),
    ] {
        let c = s.closest_point(p);
        assert!(c.normal.dot(c.point) > 0.0, "normals point outward");
    }
    assert_eq!(
        s.bbox(),
        (Vec3::new(-1.0, -1.0, -1.0), Vec3::new(1.0, 1.0, 1.0))
    );
}

#[test]
fn degenerate_triangles_give_no_nan() {
    // A unit square cut into proper triangles around a zero-area sliver along the diagonal
    // (three collinear corners), plus a triangle with two coincident corners and one that
    // repeats a vertex index.
    let v = vec![
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::new(0.5, 0.5, 0.0), // on the diagonal 0-2
        Vec3::new(1.0, 1.0, 0.0), // a copy of vertex 2
    ];
    let faces = vec![
        vec![0, 1, 4],
        vec![4, 1, 2],
        vec![0, 4, 2], // the sliver
        vec![0, 2, 3],
        vec![2, 5, 3], // coincident corners 2 and 5
        vec![4, 4, 3], // repeated index: no edges, still part of the soup
    ];
    let s = Surface::from_mesh(&PolyMesh::new(v, faces)).unwrap();
    let mut rng = Rng(4);
    for _ in 0..2000 {
        let p = rng.in_box(Vec3::new(-0.5, -0.5, -0.5), Vec3::new(1.5, 1.5, 0.5));
        let c = s.closest_point(p);
        assert!(c.point.is_finite() && c.distance.is_finite());
        assert!(is_unit(c.normal) && c.normal.z > 0.0, "{p:?} -> {c:?}");
        assert!((c.distance - brute_force(&s, p)).abs() < 1e-12);
        if let Some(b) = s.closest_boundary_point(p) {
            assert!(b.point.is_finite() && is_unit(b.tangent));
        }
    }
    // Points exactly on the sliver and on its corners.
    for p in [
        Vec3::new(0.5, 0.5, 0.0),
        Vec3::new(0.25, 0.25, 1.0),
        Vec3::new(1.0, 1.0, 0.0),
    ] {
        let c = s.closest_point(p);
        assert!(is_unit(c.normal) && c.point.is_finite());
    }
}

#[test]
fn polygons_are_triangulated() {
    // A unit hexagon next to a square, sharing an edge.
    let mut v: Vec<Vec3> = (0..6)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 6.0;
            Vec3::new(a.cos(), a.sin(), 0.0)
        })
        .collect();
    // Square on the hexagon edge 0-1, outside it.
    let e = v[1] - v[0];
    let out = Vec3::new(e.y, -e.x, 0.0);
    v.push(v[0] + out);
    v.push(v[1] + out);
    let faces = vec![vec![0, 1, 2, 3, 4, 5], vec![0, 6, 7, 1]];
    let s = Surface::from_mesh(&PolyMesh::new(v.clone(), faces)).unwrap();
    // The hexagon becomes a star of 6 around an added centroid, the square two triangles.
    assert_eq!(s.num_triangles(), 6 + 2);
    let exported = s.mesh_for_export();
    assert_eq!(exported.vertices[..8], v[..]);
    assert_eq!(exported.vertices.len(), 9);
    assert!(exported.faces.iter().all(|f| f.len() == 3));
    // The hexagon is covered: its interior points are on S.
    for p in [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(-0.6, 0.3, 0.0),
        Vec3::new(0.2, -0.8, 0.0),
    ] {
        assert!(s.closest_point(p).distance < 1e-15);
    }
    assert_eq!(s.boundary_loops().len(), 1);
    assert_eq!(s.boundary_loops()[0].len(), 8);
}

/// Timing on 200k triangles: `cargo test -p honeycomb --release --lib surface::tests::large -- --ignored --nocapture`.
#[test]
#[ignore]
fn large_mesh_timing() {
    let n = 317; // 2 * 317^2 = 200978 triangles
    let mesh = grid(n, 10.0, |x, y| 0.5 * (2.0 * x).sin() * (1.5 * y).cos());
    let t0 = std::time::Instant::now();
    let s = Surface::from_mesh(&mesh).unwrap();
    let t_all = t0.elapsed();
    let mut tris = s.triangles().to_vec();
    let t0 = std::time::Instant::now();
    let bvh = Bvh::build(&mut tris, |t| {
        let [a, b, c] = t.map(|v| s.vertices()[v]);
        (a.min(b).min(c), a.max(b).max(c))
    });
    let t_bvh = t0.elapsed();
    assert!(bvh.bounds().is_some());

    // Queries in random order: the worst case for caches.
    let time = |ps: &[Vec3]| {
        let t0 = std::time::Instant::now();
        let cs = s.closest_points(ps);
        (t0.elapsed() / ps.len() as u32, cs)
    };
    let mut rng = Rng(5);
    let ps: Vec<Vec3> = (0..200_000)
        .map(|_| rng.in_box(Vec3::new(-0.5, -0.5, -1.0), Vec3::new(10.5, 10.5, 1.0)))
        .collect();
    let (t_box, cs) = time(&ps);
    let near: Vec<Vec3> = cs.iter().map(|c| c.point + c.normal * 0.01).collect();
    let (t_near, _) = time(&near);
    // Near the surface in row order, like the nodes of a mesh lying on it.
    let m = 450;
    let rows: Vec<Vec3> = (0..m * m)
        .map(|k| {
            let (x, y) = (
                10.0 * (k % m) as f64 / m as f64,
                10.0 * (k / m) as f64 / m as f64,
            );
            Vec3::new(x, y, 0.5 * (2.0 * x).sin() * (1.5 * y).cos() + 0.01)
        })
        .collect();
    let (t_rows, _) = time(&rows);
    let t0 = std::time::Instant::now();
    let nb = ps
        .iter()
        .filter_map(|&p| s.closest_boundary_point(p))
        .count();
    let t_boundary = t0.elapsed() / ps.len() as u32;
    println!(
        "{} triangles: from_mesh {t_all:?}, BVH build {t_bvh:?}; per query: random in box \
         {t_box:?}, random near surface {t_near:?}, near surface in row order {t_rows:?}, \
         boundary {t_boundary:?}",
        s.num_triangles()
    );
    assert_eq!(nb, ps.len());
}
