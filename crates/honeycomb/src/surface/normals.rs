//! Face and vertex normals of a consistently oriented triangle mesh.

use crate::geometry::Vec3;

/// The unit normal of each triangle (right-hand rule), zero for a zero-area triangle.
pub(crate) fn face_normals(vertices: &[Vec3], tris: &[[usize; 3]]) -> Vec<Vec3> {
    tris.iter()
        .map(|&[a, b, c]| {
            let (a, b, c) = (vertices[a], vertices[b], vertices[c]);
            (b - a).cross(c - a).normalized()
        })
        .collect()
}

/// Angle-weighted vertex normals (Thürmer and Wüthrich): each face contributes its normal
/// times its angle at the vertex. Unlike area weights, the result does not depend on how a
/// polygon around the vertex was cut into triangles. Zero for a vertex touched only by
/// zero-area triangles (or by none).
pub(crate) fn vertex_normals(
    vertices: &[Vec3],
    tris: &[[usize; 3]],
    face_normals: &[Vec3],
) -> Vec<Vec3> {
    let mut sums = vec![Vec3::ZERO; vertices.len()];
    for (tri, &n) in tris.iter().zip(face_normals) {
        if n == Vec3::ZERO {
            continue;
        }
        for k in 0..3 {
            let p = vertices[tri[k]];
            let e1 = vertices[tri[(k + 1) % 3]] - p;
            let e2 = vertices[tri[(k + 2) % 3]] - p;
            // atan2 stays accurate for angles near 0 and pi, unlike acos of a dot product.
            let angle = e1.cross(e2).norm().atan2(e1.dot(e2));
            sums[tri[k]] += n * angle;
        }
    }
    sums.into_iter().map(Vec3::normalized).collect()
}

/// Gives zero-area triangles a usable unit normal: the mean of their vertex normals, or
/// +z when even that is undefined (a surface collapsed entirely), so every face normal is unit.
pub(crate) fn fill_degenerate(
    face_normals: &mut [Vec3],
    tris: &[[usize; 3]],
    vertex_normals: &[Vec3],
) {
    for (n, &[a, b, c]) in face_normals.iter_mut().zip(tris) {
        if *n == Vec3::ZERO {
            *n = (vertex_normals[a] + vertex_normals[b] + vertex_normals[c]).normalized();
        }
        if *n == Vec3::ZERO {
            *n = Vec3::new(0.0, 0.0, 1.0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangulation_does_not_bias_vertex_normals() {
        // A corner of a cube: three unit squares at vertex 0. Cutting the bottom square along
        // either diagonal gives vertex 0 one or two triangles of it (area 1/2 or 1), yet angle
        // weights give the symmetric diagonal both times.
        let v = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 1.0),
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, 1.0),
        ];
        // Outward normals -z, -x, -y.
        let tris = vec![
            [0, 2, 1],
            [0, 3, 2],
            [0, 5, 4],
            [0, 4, 3],
            [0, 1, 6],
            [0, 6, 5],
        ];
        let other_diagonal = vec![
            [0, 3, 1],
            [1, 3, 2],
            [0, 5, 4],
            [0, 4, 3],
            [0, 1, 6],
            [0, 6, 5],
        ];
        for t in [tris, other_diagonal] {
            let fnorm = face_normals(&v, &t);
            let n = vertex_normals(&v, &t, &fnorm)[0];
            let d = -1.0 / 3f64.sqrt();
            assert!((n - Vec3::new(d, d, d)).norm() < 1e-12, "{n:?}");
        }
    }
}
