//! Long work without the GIL, with steps to a callback and Ctrl-C.

use crate::{py_err, Cancelled};
use honeycomb::{Cancel, Outcome, Progress, Step};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict};
use std::sync::Mutex;

/// A step as the dict the progress callback gets.
pub(crate) fn step_dict<'py>(py: Python<'py>, step: Step<'_>) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    match step {
        Step::Init => d.set_item("step", "init")?,
        Step::Iteration(solve, number, info) => {
            d.set_item("step", "iteration")?;
            d.set_item("solve", solve)?;
            d.set_item("solve_number", number)?;
            d.set_item("iteration", info.iteration)?;
            d.set_item("max_residual", info.max_residual)?;
            d.set_item("energy", info.energy)?;
            d.set_item("eps", info.eps)?;
        }
    }
    Ok(d)
}

/// Runs `work` without the GIL. At every step the GIL is taken back to look for Ctrl-C and
/// to call `callback`; either raising, or the callback returning False, stops the work
/// before its next iteration and is raised here.
pub(crate) fn run<F>(py: Python<'_>, callback: Option<Py<PyAny>>, work: F) -> PyResult<Outcome>
where
    F: FnOnce(&mut Progress) -> honeycomb::Result<Outcome> + Send,
{
    let cancel = Cancel::new();
    let stopped: Mutex<Option<PyErr>> = Mutex::new(None);
    let result = py.detach(|| {
        let inside = cancel.clone();
        let mut progress = Progress::new(|step| {
            if inside.is_cancelled() {
                return;
            }
            Python::attach(|py| {
                let outcome = py.check_signals().and_then(|()| match &callback {
                    Some(f) => {
                        let answer = f.call1(py, (step_dict(py, step)?,))?;
                        let answer = answer.bind(py).cast::<PyBool>().map(|b| b.is_true());
                        if matches!(answer, Ok(false)) {
                            Err(Cancelled::new_err("stopped by the progress callback"))
                        } else {
                            Ok(())
                        }
                    }
                    None => Ok(()),
                });
                if let Err(e) = outcome {
                    *stopped.lock().unwrap() = Some(e);
                    inside.cancel();
                }
            });
        })
        .with_cancel(cancel.clone());
        work(&mut progress)
    });
    // An error raised by the callback (or Ctrl-C) wins, whatever the work ended with.
    if let Some(e) = stopped.lock().unwrap().take() {
        return Err(e);
    }
    result.map_err(py_err)
}
