//! Faces turned the other way than their neighbours, turned back. Exports that join patches
//! drawn separately often keep each patch's own winding; the surface is still orientable, and
//! one orientation of it is as good as the other.

use super::PolyMesh;

impl PolyMesh {
    /// Reverses the faces that run an edge the same way as the neighbour across it, so that
    /// every piece of the mesh agrees with the orientation most of its faces already have;
    /// returns how many were reversed. A mesh that cannot be oriented (a Moebius strip) or
    /// whose edges join more than two faces is left as it is, for validation to name.
    pub fn orient_faces_consistently(&mut self) -> usize {
        // Each use of an edge as (low end, high end, face, forward); sorting groups the uses of
        // each edge (faster than hashing for large meshes).
        let mut uses: Vec<(usize, usize, usize, bool)> = Vec::new();
        for (f, face) in self.faces.iter().enumerate() {
            for k in 0..face.len() {
                let (a, b) = (face[k], face[(k + 1) % face.len()]);
                if a != b {
                    uses.push((a.min(b), a.max(b), f, a < b));
                }
            }
        }
        uses.sort_unstable();
        let mut neighbours: Vec<Vec<(usize, bool)>> = vec![Vec::new(); self.faces.len()];
        for run in uses.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
            match run {
                [(_, _, f, f_forward), (_, _, g, g_forward)] => {
                    let same = f_forward == g_forward;
                    neighbours[*f].push((*g, same));
                    neighbours[*g].push((*f, same));
                }
                [_] => {}
                _ => return 0,
            }
        }
        let Ok(flips) = orientation_flips(self.faces.len(), |f| neighbours[f].iter().copied())
        else {
            return 0;
        };
        for (face, _) in self.faces.iter_mut().zip(&flips).filter(|(_, &f)| f) {
            face.reverse();
        }
        flips.iter().filter(|&&f| f).count()
    }
}

/// Which of `n` faces to reverse so that neighbours agree: `neighbours(f)` gives each face
/// across an edge of `f` and whether both run that edge the same way (then one of them must be
/// reversed). Orientation spreads over shared edges; each connected piece then keeps the
/// orientation of most of its faces, so a few faces wound wrong are repaired rather than the
/// whole surface turned over. Fails with a face that cannot agree with its neighbours (the
/// surface is not orientable).
pub(crate) fn orientation_flips<I: Iterator<Item = (usize, bool)>>(
    n: usize,
    neighbours: impl Fn(usize) -> I,
) -> Result<Vec<bool>, usize> {
    let mut flip: Vec<Option<bool>> = vec![None; n];
    let mut piece = Vec::new();
    for root in 0..n {
        if flip[root].is_some() {
            continue;
        }
        flip[root] = Some(false);
        piece.clear();
        piece.push(root);
        let mut next = 0;
        while next < piece.len() {
            let f = piece[next];
            next += 1;
            let own = flip[f] == Some(true);
            for (g, same) in neighbours(f) {
                let wanted = own != same;
                match flip[g] {
                    None => {
                        flip[g] = Some(wanted);
                        piece.push(g);
                    }
                    Some(w) if w != wanted => return Err(g),
                    Some(_) => {}
                }
            }
        }
        let flipped = piece.iter().filter(|&&f| flip[f] == Some(true)).count();
        if 2 * flipped > piece.len() {
            for &f in &piece {
                flip[f] = flip[f].map(|w| !w);
            }
        }
    }
    Ok(flip.into_iter().map(|f| f == Some(true)).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Vec3;

    /// A strip of four unit squares in a row, faces 1 and 3 wound the other way.
    fn strip() -> PolyMesh {
        let vertices = (0..10)
            .map(|k| Vec3::new((k / 2) as f64, (k % 2) as f64, 0.0))
            .collect();
        let square = |i: usize| vec![2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1];
        let mut faces: Vec<Vec<usize>> = (0..4).map(square).collect();
        faces[1].reverse();
        faces[3].reverse();
        PolyMesh::new(vertices, faces)
    }

    #[test]
    fn faces_wound_against_their_neighbours_are_turned_back() {
        let mut m = strip();
        // Half the faces each way: the first face's orientation stays.
        assert_eq!(m.orient_faces_consistently(), 2);
        assert!(crate::mesh::validate_surface_mesh(&m).is_ok());
        assert_eq!(m.faces[0], vec![0, 2, 3, 1]);
        assert_eq!(m.orient_faces_consistently(), 0);
        // Most faces wound the other way: the first face goes with them.
        let mut m = strip();
        m.faces[2].reverse();
        assert_eq!(m.orient_faces_consistently(), 1);
        assert_eq!(m.faces[0], vec![1, 3, 2, 0]);
        assert!(crate::mesh::validate_surface_mesh(&m).is_ok());
    }

    /// The strip's ends glued with a half twist cannot be oriented: it is left as it is.
    #[test]
    fn a_moebius_strip_is_left_as_it_is() {
        let mut m = strip();
        m.vertices.truncate(8);
        m.faces[3] = vec![6, 1, 0, 7];
        let before = m.clone();
        assert_eq!(m.orient_faces_consistently(), 0);
        assert_eq!(m, before);
    }
}
