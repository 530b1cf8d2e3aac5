//! Quadrangulation (paper section 4, Figs. 1, 11, 17) as an option of `optimize`: every
//! hexagon of a finished honeycomb is split into two quads that must be planar, with soft
//! fairness of the zigzag and straight polylines (see [`cap`]).

pub use crate::structure::QuadPattern;

use super::kept_walls::{kept_wall_families, onto_kept_walls, HOLD_WEIGHT};
use super::variants::check_weight;
use super::Frame;
use crate::constraints::{
    BoundedPlanarity, FixedNormalRow, FixedNormals, Layout, MinEdgeLength, QuadNormalBlock,
    QuadNormalization, QuadPlanarity, WallConvexity, ZigzagFairness,
};
use crate::error::{Error, Result};
use crate::geometry::{smallest_eigenvector, sum_of_outer_products, Vec3};
use crate::mesh::{Connectivity, PolyMesh};
use crate::solve::{
    Constraint, GuidedProjection, IterationInfo, Role, SolveReport, SolveState, SolverOptions,
};
use crate::structure::{
    edge_length_cv, face_measures, is_convex, meet_quad_floors, quad_planarities, quad_planarity,
    FaceMeasures, Honeycomb, QuadCover, FLAT_QUAD, FLAT_QUAD_MEAN,
};
use crate::surface::Surface;

#[derive(Clone, Debug)]
pub struct QuadOptions {
    pub pattern: QuadPattern,
    /// The straight polylines run along the lattice direction closest to this (model
    /// coordinates); `None`: the direction whose quads start closest to planar.
    pub direction: Option<Vec3>,
    /// Weight of the quad planarity rows (the paper's w_cons^faces; 1, against closeness to S
    /// at 0.3).
    pub w_cons_faces: f64,
    /// Weight of zigzag fairness (the paper's w_fair^zig, 0.01).
    pub w_fair_zigzag: f64,
    /// Weight of straight-polyline fairness (the paper's w_fair^str, 0.01).
    pub w_fair_straight: f64,
    /// How far the cells may re-shape for flatter quads, as the edge-length cv they may
    /// reach: where the quads held along S miss the floors, the vertices slide along S too
    /// (within their walls), and the slid capping is kept if it is flatter and its cells stay
    /// this even. `None`: each vertex keeps its place along S, and the cells their shape.
    pub reshape: Option<f64>,
    /// Every hexagon split as the pattern says. Else, where the pattern's quads stay short of
    /// the floors, the cells whose quads stay least planar take their own flattest diagonal
    /// (`QuadCover::off_pattern`), the pattern's polylines broken there.
    pub whole_pattern: bool,
}

impl Default for QuadOptions {
    fn default() -> Self {
        QuadOptions {
            pattern: QuadPattern::Zigzag,
            direction: None,
            w_cons_faces: 1.0,
            w_fair_zigzag: 0.01,
            w_fair_straight: 0.01,
            reshape: None,
            whole_pattern: false,
        }
    }
}

impl QuadOptions {
    pub fn validate(&self) -> Result<()> {
        if let Some(d) = self.direction {
            if !d.is_finite() || d.norm() < 1e-12 {
                return Err(Error::option(
                    "quad_direction",
                    crate::error::short_vector(d),
                    "expected a non-zero finite vector",
                ));
            }
        }
        check_weight("w_cons_faces", self.w_cons_faces, false)?;
        check_weight("w_fair_zig", self.w_fair_zigzag, true)?;
        check_weight("w_fair_str", self.w_fair_straight, true)?;
        match self.reshape {
            Some(cv) if !(cv.is_finite() && cv > 0.0 && cv <= MAX_RESHAPE) => Err(Error::option(
                "quads_reshape",
                crate::error::short_number(cv),
                format!("expected an edge-length cv above 0 and at most {MAX_RESHAPE}, e.g. 0.3"),
            )),
            _ => Ok(()),
        }
    }
}

/// The polyline fairness keeps its small weight to the end instead of fading with the
/// regularization: with the hold along S it is what keeps the polylines as the honeycomb drew
/// them, which the quad planarity pulls at.
const FAIRNESS_ROLE: Role = Role::Condition;

/// Which sides of a quad get a planarity row: all four (see `QuadPlanarity::sides`).
const SIDES: [usize; 4] = [0, 1, 2, 3];

/// One capping try: how firmly the vertices keep to S, and whether they may slide along it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct CappingTry {
    /// Weight of closeness to S. The freedom to planarize lies mostly across S (each vertex
    /// slides along its node axis), and this is what it costs; each vertex firms up once it
    /// strays past `FIRM_PAST` (see `BoundedCloseness`), so that the bound goes where the
    /// quads need it.
    pub closeness: f64,
    /// The vertices slide along S as freely as across it (up to their walls), the quads that
    /// stay less planar than `FLAT_ENOUGH` firm up, and the walls are held convex; else each
    /// vertex is held where it stands along S.
    pub sliding: bool,
}

/// The held tries, within one budget of iterations for all, until no vertex is farther than
/// `MAX_DISTANCE_FROM_S` from S and no wall crosses itself or runs backwards; if none is, the
/// honeycomb stays as it was. From loose to firm.
const HELD_TRIES: [CappingTry; 4] = [
    CappingTry {
        closeness: 0.03,
        sliding: false,
    },
    CappingTry {
        closeness: 0.3,
        sliding: false,
    },
    CappingTry {
        closeness: 1.0,
        sliding: false,
    },
    CappingTry {
        closeness: 3.0,
        sliding: false,
    },
];

/// Where the held quads miss the floors and the cells may re-shape: where S twists, a quad's
/// planarity needs its cell to shift along S within its walls, which only a slide gives. Its
/// closeness is firm from the start: with nothing else holding them, loose vertices wander off
/// S and back, and on the way their walls cross.
const SLIDING_TRY: CappingTry = CappingTry {
    closeness: 1.0,
    sliding: true,
};

/// The share of the budget the held tries have where a sliding try may follow; it has the
/// rest.
const HELD_SHARE: f64 = 1.0 / 3.0;

/// The hold along S of a sliding try: enough to pin the vertices' tangential moves that
/// nothing else asks for, not the planarity's.
const SLIDING_HOLD: f64 = 0.003;
/// How uneven the held tries may leave the cells (edge-length cv): as even as a honeycomb is
/// asked to be. Any capping may reach the honeycomb's own cv and a little more where that is
/// higher.
const EVEN_CELLS: f64 = 0.12;
const CV_ALLOWANCE: f64 = 0.01;
/// The most re-shaping that may be asked for: a cv past it is a typo.
const MAX_RESHAPE: f64 = 10.0;
/// The quads a sliding try firms up (see `BoundedPlanarity`): short of the floor asked of a
/// cover's worst quad (0.01), since one past it takes a few steps to come down.
const FLAT_ENOUGH: f64 = 0.008;
/// A sliding try keeps its regularization at this instead of letting it shrink: the slides
/// along S are otherwise held by nothing but it, and longer steps cross walls.
const SLIDING_EPS: f64 = 1e-2;
/// Weight of the walls' convexity in a sliding try: above the planarity's firmest.
const CONVEXITY_WEIGHT: f64 = 100.0;
/// Where a vertex starts to firm up, in mean edge lengths: short of `MAX_DISTANCE_FROM_S`,
/// since one past it takes a few steps to come back.
const FIRM_PAST: f64 = 0.09;
/// How far capping may take a vertex from S, in mean edge lengths.
const MAX_DISTANCE_FROM_S: f64 = 0.1;

/// Where a pattern's quads stay short of the floors, the cappings with cells taken off it aim
/// at these shares of the floors in turn: the floors themselves, then lower, where a capping
/// fell short of what its choice of cells guessed.
const OFF_PATTERN_AIMS: [f64; 3] = [1.0, 0.85, 0.7];
/// At most this share of a pattern's hexagons may leave it: past it, the cover is no longer
/// the pattern asked for.
const MAX_OFF_PATTERN: f64 = 0.2;

/// A step that changes the quads' largest and mean planarity by less than this has left them
/// as they are to the digits that delta_face is read to: the capping has settled.
const SETTLED_PLANARITY: f64 = 1e-5;
/// Where cells may leave the pattern after it, the pattern whole's capping settles at this
/// instead: the cappings with cells off it need the budget more than it needs its last digits.
const SETTLED_BEFORE_CELLS_OFF: f64 = 5e-5;

/// Every edge stays at least this long (mean edge lengths): a quad with a vanishing side is
/// a triangle, so planarity pulls at short edges, and where the axes at an edge's ends lean
/// together a short edge crosses its wall.
const MIN_EDGE: f64 = 0.5;

/// A honeycomb capped by planar quads, in model units.
pub struct Capped {
    /// M's vertices after capping; faces, walls and node axes are the honeycomb's.
    pub vertices: Vec<Vec3>,
    pub cover: QuadCover,
    pub solve: SolveReport,
    /// Where cells were taken off the pattern (`cover.off_pattern`): the quads' planarity as
    /// the pattern whole left them.
    pub whole: Option<FaceMeasures>,
}

/// Caps every hexagon of `honeycomb` (model units, with its unit wall normals `normals`, one
/// per edge of `conn`) by two quads and moves the vertices until the quads are
/// as planar as the walls allow within `MAX_DISTANCE_FROM_S` of S.
///
/// The walls are kept: every wall normal stays as it is, so each node keeps its angles and
/// its axis, and each edge stays in its wall plane (a linear row). What moves is where the
/// vertices sit on their walls: along the node axes (off S, softly held) and, held harder,
/// along S. A honeycomb on S keeps about one degree of freedom per cell; its two quads ask
/// for two, which the slides along the axes give. With the wall normals as unknowns too the
/// planarity pulls the node conditions with it and the solve ends off 120 degrees. Where the
/// quads held along S miss the floors and `options.reshape` lets the cells re-shape, the
/// vertices slide along S too (`SLIDING_TRY`), and the flatter capping is kept.
pub(crate) fn cap(
    honeycomb: &Honeycomb,
    conn: &Connectivity,
    normals: &[Vec3],
    surface: &PolyMesh,
    options: &QuadOptions,
    solver: &SolverOptions,
    progress: &mut dyn FnMut(&IterationInfo),
) -> Result<Capped> {
    let walls = (honeycomb, conn, normals);
    // The kept walls are weighted rows: the capping's vertices are put on them exactly.
    let on_walls = |mut c: Capped| {
        c.vertices = onto_kept_walls(&c.vertices, &conn.edges, normals);
        c
    };
    let cover = QuadCover::new(&honeycomb.base, conn, options.pattern, options.direction);
    let held_tries = |solver: &SolverOptions, progress: &mut dyn FnMut(&IterationInfo)| {
        held_with_cells_off(&cover, walls, surface, options, solver, progress)
    };
    let Some(reshape) = options.reshape else {
        return Ok(on_walls(held_tries(solver, progress)?));
    };
    let budget = solver.max_iterations;
    let held_budget = ((budget as f64 * HELD_SHARE).ceil() as usize).clamp(1, budget);
    let held_solver = SolverOptions {
        max_iterations: held_budget,
        ..solver.clone()
    };
    let held = held_tries(&held_solver, progress)?;
    let planarity = |c: &Capped| face_measures(&c.vertices, &c.cover.quads);
    let flat = planarity(&held);
    let left = budget.saturating_sub(held.solve.iterations);
    if flat.meet_floors() || left == 0 {
        return Ok(on_walls(held));
    }
    let sliding_solver = SolverOptions {
        max_iterations: left,
        ..solver.clone()
    };
    // The slide starts where the held tries left the vertices: on the same walls, flatter.
    let held_honeycomb = Honeycomb {
        base: PolyMesh::new(held.vertices.clone(), honeycomb.base.faces.clone()),
        ..honeycomb.clone()
    };
    let walls = (&held_honeycomb, conn, normals);
    // Its cover is chosen again on the flatter vertices, with the held cover's cells off the
    // pattern: a cell's flattest diagonal (and a pattern's straight class) may have changed.
    let base = &held_honeycomb.base;
    let cover = QuadCover::new(base, conn, options.pattern, options.direction);
    let cover = cover.resplit(base, conn, &held.cover.off_pattern);
    let sliding = cap_trying(
        (&[SLIDING_TRY], reshape, SETTLED_PLANARITY),
        walls,
        &cover,
        surface,
        options,
        &sliding_solver,
        progress,
    )?;
    // Not clean, the sliding try leaves the vertices where the held tries did: unless it is
    // flatter, the held quads are kept.
    let flatter = planarity(&sliding).delta_face_max < flat.delta_face_max;
    let whole = held.whole.clone();
    let (mut kept, other) = if flatter {
        (sliding, held)
    } else {
        (held, sliding)
    };
    kept.solve.iterations += other.solve.iterations;
    kept.whole = whole;
    Ok(on_walls(kept))
}

/// The held tries on `cover`. Where the pattern's quads stay short of the floors and the
/// pattern may be broken, a few hexagons take their own flattest diagonal instead (see
/// [`cells_to_take_off`]) and the honeycomb is capped again within the same budget, aiming a
/// little lower each round (`OFF_PATTERN_AIMS`, the cells taken off adding up), until a cover
/// meets the floors. Only such a cover is kept: a pattern broken and still short of them is
/// worth less than the pattern whole. The returned cover names the cells it took off.
fn held_with_cells_off(
    cover: &QuadCover,
    walls: (&Honeycomb, &Connectivity, &[Vec3]),
    surface: &PolyMesh,
    options: &QuadOptions,
    solver: &SolverOptions,
    progress: &mut dyn FnMut(&IterationInfo),
) -> Result<Capped> {
    let (honeycomb, conn, _) = walls;
    let may_break = options.pattern != QuadPattern::Flattest && !options.whole_pattern;
    let settled = if may_break {
        SETTLED_BEFORE_CELLS_OFF
    } else {
        SETTLED_PLANARITY
    };
    let whole_tries = (&HELD_TRIES[..], EVEN_CELLS, settled);
    let whole = cap_trying(
        whole_tries,
        walls,
        cover,
        surface,
        options,
        solver,
        progress,
    )?;
    let mut spent = whole.solve.iterations;
    let flat = face_measures(&whole.vertices, &whole.cover.quads);
    if !may_break || flat.meet_floors() {
        return Ok(whole);
    }
    // The last capping with cells off, which the next round adds to, and the one that met.
    let (mut last, mut met): (Option<Capped>, Option<Capped>) = (None, None);
    for aim in OFF_PATTERN_AIMS {
        if spent >= solver.max_iterations {
            break;
        }
        let from = last.as_ref().unwrap_or(&whole);
        let cells = cells_to_take_off((&from.cover, &from.vertices), &honeycomb.base, conn, aim);
        let cover = from.cover.resplit(&honeycomb.base, conn, &cells);
        if cover.off_pattern == from.cover.off_pattern {
            continue;
        }
        let left = SolverOptions {
            max_iterations: solver.max_iterations - spent,
            ..solver.clone()
        };
        let tries = (&HELD_TRIES[..], EVEN_CELLS, SETTLED_PLANARITY);
        let next = cap_trying(tries, walls, &cover, surface, options, &left, progress)?;
        spent += next.solve.iterations;
        if face_measures(&next.vertices, &next.cover.quads).meet_floors() {
            met = Some(next);
            break;
        }
        last = Some(next);
    }
    let mut kept = match met {
        Some(mixed) => Capped {
            whole: Some(flat),
            ..mixed
        },
        None => whole,
    };
    kept.solve.iterations = spent;
    Ok(kept)
}

/// The hexagons of `cover` (capped, its vertices at `vertices`) to take off its pattern next,
/// aiming at `aim` times the floors: those whose worst quad is above `aim` times the worst
/// asked, then, while the quads' mean would stay above `aim` times the mean asked, those whose
/// own flattest diagonal would gain most (its quads' planarity against the pattern's, both on
/// the capped vertices, a guess at what the next capping makes of them). Never more than
/// `MAX_OFF_PATTERN` of the hexagons in all, and none where the first alone are more. The
/// diagonals are chosen on the honeycomb `base` as it stood, as a flattest cover's.
fn cells_to_take_off(
    (cover, vertices): (&QuadCover, &[Vec3]),
    base: &PolyMesh,
    conn: &Connectivity,
    aim: f64,
) -> Vec<usize> {
    let hexagons: Vec<usize> = (0..base.faces.len())
        .filter(|&f| cover.cell_quads[f].is_some())
        .collect();
    let own = cover.resplit(base, conn, &hexagons);
    let planarity = |c: &QuadCover, f: usize| {
        let quads = c.cell_quads[f].expect("a hexagon is split");
        quads.map(|q| quad_planarity(c.corners(vertices, q)))
    };
    let room = ((MAX_OFF_PATTERN * hexagons.len() as f64) as usize)
        .saturating_sub(cover.off_pattern.len());
    // Cells whose own diagonal is another than the pattern's, with their two quads now and
    // on it.
    let candidates: Vec<(usize, [f64; 2], [f64; 2])> = (own.off_pattern.iter())
        .filter(|f| cover.off_pattern.binary_search(f).is_err())
        .map(|&f| (f, planarity(cover, f), planarity(&own, f)))
        .collect();
    let worst = |q: [f64; 2]| q[0].max(q[1]);
    let (mut taken, mut rest): (Vec<_>, Vec<_>) =
        (candidates.into_iter()).partition(|c| worst(c.1) > aim * FLAT_QUAD);
    // The worst quad cannot come down within the share: no cells are worth taking off.
    if taken.len() > room {
        return Vec::new();
    }
    let quads = cover.quads.len().max(1) as f64;
    let mut sum: f64 = quad_planarities(vertices, &cover.quads).iter().sum();
    let gain = |c: &(usize, [f64; 2], [f64; 2])| c.1[0] + c.1[1] - c.2[0] - c.2[1];
    sum -= taken.iter().map(gain).sum::<f64>();
    rest.sort_by(|a, b| gain(b).total_cmp(&gain(a)));
    for c in rest {
        if sum / quads <= aim * FLAT_QUAD_MEAN || gain(&c) <= 0.0 {
            break;
        }
        sum -= gain(&c);
        taken.push(c);
    }
    // The least planar first, where there is no room for all.
    taken.sort_by(|a, b| worst(b.1).total_cmp(&worst(a.1)));
    taken.truncate(room);
    taken.into_iter().map(|c| c.0).collect()
}

/// [`cap`] of the honeycomb, its connectivity and its wall normals, with these tries in turn,
/// each clean only if its cells are at most as uneven as `even` (edge-length cv) allows, and
/// settled once a step changes the quads' planarity by less than `settled`.
fn cap_trying(
    (tries, even, settled): (&[CappingTry], f64, f64),
    (honeycomb, conn, normals): (&Honeycomb, &Connectivity, &[Vec3]),
    cover: &QuadCover,
    surface: &PolyMesh,
    options: &QuadOptions,
    solver: &SolverOptions,
    progress: &mut dyn FnMut(&IterationInfo),
) -> Result<Capped> {
    let frame = Frame::of(&honeycomb.base);
    let normalized = frame.to_normalized(&honeycomb.base);
    let surface = Surface::from_mesh(&frame.to_normalized(surface))?;
    let (axes, depth) = (&honeycomb.axes, honeycomb.thickness / frame.unit);
    let layout = Layout::new(normalized.vertices.len(), 0);
    let vertices_of = |x: &[f64]| -> Vec<Vec3> {
        (0..layout.num_vertices)
            .map(|v| layout.vertex_at(x, v))
            .collect()
    };
    // No wall convex before may cross itself after, at the honeycomb's depth: an edge the
    // capping shortened or turned towards the axes at its ends would. Nor may an edge run
    // backwards along its wall: its node's walls would then leave the axis in another order,
    // the node mirrored. And no vertex may stray farther from S than allowed (the normalized
    // frame's unit is the mean edge length).
    let wall = |p: &[Vec3], [a, b]: [usize; 2]| {
        [p[a], p[b], p[b] + axes[b] * depth, p[a] + axes[a] * depth]
    };
    let along = |p: &[Vec3], e: usize| {
        let [a, b] = conn.edges[e];
        (p[b] - p[a]).dot(normals[e].cross(axes[a] + axes[b]))
    };
    let walls_kept = |vertices: &[Vec3]| {
        (0..conn.num_edges()).all(|e| {
            let convex = is_convex(wall(vertices, conn.edges[e]))
                || !is_convex(wall(&normalized.vertices, conn.edges[e]));
            convex && along(vertices, e) * along(&normalized.vertices, e) > 0.0
        })
    };
    // Nor may the cells re-shape past what is allowed: the vertices slide along their walls,
    // and slides that flatten the quads where S twists stretch some edges to several mean
    // lengths.
    let lengths = |p: &[Vec3]| -> Vec<f64> {
        (conn.edges.iter())
            .map(|&[a, b]| (p[a] - p[b]).norm())
            .collect()
    };
    let uneven = even.max(edge_length_cv(&lengths(&normalized.vertices)) + CV_ALLOWANCE);
    // Distances in the mean edge length as it is: the capping moves the vertices along S too.
    let is_clean = |vertices: &[Vec3]| {
        let farthest = (vertices.iter())
            .map(|&p| surface.closest_point(p).distance)
            .fold(0.0, f64::max);
        let lengths = lengths(vertices);
        let mean_edge = lengths.iter().sum::<f64>() / lengths.len().max(1) as f64;
        farthest <= MAX_DISTANCE_FROM_S * mean_edge
            && edge_length_cv(&lengths) <= uneven
            && walls_kept(vertices)
    };
    let mut iterations = 0;
    let mut tries = tries.iter().peekable();
    while let Some(&this) = tries.next() {
        let problem = CappingProblem::build(
            &normalized,
            conn,
            (normals, axes, depth),
            (&surface, cover.clone()),
            options,
            this,
        );
        let sliding = SolverOptions {
            eps: SLIDING_EPS,
            eps_min: SLIDING_EPS,
            ..solver.clone()
        };
        let solver = if this.sliding { &sliding } else { solver };
        let (mut x, cover) = (problem.x, problem.cover);
        let mut projection =
            GuidedProjection::with_positions(x.len(), problem.families, Some(&problem.positions))?;
        // The tries share one budget of iterations. A try that has crossed a wall or turned an
        // edge back once it has spent half of what is left is given up for the next, firmer
        // one, which then has the rest: vertices come back to S as their closeness firms up,
        // such walls stay as they are.
        let left = solver.max_iterations.saturating_sub(iterations);
        let checkpoint = (tries.peek().is_some()).then(|| left.div_ceil(2));
        // The planarity rows cannot all vanish (the vertices keep to S within a bound), so the
        // solve stops once the quads' planarity has settled.
        let mut state = SolveState::new(solver.eps);
        let planarity = |x: &[f64]| {
            let m = face_measures(&vertices_of(x), &cover.quads);
            [m.delta_face_max, m.delta_face_avg]
        };
        let mut before = planarity(&x);
        // A sliding try may stray after it was clean: its flattest clean iterate is kept.
        let mut flattest: Option<([f64; 2], Vec<Vec3>)> = None;
        while state.iterations() < left {
            let Some(info) = projection.iterate(&mut x, &mut state, solver)? else {
                break;
            };
            progress(&info);
            let after = planarity(&x);
            // The cells re-shape a little more at every step of a slide: it stops at the first
            // clean iterate that meets the floors, or whose every quad is flat enough (the
            // firming has nothing left to do then).
            let meets = meet_quad_floors(after[0], after[1]);
            let flatter = flattest.as_ref().is_none_or(|(f, _)| after < *f);
            if this.sliding && (meets || flatter) {
                let vertices = vertices_of(&x);
                if is_clean(&vertices) {
                    flattest = Some((after, vertices));
                    if meets || after[0] <= FLAT_ENOUGH {
                        break;
                    }
                }
            }
            if (0..2).all(|k| (after[k] - before[k]).abs() < settled) {
                break;
            }
            before = after;
            if Some(state.iterations()) == checkpoint && !walls_kept(&vertices_of(&x)) {
                break;
            }
        }
        let mut solve = projection.report(&x, state, solver);
        iterations += solve.iterations;
        // A slide ends on its flattest clean iterate (the last one only if that is it).
        let (vertices, clean) = match flattest {
            Some((_, kept)) => (kept, true),
            None => {
                let vertices = vertices_of(&x);
                let clean = is_clean(&vertices);
                (vertices, clean)
            }
        };
        let last = tries.peek().is_none() || iterations >= solver.max_iterations;
        if last || clean {
            solve.iterations = iterations;
            // A last try that is not clean leaves the honeycomb as it was.
            let vertices = if clean { vertices } else { normalized.vertices };
            return Ok(Capped {
                vertices: vertices.into_iter().map(|p| frame.to_model(p)).collect(),
                cover: cover.clone(),
                solve,
                whole: None,
            });
        }
    }
    unreachable!("the last try returns")
}

/// The capping solve's unknowns (the vertices, one unit normal per quad, one minimum-length
/// dummy per edge) and families, in the normalized frame.
pub(crate) struct CappingProblem<'a> {
    pub x: Vec<f64>,
    pub families: Vec<Box<dyn Constraint + 'a>>,
    pub cover: QuadCover,
    /// Where each block of three unknowns sits (for the solver's ordering).
    pub positions: Vec<Option<Vec3>>,
}

impl<'a> CappingProblem<'a> {
    pub fn build(
        normalized: &PolyMesh,
        conn: &Connectivity,
        (normals, axes, depth): (&[Vec3], &[Vec3], f64),
        (surface, cover): (&'a Surface, QuadCover),
        options: &QuadOptions,
        this: CappingTry,
    ) -> CappingProblem<'a> {
        let layout = Layout::new(normalized.vertices.len(), 0);
        let mut x: Vec<f64> = normalized
            .vertices
            .iter()
            .flat_map(|p| p.to_array())
            .collect();
        let block = QuadNormalBlock { start: x.len() };
        for q in 0..cover.quads.len() {
            x.extend(best_fit_normal(cover.corners(&normalized.vertices, q), surface).to_array());
        }
        // An edge shorter than that already is held at its own length: pushed out to it, it
        // could as well swing through its other end and run backwards.
        let least: Vec<f64> = (conn.edges.iter())
            .map(|&[a, b]| MIN_EDGE.min((normalized.vertices[a] - normalized.vertices[b]).norm()))
            .collect();
        let dummies = MinEdgeLength::initial_dummies_for(&conn.edges, &least, &normalized.vertices);
        let dummy_start = x.len();
        x.extend(dummies);
        let hold = if this.sliding {
            SLIDING_HOLD
        } else {
            HOLD_WEIGHT
        };
        let mut families = kept_wall_families(
            layout,
            normalized,
            (conn, normals),
            surface,
            (this.closeness, FIRM_PAST),
            hold,
        );
        if this.sliding {
            families.push(Box::new(WallConvexity::new(
                layout,
                &normalized.vertices,
                &conn.edges,
                normals,
                axes,
                depth,
                CONVEXITY_WEIGHT,
            )));
        }
        families.push(Box::new(MinEdgeLength::with_lengths(
            layout,
            conn.edges.clone(),
            least,
            dummy_start,
            1.0,
        )));
        families.push(Box::new(QuadNormalization {
            block,
            num_quads: cover.quads.len(),
            weight: 1.0,
        }));
        let planarity = QuadPlanarity {
            layout,
            block,
            quads: cover.quads.clone(),
            sides: SIDES.to_vec(),
            weight: options.w_cons_faces,
        };
        if this.sliding {
            families.push(Box::new(BoundedPlanarity::new(planarity, FLAT_ENOUGH)));
        } else {
            families.push(Box::new(planarity));
        }
        if options.w_fair_zigzag > 0.0 && !cover.zigzag_runs.is_empty() {
            families.push(Box::new(ZigzagFairness {
                layout,
                runs: cover.zigzag_runs.clone(),
                weight: options.w_fair_zigzag,
                role: FAIRNESS_ROLE,
            }));
        }
        if options.w_fair_straight > 0.0 && !cover.straight_runs.is_empty() {
            // The sideways direction of a straight run is its wall's normal, which is kept.
            let rows = (cover.straight_runs.iter())
                .map(|r| FixedNormalRow {
                    normal: normals[r.edge] * conn.edge_sign(r.edge, r.i),
                    a: r.j,
                    b: r.k,
                })
                .collect();
            families.push(Box::new(FixedNormals {
                name: "fairness_straight",
                layout,
                rows,
                weight: options.w_fair_straight,
                role: FAIRNESS_ROLE,
            }));
        }
        let mut positions: Vec<Option<Vec3>> = (normalized.vertices.iter().map(|&p| Some(p)))
            .chain((0..cover.quads.len()).map(|q| {
                let c = cover.corners(&normalized.vertices, q);
                Some((c[0] + c[1] + c[2] + c[3]) / 4.0)
            }))
            .collect();
        // The dummies are unplaced.
        positions.resize(x.len().div_ceil(3), None);
        CappingProblem {
            x,
            families,
            cover,
            positions,
        }
    }
}

/// The normal of the plane through the quad's centroid that is closest to its corners (least
/// squares), on the side of S's normal there.
fn best_fit_normal(corners: [Vec3; 4], surface: &Surface) -> Vec3 {
    let c = corners.iter().fold(Vec3::ZERO, |s, &p| s + p) / 4.0;
    let n = smallest_eigenvector(sum_of_outer_products(corners.map(|p| p - c)));
    if n.dot(surface.normal_at(c)) < 0.0 {
        -n
    } else {
        n
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A loose try that has crossed a wall by the time it has spent half the budget is given
    /// up, and the firmer try after it caps the honeycomb: walls deep for their cells (three
    /// edge lengths) on the built-in wave, where the loosest closeness sends the vertices far
    /// enough along their axes to cross one.
    #[test]
    fn a_try_that_crossed_a_wall_leaves_the_budget_to_the_next() {
        let (surface, mut honeycomb, conn) =
            crate::tests::default_honeycomb(crate::generate::Shape::Wave, 300);
        honeycomb.thickness = 3.0 * honeycomb.base.mean_edge_length();
        let normals = super::super::kept_walls::realized_normals(&honeycomb, &conn);
        let solver = SolverOptions {
            max_iterations: 6,
            ..SolverOptions::default()
        };
        let options = QuadOptions::default();
        let walls = (&honeycomb, &conn, normals.as_slice());
        let cover = QuadCover::new(&honeycomb.base, &conn, options.pattern, None);
        let capped = cap_trying(
            (
                &[
                    CappingTry {
                        closeness: 1e-3,
                        sliding: false,
                    },
                    CappingTry {
                        closeness: 3.0,
                        sliding: false,
                    },
                ],
                EVEN_CELLS,
                SETTLED_PLANARITY,
            ),
            walls,
            &cover,
            surface.source_mesh(),
            &options,
            &solver,
            &mut |_| {},
        )
        .unwrap();
        assert!(capped.solve.iterations <= 6, "{}", capped.solve.iterations);
        let unit = honeycomb.base.mean_edge_length();
        let moved = (capped.vertices.iter().zip(&honeycomb.base.vertices))
            .map(|(p, q)| (*p - *q).norm() / unit)
            .fold(0.0, f64::max);
        assert!(moved > 1e-3, "the honeycomb was left as it was");
        let farthest = (capped.vertices.iter())
            .map(|&p| surface.closest_point(p).distance / unit)
            .fold(0.0, f64::max);
        assert!(farthest <= MAX_DISTANCE_FROM_S + 1e-9, "{farthest}");
        let before = face_measures(&honeycomb.base.vertices, &capped.cover.quads);
        let after = face_measures(&capped.vertices, &capped.cover.quads);
        assert!(
            after.delta_face_avg < before.delta_face_avg,
            "{} -> {}",
            before.delta_face_avg,
            after.delta_face_avg
        );
    }

    /// The cells taken off a pattern: none where its quads are far inside the floors aimed at,
    /// nor where more than a fifth of the hexagons are past them; else those past them, the
    /// least planar first, and more for the mean, never more than a fifth in all.
    #[test]
    fn at_most_a_fifth_of_the_cells_leave_the_pattern() {
        let (_, honeycomb, conn) =
            crate::tests::default_honeycomb(crate::generate::Shape::Wave, 300);
        let base = &honeycomb.base;
        let cover = QuadCover::new(base, &conn, QuadPattern::Zigzag, None);
        let capped = (&cover, base.vertices.as_slice());
        assert!(cells_to_take_off(capped, base, &conn, 1e3).is_empty());
        assert!(cells_to_take_off(capped, base, &conn, 0.0).is_empty());
        let worst = |f: usize| {
            (cover.cell_quads[f].unwrap().iter())
                .map(|&q| quad_planarity(cover.corners(&base.vertices, q)))
                .fold(0.0, f64::max)
        };
        // Aimed so that a tenth of the cells whose own diagonal is another are past it.
        let own = cover.resplit(base, &conn, &(0..base.faces.len()).collect::<Vec<_>>());
        let mut worsts: Vec<f64> = own.off_pattern.iter().map(|&f| worst(f)).collect();
        worsts.sort_by(|a, b| b.total_cmp(a));
        let hexagons = cover.cell_quads.iter().flatten().count();
        let aim = worsts[hexagons / 10] / FLAT_QUAD;
        let taken = cells_to_take_off(capped, base, &conn, aim);
        assert!(taken.len() <= hexagons / 5, "{} of {hexagons}", taken.len());
        let past = (own.off_pattern.iter()).filter(|&&f| worst(f) > aim * FLAT_QUAD);
        assert!(past.clone().count() >= 1);
        for f in past {
            assert!(taken.contains(f), "cell {f}");
        }
        assert!(taken.windows(2).all(|w| worst(w[0]) >= worst(w[1])));
        assert_eq!(
            cover.resplit(base, &conn, &taken).off_pattern.len(),
            taken.len()
        );
    }

    #[test]
    fn bad_options_are_named() {
        let bad = [
            QuadOptions {
                direction: Some(Vec3::ZERO),
                ..QuadOptions::default()
            },
            QuadOptions {
                direction: Some(Vec3::new(f64::NAN, 0.0, 1.0)),
                ..QuadOptions::default()
            },
            QuadOptions {
                w_cons_faces: 0.0,
                ..QuadOptions::default()
            },
            QuadOptions {
                w_fair_zigzag: -1.0,
                ..QuadOptions::default()
            },
            QuadOptions {
                w_fair_straight: f64::INFINITY,
                ..QuadOptions::default()
            },
        ];
        let words = [
            "quad_direction",
            "quad_direction",
            "w_cons_faces",
            "w_fair_zig",
            "w_fair_str",
        ];
        for (o, word) in bad.iter().zip(words) {
            let e = o.validate().unwrap_err().to_string();
            assert!(e.contains(word), "{e}");
        }
        QuadOptions::default().validate().unwrap();
    }
}
