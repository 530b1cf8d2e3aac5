//! Consistent orientation of a triangle mesh, and its boundary half-edges.

use crate::error::{Error, Result};
use crate::mesh::orientation_flips;

/// An empty slot in a triangle's neighbour list.
const NONE: u32 = u32::MAX;

/// One use of an undirected edge `key = (min, max)` by triangle `tri`; `forward` when the
/// triangle traverses it from `key.0` to `key.1`.
#[derive(Clone, Copy)]
struct EdgeUse {
    key: (usize, usize),
    tri: u32,
    forward: bool,
}

/// Orients the triangles consistently: two triangles sharing an edge must traverse it in
/// opposite directions. Orientation spreads over shared edges (BFS); each connected component
/// then keeps the orientation of the majority of its triangles, so a few flipped input faces
/// are repaired rather than turning the whole surface over.
///
/// Returns the boundary half-edges (edges of a single triangle), directed as in their
/// triangle, so the surface lies to their left seen from the normal side.
/// Triangles that repeat a vertex index have no meaningful edges and are skipped.
///
/// Fails on edges shared by more than two triangles and on non-orientable surfaces.
pub(crate) fn orient(tris: &mut [[usize; 3]]) -> Result<Vec<[usize; 2]>> {
    assert!(tris.len() < NONE as usize, "too many triangles");
    let mut uses = Vec::with_capacity(3 * tris.len());
    for (t, tri) in tris.iter().enumerate() {
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0] {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            uses.push(EdgeUse {
                key: (a.min(b), a.max(b)),
                tri: t as u32,
                forward: a < b,
            });
        }
    }
    // Sorting groups the uses of each edge (faster than hashing for large meshes).
    uses.sort_unstable_by_key(|u| u.key);

    // neighbours[t]: (triangle across an edge, whether both traverse that edge the same way).
    let mut neighbours = vec![[(NONE, false); 3]; tris.len()];
    let mut single = Vec::new();
    for run in uses.chunk_by(|x, y| x.key == y.key) {
        match run {
            [u] => single.push(*u),
            [u, v] => {
                let same = u.forward == v.forward;
                add_neighbour(&mut neighbours[u.tri as usize], v.tri, same);
                add_neighbour(&mut neighbours[v.tri as usize], u.tri, same);
            }
            _ => {
                let (a, b) = run[0].key;
                return Err(Error::Mesh(format!(
                    "non-manifold edge {a}-{b}: shared by {} triangles; the surface must have \
                     at most two faces at every edge",
                    run.len()
                )));
            }
        }
    }

    let flipped = orientation_flips(tris.len(), |t| {
        neighbours[t]
            .into_iter()
            .filter(|s| s.0 != NONE)
            .map(|(u, same)| (u as usize, same))
    })
    .map_err(|t| {
        let [a, b, c] = tris[t];
        Error::Mesh(format!(
            "the surface is not orientable (like a Moebius strip): triangle {a}-{b}-{c} cannot \
             be oriented consistently with its neighbours"
        ))
    })?;
    for (tri, &f) in tris.iter_mut().zip(&flipped) {
        if f {
            tri.swap(1, 2);
        }
    }
    Ok(single
        .iter()
        .map(|u| {
            let (a, b) = u.key;
            if u.forward != flipped[u.tri as usize] {
                [a, b]
            } else {
                [b, a]
            }
        })
        .collect())
}

fn add_neighbour(slots: &mut [(u32, bool); 3], t: u32, same: bool) {
    let slot = slots
        .iter_mut()
        .find(|s| s.0 == NONE)
        .expect("a triangle has three edges, each shared with at most one other triangle");
    *slot = (t, same);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every interior edge is traversed once in each direction.
    fn consistent(tris: &[[usize; 3]]) -> bool {
        let mut directed = std::collections::HashSet::new();
        tris.iter()
            .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
            .all(|e| directed.insert(e))
    }

    #[test]
    fn flipped_minority_is_repaired() {
        // A fan of 6 triangles around vertex 0 (a hexagon), two of them flipped.
        let mut tris: Vec<[usize; 3]> = (0..6).map(|k| [0, 1 + k, 1 + (k + 1) % 6]).collect();
        tris[1].swap(1, 2);
        tris[4].swap(1, 2);
        let boundary = orient(&mut tris).unwrap();
        assert!(consistent(&tris));
        assert_eq!(tris[0], [0, 1, 2], "the majority orientation is kept");
        assert_eq!(boundary.len(), 6);
        assert!(boundary.contains(&[1, 2]));
    }

    #[test]
    fn moebius_strip_is_rejected() {
        // A strip of 4 quads whose ends are glued with a half twist.
        let n = 4;
        let mut tris = Vec::new();
        for k in 0..n {
            let (a, b) = (2 * k, 2 * k + 1);
            let (c, d) = if k + 1 < n {
                (2 * k + 2, 2 * k + 3)
            } else {
                (1, 0)
            };
            tris.push([a, c, d]);
            tris.push([a, d, b]);
        }
        assert!(matches!(orient(&mut tris), Err(Error::Mesh(_))));
    }

    #[test]
    fn non_manifold_edge_is_rejected() {
        let mut tris = vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]];
        assert!(matches!(orient(&mut tris), Err(Error::Mesh(_))));
    }
}
