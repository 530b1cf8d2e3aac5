//! How a long run talks to the terminal: a progress bar, nothing (`--quiet`), or JSON on stdout.

use honeycomb::{IterationInfo, Step};
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

/// A bar over the solver's iterations (drawn on stderr, hidden when not a terminal). Each
/// solve of a run (fitting the node axes, placing the vertices, a guided projection, a retry)
/// restarts it under its own name.
pub struct IterationBar {
    bar: Option<ProgressBar>,
    /// The solve shown: its name and number.
    current: Option<(String, usize)>,
    length: u64,
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
        IterationBar {
            bar,
            current: None,
            length: iterations as u64,
        }
    }

    pub fn update(&self, info: &IterationInfo) {
        if let Some(bar) = &self.bar {
            if info.iteration as u64 > bar.length().unwrap_or(0) {
                bar.set_length(info.iteration as u64);
            }
            bar.set_position(info.iteration as u64);
            bar.set_message(format!("residual {:.1e}", info.max_residual));
        }
    }

    /// A step of a pipeline: a new solve restarts the bar under its name.
    pub fn step(&mut self, step: Step) {
        let Step::Iteration(name, solve, info) = step else {
            return;
        };
        let this = (name.to_string(), solve);
        if self.current.as_ref() != Some(&this) {
            if let Some(bar) = &self.bar {
                let number = if solve > 1 {
                    format!(" (solve {solve})")
                } else {
                    String::new()
                };
                bar.set_prefix(format!("{name}{number}"));
                bar.set_length(self.length);
                bar.set_position(0);
            }
            self.current = Some(this);
        }
        self.update(info);
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
