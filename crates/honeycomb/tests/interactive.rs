//! The three editing modes of the paper's Fig. 10 on a live session, measured from the realized
//! geometry after each edit.

use honeycomb::generate::{lifted_hex_patch, Shape};
use honeycomb::interactive::{Edit, EditSession, SessionOptions, Workspace};
use honeycomb::structure::Honeycomb;
use honeycomb::Vec3;

fn dome() -> Workspace {
    let (base, surface) = lifted_hex_patch(Shape::Dome, 1500);
    Workspace::new(&base, Some(&surface), None).unwrap()
}

fn angle_deg(a: Vec3, b: Vec3) -> f64 {
    a.normalized()
        .dot(b.normalized())
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}

/// The interior vertex closest to the centroid.
fn middle(h: &Honeycomb) -> usize {
    let c = h.base.centroid();
    (0..h.base.vertices.len())
        .min_by(|&a, &b| {
            let d = |v: usize| (h.base.vertices[v] - c).norm();
            d(a).total_cmp(&d(b))
        })
        .unwrap()
}

fn largest_move(a: &Honeycomb, b: &Honeycomb) -> f64 {
    a.base
        .vertices
        .iter()
        .zip(&b.base.vertices)
        .map(|(p, q)| (*p - *q).norm())
        .fold(0.0, f64::max)
}

/// A session owns its data (no borrowed workspace): it can be kept anywhere, by a thread or
/// a binding's object, for as long as it is needed.
#[test]
fn a_session_owns_its_data() {
    fn owned<T: Send + 'static>() {}
    owned::<EditSession>();
}

#[test]
fn first_solve_makes_a_honeycomb() {
    let s = EditSession::new(dome(), SessionOptions::default()).unwrap();
    assert!(!s.solving());
    let m = s.view().measures;
    assert!(m.omega_max_deg < 0.01, "omega {}", m.omega_max_deg);
    assert!(m.delta_max < 1e-6, "delta {}", m.delta_max);
    assert!(m.closeness_max < 0.05, "closeness {}", m.closeness_max);
}

#[test]
fn turning_an_axis_spreads_and_stays_a_honeycomb() {
    let mut s = EditSession::new(dome(), SessionOptions::default()).unwrap();
    s.finish().unwrap();
    let before = s.view().honeycomb;
    let v = middle(&before);
    let a = before.axes[v];
    let tilt = a.any_orthogonal().normalized();
    let direction = (a + tilt * 0.176).normalized(); // 10 degrees
    s.apply(
        Edit::TurnAxis {
            vertex: v,
            direction,
            radius: 3,
        },
        Some(1),
    )
    .unwrap();
    s.finish().unwrap();
    let after = s.view();
    let m = &after.measures;
    assert!(m.omega_max_deg < 0.05, "omega {}", m.omega_max_deg);
    // A compromise with the wish: walls planar to a ten-thousandth of an edge, not to 1e-9.
    assert!(m.delta_max < 5e-4, "delta {}", m.delta_max);
    // The axis turned most of the way (the axes are a wish at low weight) ...
    let turned = angle_deg(after.honeycomb.axes[v], a);
    let wanted = angle_deg(direction, a);
    assert!(
        turned > 0.5 * wanted && angle_deg(after.honeycomb.axes[v], direction) < 0.5 * wanted,
        "turned {turned} of {wanted} degrees"
    );
    // ... its neighbours along, and far away the honeycomb barely moved.
    let far = (0..before.base.vertices.len())
        .max_by(|&x, &y| {
            let d = |u: usize| (before.base.vertices[u] - before.base.vertices[v]).norm();
            d(x).total_cmp(&d(y))
        })
        .unwrap();
    assert!(angle_deg(after.honeycomb.axes[far], before.axes[far]) < 0.2 * turned);
    assert!(s.can_undo());
    assert!(s.undo());
    let undone = s.view().honeycomb;
    assert_eq!(largest_move(&undone, &before), 0.0);
    assert!(s.redo());
    assert_eq!(largest_move(&s.view().honeycomb, &after.honeycomb), 0.0);
}

#[test]
fn moving_a_vertex_follows_the_pointer_on_s() {
    let mut s = EditSession::new(dome(), SessionOptions::default()).unwrap();
    s.finish().unwrap();
    let before = s.view();
    let v = middle(&before.honeycomb);
    let edge = before.measures.mean_edge_length;
    let target = before.honeycomb.base.vertices[v] + Vec3::new(0.4 * edge, 0.0, 0.0);
    s.apply(
        Edit::MoveVertex {
            vertex: v,
            target,
            radius: 2,
        },
        Some(7),
    )
    .unwrap();
    s.finish().unwrap();
    let after = s.view();
    let m = &after.measures;
    assert!(m.omega_max_deg < 0.05, "omega {}", m.omega_max_deg);
    assert!(m.closeness_max < 0.05, "closeness {}", m.closeness_max);
    let moved = after.honeycomb.base.vertices[v] - before.honeycomb.base.vertices[v];
    assert!(
        moved.x > 0.2 * edge,
        "moved {:.3} edges towards the target",
        moved.x / edge
    );
}

#[test]
fn sliding_along_the_axis_keeps_the_walls() {
    let mut s = EditSession::new(dome(), SessionOptions::default()).unwrap();
    s.finish().unwrap();
    let before = s.view();
    let v = middle(&before.honeycomb);
    let d = 0.1 * before.measures.mean_edge_length;
    s.apply(
        Edit::SlideVertex {
            vertex: v,
            distance: d,
        },
        None,
    )
    .unwrap();
    assert!(!s.solving(), "a slide is not optimized");
    let after = s.view();
    let h = &after.honeycomb;
    let moved = h.base.vertices[v] - before.honeycomb.base.vertices[v];
    assert!((moved.norm() - d).abs() < 1e-12);
    assert!(angle_deg(moved, before.honeycomb.axes[v]) < 1e-6);
    // M' stays, every other vertex stays, the walls stay planar at 120 degrees.
    let offset_moved = h
        .offset
        .vertices
        .iter()
        .zip(&before.honeycomb.offset.vertices)
        .map(|(p, q)| (*p - *q).norm())
        .fold(0.0, f64::max);
    assert!(offset_moved < 1e-12, "M' moved by {offset_moved}");
    assert!(after.measures.omega_max_deg < before.measures.omega_max_deg + 1e-6);
    assert!(after.measures.delta_max < before.measures.delta_max + 1e-6);
    // The slide can not carry v past M'.
    s.apply(
        Edit::SlideVertex {
            vertex: v,
            distance: 5.0 * before.measures.mean_edge_length,
        },
        None,
    )
    .unwrap();
    let h = s.view().honeycomb;
    assert!((h.offset.vertices[v] - h.base.vertices[v]).norm() > 0.0);
    assert!(s.undo() && s.undo());
    assert_eq!(largest_move(&s.view().honeycomb, &before.honeycomb), 0.0);
}

#[test]
fn a_newer_edit_replaces_a_running_one() {
    let mut s = EditSession::new(dome(), SessionOptions::default()).unwrap();
    s.finish().unwrap();
    let h = s.view().honeycomb;
    let v = middle(&h);
    let a = h.axes[v];
    let t = a.any_orthogonal().normalized();
    let first = (a + t * 0.3).normalized();
    let second = (a - t * 0.3).normalized();
    let turn = |direction| Edit::TurnAxis {
        vertex: v,
        direction,
        radius: 2,
    };
    s.apply(turn(first), Some(3)).unwrap();
    assert!(s.step().unwrap().is_some());
    s.apply(turn(second), Some(3)).unwrap();
    s.finish().unwrap();
    let axis = s.view().honeycomb.axes[v];
    assert!(angle_deg(axis, second) < angle_deg(axis, first));
    // One gesture, one undo step.
    assert!(s.undo());
    assert!(!s.can_undo());
}

#[test]
fn nonsense_edits_are_refused() {
    let mut s = EditSession::new(dome(), SessionOptions::default()).unwrap();
    let n = s.num_vertices();
    let bad = [
        Edit::MoveVertex {
            vertex: n,
            target: Vec3::ZERO,
            radius: 0,
        },
        Edit::MoveVertex {
            vertex: 0,
            target: Vec3::new(f64::NAN, 0.0, 0.0),
            radius: 0,
        },
        Edit::MoveVertex {
            vertex: 0,
            target: Vec3::ZERO,
            radius: 51,
        },
        Edit::TurnAxis {
            vertex: 0,
            direction: Vec3::ZERO,
            radius: 1,
        },
        Edit::TurnAxis {
            vertex: 0,
            direction: Vec3::new(0.0, 0.0, 1.0),
            radius: 10_000,
        },
        Edit::SlideVertex {
            vertex: 0,
            distance: f64::INFINITY,
        },
    ];
    for e in bad {
        let err = s.apply(e, None).unwrap_err().to_string();
        assert!(!err.is_empty());
    }
    assert!(!s.can_undo(), "a refused edit leaves no undo step");
}

#[test]
fn a_long_vertex_drag_bends_the_cells_instead_of_folding_them() {
    use honeycomb::interactive::MOVE_PER_RING;
    let mut s = EditSession::new(dome(), SessionOptions::default()).unwrap();
    let before = s.view();
    let v = middle(&before.honeycomb);
    let edge = before.measures.mean_edge_length;
    // Three edges away in one gesture of several messages.
    for k in 1..=6 {
        let target = before.honeycomb.base.vertices[v] + Vec3::new(0.5 * k as f64 * edge, 0.0, 0.0);
        s.apply(
            Edit::MoveVertex {
                vertex: v,
                target,
                radius: 3,
            },
            Some(1),
        )
        .unwrap();
        s.step().unwrap();
    }
    s.finish().unwrap();
    let after = s.view();
    let moved =
        (after.honeycomb.base.vertices[v] - before.honeycomb.base.vertices[v]).norm() / edge;
    assert!(
        moved > 0.8 * MOVE_PER_RING * 4.0 && moved < 1.05 * MOVE_PER_RING * 4.0,
        "moved {moved:.3} edges"
    );
    let m = &after.measures;
    assert!(m.omega_max_deg < 0.05, "omega {}", m.omega_max_deg);
    let shortest = before.measures.min_edge_length;
    assert!(
        m.min_edge_length > 0.5 * shortest,
        "shortest edge {} edges, {} before",
        m.min_edge_length / edge,
        shortest / edge
    );
    assert!(s.undo() && !s.can_undo(), "one gesture, one undo step");
}

/// A slide stops `MAX_SLIDE_OFF_S` from S with a warning; one that stays on S has none.
#[test]
fn a_slide_stops_at_the_limit_off_s_and_says_so() {
    use honeycomb::interactive::MAX_SLIDE_OFF_S;
    let mut s = EditSession::new(dome(), SessionOptions::default()).unwrap();
    let before = s.view();
    let v = middle(&before.honeycomb);
    let edge = before.measures.mean_edge_length;
    let slide = |s: &mut EditSession, d: f64| {
        s.apply(
            Edit::SlideVertex {
                vertex: v,
                distance: d * edge,
            },
            None,
        )
        .unwrap()
    };
    assert!(slide(&mut s, 0.01).warning.is_none());
    let far = slide(&mut s, -3.0).warning.expect("a warning");
    assert!(far.contains("stopped") && far.contains("off S"), "{far}");
    let off = s.view().measures.closeness_per_vertex[v];
    assert!((off - MAX_SLIDE_OFF_S).abs() < 5e-3, "{off}");
    // Between S's tolerance and the limit: through, with a warning.
    let near = slide(&mut s, 0.1).warning.expect("a warning");
    assert!(near.contains("pulls it back"), "{near}");
}

/// Undo steps remember who made them (an editor's pages undo only their own).
#[test]
fn undo_steps_know_their_author() {
    let mut s = EditSession::new(dome(), SessionOptions::default()).unwrap();
    let slide = Edit::SlideVertex {
        vertex: 3,
        distance: 0.01,
    };
    assert_eq!(s.undo_author(), None);
    s.apply_by(slide, Some(1), 7).unwrap();
    s.apply_by(slide, Some(2), 9).unwrap();
    assert_eq!(s.undo_author(), Some(9));
    assert!(s.undo());
    assert_eq!((s.undo_author(), s.redo_author()), (Some(7), Some(9)));
    assert!(s.redo());
    assert_eq!((s.undo_author(), s.redo_author()), (Some(9), None));
}

/// A saved structure without its design surface (`optimize` without `--surface` writes none)
/// is edited on M itself: the session's first solve keeps it a honeycomb on M, not pulling
/// its zigzag boundary onto M's own boundary (which folded nodes over, 130 degrees off).
#[test]
fn a_structure_without_its_surface_stays_a_honeycomb() {
    use honeycomb::generate::design_surface;
    use honeycomb::{pipeline, PipelineOptions, Progress, Surface};
    let surface = Surface::new(design_surface(Shape::Saddle)).unwrap();
    let made = pipeline(
        &surface,
        &PipelineOptions::new(150),
        &mut Progress::silent(),
    )
    .unwrap();
    assert!(made.is_honeycomb());
    let ws = Workspace::from_honeycomb(&made.honeycomb, None).unwrap();
    let mut s = EditSession::new(ws, SessionOptions::default()).unwrap();
    let view = s.view();
    assert!(
        view.measures.omega_max_deg < 1e-6,
        "{}",
        view.measures.omega_max_deg
    );
    assert!(
        view.measures.delta_max < 1e-6,
        "{}",
        view.measures.delta_max
    );
    assert!(
        view.measures.closeness_max < 0.05,
        "{}",
        view.measures.closeness_max
    );
    // And an edit there keeps it one.
    let v = middle(&view.honeycomb);
    s.apply(
        Edit::SlideVertex {
            vertex: v,
            distance: 0.01,
        },
        None,
    )
    .unwrap();
    s.finish().unwrap();
    assert!(s.view().measures.omega_max_deg < 0.01);
}
