//! Boundary cells of a finished honeycomb that stand out beyond S's border, trimmed.
//!
//! A lattice cell that S's border cuts through keeps its whole hexagon. Where the border runs
//! steeply across the walls, the placement cannot bring such a cell's outer vertices onto S:
//! their node axes pass beside S. Taking the cell away leaves a honeycomb as it was: every
//! other wall keeps its plane and every node its angles (a node that loses a wall keeps the two
//! that meet at 120 degrees), so nothing is solved again.

use super::Across;
use crate::error::Result;
use crate::mesh::{validate_base_mesh, Connectivity};
use crate::optimize::{keeping_one_piece, kept_vertices, without_cells};
use crate::structure::{edge_length_cv, measure, Honeycomb, Measures};
use crate::surface::Surface;

/// A vertex within this many mean edge lengths of S is on S.
pub const ON_S: f64 = 0.05;

/// `across` without the cells [`overhanging_cells`] lists (with at most `max_share` of the
/// cells), measured again on `surface`.
pub fn trim_overhang(across: Across, max_share: f64, surface: &Surface) -> Across {
    let (h, conn, m) = (&across.honeycomb, &across.connectivity, &across.measures);
    let trimmed = overhanging_cells(h, conn, m, max_share);
    without_trimmed(across, &trimmed, surface)
}

/// `across` without the cells `trimmed` (sorted), measured again on `surface`; as it was when
/// there are none, or when the mesh checks refuse what is left (a cell left too thin).
fn without_trimmed(across: Across, trimmed: &[usize], surface: &Surface) -> Across {
    if trimmed.is_empty() {
        return across;
    }
    let Ok((honeycomb, connectivity)) = without_honeycomb_cells(&across.honeycomb, trimmed) else {
        return across;
    };
    let measures = measure(&honeycomb, surface);
    Across {
        base: without_cells(&across.base, trimmed),
        honeycomb,
        connectivity,
        measures,
        dropped_cells: across.dropped_cells + trimmed.len(),
        trimmed_cells: across.trimmed_cells + trimmed.len(),
        ..across
    }
}

/// The edge-length cv of `h` without the cells `gone` (sorted) and those [`trim_overhang`]
/// would trim (at most `max_share` of the cells), `m` its measures.
pub fn edge_cv_without(
    h: &Honeycomb,
    conn: &Connectivity,
    m: &Measures,
    gone: &[usize],
    max_share: f64,
) -> f64 {
    let trimmed = overhanging_cells(h, conn, m, max_share);
    let kept = |f: &usize| trimmed.binary_search(f).is_err() && gone.binary_search(f).is_err();
    let lengths: Vec<f64> = (conn.edges.iter().zip(&conn.edge_faces))
        .filter(|(_, faces)| faces.iter().flatten().any(kept))
        .map(|(&[a, b], _)| (h.base.vertices[a] - h.base.vertices[b]).norm())
        .collect();
    edge_length_cv(&lengths)
}

/// The boundary cells of `h` that hold a vertex off S (farther than [`ON_S`] by `m`), with
/// the few cells their loss would cut off (sorted): all of them, when they are at most
/// `max_share` of the cells, can go without cutting a lobe off the rest and take every vertex
/// off S with them; else none.
pub fn overhanging_cells(
    h: &Honeycomb,
    conn: &Connectivity,
    m: &Measures,
    max_share: f64,
) -> Vec<usize> {
    let cells = h.base.faces.len();
    let off_s = |v: &usize| m.closeness_per_vertex[*v] > ON_S;
    let overhanging: Vec<usize> = (0..cells)
        .filter(|&f| conn.is_boundary_face(f) && h.base.faces[f].iter().any(off_s))
        .collect();
    let allowed = (max_share * cells as f64).floor() as usize;
    if overhanging.is_empty() || overhanging.len() > allowed {
        return Vec::new();
    }
    let trimmed = keeping_one_piece(conn, cells, &overhanging);
    // A cell kept for the structure's sake, or a vertex off S that a kept cell holds, would
    // still stand out: no use trimming the others.
    if trimmed.len() > allowed
        || overhanging
            .iter()
            .any(|f| trimmed.binary_search(f).is_err())
    {
        return Vec::new();
    }
    let kept_cell_off_s = (0..cells)
        .filter(|f| trimmed.binary_search(f).is_err())
        .any(|f| h.base.faces[f].iter().any(off_s));
    if kept_cell_off_s {
        return Vec::new();
    }
    trimmed
}

/// A boundary cell with an edge this many mean edge lengths long, or longer, is drawn out.
pub const DRAWN_OUT: f64 = 1.5;

/// `across` without its drawn-out boundary cells ([`drawn_out_cells`]), measured again on
/// `surface`: where the axes lean steeply at S's border a few boundary cells are drawn out to
/// two or three times the mean edge, and those alone can make the cells uneven.
pub fn trim_drawn_out(across: Across, uneven: f64, max_share: f64, surface: &Surface) -> Across {
    let trimmed = drawn_out_cells(&across.honeycomb, &across.connectivity, uneven, max_share);
    without_trimmed(across, &trimmed, surface)
}

/// The boundary cells of `h` with an edge [`DRAWN_OUT`] mean edge lengths long or longer,
/// longest edge first, each taken while it lowers the edge-length cv and leaves one piece,
/// until the cv is below `uneven` (sorted): all of them when that takes at most `max_share`
/// of the cells, else none (the cells stay uneven either way; coverage is not given up for a
/// little evenness).
pub fn drawn_out_cells(
    h: &Honeycomb,
    conn: &Connectivity,
    uneven: f64,
    max_share: f64,
) -> Vec<usize> {
    let cells = h.base.faces.len();
    let length: Vec<f64> = (conn.edges.iter())
        .map(|&[a, b]| (h.base.vertices[a] - h.base.vertices[b]).norm())
        .collect();
    // Per edge, the cells on it that stay.
    let mut sides: Vec<usize> = (conn.edge_faces.iter())
        .map(|f| f.iter().flatten().count())
        .collect();
    let cv = |sides: &[usize]| {
        let kept: Vec<f64> = (length.iter().zip(sides))
            .filter(|(_, &n)| n > 0)
            .map(|(l, _)| *l)
            .collect();
        edge_length_cv(&kept)
    };
    let mut now = cv(&sides);
    let unit = length.iter().sum::<f64>() / length.len().max(1) as f64;
    let longest = |f: usize| {
        conn.face_edges[f]
            .iter()
            .map(|&e| length[e])
            .fold(0.0, f64::max)
    };
    let mut drawn_out: Vec<usize> = (0..cells)
        .filter(|&f| conn.is_boundary_face(f) && longest(f) >= DRAWN_OUT * unit)
        .collect();
    drawn_out.sort_by(|&a, &b| longest(b).total_cmp(&longest(a)));
    let allowed = (max_share * cells as f64).floor() as usize;
    let mut gone = vec![false; cells];
    let mut trimmed = Vec::new();
    for f in drawn_out {
        if now < uneven || trimmed.len() == allowed {
            break;
        }
        gone[f] = true;
        for &e in &conn.face_edges[f] {
            sides[e] -= 1;
        }
        let lower = cv(&sides);
        if lower < now && conn.pieces(&gone).len() == 1 {
            now = lower;
            trimmed.push(f);
        } else {
            gone[f] = false;
            for &e in &conn.face_edges[f] {
                sides[e] += 1;
            }
        }
    }
    if now >= uneven {
        return Vec::new();
    }
    trimmed.sort_unstable();
    trimmed
}

/// `h` without the cells `drop` (sorted) and the vertices no other cell holds; every other
/// vertex keeps its position and axis, so M' keeps its offset.
pub fn without_honeycomb_cells(h: &Honeycomb, drop: &[usize]) -> Result<(Honeycomb, Connectivity)> {
    let kept = kept_vertices(&h.base, drop);
    let base = without_cells(&h.base, drop);
    let conn = validate_base_mesh(&base)?;
    let axes = kept.iter().map(|&v| h.axes[v]).collect();
    Ok((Honeycomb::new(base, &conn, axes, h.thickness), conn))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::hex_disk;
    use crate::geometry::Vec3;

    /// A plane hex disk with vertical axes: a honeycomb on itself.
    fn flat() -> (Honeycomb, Connectivity, Surface) {
        let disk = hex_disk(6.0);
        let conn = validate_base_mesh(&disk).unwrap();
        let axes = vec![Vec3::new(0.0, 0.0, 1.0); disk.vertices.len()];
        let surface = Surface::from_mesh(&disk).unwrap();
        (Honeycomb::new(disk, &conn, axes, 0.3), conn, surface)
    }

    /// The boundary vertices farthest out along +x, lifted off the plane by `lift` edges.
    fn lifted(h: &Honeycomb, conn: &Connectivity, count: usize, lift: f64) -> Honeycomb {
        let mut outer: Vec<usize> = (0..h.base.vertices.len())
            .filter(|&v| conn.valence(v) == 2)
            .collect();
        outer.sort_by(|&a, &b| h.base.vertices[b].x.total_cmp(&h.base.vertices[a].x));
        let mut base = h.base.clone();
        let unit = base.mean_edge_length();
        for &v in &outer[..count] {
            base.vertices[v].z += lift * unit;
        }
        Honeycomb::new(base, conn, h.axes.clone(), h.thickness)
    }

    #[test]
    fn a_cell_standing_out_is_trimmed_and_the_rest_stays_a_honeycomb() {
        let (h, conn, surface) = flat();
        let out = lifted(&h, &conn, 1, 0.5);
        let m = measure(&out, &surface);
        assert!(m.closeness_max > ON_S);
        let trimmed = overhanging_cells(&out, &conn, &m, 0.1);
        assert_eq!(trimmed.len(), 1, "{trimmed:?}");
        let (rest, _) = without_honeycomb_cells(&out, &trimmed).unwrap();
        let m = measure(&rest, &surface);
        assert_eq!(rest.base.faces.len(), h.base.faces.len() - 1);
        assert!(m.closeness_max < 1e-12, "{}", m.closeness_max);
        assert!(m.omega_max_deg < 1e-9, "{}", m.omega_max_deg);
        assert!(m.delta_max < 1e-12, "{}", m.delta_max);
    }

    /// `count` boundary cells of `h` whose outer corners (held by no other cell) are pushed
    /// out in the plane by `push` edges: drawn out, the rest as it was. Sorted.
    fn drawn(
        h: &Honeycomb,
        conn: &Connectivity,
        count: usize,
        push: f64,
    ) -> (Honeycomb, Vec<usize>) {
        let faces = &h.base.faces;
        let outer = |v: usize| conn.valence(v) == 2;
        let mut cells: Vec<usize> = (0..faces.len())
            .filter(|&f| faces[f].iter().filter(|&&v| outer(v)).count() >= 2)
            .collect();
        // Spread around the disk, so that no two share a corner.
        let step = cells.len() / count;
        cells = (0..count).map(|k| cells[k * step]).collect();
        let mut base = h.base.clone();
        for &f in &cells {
            for &v in faces[f].iter().filter(|&&v| outer(v)) {
                let p = base.vertices[v];
                base.vertices[v] = p + Vec3::new(p.x, p.y, 0.0).normalized() * push;
            }
        }
        cells.sort_unstable();
        (
            Honeycomb::new(base, conn, h.axes.clone(), h.thickness),
            cells,
        )
    }

    #[test]
    fn drawn_out_boundary_cells_go_until_the_cells_are_even() {
        let (h, conn, surface) = flat();
        assert!(drawn_out_cells(&h, &conn, 0.12, 0.1).is_empty());
        let (out, stretched) = drawn(&h, &conn, 4, 1.5);
        let before = measure(&out, &surface).edge_length_cv;
        assert!(before >= 0.12, "{before}");
        let trimmed = drawn_out_cells(&out, &conn, 0.12, 0.1);
        assert!(!trimmed.is_empty(), "{before}");
        assert!(
            trimmed.iter().all(|f| stretched.contains(f)),
            "{trimmed:?} of {stretched:?}"
        );
        let (rest, rest_conn) = without_honeycomb_cells(&out, &trimmed).unwrap();
        let m = measure(&rest, &surface);
        assert!(m.edge_length_cv < 0.12, "{before} -> {}", m.edge_length_cv);
        assert!(m.omega_max_deg < 1e-9, "{}", m.omega_max_deg);
        assert!(m.delta_max < 1e-12, "{}", m.delta_max);
        assert_eq!(
            rest_conn.pieces(&vec![false; rest.base.faces.len()]).len(),
            1
        );
        // More than the share allows: none goes, the cells stay as they are.
        let share = (trimmed.len() - 1) as f64 / h.base.faces.len() as f64;
        assert!(drawn_out_cells(&out, &conn, 0.12, share).is_empty());
        // Cells drawn out less (every edge under 1.5 mean edges) stay, however uneven.
        let (mild, _) = drawn(&h, &conn, 4, 0.3);
        assert!(drawn_out_cells(&mild, &conn, 0.0, 0.1).is_empty());
    }

    #[test]
    fn nothing_is_trimmed_beyond_its_share_or_on_s() {
        let (h, conn, surface) = flat();
        assert!(overhanging_cells(&h, &conn, &measure(&h, &surface), 0.1).is_empty());
        let out = lifted(&h, &conn, 6, 0.5);
        let m = measure(&out, &surface);
        let share = 2.0 / h.base.faces.len() as f64;
        assert!(overhanging_cells(&out, &conn, &m, share).is_empty());
        assert!(!overhanging_cells(&out, &conn, &m, 0.5).is_empty());
        // A vertex of a boundary cell and of an inner one, off S: the inner cell keeps it.
        let faces = &h.base.faces;
        let cells_of = |v: usize| -> Vec<usize> {
            (0..faces.len())
                .filter(|&f| faces[f].contains(&v))
                .collect()
        };
        let inner = (0..h.base.vertices.len())
            .find(|&v| {
                let cells = cells_of(v);
                cells.iter().any(|&f| conn.is_boundary_face(f))
                    && cells.iter().any(|&f| !conn.is_boundary_face(f))
            })
            .unwrap();
        let mut base = h.base.clone();
        base.vertices[inner].z += 0.5 * base.mean_edge_length();
        let out = Honeycomb::new(base, &conn, h.axes.clone(), h.thickness);
        let m = measure(&out, &surface);
        assert!(m.closeness_max > ON_S);
        assert!(overhanging_cells(&out, &conn, &m, 0.5).is_empty());
    }
}
