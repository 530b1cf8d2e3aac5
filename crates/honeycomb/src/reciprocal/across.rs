//! A honeycomb whose node axes follow S's normals as closely as a honeycomb allows: the sheet
//! fitted to the normals, the base mesh placed on its walls, and boundary cells that placement
//! breaks dropped (the sheet of the rest starts from the same points and is fitted again), and
//! the cells that stand out beyond S's border trimmed.

use super::{
    edge_cv_without, place, trim::overhanging_cells, trim_overhang, unit_gap, AxisFieldOptions,
    AxisFit, AxisTargets, FittedSheet, PlacementOptions, Sheet, ON_S,
};
use crate::error::Result;
use crate::geometry::Vec3;
use crate::mesh::{validate_base_mesh, Connectivity, PolyMesh};
use crate::optimize::{broken_boundary_cells, kept_vertices, without_cells, Frame};
use crate::solve::{IterationInfo, SolveReport};
use crate::structure::{measure, Honeycomb, Measures};
use crate::surface::Surface;

/// Rounds of dropping broken boundary cells at most, on a grid the pipeline laid.
pub const DROP_ROUNDS: usize = 8;
/// At most this share of a laid grid's cells is dropped. Where S's border turns tightly or
/// runs steeply across the walls, the sheet folds along it and the boundary cells break in a
/// ring a few cells long at each such place; a long border (a narrow roof, a ring) holds more
/// of them than the share a designer's mesh may lose (`crate::optimize::MAX_DROPPED_SHARE`).
pub const GRID_DROPPED_SHARE: f64 = 0.06;
/// How close to unit walls (in `|p_a - p_b|^2 - 1`) a provisional sheet is fitted
/// ([`AcrossOptions::provisional_if_uneven`]): its fold is set (the cells placed on it are as
/// uneven as on the exact one), its nodes a fraction of a degree off 120.
pub const PROVISIONAL_GAP: f64 = 1e-2;
/// Dropping broken boundary cells and placing the rest again evens the cells by up to about
/// this much (edge cv): a provisional result with cells to drop is found even below the
/// evening's threshold plus this.
const DROPS_EVEN_BY: f64 = 0.015;

#[derive(Clone, Debug)]
pub struct AcrossOptions {
    pub field: AxisFieldOptions,
    pub placement: PlacementOptions,
    /// Distance between M and M' (model units); `None`: `default_depth` mean edge lengths.
    pub thickness: Option<f64>,
    pub default_depth: f64,
    /// Rounds of dropping broken boundary cells at most.
    pub max_drops: usize,
    /// At most this share of the cells is dropped.
    pub max_dropped_share: f64,
    /// At most this share of the cells is trimmed where it stands out beyond S's border
    /// ([`trim_overhang`]).
    pub max_trimmed_share: f64,
    /// What the node axes are fitted to.
    pub targets: AxisTargets,
    /// Where the cells placed on the sheet (fitted from the base mesh) are this uneven (edge
    /// cv) or more, the sheet is fitted only to [`PROVISIONAL_GAP`] and the result is
    /// `provisional`: the evening fits the walls again from where its steps get to, and would throw
    /// away the fit's last steps. Otherwise the fit goes on from where it stopped to unit
    /// walls, and the vertices are put on those from where they stand.
    pub provisional_if_uneven: Option<f64>,
}

impl Default for AcrossOptions {
    fn default() -> Self {
        AcrossOptions {
            field: AxisFieldOptions::default(),
            placement: PlacementOptions::default(),
            thickness: None,
            default_depth: crate::optimize::DEFAULT_THICKNESS,
            max_drops: DROP_ROUNDS,
            max_dropped_share: GRID_DROPPED_SHARE,
            max_trimmed_share: 0.01,
            targets: AxisTargets::Normals,
            provisional_if_uneven: None,
        }
    }
}

/// What [`walls_across`] made.
pub struct Across {
    pub honeycomb: Honeycomb,
    pub connectivity: Connectivity,
    /// The base mesh the kept result started from (without dropped cells), model units.
    pub base: PolyMesh,
    pub measures: Measures,
    /// Boundary cells dropped, the trimmed ones among them.
    pub dropped_cells: usize,
    pub trimmed_cells: usize,
    /// Iterations of the sheet's fits.
    pub field_iterations: usize,
    /// Every solve, one after the other (the sheet's fits, then the placements).
    pub solve: SolveReport,
    /// The sheet's walls reached unit length.
    pub field_converged: bool,
    /// The sheet fitted only to [`PROVISIONAL_GAP`] (`AcrossOptions::provisional_if_uneven`),
    /// not to unit walls.
    pub provisional: bool,
}

/// Which solve an iteration belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    AxisField,
    Placement,
}

/// Where the sheet starts other than from the base mesh's cells: a honeycomb on the base
/// mesh that is not exact (a few steps of the guided projection from one), model units.
#[derive(Clone, Copy)]
pub struct Start<'a> {
    /// Its vertices, where the placement starts (as from an earlier placement: they are near
    /// S, so it does not need its three iterations at least) and which it stays close to.
    pub vertices: &'a [Vec3],
    /// One per edge, as seen from its first vertex.
    pub wall_normals: &'a [Vec3],
    /// One per vertex; the sheet is fitted to these rather than to `options.targets`.
    pub axes: &'a [Vec3],
}

/// A honeycomb on `base` (a valid base mesh on `surface`, both in model units) with walls
/// across `surface`, measured against `model_surface` (the same surface); the sheet from the
/// base mesh's cells, or from `start` (on the base mesh's faces). Provisional where
/// `options.provisional_if_uneven` finds the cells uneven (never from a `start`).
pub fn walls_across(
    base: &PolyMesh,
    start: Option<Start>,
    surface: &PolyMesh,
    model_surface: &Surface,
    options: &AcrossOptions,
    progress: &mut dyn FnMut(Stage, &IterationInfo),
) -> Result<Across> {
    let frame = Frame::of(base);
    let normalized = Surface::from_mesh(&frame.to_normalized(surface))?;
    let allowed = (options.max_dropped_share * base.faces.len() as f64).floor() as usize;
    let mut model_base = base.clone();
    let mut mesh = match start {
        Some(start) => {
            frame.to_normalized(&PolyMesh::new(start.vertices.to_vec(), base.faces.clone()))
        }
        None => frame.to_normalized(base),
    };
    let mut conn = validate_base_mesh(&mesh)?;
    let mut sheet = Sheet::new(&mesh, &conn)?;
    let mut points = match start {
        Some(start) => sheet.points_of(start.wall_normals)?,
        None => sheet.initial_points(&mesh, &conn, |p| {
            options.targets.at(normalized.normal_at(p))
        }),
    };
    let mut given_axes = start.map(|s| s.axes.to_vec());
    let mut dropped_cells = 0;
    let mut solves = Solves::default();
    let mut drops = 0;
    // Where the last placement put the vertices that are kept; at first, where a start's
    // steps put them (near S and near its walls already, so its placement starts warm too).
    let mut placed_before: Option<Vec<Vec3>> = start.map(|_| mesh.vertices.clone());
    let mut unconverged_before = false;
    let placement = PlacementOptions {
        edges_along_s: options.targets != AxisTargets::Normals,
        ..options.placement.clone()
    };
    // Until the cells are found even enough for no evening.
    let mut provisional = options.provisional_if_uneven.filter(|_| start.is_none());
    // A fit of the rest after a provisional round of drops takes up the guides' fade and the
    // regularization where the last fit left them, as if it went on.
    let mut field_options = options.field.clone();
    let mut first_round: Option<FirstRound> = None;
    let thickness = options
        .thickness
        .unwrap_or(options.default_depth * frame.unit);
    loop {
        let targets: Vec<Vec3> = match &given_axes {
            Some(axes) => axes.clone(),
            None => (mesh.vertices.iter())
                .map(|&p| options.targets.at(normalized.normal_at(p)))
                .collect(),
        };
        let edges: Vec<Vec3> = conn
            .edges
            .iter()
            .map(|&[a, b]| (mesh.vertices[a] - mesh.vertices[b]).normalized())
            .collect();
        let facing: Vec<Vec3> = conn
            .edges
            .iter()
            .zip(&edges)
            .map(|(&[a, b], &d)| d.cross(targets[a] + targets[b]).normalized())
            .collect();
        let tolerance = match provisional {
            Some(_) => options.field.tolerance.max(PROVISIONAL_GAP),
            None => options.field.tolerance,
        };
        let new_fit = |points: &[Vec3]| {
            AxisFit::new(&sheet, points, &targets, &edges, &facing, &field_options)
        };
        // None where the sheet is fitted already (the rest of one whose broken cells were
        // dropped); kept until the result is, to go on from where a provisional fit stopped.
        let mut fit = match unit_gap(&sheet, &points) < tolerance {
            true => None,
            false => Some(new_fit(&points)?),
        };
        let mut field_converged = true;
        if let Some(fit) = &mut fit {
            field_converged = fit.run(tolerance, &mut |i| progress(Stage::AxisField, i))?;
            points = fit.points();
        }
        let placed_on = |points: &[Vec3],
                         from: Option<&[Vec3]>,
                         how,
                         progress: &mut dyn FnMut(Stage, &IterationInfo)| {
            let sheet = FittedSheet {
                sheet: &sheet,
                points,
            };
            let placed = place(&mesh, from, &conn, sheet, &normalized, how, &mut |i| {
                progress(Stage::Placement, i)
            })?;
            let vertices = placed.vertices.iter().map(|&p| frame.to_model(p)).collect();
            let mesh = PolyMesh::new(vertices, mesh.faces.clone());
            let honeycomb = Honeycomb::new(mesh, &conn, placed.axes.clone(), thickness);
            let measures = measure(&honeycomb, model_surface);
            Ok::<_, crate::error::Error>((placed, honeycomb, measures))
        };
        let (mut placed, mut honeycomb, mut measures) =
            placed_on(&points, placed_before.as_deref(), &placement, progress)?;
        let mut broken = broken_boundary_cells(&honeycomb, &conn, &measures);
        let share = options.max_trimmed_share;
        let margin = if broken.is_empty() {
            0.0
        } else {
            DROPS_EVEN_BY
        };
        let even = |uneven| {
            edge_cv_without(&honeycomb, &conn, &measures, &broken, share) < uneven + margin
        };
        let last = |broken: &[usize]| {
            broken.is_empty()
                || drops == options.max_drops
                || dropped_cells + broken.len() > allowed
        };
        // A provisional result goes to the evening only as one the pipeline would keep, but for
        // its nodes' last digits; else the fit goes on to unit walls.
        let flawed = || last(&broken) && !usable(&honeycomb, &conn, &measures, share);
        let finish = provisional.is_some_and(even);
        let broke = provisional.is_some() && !finish && flawed();
        if let (true, Some(first)) = (finish || broke, first_round.take()) {
            // Cells were dropped where the provisional sheet broke them, which a sheet of unit
            // walls breaks otherwise: back to the first round, its sheet fitted on to unit
            // walls (its guides and regularization where they were), and the rounds again.
            if let Some(field) = fit.map(AxisFit::finish) {
                solves.fit(field);
            }
            solves.then(placed.solve);
            (mesh, conn, points, field_options) =
                (first.mesh, first.conn, first.points, first.field);
            sheet = Sheet::new(&mesh, &conn)?;
            model_base = base.clone();
            (dropped_cells, drops, placed_before) = (0, 0, None);
            (provisional, unconverged_before) = (None, false);
            continue;
        }
        if finish || broke {
            // The fit taken on to unit walls, and the vertices placed on those walls from where
            // they stand (as after a round of drops) or, where the provisional result is
            // flawed, as on the walls of a fit that never stopped.
            provisional = None;
            let mut exact = match fit.take() {
                Some(fit) => fit,
                None => new_fit(&points)?,
            };
            let to_unit = options.field.tolerance;
            field_converged = exact.run(to_unit, &mut |i| progress(Stage::AxisField, i))?;
            points = exact.points();
            fit = Some(exact);
            solves.then(placed.solve);
            let stood = placed.vertices;
            let from = if broke {
                placed_before.as_deref()
            } else {
                Some(&stood[..])
            };
            (placed, honeycomb, measures) = placed_on(&points, from, &placement, progress)?;
            broken = broken_boundary_cells(&honeycomb, &conn, &measures);
        }
        // A sheet whose fit falls short of unit walls twice in a row folds too sharply for
        // fewer boundary cells to help.
        let hopeless = !field_converged && unconverged_before;
        unconverged_before = !field_converged;
        if hopeless || last(&broken) {
            if let Some(field) = fit.map(AxisFit::finish) {
                solves.fit(field);
            }
            solves.then(placed.solve);
            let across = Across {
                honeycomb,
                connectivity: conn,
                base: model_base,
                measures,
                dropped_cells,
                trimmed_cells: 0,
                field_iterations: solves.field_iterations,
                solve: solves.all.expect("a solve ran"),
                field_converged,
                provisional: provisional.is_some(),
            };
            return Ok(trim_overhang(
                across,
                options.max_trimmed_share,
                model_surface,
            ));
        }
        if let Some(field) = fit.map(AxisFit::finish) {
            if let (Some(_), Some(last)) = (provisional, field.history.last()) {
                field_options.faded += field.iterations;
                field_options.eps = last.eps;
            }
            solves.fit(field);
        }
        solves.then(placed.solve);
        if provisional.is_some() && drops == 0 {
            first_round = Some(FirstRound {
                mesh: mesh.clone(),
                conn: conn.clone(),
                points: points.clone(),
                field: field_options.clone(),
            });
        }
        // The sheet's points without the broken cells: each dropped cell's point becomes the
        // ghost of the walls it bordered.
        let kept = kept_vertices(&mesh, &broken);
        let rest = without_cells(&mesh, &broken);
        let rest_conn = validate_base_mesh(&rest)?;
        let rest_sheet = Sheet::new(&rest, &rest_conn)?;
        points = inherited_points(
            &conn,
            &sheet,
            &points,
            &broken,
            &kept,
            &rest_conn,
            &rest_sheet,
        );
        if let Some(axes) = &mut given_axes {
            *axes = kept.iter().map(|&v| axes[v]).collect();
        }
        placed_before = Some(kept.iter().map(|&v| placed.vertices[v]).collect());
        model_base = without_cells(&model_base, &broken);
        mesh = rest;
        conn = rest_conn;
        sheet = rest_sheet;
        dropped_cells += broken.len();
        drops += 1;
    }
}

/// Where a provisional first round stood before it dropped cells: its mesh, its sheet's
/// points, and its fit's options with the guides and regularization where it left them.
struct FirstRound {
    mesh: PolyMesh,
    conn: Connectivity,
    points: Vec<Vec3>,
    field: AxisFieldOptions,
}

/// A node this far off 120 degrees in a provisional result (the sheet fitted to
/// [`PROVISIONAL_GAP`]) is mirrored, as one of 120 degrees or so is in an exact one.
pub const PROVISIONAL_OMEGA_DEG: f64 = 2.0;

/// Whether walls across S fitted provisionally may go to the evening as they stand: no node
/// mirrored, no wall crossed and every vertex on S once the cells that stand out beyond its
/// border are trimmed ([`trim_overhang`], at most `share` of the cells).
fn usable(h: &Honeycomb, conn: &Connectivity, m: &Measures, share: f64) -> bool {
    let on_s = m.closeness_max <= ON_S || !overhanging_cells(h, conn, m, share).is_empty();
    m.omega_max_deg < PROVISIONAL_OMEGA_DEG && m.nonconvex_walls == 0 && on_s
}

/// Every solve, one after the other, and the iterations of the sheet's fits among them.
#[derive(Default)]
struct Solves {
    all: Option<SolveReport>,
    field_iterations: usize,
}

impl Solves {
    fn then(&mut self, next: SolveReport) {
        self.all = Some(match self.all.take() {
            Some(s) => s.then(next),
            None => next,
        })
    }

    fn fit(&mut self, field: SolveReport) {
        self.field_iterations += field.iterations;
        self.then(field);
    }
}

/// The points of `rest_sheet` (the sheet of the mesh without the cells `dropped`, whose vertex
/// `k` was `kept[k]`) taken from `points` of `sheet`: kept cells keep theirs, each ghost takes
/// the mean of the old points across its walls.
fn inherited_points(
    conn: &Connectivity,
    sheet: &Sheet,
    points: &[Vec3],
    dropped: &[usize],
    kept: &[usize],
    rest_conn: &Connectivity,
    rest_sheet: &Sheet,
) -> Vec<Vec3> {
    let kept_cells: Vec<usize> = (0..sheet.cells)
        .filter(|f| dropped.binary_search(f).is_err())
        .collect();
    let mut new_points: Vec<Vec3> = kept_cells.iter().map(|&f| points[f]).collect();
    let mut sums = vec![(Vec3::ZERO, 0usize); rest_sheet.ghosts];
    for (e, &[a, b]) in rest_conn.edges.iter().enumerate() {
        let (old_a, old_b) = (kept[a], kept[b]);
        let Some(&old_e) = conn.vertex_edges[old_a]
            .iter()
            .find(|&&e| conn.edges[e].contains(&old_b))
        else {
            continue;
        };
        // Both connectivities store an edge from its lower vertex, and the kept vertices keep
        // their order: the sides correspond slot by slot.
        for slot in 0..2 {
            let p = rest_sheet.sides[e][slot];
            if p >= rest_sheet.cells {
                let s = &mut sums[p - rest_sheet.cells];
                *s = (s.0 + points[sheet.sides[old_e][slot]], s.1 + 1);
            }
        }
    }
    new_points.extend(sums.iter().map(|&(s, k)| s / k.max(1) as f64));
    new_points
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::hex_disk;

    /// Started from a honeycomb's own vertices, walls and axes (as the evening starts from its
    /// steps), the sheet needs no fit and the placement starts where the vertices stand: one
    /// step besides its start, where one from the base mesh takes three at least, and it puts
    /// the vertices back where they were.
    #[test]
    fn a_start_is_placed_from_where_its_vertices_stand() {
        let base = hex_disk(4.0);
        let plane = PolyMesh::square(20.0);
        let surface = Surface::from_mesh(&plane).unwrap();
        let options = AcrossOptions::default();
        let cold = walls_across(&base, None, &plane, &surface, &options, &mut |_, _| {}).unwrap();
        assert!(cold.solve.iterations > options.placement.iterations);
        let h = &cold.honeycomb;
        let normals: Vec<Vec3> = (0..h.edges.len()).map(|e| h.wall_normal(e)).collect();
        let start = Start {
            vertices: &h.base.vertices,
            wall_normals: &normals,
            axes: &h.axes,
        };
        let warm = walls_across(
            &base,
            Some(start),
            &plane,
            &surface,
            &options,
            &mut |_, _| {},
        )
        .unwrap();
        assert_eq!((warm.field_iterations, warm.solve.iterations), (0, 2));
        let edge = base.mean_edge_length();
        for (a, b) in warm.honeycomb.base.vertices.iter().zip(&h.base.vertices) {
            assert!((*a - *b).norm() < 1e-6 * edge, "{a:?} against {b:?}");
        }
    }
}
