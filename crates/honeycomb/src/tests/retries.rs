//! What the pipeline tries where walls across S give no clean honeycomb, judged by what it
//! returns and the iterations it spends.

use super::height_field;
use crate::{pipeline, Options, PipelineOptions, Progress, Step, Walls};

/// A deep bowl, `z = 4 r^2` over the unit square (slopes up to 80 degrees).
fn deep_bowl() -> crate::Surface {
    height_field(60, |x, y| 4.0 * ((x - 0.5).powi(2) + (y - 0.5).powi(2)))
}

/// The pipeline's result on `surface` for `options`, and the solver iterations it reported.
fn counted(
    surface: &crate::Surface,
    options: &PipelineOptions,
) -> (crate::Result<crate::Outcome>, usize) {
    let mut iterations = 0;
    let out = pipeline(
        surface,
        options,
        &mut Progress::new(|step| iterations += matches!(step, Step::Iteration(..)) as usize),
    );
    (out, iterations)
}

/// On the deep bowl at 300 cells the fitted node axes turn a node over on each mesh the
/// pipeline lays, and the guided projection from walls orthogonal to S (asked for with
/// `--walls free`) is no honeycomb there either. The default pipeline says so in one error
/// that names both and what else to ask, without spending the guided projection's
/// iterations on it.
#[test]
fn a_node_turned_over_on_every_mesh_ends_the_pipeline() {
    let surface = deep_bowl();
    let (out, spent) = counted(&surface, &PipelineOptions::new(300));
    let e = out.err().expect("no honeycomb").to_string();
    for said in [
        "turned a node over on each of the 2 meshes",
        "--walls free",
        "uniform",
    ] {
        assert!(e.contains(said), "{e}");
    }
    let free = PipelineOptions {
        options: Options {
            walls: Walls::Free,
            ..Options::default()
        },
        ..PipelineOptions::new(300)
    };
    let (out, free_spent) = counted(&surface, &free);
    if let Ok(out) = out {
        assert!(
            !out.verdict.honeycomb,
            "the guided projection made a honeycomb"
        );
    }
    assert!(
        spent < free_spent,
        "{spent} iterations for the error, {free_spent} for the guided projection alone"
    );
}
