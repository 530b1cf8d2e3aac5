//! Wall translations keep a honeycomb a honeycomb.

use super::guided_to_the_normals;
use crate::edit::{reciprocal, resize_cell, subdivide, translate_walls};
use crate::generate::{lifted_hex_patch, Shape};
use crate::mesh::Connectivity;
use crate::optimize::{optimize, OptimizeOptions};
use crate::structure::{measure, Honeycomb};
use crate::surface::Surface;

fn honeycomb() -> (Honeycomb, Connectivity, Surface) {
    let (base, surface) = lifted_hex_patch(Shape::Dome, 600);
    let opt = optimize(
        &base,
        Some(&surface),
        &OptimizeOptions::default(),
        &mut |_| {},
    )
    .unwrap();
    (
        opt.honeycomb,
        opt.connectivity,
        Surface::from_mesh(&surface).unwrap(),
    )
}

/// A honeycomb whose axes all differ: walls across a cylinder (guided towards its normals).
fn tilted_honeycomb() -> (Honeycomb, Connectivity, Surface) {
    let (base, surface) = lifted_hex_patch(Shape::Cylinder, 600);
    let options = guided_to_the_normals();
    let opt = optimize(&base, Some(&surface), &options, &mut |_| {}).unwrap();
    (
        opt.honeycomb,
        opt.connectivity,
        Surface::from_mesh(&surface).unwrap(),
    )
}

/// A hexagon all of whose corners are trivalent, nearest the middle.
fn middle_cell(h: &Honeycomb, conn: &Connectivity) -> usize {
    let c = h.base.centroid();
    (0..h.base.faces.len())
        .filter(|&f| h.base.faces[f].len() == 6)
        .filter(|&f| h.base.faces[f].iter().all(|&v| conn.valence(v) == 3))
        .min_by(|&a, &b| {
            let d = |f: usize| {
                (h.base.faces[f]
                    .iter()
                    .fold(c * 0.0, |s, &v| s + h.base.vertices[v])
                    / 6.0
                    - c)
                    .norm()
            };
            d(a).total_cmp(&d(b))
        })
        .unwrap()
}

fn perimeter(h: &Honeycomb, f: usize) -> f64 {
    let face = &h.base.faces[f];
    (0..face.len())
        .map(|k| (h.base.vertices[face[k]] - h.base.vertices[face[(k + 1) % face.len()]]).norm())
        .sum()
}

#[test]
fn resizing_a_cell_keeps_every_node_and_wall() {
    let (h, conn, s) = honeycomb();
    let cell = middle_cell(&h, &conn);
    let before = measure(&h, &s);
    let resized = resize_cell(&h, &conn, cell, 0.2).unwrap();
    let after = measure(&resized, &s);
    let corners = &h.base.faces[cell];
    let mut moved = 0;
    for v in 0..h.base.vertices.len() {
        let d = (resized.base.vertices[v] - h.base.vertices[v]).norm();
        if corners.contains(&v) {
            assert!(d > 0.1, "corner {v} moved only {d}");
            moved += 1;
        } else {
            assert_eq!(d, 0.0, "vertex {v} is not a corner of the cell but moved");
            // Up to roundoff: a neighbour's edge to a moved corner turns within its wall.
            assert!(
                (after.omega_per_node[v] - before.omega_per_node[v]).abs() < 1e-12,
                "node {v}"
            );
        }
        assert!(
            (after.omega_per_node[v] - before.omega_per_node[v]).abs() < 1e-9,
            "node {v}"
        );
    }
    assert_eq!(moved, 6);
    assert!(after.delta_max < 1e-9, "delta_max {}", after.delta_max);
    // Walls away from the cell's corners keep their planarity exactly.
    for (e, &[a, b]) in h.edges.iter().enumerate() {
        if !corners.contains(&a) && !corners.contains(&b) {
            assert_eq!(
                after.delta_per_wall[e], before.delta_per_wall[e],
                "wall {e}"
            );
        }
    }
    // The axes keep their directions, and the cell shrank: its walls moved 0.2 inwards, so each
    // side shortens by 2 * 0.2 / tan(60 deg).
    assert_eq!(resized.axes, h.axes);
    let shrink = perimeter(&h, cell) - perimeter(&resized, cell);
    let expected = 6.0 * 2.0 * 0.2 / 3f64.sqrt();
    assert!(
        (shrink - expected).abs() < 0.05 * expected,
        "{shrink} vs {expected}"
    );
    // Growing back restores the honeycomb.
    let back = resize_cell(&resized, &conn, cell, -0.2).unwrap();
    let err = back
        .base
        .vertices
        .iter()
        .zip(&h.base.vertices)
        .map(|(a, b)| (*a - *b).norm())
        .fold(0.0, f64::max);
    assert!(err < 1e-9, "{err}");
}

#[test]
fn a_translation_breaking_the_sum_rule_is_refused_with_its_nodes() {
    let (h, conn, _) = honeycomb();
    // Move a single interior wall: both of its end nodes lose their common axis.
    let e = (0..h.edges.len())
        .find(|&e| h.edges[e].iter().all(|&v| conn.valence(v) == 3))
        .unwrap();
    let mut lambda = vec![0.0; h.edges.len()];
    lambda[e] = 0.1;
    let err = translate_walls(&h, &conn, &lambda).unwrap_err().to_string();
    let [a, b] = h.edges[e];
    assert!(err.contains("2 node(s)"), "{err}");
    assert!(
        err.contains(&format!("node {a} ")) && err.contains(&format!("node {b} ")),
        "{err}"
    );
}

#[test]
fn an_inverting_resize_and_a_missing_cell_are_refused() {
    let (h, conn, _) = honeycomb();
    let cell = middle_cell(&h, &conn);
    let err = resize_cell(&h, &conn, cell, 3.0).unwrap_err().to_string();
    assert!(err.contains("turns edge"), "{err}");
    let err = resize_cell(&h, &conn, 1_000_000, 0.1)
        .unwrap_err()
        .to_string();
    assert!(err.contains("does not exist"), "{err}");
}

#[test]
fn subdivision_quadruples_the_cells_and_keeps_angles_and_the_spherical_image() {
    let (h, conn, s) = tilted_honeycomb();
    let before = measure(&h, &s);
    let interior_walls = (0..h.edges.len())
        .filter(|&e| !conn.is_boundary_edge(e))
        .count();
    let (sub, sub_conn) = subdivide(&h, &conn, 0.5).unwrap();
    assert_eq!(sub.base.faces.len(), h.base.faces.len() + interior_walls);
    let ratio = sub.base.faces.len() as f64 / h.base.faces.len() as f64;
    assert!(ratio > 3.5 && ratio < 4.0, "{ratio}");
    assert!((0..sub.base.vertices.len()).all(|v| (2..=3).contains(&sub_conn.valence(v))));
    let after = measure(&sub, &s);
    println!(
        "cells {} -> {}, omega {:.2e} -> {:.2e}, delta {:.1e}",
        h.base.faces.len(),
        sub.base.faces.len(),
        before.omega_max_deg,
        after.omega_max_deg,
        after.delta_max
    );
    assert!((after.omega_max_deg - before.omega_max_deg).abs() < 1e-9);
    assert!(after.delta_max < 1e-9, "delta_max {}", after.delta_max);
    // Same spherical image: every new axis is an old one, and every old one is still there.
    let key = |a: &crate::geometry::Vec3| a.to_array().map(|x| x.to_bits());
    let old: std::collections::HashSet<_> = h.axes.iter().map(key).collect();
    let new: std::collections::HashSet<_> = sub.axes.iter().map(key).collect();
    assert!(
        old.len() > 100,
        "the test needs varied axes, has {}",
        old.len()
    );
    assert_eq!(old, new);
    // The shrunken cells keep their number of sides; the new ones are hexagons.
    for (f, face) in h.base.faces.iter().enumerate() {
        assert_eq!(sub.base.faces[f].len(), face.len());
    }
    assert!(sub.base.faces[h.base.faces.len()..]
        .iter()
        .all(|f| f.len() == 6));
    assert!(subdivide(&h, &conn, 1.5).is_err());
}

#[test]
fn the_reciprocal_structure_has_a_triangle_per_node_and_straight_t_junctions() {
    let (h, conn, _) = tilted_honeycomb();
    let trivalent = (0..h.base.vertices.len())
        .filter(|&v| conn.valence(v) == 3)
        .count();
    let r = reciprocal(&h, &conn, 0.15).unwrap();
    let m = &r.honeycomb.base;
    assert_eq!(m.faces.len(), h.base.faces.len() + trivalent);
    assert_eq!(
        m.faces[h.base.faces.len()..]
            .iter()
            .filter(|f| f.len() == 3)
            .count(),
        trivalent
    );
    // Each triangle corner is a T-junction: of its three walls, two are pieces of one wall that
    // continues through it (coplanar: parallel normals), the third ends on it.
    assert!(r.t_junctions.len() >= trivalent);
    for &v in &r.t_junctions {
        let walls: Vec<_> = r.connectivity.vertex_edges[v]
            .iter()
            .map(|&e| r.honeycomb.wall_normal(e))
            .collect();
        assert_eq!(walls.len(), 3, "T-junction {v}");
        let through = (0..3).any(|a| (a + 1..3).any(|b| walls[a].dot(walls[b]).abs() > 1.0 - 1e-9));
        assert!(
            through,
            "no wall continues through T-junction {v}: {walls:?}"
        );
    }
    // Walls keep their planes' directions and stay planar; the axes are the old ones.
    let s = Surface::from_mesh(&h.base).unwrap();
    let after = measure(&r.honeycomb, &s);
    assert!(after.delta_max < 1e-9, "delta_max {}", after.delta_max);
    let key = |a: &crate::geometry::Vec3| a.to_array().map(|x| x.to_bits());
    let old: std::collections::HashSet<_> = h.axes.iter().map(key).collect();
    let new: std::collections::HashSet<_> = r.honeycomb.axes.iter().map(key).collect();
    assert!(new.is_subset(&old));
    assert!(reciprocal(&h, &conn, -1.0).is_err());
}
