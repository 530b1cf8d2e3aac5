//! How a long run talks to the terminal: a progress bar, nothing (`--quiet`), or JSON on stdout.

use honeycomb::optimize::Attempt;
use honeycomb::solve::IterationInfo;
use indicatif::{ProgressBar, ProgressStyle};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Output {
    Human,
    Quiet,
    Json,
}

impl Output {
    pub fn from_flags(quiet: bool, json: bool) -> Output {
        if json {
            Output::Json
        } else if quiet {
            Output::Quiet
        } else {
            Output::Human
        }
    }
}

/// A bar over the solver's iterations (drawn on stderr, hidden when not a terminal).
pub struct IterationBar {
    bar: Option<ProgressBar>,
}

impl IterationBar {
    pub fn new(output: Output, iterations: usize) -> IterationBar {
        let bar = (output == Output::Human).then(|| {
            let bar = ProgressBar::new(iterations as u64);
            bar.set_style(
                ProgressStyle::with_template("{prefix} [{bar:30}] {pos}/{len} {msg}")
                    .expect("static template")
                    .progress_chars("=> "),
            );
            bar.set_prefix("optimizing");
            bar
        });
        IterationBar { bar }
    }

    pub fn update(&self, info: &IterationInfo) {
        if let Some(bar) = &self.bar {
            bar.set_position(info.iteration as u64);
            bar.set_message(format!("residual {:.1e}", info.max_residual));
        }
    }

    /// A new solve begins: after broken boundary cells were dropped, or the second try.
    pub fn restart(&self, attempt: Attempt) {
        if let Some(bar) = &self.bar {
            let again = match (attempt.per_edge, attempt.second_try) {
                (false, false) => "",
                (false, true) => ", second try",
                (true, false) => ", normals per edge",
                (true, true) => ", normals per edge, second try",
            };
            bar.set_prefix(format!("optimizing (solve {}{again})", attempt.solve));
            bar.set_position(0);
        }
    }

    pub fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

/// A spinner for work of unknown length (drawn on stderr, hidden when not a terminal).
pub struct Spinner {
    bar: Option<ProgressBar>,
}

impl Spinner {
    pub fn new(output: Output, message: &'static str) -> Spinner {
        let bar = (output == Output::Human).then(|| {
            let bar = ProgressBar::new_spinner();
            bar.set_message(message);
            bar.enable_steady_tick(std::time::Duration::from_millis(100));
            bar
        });
        Spinner { bar }
    }

    pub fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
