//! A hexagonal base mesh M on a design surface S (the paper's section 3, "Initialization of the
//! base mesh"; Figure 6).
//!
//! Method `flatten`, for disk-like, gently curved surfaces (holes allowed): S is flattened by
//! least-squares conformal maps, a regular hexagonal lattice is laid over the flat domain,
//! cells outside it are dropped (or, with `BoundaryMode::Keep`, closed against its boundary),
//! and the corners are mapped back onto S through the triangles that contain them, so every
//! vertex lies on S exactly. Cell sizes on S inherit the flattening's scale variation, which
//! the report gives (the paper's Figure 6b).
//!
//! Method `field`, for any surface (strongly curved ones too; no flattening): a field-aligned
//! remesher in the manner of Instant Field-Aligned Meshes (see [`field`]) whose triangular
//! lattice is dualized into hexagons on S; cells S's boundary cuts are dropped.

mod arap;
pub mod field;
mod flatten;
mod lattice;
mod locate;
mod principal;
mod seam;
mod strokes;

#[cfg(test)]
pub(crate) use flatten::lifted_grid;
pub use flatten::{flatten, flatten_viewed, Distortion, Flattener, Flattening, Point2};
pub use lattice::{Corner, Lattice};
pub use strokes::{read_strokes, sixfold_mean};

use crate::error::{about, rounded, rounded_down, Error, Result};
use crate::geometry::Vec3;
use crate::mesh::{
    validate_base_mesh, validate_repaired_surface, validate_surface_mesh, Connectivity, PolyMesh,
};
use crate::surface::Surface;
use field::UnionFind;
use locate::Locator;
use serde::Serialize;
use std::cmp::Reverse;
use std::collections::{BTreeMap, HashMap};
use std::str::FromStr;
use std::time::Instant;

/// How large the cells are.
#[derive(Clone, Copy, Debug)]
pub enum CellSize {
    /// About this many cells over S's area.
    Cells(usize),
    /// This edge length (model units).
    EdgeLength(f64),
}

impl CellSize {
    /// The cells' edge length on a surface of `area`.
    pub fn edge_on(self, area: f64) -> f64 {
        match self {
            CellSize::Cells(n) => (area / (n as f64 * hexagon_area(1.0))).sqrt(),
            CellSize::EdgeLength(l) => l,
        }
    }
}

/// The area of a regular hexagon of this edge length.
pub fn hexagon_area(edge: f64) -> f64 {
    1.5 * 3f64.sqrt() * edge * edge
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    Flatten,
    Field,
}

impl Method {
    /// The name `--method` takes.
    pub fn label(self) -> &'static str {
        match self {
            Method::Flatten => "flatten",
            Method::Field => "field",
        }
    }
}

impl FromStr for Method {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Method, String> {
        [Method::Flatten, Method::Field]
            .into_iter()
            .find(|m| m.label() == s)
            .ok_or_else(|| format!("unknown method '{s}': expected flatten or field"))
    }
}

/// Which way the lattice turns.
#[derive(Clone, Debug)]
pub enum Align {
    /// As the flattening leaves it.
    None,
    /// Its edges follow S's boundary as well as they can (6-fold mean direction).
    Boundary,
    /// Its edges follow these polylines on S (the paper's user strokes).
    Strokes(Vec<Vec<Vec3>>),
    /// One of its edge directions follows S's principal curvature directions as well as one
    /// direction can: the long diagonals along it split the cells into the flattest quads
    /// (see `principal.rs`).
    Curvature,
}

impl Align {
    /// `boundary`, `curvature`, `none`, or the path of a polyline file of strokes
    /// ([`read_strokes`]).
    pub fn parse(text: &str) -> Result<Align> {
        match text {
            "boundary" => Ok(Align::Boundary),
            "curvature" => Ok(Align::Curvature),
            "none" => Ok(Align::None),
            path => read_strokes(std::path::Path::new(path))
                .map(Align::Strokes)
                .map_err(|e| match e {
                    Error::Io { path, source } => Error::option(
                        "align",
                        path.display(),
                        format!("expected boundary, curvature, none or a polyline file ({source})"),
                    ),
                    e => e,
                }),
        }
    }
}

/// What a flattened lattice's edges follow (`init.json`'s `lattice_follows`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum LatticeFollows {
    /// Nothing: as the flattening leaves it (asked, or no direction was preferred).
    None,
    Boundary,
    /// S's principal curvature directions.
    Curvature,
    Strokes,
}

/// What happens to cells that S's boundary cuts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum BoundaryMode {
    /// Dropped: every cell lies wholly on S.
    Trim,
    /// Kept when their center is on S, their outside corners moved onto S's boundary.
    Keep,
}

impl FromStr for BoundaryMode {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<BoundaryMode, String> {
        match s {
            "trim" => Ok(BoundaryMode::Trim),
            "keep" => Ok(BoundaryMode::Keep),
            _ => Err(format!(
                "unknown boundary mode '{s}': expected trim or keep"
            )),
        }
    }
}

#[derive(Clone, Debug)]
pub struct InitOptions {
    pub size: CellSize,
    pub method: Method,
    pub align: Align,
    pub boundary: BoundaryMode,
    pub flattener: Flattener,
    /// With `Flattener::Project`: the view direction (unit); `None`: S's mean normal, or the
    /// direction that S's worst triangle faces best.
    pub view: Option<Vec3>,
    /// Shifts the lattice by a pseudo-random offset within one cell (0: no shift); the same
    /// seed gives the same mesh.
    pub seed: u64,
    /// With `Method::Flatten`: turns the lattice by this much more than `align` does
    /// (radians).
    pub turn: f64,
    /// With `Flattener::Arap`: the lattice may turn round a hole that holds curvature (see
    /// `seam`); false flattens S whole.
    pub round_holes: bool,
}

/// A cell edge longer on S than this many lattice edges marks a fold of the flattening.
const MAX_EDGE_STRETCH: f64 = 3.0;

/// Cells more than this are refused as a typo rather than attempted.
pub const MAX_CELLS: usize = 2_000_000;

#[derive(Clone, Debug, Serialize)]
pub struct InitReport {
    pub method: Method,
    /// The seed the mesh was made with (`pipeline` may have moved on from the one asked for).
    pub seed: u64,
    /// Method `flatten`: the flattening, as top-level keys.
    #[serde(flatten)]
    pub flat: Option<FlatteningReport>,
    pub boundary: BoundaryMode,
    pub vertices: usize,
    pub edges: usize,
    pub cells: usize,
    /// Cells by number of sides.
    pub cells_by_sides: BTreeMap<usize, usize>,
    /// Cells with no edge on the boundary, and the share of hexagons among them.
    pub interior_cells: usize,
    pub interior_hexagon_share: f64,
    /// The lattice's edge length in the plane (model units).
    pub edge_length_target: f64,
    pub edge_length_mean: f64,
    /// Standard deviation over mean of the edge lengths on S.
    pub edge_length_cv: f64,
    /// Largest distance of a vertex to S over the mean edge length.
    pub distance_to_surface_max: f64,
    pub valence_histogram: BTreeMap<usize, usize>,
    pub seconds: f64,
}

/// What method `flatten` reports about its flattening.
#[derive(Clone, Debug, Serialize)]
pub struct FlatteningReport {
    /// The flattening used (LSCM when ARAP was asked for but turned triangles over).
    pub flattener: Flattener,
    /// The lattice's rotation in the flattened plane (degrees).
    pub lattice_angle_deg: f64,
    /// What the lattice's edges were turned to follow.
    pub lattice_follows: LatticeFollows,
    /// How far the flattening is from an isometry.
    pub flattening: Distortion,
    /// Triangles of S that the flattening turned over (0 for a good flattening).
    pub flipped_triangles: usize,
    /// Where S has a hole whose border turns by a share of a full turn: the lattice's turn
    /// round it (degrees, a multiple of 60; see `seam`), else null.
    pub hole_turn_deg: Option<f64>,
}

pub struct Initialized {
    pub base: PolyMesh,
    pub report: InitReport,
}

impl InitOptions {
    /// Cells of `size`, the rest as `honeycomb init` has it by default: flatten with ARAP,
    /// aligned with the boundary, cut cells trimmed, no shift.
    pub fn new(size: CellSize) -> InitOptions {
        InitOptions {
            size,
            method: Method::Flatten,
            align: Align::Boundary,
            boundary: BoundaryMode::Trim,
            flattener: Flattener::Arap,
            view: None,
            seed: 0,
            turn: 0.0,
            round_holes: true,
        }
    }

    pub fn validate(&self) -> Result<()> {
        match self.size {
            CellSize::Cells(n) if n == 0 || n > MAX_CELLS => Err(Error::option(
                "cells",
                n,
                format!("expected 1 to {MAX_CELLS}"),
            )),
            CellSize::EdgeLength(l) => crate::error::check_positive_length("edge_length", l),
            _ => Ok(()),
        }
    }
}

/// The edge lengths that make at most [`MAX_CELLS`] cells of `surface`'s area, and cells no
/// larger than the surface: a regular hexagon of S's whole area (and no longer than the
/// diagonal of its bounding box). No longer edge lays a mesh, and no shorter one is allowed;
/// whether the longest in it do depends on S's outline and the method, and
/// [`largest_fitting_edge`] searches for the longest that does.
pub fn edge_length_range(surface: &PolyMesh) -> (f64, f64) {
    let first = surface.vertices.first().copied().unwrap_or(Vec3::ZERO);
    let (lo, hi) = surface
        .vertices
        .iter()
        .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    let area = surface.area();
    let shortest = (area / (MAX_CELLS as f64 * hexagon_area(1.0))).sqrt();
    let one_cell = (area / hexagon_area(1.0)).sqrt();
    (shortest, one_cell.min((hi - lo).norm()))
}

/// The largest edges [`largest_fitting_edge`] tries are found to this many significant digits.
const FITTING_DIGITS: usize = 4;
/// It tries edges down from the top of [`edge_length_range`] by this factor, then halves the
/// step between the last that laid no cell and the first that did.
const FITTING_STEP: f64 = 0.8;
/// It gives up below this share of the top of the range (ten thousand cells' worth).
const FITTING_BOTTOM: f64 = 0.01;
/// It tries sizes for this many seconds at most.
const FITTING_SECONDS: f64 = 2.0;

/// The shortest edge [`largest_fitting_edge`] tries in the range `shortest` to `longest`.
fn fitting_bottom(shortest: f64, longest: f64) -> f64 {
    shortest.max(FITTING_BOTTOM * longest)
}

/// The longest edge length found (to `FITTING_DIGITS` significant digits, and within
/// [`edge_length_range`]) at which `init` with `options` lays a base mesh on `surface`, or
/// `None` when none down to a hundredth of the range's top does within `FITTING_SECONDS`.
/// Found by trying, from the top down and then by halving: cells longer than the surface's
/// outline holds fit nowhere, and where the longest that fit lie depends on the outline, the
/// flattening and the lattice (a size that misses between two that fit can hide a longer
/// one). Deterministic for `options` unless the time runs out; the sizes tried make few
/// cells, each a quick `init`.
pub fn largest_fitting_edge(surface: &PolyMesh, options: &InitOptions) -> Option<f64> {
    let (shortest, longest) = edge_length_range(surface);
    let start = Instant::now();
    let sized = |edge: f64| InitOptions {
        size: CellSize::EdgeLength(edge),
        ..options.clone()
    };
    let bottom = fitting_bottom(shortest, longest);
    // Only a message waits for the answer: sizes past the budget count as not fitting.
    let in_time = || start.elapsed().as_secs_f64() < FITTING_SECONDS;
    match options.method {
        Method::Field => search_down(longest, bottom, |edge| {
            in_time() && init_field(surface, &sized(edge), start).is_ok()
        }),
        Method::Flatten => {
            let (vertices, triangles) = surface.star_triangulated();
            let flat =
                flatten_viewed(&vertices, &triangles, options.flattener, options.view).ok()?;
            let domain = Domain::whole(&vertices, &triangles, &flat);
            search_down(longest, bottom, |edge| {
                in_time() && lay_lattice(surface, &domain, &sized(edge), start).is_ok()
            })
        }
    }
}

/// The largest number of `FITTING_DIGITS` digits from `top` down to `bottom` for which
/// `lays` holds, found in steps of [`FITTING_STEP`] and then by halving the last step.
fn search_down(top: f64, bottom: f64, lays: impl Fn(f64) -> bool) -> Option<f64> {
    let digits = |x: f64| rounded_down(x, FITTING_DIGITS);
    let mut edge = digits(top);
    let mut failed = None;
    let mut fits = loop {
        if !(edge >= bottom && edge > 0.0) {
            return None;
        }
        if lays(edge) {
            break edge;
        }
        failed = Some(edge);
        edge = digits(FITTING_STEP * edge);
    };
    let Some(mut fails) = failed else {
        return Some(fits);
    };
    loop {
        let mid = digits(0.5 * (fits + fails));
        if mid <= fits || mid >= fails {
            return Some(fits);
        }
        if lays(mid) {
            fits = mid;
        } else {
            fails = mid;
        }
    }
}

/// An edge length outside [`edge_length_range`] is refused before any lattice is laid (a
/// longer one fits no cell and overflows the lattice's extent, a shorter one is a memory
/// bomb), naming the range that works: its top the longest edge that lays cells on `surface`
/// with `options` ([`largest_fitting_edge`], tried only for the message).
pub fn check_edge_length(surface: &PolyMesh, options: &InitOptions) -> Result<()> {
    let CellSize::EdgeLength(l) = options.size else {
        return Ok(());
    };
    let (shortest, longest) = edge_length_range(surface);
    if l > longest {
        return Err(too_long(
            surface,
            options,
            l,
            largest_fitting_edge(surface, options),
        ));
    }
    if l < shortest {
        let area = surface.area();
        let cells = area / hexagon_area(1.0) / l / l;
        return Err(Error::Parameter(format!(
            "{}: choose larger cells, {}",
            too_many_cells("--edge-length", l, area, cells),
            working_range(surface, options, largest_fitting_edge(surface, options))
        )));
    }
    Ok(())
}

/// `label edge` (an option, or the words for it) makes `cells` cells on a surface of `area`,
/// more than [`MAX_CELLS`], in words.
fn too_many_cells(label: &str, edge: f64, area: f64, cells: f64) -> String {
    format!(
        "{label} {}: {} on a surface of area {}; expected at most {MAX_CELLS}",
        rounded(edge, 6),
        about(cells, "cells"),
        rounded(area, 6)
    )
}

/// No `cell` ("cell", "whole cell") of `edge` fits on a surface of `area`, which holds about
/// `cells` of them.
fn no_cell_fits(cell: &str, edge: f64, area: f64, cells: f64) -> Error {
    Error::Mesh(format!(
        "no {cell} of edge length {} fits on the surface (area {}, about {} cells): choose \
         smaller cells",
        rounded(edge, 6),
        rounded(area, 6),
        rounded(cells, 2)
    ))
}

/// `--edge-length l`, which lays no cell on `surface`, refused with the range that does
/// (`fits`: the longest edge that lays cells, if one was found).
fn too_long(surface: &PolyMesh, options: &InitOptions, l: f64, fits: Option<f64>) -> Error {
    // About the surface as much as the option: the front names the file.
    Error::Mesh(format!(
        "--edge-length {}: no cell of that size fits on the surface (area {}): choose smaller \
         cells, {}",
        rounded(l, 6),
        rounded(surface.area(), 6),
        working_range(surface, options, fits)
    ))
}

/// `A to B model units`: the range of edge lengths that lays cells on `surface`
/// with `options`, from [`edge_length_range`] and `fits` ([`largest_fitting_edge`]).
fn working_range(surface: &PolyMesh, options: &InitOptions, fits: Option<f64>) -> String {
    let (shortest, longest) = edge_length_range(surface);
    let method = options.method.label();
    match fits {
        Some(fits) => format!(
            "{} to {} model units (the longest that lays cells by the {method} method)",
            rounded(shortest, 6),
            rounded(fits, 6)
        ),
        None => format!(
            "from {}; none of {} down to {} model units lays cells on it by the {method} method",
            rounded(shortest, 6),
            rounded(longest, 6),
            rounded(fitting_bottom(shortest, longest), 6)
        ),
    }
}

/// Cells within this share of the count asked for are taken as they come; beyond it the
/// lattice is rescaled: trimming the boundary and the flattening's area scale move the count.
const COUNT_SLACK: f64 = 0.05;
/// Rescalings of the lattice at most.
const COUNT_ROUNDS: usize = 3;
/// A count still further than this from the one asked for is refused: the method cannot lay
/// cells of one size on this surface.
const COUNT_TOLERANCE: f64 = 0.15;
/// A mesh covering less than this share of S's area (with `--cells`) comes from a flattening
/// that folded over: ARAP is given up for LSCM.
const MIN_COVERED_SHARE: f64 = 0.5;
/// Cells counted to the number asked that cover less than this share of S's area are no base
/// mesh for S: the flattening shrank most of S into a corner of the plane, where the lattice
/// laid few cells or none.
const MIN_LAID_SHARE: f64 = 0.25;

/// A hexagonal base mesh on `surface` (a triangle, quad or polygon mesh, repaired as
/// [`crate::Surface::new`] repairs it). With a number of
/// cells, the lattice is rescaled until the count is within a few percent of it (or as
/// close as three tries come).
pub fn init(surface: &PolyMesh, options: &InitOptions) -> Result<Initialized> {
    let start = Instant::now();
    options.validate()?;
    // A mesh that needs no repair (a pipeline's S, already repaired) is taken as it is.
    let mut repaired = None;
    let conn = match validate_surface_mesh(surface) {
        Ok(conn) if !surface.has_coincident_vertices() => conn,
        _ => {
            let mut mesh = surface.clone();
            let conn = validate_repaired_surface(&mut mesh)?;
            repaired = Some(mesh);
            conn
        }
    };
    let surface = repaired.as_ref().unwrap_or(surface);
    let components = conn.pieces(&vec![false; surface.faces.len()]).len();
    if components > 1 {
        return Err(Error::Mesh(format!(
            "the surface has {components} separate pieces; init needs one (split the file)"
        )));
    }
    check_edge_length(surface, options)?;
    let mut made = made_or_too_long(surface, options, laid(surface, options, start))?;
    made.report.seconds = start.elapsed().as_secs_f64();
    Ok(made)
}

/// `made`, or when it laid no mesh at an edge length longer than the longest that does on
/// `surface`, that edge length refused with the range that works. Below that longest one a
/// failure says that it does lay cells (the lattice can miss at one size and fit at a longer
/// one); failures no edge length mends stay as they were.
fn made_or_too_long(
    surface: &PolyMesh,
    options: &InitOptions,
    made: Result<Initialized>,
) -> Result<Initialized> {
    match (made, options.size) {
        (Err(Error::Mesh(m)), CellSize::EdgeLength(l)) => {
            match largest_fitting_edge(surface, options) {
                Some(fits) if l > fits => Err(too_long(surface, options, l, Some(fits))),
                Some(fits) => Err(Error::Mesh(format!(
                    "--edge-length {}: {m}; yet the lattice misses at some sizes: {}, the \
                     longest edge length found that lays cells by the {} method, does",
                    rounded(l, 6),
                    rounded(fits, 6),
                    options.method.label()
                ))),
                None => Err(Error::Mesh(m)),
            }
        }
        (made, _) => made,
    }
}

/// The base mesh `options` asks for on `surface` (checked, in one piece).
fn laid(surface: &PolyMesh, options: &InitOptions, start: Instant) -> Result<Initialized> {
    let made = match options.method {
        Method::Field => counted(options, |o| init_field(surface, o, start))?,
        Method::Flatten => {
            let (vertices, triangles) = surface.star_triangulated();
            let flat = flatten_viewed(&vertices, &triangles, options.flattener, options.view)?;
            let seamings = if options.round_holes && flat.flattener == Flattener::Arap {
                seam::round_holes(&vertices, &triangles, &flat)
            } else {
                Vec::new()
            };
            let whole = Domain::whole(&vertices, &triangles, &flat);
            let lay =
                |domain: &Domain| counted(options, |o| lay_lattice(surface, domain, o, start));
            // A lattice run on across a seam that gives no valid mesh gives way to the next
            // seam, and the last to the whole.
            let made = match seamings.iter().find_map(|s| lay(&Domain::seamed(s)).ok()) {
                Some(made) => made,
                None => lay(&whole)?,
            };
            let counted = matches!(options.size, CellSize::Cells(_));
            let (made, flat) = if options.flattener == Flattener::Arap
                && flat.flattener == Flattener::Arap
                && counted
                && covered(&made, &flat) < MIN_COVERED_SHARE
            {
                // The refinement folded the domain over itself and cut it apart.
                let lscm = flatten(&vertices, &triangles, Flattener::Lscm)?;
                (lay(&Domain::whole(&vertices, &triangles, &lscm))?, lscm)
            } else {
                (made, flat)
            };
            let share = covered(&made, &flat);
            if counted && share < MIN_LAID_SHARE {
                return Err(Error::Mesh(format!(
                    "the cells asked for cover {}% of S only: its flattening ({}) shrinks \
                     areas down to {} and stretches them up to {} times, so that most of S \
                     lies in a corner of the plane (S wraps around a hole, or curves too much \
                     to lie flat); --method field remeshes S without flattening it",
                    (100.0 * share).round(),
                    format!("{:?}", flat.flattener).to_lowercase(),
                    rounded(flat.distortion.area_scale_min, 3),
                    rounded(flat.distortion.area_scale_max, 3),
                )));
            }
            made
        }
    };
    Ok(made)
}

/// The share of S's area (that of its flattening `flat`) that the cells of `made` cover.
fn covered(made: &Initialized, flat: &Flattening) -> f64 {
    made.base.area() / flat.area
}

/// A flattened S to lay the lattice on: S (or S cut open along a seam) and its flattening.
struct Domain<'a> {
    vertices: &'a [Vec3],
    triangles: &'a [[usize; 3]],
    flat: &'a Flattening,
    /// S's own border (without the seam's sides).
    border: Vec<[usize; 2]>,
    /// The seam and the lattice's turn across it (degrees).
    seam: Option<(&'a seam::PlaneSeam, f64)>,
}

impl<'a> Domain<'a> {
    fn whole(vertices: &'a [Vec3], triangles: &'a [[usize; 3]], flat: &'a Flattening) -> Self {
        Domain {
            vertices,
            triangles,
            flat,
            border: flatten::boundary_half_edges(triangles),
            seam: None,
        }
    }

    fn seamed(s: &'a seam::Seamed) -> Self {
        let sides: std::collections::HashSet<[usize; 2]> = s
            .cut
            .pairs
            .windows(2)
            .flat_map(|w| {
                let (a, b) = ([w[0].0, w[1].0], [w[0].1, w[1].1]);
                [a, [a[1], a[0]], b, [b[1], b[0]]]
            })
            .collect();
        let mut border = flatten::boundary_half_edges(&s.cut.triangles);
        border.retain(|e| !sides.contains(e));
        Domain {
            vertices: &s.cut.vertices,
            triangles: &s.cut.triangles,
            flat: &s.flat,
            border,
            seam: Some((&s.seam, s.turn_deg)),
        }
    }
}

/// `make` with `options`, and with rescaled cells while the count is off what `options` asks.
fn counted(
    options: &InitOptions,
    make: impl Fn(&InitOptions) -> Result<Initialized>,
) -> Result<Initialized> {
    let mut made = make(options)?;
    let CellSize::Cells(target) = options.size else {
        return Ok(made);
    };
    let off = |m: &Initialized| (m.report.cells as f64 / target as f64 - 1.0).abs();
    for _ in 0..COUNT_ROUNDS {
        if off(&made) <= COUNT_SLACK {
            break;
        }
        let ratio = made.report.cells as f64 / target as f64;
        let edge = made.report.edge_length_target * ratio.sqrt();
        let rescaled = InitOptions {
            size: CellSize::EdgeLength(edge),
            ..options.clone()
        };
        match make(&rescaled) {
            Ok(again) if off(&again) < off(&made) => made = again,
            _ => break,
        }
    }
    if off(&made) > COUNT_TOLERANCE {
        let why = match &made.report.flat {
            Some(f) => format!(
                "its flattening ({}) stretches lengths by a cv of {} and areas from {} to {} \
                 times (S wraps around a hole, or curves too much to lie flat); --method field \
                 remeshes S without flattening it",
                format!("{:?}", f.flattener).to_lowercase(),
                crate::error::rounded(f.flattening.length_scale_cv, 3),
                crate::error::rounded(f.flattening.area_scale_min, 3),
                crate::error::rounded(f.flattening.area_scale_max, 3),
            ),
            None => "the field-aligned lattice does not cover S at this size; try another \
                     --cells or --seed"
                .into(),
        };
        return Err(Error::Mesh(format!(
            "{} cells for the {target} asked (more than {}% off): {why}",
            made.report.cells,
            (100.0 * COUNT_TOLERANCE).round()
        )));
    }
    Ok(made)
}

/// A regular hexagonal lattice laid over `domain`, a flattening of `surface` (perhaps cut open
/// along a seam that the lattice runs on across), its corners mapped back onto S.
fn lay_lattice(
    surface: &PolyMesh,
    domain: &Domain,
    options: &InitOptions,
    start: Instant,
) -> Result<Initialized> {
    let (vertices, triangles, flat) = (domain.vertices, domain.triangles, domain.flat);
    let area = flat.area;
    let edge = options.size.edge_on(area);
    let fits = area / hexagon_area(edge);
    if fits > MAX_CELLS as f64 {
        return Err(Error::Parameter(too_many_cells(
            "--edge-length",
            edge,
            area,
            fits,
        )));
    }
    let border = &domain.border;
    let (angle, follows) = lattice_angle(options, vertices, triangles, &flat.points, border)?;
    let seeded = Lattice {
        edge,
        angle,
        offset: seeded_offset(options.seed, edge),
    };
    let lattice = match domain.seam.map(|s| s.0.carry) {
        // Round a seam the lattice turns about a cell's center, which must be the seam's: a
        // seed turns it about there instead of shifting it.
        Some(seam::Carry::Turn { center, .. }) => {
            let share = seeded_offset(options.seed, 1.0)[0] / 3f64.sqrt();
            Lattice {
                edge,
                angle: angle + share * std::f64::consts::FRAC_PI_3,
                offset: center,
            }
        }
        // Round a tube the shift across the seam must be a step of the lattice.
        Some(seam::Carry::Shift(shift)) => seeded.with_step(shift).ok_or_else(|| {
            Error::Mesh(format!(
                "cells of edge length {} are wider than the tube S wraps round",
                rounded(edge, 6)
            ))
        })?,
        None => seeded,
    };
    let (edge, angle) = (lattice.edge, lattice.angle);
    // The lattice covers the flat domain's bounding box: a thin diagonal strip could ask for
    // far more cells there than the surface holds.
    let (lo, hi) = bounds(&flat.points);
    let covering = (hi[0] - lo[0] + 4.0 * edge) * (hi[1] - lo[1] + 4.0 * edge) / hexagon_area(edge);
    // A NaN comes from an extent that overflows.
    if covering.is_nan() || covering > 10.0 * MAX_CELLS as f64 {
        return Err(Error::Mesh(format!(
            "the flattened surface spreads over {} of its bounding box for {fits:.0} on \
             the surface: too thin for a grid of this size",
            about(covering, "cells"),
        )));
    }
    let locator = Locator::new(&flat.points, triangles);
    let placed = place_cells(
        &lattice,
        &flat.points,
        &locator,
        border,
        options.boundary,
        domain.seam.map(|s| s.0),
    );
    if placed.is_empty() {
        return Err(no_cell_fits("cell", edge, area, fits));
    }
    // Each corner's position on S: through its triangle, or along its boundary edge.
    let to_surface = |p: &Placed| match p {
        Placed::Inside(l) => triangles[l.triangle]
            .iter()
            .zip(l.weights)
            .fold(Vec3::ZERO, |s, (&v, w)| s + vertices[v] * w),
        Placed::OnBoundary { segment, t, .. } => {
            let [a, b] = border[*segment];
            vertices[a] * (1.0 - t) + vertices[b] * *t
        }
    };
    // A cell whose corners land far apart on S straddles a place where the flattening
    // overlaps itself (an annulus can wrap over its own hole): dropped.
    let folded = |corners: &[Corner; 6]| {
        let corners = corners.map(|c| to_surface(&placed.corners[&c]));
        (0..6).any(|k| (corners[k] - corners[(k + 1) % 6]).norm() > MAX_EDGE_STRETCH * edge)
    };
    let corners_of: HashMap<(i64, i64), [Corner; 6]> = placed.cells.iter().copied().collect();
    let unfolded: Vec<(i64, i64)> = placed
        .cells
        .iter()
        .filter(|(_, corners)| !folded(corners))
        .map(|&(cell, _)| cell)
        .collect();
    if unfolded.is_empty() {
        return Err(Error::Mesh(format!(
            "every one of the {} cells of edge length {} straddles a place where the \
             flattening overlaps itself; try other --cells or --method field",
            placed.cells.len(),
            rounded(edge, 6)
        )));
    }
    let cells = one_piece(&unfolded, &corners_of);
    let mut index: HashMap<Corner, usize> = HashMap::new();
    let mut mesh_vertices = Vec::new();
    let mut faces = Vec::new();
    for cell in &cells {
        let face = corners_of[cell]
            .iter()
            .map(|c| {
                *index.entry(*c).or_insert_with(|| {
                    mesh_vertices.push(to_surface(&placed.corners[c]));
                    mesh_vertices.len() - 1
                })
            })
            .collect();
        faces.push(face);
    }
    let base = PolyMesh::new(mesh_vertices, faces);
    let base_conn = validate_base_mesh(&base).map_err(|e| match (e, options.boundary) {
        (Error::Mesh(m), BoundaryMode::Keep) => Error::Mesh(format!(
            "closing the cells against the boundary gave an invalid base mesh ({m}); \
             --boundary trim always gives a valid one"
        )),
        (e, _) => e,
    })?;
    let report = report(
        &base,
        &base_conn,
        surface,
        options,
        edge,
        Some(FlatteningReport {
            flattener: flat.flattener,
            lattice_angle_deg: angle.to_degrees(),
            lattice_follows: follows,
            flattening: flat.distortion.clone(),
            flipped_triangles: flat.flipped,
            hole_turn_deg: domain.seam.map(|s| s.1),
        }),
        start,
    )?;
    Ok(Initialized { base, report })
}

/// Method `field`: the field-aligned remesher on S itself; cells S's boundary cuts are dropped.
fn init_field(surface: &PolyMesh, options: &InitOptions, start: Instant) -> Result<Initialized> {
    if options.boundary == BoundaryMode::Keep {
        return Err(Error::Parameter(
            "--boundary keep closes cells in a flattening; --method field trims them (use \
             --method flatten to keep them)"
                .into(),
        ));
    }
    let edge = options.size.edge_on(surface.area());
    // Strokes come on top of the boundary: near a stroke the hex edges follow it.
    let (strokes, follow_boundary): (&[Vec<Vec3>], bool) = match &options.align {
        Align::Strokes(lines) => (lines, true),
        Align::Boundary => (&[], true),
        Align::None => (&[], false),
        Align::Curvature => {
            return Err(Error::Parameter(
                "--align curvature turns the flattened lattice (--method flatten); --method \
                 field follows the boundary, strokes or nothing"
                    .into(),
            ))
        }
    };
    let base = field::field_hex_mesh(surface, edge, strokes, follow_boundary, options.seed)?;
    let conn = validate_base_mesh(&base)?;
    let report = report(&base, &conn, surface, options, edge, None, start)?;
    Ok(Initialized { base, report })
}

/// The rotation that makes the lattice's edges follow the boundary, S's principal directions
/// or the strokes, and what they follow.
fn lattice_angle(
    options: &InitOptions,
    vertices: &[Vec3],
    triangles: &[[usize; 3]],
    points: &[Point2],
    border: &[[usize; 2]],
) -> Result<(f64, LatticeFollows)> {
    // Lattice edges run at 30, 90 and 150 degrees before rotation: turn 30 degrees less.
    let edge_direction = std::f64::consts::FRAC_PI_6;
    let boundary = || sixfold_mean(border.iter().map(|&[a, b]| (points[a], points[b])));
    let (mean, follows) = match &options.align {
        Align::None => return Ok((options.turn, LatticeFollows::None)),
        Align::Boundary => (boundary(), LatticeFollows::Boundary),
        // Where S's principal directions do not agree, the boundary's.
        Align::Curvature => match principal::least_twist_direction(vertices, triangles, points) {
            Some(direction) => (Some(direction), LatticeFollows::Curvature),
            None => (boundary(), LatticeFollows::Boundary),
        },
        Align::Strokes(lines) => {
            // Each stroke point goes where its nearest vertex of S went.
            let nearest = |p: Vec3| {
                (0..vertices.len())
                    .min_by(|&a, &b| {
                        (vertices[a] - p)
                            .norm_squared()
                            .total_cmp(&(vertices[b] - p).norm_squared())
                    })
                    .map(|v| points[v])
                    .unwrap_or([0.0, 0.0])
            };
            let planar: Vec<Vec<Point2>> = lines
                .iter()
                .map(|l| l.iter().map(|&p| nearest(p)).collect())
                .collect();
            let segments = planar
                .iter()
                .flat_map(|l| l.windows(2).map(|w| (w[0], w[1])));
            let mean = sixfold_mean(segments);
            if mean.is_none() {
                return Err(Error::Parameter(
                    "--align: the strokes give no direction on the surface (too short, or \
                     spread evenly over all directions)"
                        .into(),
                ));
            }
            (mean, LatticeFollows::Strokes)
        }
    };
    match mean {
        Some(m) => Ok((m - edge_direction + options.turn, follows)),
        None => Ok((options.turn, LatticeFollows::None)),
    }
}

/// A pseudo-random shift of the lattice within one cell (splitmix64 of the seed).
fn seeded_offset(seed: u64, edge: f64) -> Point2 {
    if seed == 0 {
        return [0.0, 0.0];
    }
    let mut z = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut next = || {
        z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut x = z;
        x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((x ^ (x >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    };
    [next() * 3f64.sqrt() * edge, next() * 1.5 * edge]
}

/// Where a lattice corner landed.
#[derive(Clone, Copy, Debug)]
enum Placed {
    Inside(locate::Located),
    /// Moved onto boundary segment `segment` at parameter `t` (`Keep` only).
    OnBoundary {
        segment: usize,
        t: f64,
        point: Point2,
    },
}

impl Placed {
    fn point(&self, points: &[Point2], triangles: &[[usize; 3]]) -> Point2 {
        match self {
            Placed::Inside(l) => {
                let t = triangles[l.triangle];
                let mut p = [0.0, 0.0];
                for (&v, w) in t.iter().zip(l.weights) {
                    p[0] += w * points[v][0];
                    p[1] += w * points[v][1];
                }
                p
            }
            Placed::OnBoundary { point, .. } => *point,
        }
    }
}

struct PlacedCells {
    /// Each cell and its corners (across a seam, the corners it runs on into).
    cells: Vec<((i64, i64), [Corner; 6])>,
    corners: HashMap<Corner, Placed>,
}

impl PlacedCells {
    fn is_empty(&self) -> bool {
        self.cells.is_empty()
    }
}

fn place_cells(
    lattice: &Lattice,
    points: &[Point2],
    locator: &Locator,
    boundary: &[[usize; 2]],
    mode: BoundaryMode,
    seam: Option<&seam::PlaneSeam>,
) -> PlacedCells {
    let triangles = locator.triangles();
    let (lo, hi) = bounds(points);
    let mut corners: HashMap<Corner, Option<Placed>> = HashMap::new();
    let mut locate_corner = |c: Corner| {
        *corners
            .entry(c)
            .or_insert_with(|| locator.locate(lattice.corner(c)).map(Placed::Inside))
    };
    // A point a step from a cell's center that lies beyond a side of the seam is the point
    // the lattice runs on into across it.
    let across = |center: Point2, p: Point2| {
        let q = seam.and_then(|s| s.across(center, p))?;
        locator.locate(q).map(|l| (q, l))
    };
    // Cells holding a boundary vertex: over a hole smaller than a cell, all their corners can
    // lie on S while the cell spans the hole.
    let holding: std::collections::HashSet<(i64, i64)> = boundary
        .iter()
        .map(|&[a, _]| lattice.cell_containing(points[a]))
        .collect();
    let mut cells = Vec::new();
    let mut placed: HashMap<Corner, Placed> = HashMap::new();
    for cell in lattice.cells_covering(lo, hi) {
        let center = lattice.center(cell);
        let center_inside = locator.locate(center).is_some();
        // Round a seam, a cell whose center lies beyond it is laid as the cell it runs on into.
        if seam.is_some() && !center_inside {
            continue;
        }
        let keys = Lattice::cell_corners(cell);
        let mut canonical = keys;
        let mut found = keys.map(&mut locate_corner);
        for k in 0..6 {
            if found[k].is_none() {
                if let Some((q, l)) = across(center, lattice.corner(keys[k])) {
                    canonical[k] = lattice.corner_near(q);
                    found[k] = Some(Placed::Inside(l));
                }
            }
        }
        let all_inside = found.iter().all(Option::is_some);
        // A concave stretch of boundary can cross an edge whose ends are both inside.
        let edges_inside = all_inside
            && !holding.contains(&cell)
            && (0..6).all(|k| {
                let (p, q) = (lattice.corner(keys[k]), lattice.corner(keys[(k + 1) % 6]));
                let middle = [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])];
                locator.locate(middle).is_some() || across(center, middle).is_some()
            });
        if edges_inside {
            for (k, f) in canonical.iter().zip(found) {
                placed.insert(*k, f.expect("inside"));
            }
            cells.push((cell, canonical));
            continue;
        }
        // Keep closes cells cut by the boundary; one with every corner on S yet not whole
        // spans a hole or a notch of the boundary, and is dropped in both modes.
        if mode == BoundaryMode::Trim || all_inside || !center_inside {
            continue;
        }
        // Keep: outside corners onto the nearest boundary point; the closed cell must stay a
        // fair convex hexagon, else it is dropped. A corner across a seam keeps its place in
        // the cell's own frame for that test.
        let closed: Vec<Placed> = keys
            .iter()
            .zip(found)
            .map(|(k, f)| f.unwrap_or_else(|| snap(lattice.corner(*k), points, boundary)))
            .collect();
        let polygon: Vec<Point2> = closed
            .iter()
            .zip(canonical.iter().zip(keys))
            .map(|(p, (c, k))| {
                if *c == k {
                    p.point(points, triangles)
                } else {
                    lattice.corner(k)
                }
            })
            .collect();
        if fair_hexagon(&polygon, lattice.edge) {
            for (k, p) in canonical.iter().zip(closed) {
                placed.entry(*k).or_insert(p);
            }
            cells.push((cell, canonical));
        }
    }
    PlacedCells {
        cells,
        corners: placed,
    }
}

/// The bounding box of planar points.
pub(crate) fn bounds(points: &[Point2]) -> (Point2, Point2) {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for c in 0..2 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    (lo, hi)
}

/// The nearest point of the boundary to `p`.
fn snap(p: Point2, points: &[Point2], boundary: &[[usize; 2]]) -> Placed {
    let mut best = (f64::INFINITY, 0, 0.0, p);
    for (s, &[a, b]) in boundary.iter().enumerate() {
        let (pa, pb) = (points[a], points[b]);
        let d = [pb[0] - pa[0], pb[1] - pa[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        let t = if len2 > 0.0 {
            (((p[0] - pa[0]) * d[0] + (p[1] - pa[1]) * d[1]) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let q = [pa[0] + t * d[0], pa[1] + t * d[1]];
        let dist = (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
        if dist < best.0 {
            best = (dist, s, t, q);
        }
    }
    Placed::OnBoundary {
        segment: best.1,
        t: best.2,
        point: best.3,
    }
}

/// Convex, counter-clockwise, no edge shorter than a quarter of the lattice's, and at least
/// a third of a full cell's area.
fn fair_hexagon(polygon: &[Point2], edge: f64) -> bool {
    let n = polygon.len();
    let mut area = 0.0;
    for k in 0..n {
        let (a, b, c) = (polygon[k], polygon[(k + 1) % n], polygon[(k + 2) % n]);
        let length = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
        let turn = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
        if length < 0.25 * edge || turn <= 0.0 {
            return false;
        }
        area += a[0] * b[1] - b[0] * a[1];
    }
    0.5 * area >= 0.5 * 3f64.sqrt() * edge * edge
}

/// The cells of the largest piece joined through shared edges (stray cells dropped), less
/// those that touch it only at a corner: across a seam, where the cell between two laid
/// cells lies beyond S's border, they meet at a corner alone, which no mesh can hold.
fn one_piece(
    cells: &[(i64, i64)],
    corners_of: &HashMap<(i64, i64), [Corner; 6]>,
) -> Vec<(i64, i64)> {
    let edge = |c: &[Corner; 6], k: usize| {
        let (a, b) = (c[k], c[(k + 1) % 6]);
        (a.min(b), a.max(b))
    };
    let mut kept = cells.to_vec();
    loop {
        let mut by_edge: HashMap<(Corner, Corner), Vec<usize>> = HashMap::new();
        let mut round: HashMap<Corner, Vec<usize>> = HashMap::new();
        for (n, cell) in kept.iter().enumerate() {
            for k in 0..6 {
                by_edge
                    .entry(edge(&corners_of[cell], k))
                    .or_default()
                    .push(n);
                round.entry(corners_of[cell][k]).or_default().push(n);
            }
        }
        // The pieces joined through shared edges: all but the largest go.
        let mut piece = UnionFind::new(kept.len());
        for sharing in by_edge.values() {
            for w in sharing.windows(2) {
                piece.union(w[0], w[1]);
            }
        }
        let mut drop = all_but_largest(&mut piece);
        // Round each corner, the cells joined through the edges that end there: where they
        // make two groups, all but the largest go.
        for (corner, sharing) in &round {
            let mut group = UnionFind::new(sharing.len());
            for (a, &n) in sharing.iter().enumerate() {
                let c = &corners_of[&kept[n]];
                for k in (0..6).filter(|&k| c[k] == *corner || c[(k + 1) % 6] == *corner) {
                    for m in &by_edge[&edge(c, k)] {
                        if let Some(b) = sharing.iter().position(|x| x == m) {
                            group.union(a, b);
                        }
                    }
                }
            }
            for (a, gone) in all_but_largest(&mut group).into_iter().enumerate() {
                drop[sharing[a]] |= gone;
            }
        }
        if !drop.contains(&true) {
            return kept;
        }
        kept = kept
            .iter()
            .zip(&drop)
            .filter(|(_, &d)| !d)
            .map(|(&c, _)| c)
            .collect();
    }
}

/// Per member of `sets`: whether it lies outside the largest set (of equals, the one holding
/// the first member).
fn all_but_largest(sets: &mut UnionFind) -> Vec<bool> {
    let n = sets.members();
    let largest = (0..n)
        .max_by_key(|&k| (sets.size_of(k), Reverse(k)))
        .map(|k| sets.find(k));
    (0..n).map(|k| Some(sets.find(k)) != largest).collect()
}

#[allow(clippy::too_many_arguments)]
fn report(
    base: &PolyMesh,
    conn: &Connectivity,
    surface: &PolyMesh,
    options: &InitOptions,
    edge: f64,
    flat: Option<FlatteningReport>,
    start: Instant,
) -> Result<InitReport> {
    let mut cells_by_sides = BTreeMap::new();
    for f in &base.faces {
        *cells_by_sides.entry(f.len()).or_insert(0) += 1;
    }
    let interior: Vec<usize> = (0..base.faces.len())
        .filter(|&f| !conn.is_boundary_face(f))
        .collect();
    let interior_hexagons = interior
        .iter()
        .filter(|&&f| base.faces[f].len() == 6)
        .count();
    let lengths: Vec<f64> = conn
        .edges
        .iter()
        .map(|&[a, b]| (base.vertices[a] - base.vertices[b]).norm())
        .collect();
    let mean = lengths.iter().sum::<f64>() / lengths.len() as f64;
    let var = lengths.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / lengths.len() as f64;
    let s = Surface::from_mesh(surface)?;
    let distance = s
        .closest_points(&base.vertices)
        .iter()
        .fold(0.0f64, |m, c| m.max(c.distance));
    let mut valence_histogram = BTreeMap::new();
    for v in 0..base.vertices.len() {
        *valence_histogram.entry(conn.valence(v)).or_insert(0) += 1;
    }
    Ok(InitReport {
        method: options.method,
        seed: options.seed,
        flat,
        boundary: options.boundary,
        vertices: base.vertices.len(),
        edges: conn.num_edges(),
        cells: base.faces.len(),
        cells_by_sides,
        interior_cells: interior.len(),
        interior_hexagon_share: if interior.is_empty() {
            0.0
        } else {
            interior_hexagons as f64 / interior.len() as f64
        },
        edge_length_target: edge,
        edge_length_mean: mean,
        edge_length_cv: var.sqrt() / mean,
        distance_to_surface_max: distance / mean,
        valence_histogram,
        seconds: start.elapsed().as_secs_f64(),
    })
}
