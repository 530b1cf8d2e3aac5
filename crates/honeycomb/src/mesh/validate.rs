//! Acceptance checks for input meshes. Each failure is one [`Error::Mesh`] saying what is wrong,
//! where, and, when there is an obvious one, how to fix it.

use super::{Connectivity, PolyMesh};
use crate::error::{rounded, short_number, short_point as point, Error, Result};

/// How many offending vertices a message lists before summarising the rest.
const LISTED: usize = 5;

/// Model coordinates beyond this are refused: squared lengths of such meshes overflow or keep
/// no digits for a cell's size (a 10 km site in micrometres is 1e10).
pub const MAX_COORDINATE: f64 = 1e12;

/// A mesh smaller than this across is refused, as one beyond `MAX_COORDINATE` is: its
/// squared lengths and areas fall below what a float holds (a 1 mm part in kilometres is 1e-6).
pub const MIN_EXTENT: f64 = 1e-6;

/// A face whose corners span less than this share of its longest edge squared has no area
/// (its corners lie on one line): its normal and any map of it are undefined.
const FLAT_FACE: f64 = 1e-12;

/// Repairs a base mesh's file where it gives its faces corners of their own (an unwelded
/// export): otherwise each cell would stand alone, a honeycomb of separate cells. Returns
/// what was repaired, a sentence. A base mesh's orientation is the designer's to fix.
pub fn repair_base_mesh(mesh: &mut PolyMesh) -> Vec<String> {
    let joined = mesh.join_coincident_vertices();
    (joined > 0)
        .then(|| {
            format!(
                "{joined} vertices repeat the position of another and were joined to it (the \
                 file gives faces corners of their own); vertex numbers count the joined mesh"
            )
        })
        .into_iter()
        .collect()
}

/// Repairs what a design surface's file often gets wrong where the repair is plain: vertices
/// it repeats at one position are joined, faces wound against their neighbours turned back.
/// Returns what was repaired, a sentence each.
pub fn repair_surface_mesh(mesh: &mut PolyMesh) -> Vec<String> {
    let mut repaired = repair_base_mesh(mesh);
    let turned = mesh.orient_faces_consistently();
    if turned > 0 {
        repaired.push(format!(
            "{turned} faces were wound against their neighbours and were turned to agree with \
             them"
        ));
    }
    repaired
}

/// Accepts a design surface as [`validate_surface_mesh`] does, repaired first as
/// [`repair_surface_mesh`] would (silently): its vertices at one position joined, and, when
/// that mesh is refused, its faces turned to agree before it is checked again. A consistently
/// wound mesh is not searched for faces to turn.
pub fn validate_repaired_surface(mesh: &mut PolyMesh) -> Result<Connectivity> {
    mesh.join_coincident_vertices();
    validate_surface_mesh(mesh).or_else(|e| {
        if mesh.orient_faces_consistently() > 0 {
            validate_surface_mesh(mesh)
        } else {
            Err(e)
        }
    })
}

/// Accepts a design surface: any non-empty manifold polygon mesh with finite coordinates within
/// `MAX_COORDINATE`, no isolated vertices, no zero-length edges and no face without area.
pub fn validate_surface_mesh(mesh: &PolyMesh) -> Result<Connectivity> {
    if mesh.vertices.is_empty() || mesh.faces.is_empty() {
        return Err(Error::Mesh(format!(
            "empty mesh ({} vertices, {} faces)",
            mesh.vertices.len(),
            mesh.faces.len()
        )));
    }
    if let Some((v, p)) = mesh
        .vertices
        .iter()
        .enumerate()
        .find(|(_, p)| !p.is_finite())
    {
        return Err(Error::Mesh(format!(
            "vertex {v} has a non-finite coordinate: {}",
            point(*p)
        )));
    }
    if let Some((v, p)) = mesh
        .vertices
        .iter()
        .enumerate()
        .find(|(_, p)| p.to_array().iter().any(|c| c.abs() > MAX_COORDINATE))
    {
        return Err(Error::Mesh(format!(
            "vertex {v} at ({}, {}, {}) lies beyond {MAX_COORDINATE:e} model units; rescale \
             the mesh",
            short_number(p.x),
            short_number(p.y),
            short_number(p.z)
        )));
    }
    // At 0 every vertex coincides, which the edge check names.
    let extent = extent(mesh);
    if extent > 0.0 && extent < MIN_EXTENT {
        return Err(Error::Mesh(format!(
            "the mesh spans only {} model units (its bounding box's longest side); expected at \
             least {MIN_EXTENT:e}: rescale the mesh",
            rounded(extent, 6)
        )));
    }
    let conn = Connectivity::build(mesh)?;
    let isolated: Vec<usize> = (0..mesh.vertices.len())
        .filter(|&v| conn.valence(v) == 0)
        .collect();
    if !isolated.is_empty() {
        return Err(Error::Mesh(format!(
            "{} (used by no face): {}; remove {}",
            match isolated.len() {
                1 => "1 isolated vertex".to_string(),
                n => format!("{n} isolated vertices"),
            },
            describe(mesh, &conn, &isolated, false),
            if isolated.len() == 1 { "it" } else { "them" }
        )));
    }
    check_edge_lengths(mesh, &conn)?;
    check_face_areas(mesh)?;
    Ok(conn)
}

/// Accepts a honeycomb base mesh: a valid surface mesh whose vertices all have valence 3
/// (2 on the boundary).
pub fn validate_base_mesh(mesh: &PolyMesh) -> Result<Connectivity> {
    let conn = validate_surface_mesh(mesh)?;
    // Every vertex lies in a face of 3 or more vertices, so valence >= 2 already holds.
    let high: Vec<usize> = (0..mesh.vertices.len())
        .filter(|&v| conn.valence(v) > 3)
        .collect();
    if !high.is_empty() {
        return Err(Error::Mesh(format!(
            "{} valence > 3 (a honeycomb base mesh must be trivalent): {}; split {} into \
             valence-3 vertices",
            match high.len() {
                1 => "1 vertex has".to_string(),
                n => format!("{n} vertices have"),
            },
            describe(mesh, &conn, &high, true),
            if high.len() == 1 { "it" } else { "them" }
        )));
    }
    Ok(conn)
}

/// Edges much shorter than the mesh size are coincident vertices, which leave wall directions
/// undefined.
fn check_edge_lengths(mesh: &PolyMesh, conn: &Connectivity) -> Result<()> {
    let first = mesh.vertices[0];
    let (lo, hi) = mesh
        .vertices
        .iter()
        .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    let tolerance = 1e-12 * (hi - lo).norm();
    for &[a, b] in &conn.edges {
        let (pa, pb) = (mesh.vertices[a], mesh.vertices[b]);
        if (pa - pb).norm() <= tolerance {
            return Err(Error::Mesh(format!(
                "zero-length edge {a}-{b}: vertex {a} at {} and vertex {b} at {} coincide; \
                 merge them",
                point(pa),
                point(pb)
            )));
        }
    }
    Ok(())
}

/// A base mesh whose bounding box lies farther than this many of its mean edge lengths from
/// the design surface's is on another surface (or in other units): closeness cannot pull it
/// there in a solve.
pub const MAX_SURFACE_GAP: f64 = 10.0;

/// Refuses a base mesh that lies far from its design surface (their bounding boxes more than
/// `MAX_SURFACE_GAP` mean edge lengths apart), before a solve that could only fail.
pub fn check_base_near_surface(base: &PolyMesh, surface: &PolyMesh) -> Result<()> {
    let (Some(a), Some(b)) = (bounds(base), bounds(surface)) else {
        return Ok(());
    };
    let gap = (0..3)
        .map(|k| (a.0[k] - b.1[k]).max(b.0[k] - a.1[k]).max(0.0))
        .fold(0.0f64, f64::hypot);
    let edge = base.mean_edge_length();
    if gap > MAX_SURFACE_GAP * edge {
        return Err(Error::Mesh(format!(
            "the base mesh lies {} model units ({} of its mean edge lengths) from the surface \
             (between their bounding boxes); expected it on the surface, within {MAX_SURFACE_GAP} \
             edge lengths: are they in the same place and units?",
            rounded(gap, 6),
            rounded(gap / edge, 6)
        )));
    }
    Ok(())
}

/// The corners of the mesh's bounding box as arrays, `None` without vertices.
fn bounds(mesh: &PolyMesh) -> Option<([f64; 3], [f64; 3])> {
    let first = *mesh.vertices.first()?;
    let (lo, hi) = mesh
        .vertices
        .iter()
        .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    Some((lo.to_array(), hi.to_array()))
}

/// The longest side of the mesh's bounding box (no squares, which underflow on tiny meshes).
fn extent(mesh: &PolyMesh) -> f64 {
    bounds(mesh).map_or(0.0, |(lo, hi)| {
        (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max)
    })
}

/// A face whose corners all lie on one line: every corner's two edges are parallel.
fn check_face_areas(mesh: &PolyMesh) -> Result<()> {
    for (f, face) in mesh.faces.iter().enumerate() {
        let corner = |i: usize| mesh.vertices[face[i % face.len()]];
        let (mut span, mut longest) = (0.0f64, 0.0f64);
        for i in 0..face.len() {
            let (p, q, r) = (corner(i), corner(i + 1), corner(i + 2));
            span = span.max((q - p).cross(r - q).norm());
            longest = longest.max((q - p).norm_squared());
        }
        if span <= FLAT_FACE * longest {
            let listed: Vec<String> = face.iter().map(|v| v.to_string()).collect();
            return Err(Error::Mesh(format!(
                "face {f} (vertices {}) has no area: its corners lie on one line; collapse it",
                listed.join(", ")
            )));
        }
    }
    Ok(())
}

/// "vertex 12 (valence 4) at (1, 2, 3), ..." for the first few of `vertices`.
fn describe(mesh: &PolyMesh, conn: &Connectivity, vertices: &[usize], valence: bool) -> String {
    let mut parts: Vec<String> = vertices
        .iter()
        .take(LISTED)
        .map(|&v| {
            let p = mesh.vertices[v];
            let valence = if valence {
                format!(" (valence {})", conn.valence(v))
            } else {
                String::new()
            };
            format!("vertex {v}{valence} at {}", point(p))
        })
        .collect();
    if vertices.len() > LISTED {
        parts.push(format!("and {} more", vertices.len() - LISTED));
    }
    parts.join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Vec3;

    fn error(result: Result<Connectivity>) -> String {
        match result {
            Err(Error::Mesh(message)) => message,
            other => panic!("expected a mesh error, got {other:?}"),
        }
    }

    /// Two regular hexagons sharing the edge 1-2: a valid (boundary) honeycomb patch.
    fn hexagon_pair() -> PolyMesh {
        let s = 3f64.sqrt() / 2.0;
        let vertices = [
            (0.0, 1.0),
            (s, 0.5),
            (s, -0.5),
            (0.0, -1.0),
            (-s, -0.5),
            (-s, 0.5),
            (2.0 * s, 1.0),
            (3.0 * s, 0.5),
            (3.0 * s, -0.5),
            (2.0 * s, -1.0),
        ]
        .map(|(x, y)| Vec3::new(x, y, 0.0))
        .to_vec();
        // Both counter-clockwise, so the shared edge runs in opposite directions.
        let faces = vec![vec![0, 5, 4, 3, 2, 1], vec![1, 2, 9, 8, 7, 6]];
        PolyMesh::new(vertices, faces)
    }

    /// A 3 x 3 vertex grid of four quads: the centre vertex 4 has valence 4.
    fn quad_grid() -> PolyMesh {
        let vertices = (0..9)
            .map(|k| Vec3::new((k % 3) as f64, (k / 3) as f64, 0.0))
            .collect();
        let faces = vec![
            vec![0, 1, 4, 3],
            vec![1, 2, 5, 4],
            vec![3, 4, 7, 6],
            vec![4, 5, 8, 7],
        ];
        PolyMesh::new(vertices, faces)
    }

    #[test]
    fn hexagon_pair_is_a_valid_base_mesh() {
        let conn = validate_base_mesh(&hexagon_pair()).unwrap();
        assert_eq!(conn.num_edges(), 11);
        assert_eq!(conn.valence(1), 3);
        validate_surface_mesh(&hexagon_pair()).unwrap();
    }

    #[test]
    fn a_mesh_below_the_smallest_scale_is_refused_with_short_numbers() {
        for scale in [1e-100, 1e-300, 1e-7] {
            let mut mesh = hexagon_pair();
            mesh.vertices.iter_mut().for_each(|p| *p = *p * scale);
            let message = error(validate_surface_mesh(&mesh));
            let spans = format!(
                "the mesh spans only {} model units",
                rounded(2.0 * 3f64.sqrt() * scale, 6)
            );
            assert!(message.starts_with(&spans), "{message}");
            assert!(message.contains("at least 1e-6: rescale"), "{message}");
        }
        // Just above the bound, the mesh is taken as it is.
        let mut mesh = hexagon_pair();
        mesh.vertices.iter_mut().for_each(|p| *p = *p * 1e-6);
        validate_base_mesh(&mesh).unwrap();
    }

    #[test]
    fn a_base_mesh_far_from_its_surface_is_refused() {
        let surface = hexagon_pair();
        let mut base = hexagon_pair();
        base.vertices.iter_mut().for_each(|p| p.z += 1e6);
        let message = check_base_near_surface(&base, &surface)
            .unwrap_err()
            .to_string();
        assert!(
            message.contains(
                "the base mesh lies 1000000 model units (1000000 of its mean edge lengths)"
            ),
            "{message}"
        );
        // Beside it by a few edge lengths (a base beyond S's edge), or on it: taken.
        base.vertices.iter_mut().for_each(|p| p.z -= 1e6 - 5.0);
        check_base_near_surface(&base, &surface).unwrap();
        check_base_near_surface(&surface, &surface).unwrap();
    }

    #[test]
    fn coordinates_in_messages_have_at_most_six_digits() {
        let mut mesh = hexagon_pair();
        mesh.vertices[8] = mesh.vertices[7];
        let message = error(validate_surface_mesh(&mesh));
        assert!(
            message.contains("vertex 7 at (2.59808, 0.5, 0) and vertex 8 at (2.59808, 0.5, 0)"),
            "{message}"
        );
    }

    #[test]
    fn valence_four_is_rejected_for_base_meshes_only() {
        let mesh = quad_grid();
        let message = error(validate_base_mesh(&mesh));
        assert!(
            message
                .starts_with("1 vertex has valence > 3 (a honeycomb base mesh must be trivalent)"),
            "{message}"
        );
        assert!(
            message.contains("vertex 4 (valence 4) at (1, 1, 0)"),
            "{message}"
        );
        assert!(
            message.contains("split it into valence-3 vertices"),
            "{message}"
        );
        validate_surface_mesh(&mesh).unwrap();
    }

    #[test]
    fn many_high_valence_vertices_are_summarised() {
        // A fan of 4 triangles around each of 7 hubs.
        let mut mesh = PolyMesh::default();
        for hub in 0..7 {
            let base = mesh.vertices.len();
            let x = 10.0 * hub as f64;
            mesh.vertices.push(Vec3::new(x, 0.0, 0.0));
            for (dx, dy) in [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)] {
                mesh.vertices.push(Vec3::new(x + dx, dy, 0.0));
            }
            for k in 0..4 {
                mesh.faces
                    .push(vec![base, base + 1 + k, base + 1 + (k + 1) % 4]);
            }
        }
        let message = error(validate_base_mesh(&mesh));
        assert!(
            message.starts_with("7 vertices have valence > 3"),
            "{message}"
        );
        assert!(
            message.contains("vertex 20 (valence 4) at (40, 0, 0), and 2 more"),
            "{message}"
        );
        assert!(!message.contains("vertex 25 "), "{message}");
        assert!(message.contains("split them"), "{message}");
    }

    #[test]
    fn empty_meshes() {
        let message = error(validate_surface_mesh(&PolyMesh::default()));
        assert!(
            message.contains("empty mesh (0 vertices, 0 faces)"),
            "{message}"
        );
        let mut mesh = hexagon_pair();
        mesh.faces.clear();
        let message = error(validate_base_mesh(&mesh));
        assert!(
            message.contains("empty mesh (10 vertices, 0 faces)"),
            "{message}"
        );
    }

    #[test]
    fn non_finite_coordinate() {
        let mut mesh = hexagon_pair();
        mesh.vertices[7].z = f64::NAN;
        let message = error(validate_surface_mesh(&mesh));
        assert!(
            message.contains("vertex 7 has a non-finite coordinate"),
            "{message}"
        );
        assert!(message.contains("NaN"), "{message}");
    }

    #[test]
    fn non_manifold_edge_with_three_faces() {
        let mesh = PolyMesh::new(
            vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(0.5, 1.0, 0.0),
                Vec3::new(0.5, -1.0, 0.0),
                Vec3::new(0.5, 0.0, 1.0),
            ],
            vec![vec![0, 1, 2], vec![1, 0, 3], vec![0, 1, 4]],
        );
        let message = error(validate_surface_mesh(&mesh));
        assert!(message.contains("edge 0-1"), "{message}");
        assert!(message.contains("non-manifold"), "{message}");
    }

    #[test]
    fn bow_tie_vertex() {
        let mesh = PolyMesh::new(
            vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.5, 0.0),
                Vec3::new(1.0, -0.5, 0.0),
                Vec3::new(-1.0, -0.5, 0.0),
                Vec3::new(-1.0, 0.5, 0.0),
            ],
            vec![vec![0, 2, 1], vec![0, 4, 3]],
        );
        let message = error(validate_surface_mesh(&mesh));
        assert!(message.contains("non-manifold vertex 0"), "{message}");
    }

    #[test]
    fn isolated_vertex() {
        let mut mesh = hexagon_pair();
        mesh.vertices.push(Vec3::new(5.0, 5.0, 5.0));
        let message = error(validate_surface_mesh(&mesh));
        assert!(
            message.contains("1 isolated vertex (used by no face): vertex 10 at (5, 5, 5)"),
            "{message}"
        );
    }

    #[test]
    fn zero_length_edge() {
        let mut mesh = hexagon_pair();
        mesh.vertices[8] = mesh.vertices[7];
        let message = error(validate_base_mesh(&mesh));
        assert!(message.contains("zero-length edge 7-8"), "{message}");
        assert!(message.contains("vertex 7 at (2.598"), "{message}");
        assert!(message.contains("merge them"), "{message}");
    }

    #[test]
    fn a_cell_without_area() {
        let mut mesh = hexagon_pair();
        // The second cell's corners spread along the x axis: no zero-length edge, no area.
        for (k, &v) in [1, 2, 9, 8, 7, 6].iter().enumerate() {
            mesh.vertices[v] = Vec3::new(k as f64, 0.0, 0.0);
        }
        let message = error(validate_surface_mesh(&mesh));
        assert!(
            message.contains("face 1 (vertices 1, 2, 9, 8, 7, 6) has no area"),
            "{message}"
        );
        // A thin sliver still has area, and is accepted.
        let mut mesh = hexagon_pair();
        for &v in &[6, 7, 8, 9] {
            mesh.vertices[v].y *= 1e-6;
        }
        validate_base_mesh(&mesh).unwrap();
    }

    #[test]
    fn a_coordinate_too_large_to_compute_with() {
        let mut mesh = hexagon_pair();
        mesh.vertices[4].z = 1e308;
        let message = error(validate_surface_mesh(&mesh));
        assert!(message.contains("vertex 4 at ("), "{message}");
        assert!(message.contains("1e308) lies beyond 1e12"), "{message}");
        // A building in micrometres is fine.
        for p in &mut mesh.vertices {
            *p = Vec3::new(p.x * 1e9, p.y * 1e9, 0.0);
        }
        validate_base_mesh(&mesh).unwrap();
    }

    #[test]
    fn out_of_range_face_index() {
        let mut mesh = hexagon_pair();
        mesh.faces[1][3] = 10;
        let message = error(validate_surface_mesh(&mesh));
        assert!(message.contains("face 1 refers to vertex 10"), "{message}");
    }
}
