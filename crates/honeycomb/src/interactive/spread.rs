//! Mode (iii) of the paper's Fig. 10: a node axis turned by the user drags the axes around it
//! along, less with every ring of graph distance.

use crate::geometry::Vec3;
use crate::mesh::Connectivity;
use std::collections::VecDeque;

/// Graph distance (in edges) from `source` of every vertex at most `radius` away.
pub fn rings(conn: &Connectivity, source: usize, radius: usize) -> Vec<(usize, usize)> {
    let mut distance = vec![usize::MAX; conn.vertex_edges.len()];
    let mut queue = VecDeque::from([source]);
    distance[source] = 0;
    let mut reached = Vec::new();
    while let Some(v) = queue.pop_front() {
        reached.push((v, distance[v]));
        if distance[v] == radius {
            continue;
        }
        for &e in &conn.vertex_edges[v] {
            let w = conn.other_end(e, v);
            if distance[w] == usize::MAX {
                distance[w] = distance[v] + 1;
                queue.push_back(w);
            }
        }
    }
    reached
}

/// The share of the user's turn a vertex `d` rings away takes: 1 at the dragged node, falling
/// smoothly (zero slope at both ends) to 0 one ring beyond `radius`.
pub fn damping(d: usize, radius: usize) -> f64 {
    let s = d as f64 / (radius + 1) as f64;
    (1.0 - s * s).powi(2)
}

/// `p` rotated about the unit axis `k` by `angle` (Rodrigues).
pub fn rotate(p: Vec3, k: Vec3, angle: f64) -> Vec3 {
    let (s, c) = angle.sin_cos();
    p * c + k.cross(p) * s + k * (k.dot(p) * (1.0 - c))
}

/// Target axes after turning the axis of `source` from `axes[source]` to the unit `direction`:
/// every vertex within `radius` rings turns about the same line by the damped angle.
pub fn spread_turn(
    conn: &Connectivity,
    axes: &[Vec3],
    source: usize,
    direction: Vec3,
    radius: usize,
) -> Vec<(usize, Vec3)> {
    let from = axes[source];
    let k = from.cross(direction);
    let angle = k.norm().atan2(from.dot(direction));
    let k = if k.norm() > 1e-12 {
        k.normalized()
    } else {
        from.any_orthogonal().normalized()
    };
    rings(conn, source, radius)
        .into_iter()
        .map(|(v, d)| {
            let target = if v == source {
                direction
            } else {
                rotate(axes[v], k, angle * damping(d, radius)).normalized()
            };
            (v, target)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{lifted_hex_patch, Shape};

    #[test]
    fn turn_spreads_with_damping() {
        let (base, _) = lifted_hex_patch(Shape::Dome, 300);
        let conn = Connectivity::build(&base).unwrap();
        let up = Vec3::new(0.0, 0.0, 1.0);
        let axes = vec![up; base.vertices.len()];
        let c = base.centroid();
        let source = (0..base.vertices.len())
            .min_by(|&a, &b| {
                let d = |v: usize| (base.vertices[v] - c).norm();
                d(a).total_cmp(&d(b))
            })
            .unwrap();
        let direction = Vec3::new(0.5, 0.0, 1.0).normalized();
        let targets = spread_turn(&conn, &axes, source, direction, 3);
        let angle = |a: Vec3| a.dot(up).clamp(-1.0, 1.0).acos();
        let full = angle(direction);
        let by_ring = rings(&conn, source, 3);
        assert_eq!(targets.len(), by_ring.len());
        // 1 + 3 + 6 + 9 vertices within three rings of an interior node.
        assert_eq!(by_ring.len(), 19);
        for ((v, t), (w, d)) in targets.iter().zip(&by_ring) {
            assert_eq!(v, w);
            assert!((t.norm() - 1.0).abs() < 1e-12);
            let expected = full * damping(*d, 3);
            assert!((angle(*t) - expected).abs() < 1e-12, "ring {d}");
        }
        assert_eq!(damping(0, 3), 1.0);
        assert!(damping(3, 3) > 0.0 && damping(3, 3) < damping(2, 3));
    }
}
