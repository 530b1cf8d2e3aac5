//! Sizes and counts that options imply are refused before anything is allocated: each case
//! runs under an address-space limit (`common::run_bounded`), so that a regression aborts the
//! run and fails the test instead of eating the machine, and under a time limit, so that a
//! hang fails too.

mod common;

use common::{assert_clean_failure, assert_success, run_bounded, TempDir};
use honeycomb::generate::{lifted_hex_patch, Shape};
use honeycomb::mesh::write_mesh;
use std::ffi::OsString;
use std::path::{Path, PathBuf};

/// Seconds a refusal may take: it comes before any real work.
const REFUSED_WITHIN: u64 = 30;

/// The demo's saddle surface (area 566 model units squared) written into `dir`.
fn saddle(dir: &TempDir) -> PathBuf {
    let path = dir.join("saddle.obj");
    let (_, surface) = lifted_hex_patch(Shape::Saddle, 200);
    write_mesh(&path, &surface).expect("write the surface");
    path
}

fn args(parts: &[&dyn AsRef<std::ffi::OsStr>]) -> Vec<OsString> {
    parts.iter().map(|p| p.as_ref().to_os_string()).collect()
}

/// Runs `args` bounded and checks a clean refusal naming every keyword, with nothing in `out`.
fn refused(args: &[OsString], keywords: &[&str], out: Option<&Path>) -> String {
    let output = run_bounded(args, REFUSED_WITHIN);
    let line = assert_clean_failure(&output, keywords, out);
    if let Some(out) = out {
        assert!(!out.exists(), "{} was created", out.display());
    }
    line
}

#[test]
fn an_edge_length_beyond_the_surface_is_refused() {
    let dir = TempDir::new("an_edge_length_beyond_the_surface_is_refused");
    let surface = saddle(&dir);
    let base = dir.join("base.obj");
    // 2e308 padding overflowed to inf, and a NaN lattice extent slipped past its guard.
    for edge in ["1e308", "9e307", "1000", "1e-300"] {
        let shown = format!("--edge-length {edge}:");
        for method in ["flatten", "field"] {
            // The top of the range is the longest edge that lays cells (see bad_input.rs).
            let by = format!("model units (the longest that lays cells by the {method} method)");
            let keywords = [shown.as_str(), "cells, 0.0104407 to ", &by];
            let a = args(&[
                &"init",
                &surface,
                &"--edge-length",
                &edge,
                &"--method",
                &method,
            ]);
            refused(&[a, args(&[&"-o", &base])].concat(), &keywords, None);
            assert!(!base.exists());
        }
        let out = dir.join("out");
        let a = args(&[&"pipeline", &surface, &"--edge-length", &edge, &"-o", &out]);
        refused(&a, &[&shown, "cells, 0.0104407 to "], Some(&out));
    }
    // Inside the range the message names, init makes a mesh.
    let a = args(&[
        &"init",
        &surface,
        &"--edge-length",
        &"1",
        &"-q",
        &"-o",
        &base,
    ]);
    assert_success(&run_bounded(&a, 60), "init --edge-length 1");
}

#[test]
fn solves_larger_than_a_machine_holds_are_refused() {
    let dir = TempDir::new("solves_larger_than_a_machine_holds_are_refused");
    let surface = saddle(&dir);
    let out = dir.join("out");
    let pipeline =
        |size: &str, value: &str| args(&[&"pipeline", &surface, &size, &value, &"-o", &out]);
    refused(
        &pipeline("--cells", "1000000"),
        &["--cells 1000000", "at most 150000"],
        Some(&out),
    );
    // 0.02 gives about 540000 cells: within init's 2000000, beyond a solve.
    refused(
        &pipeline("--edge-length", "0.02"),
        &["--edge-length 0.02", "cells to solve", "at most 150000"],
        Some(&out),
    );
    let demo = |extra: &[&str]| {
        let mut a = args(&[&"demo", &"-o", &out]);
        a.extend(extra.iter().map(OsString::from));
        a
    };
    refused(
        &demo(&["--vertices", "2000000"]),
        &["--vertices 2000000", "expected 50 to 295000"],
        Some(&out),
    );
    // Iterations times unknowns: ten thousand iterations of 20k vertices are days.
    let line = refused(
        &demo(&["--vertices", "20000", "--iterations", "10000"]),
        &["--iterations 10000: on", "vertices expected at most"],
        Some(&out),
    );
    assert!(line.contains("vertex-iterations"), "{line}");
    refused(
        &args(&[&"bench", &"--sizes", &"2000000"]),
        &["--sizes 2000000", "expected 50 to 295000"],
        None,
    );
    refused(
        &args(&[&"bench", &"--sizes", &"295000", &"--iterations", &"1000"]),
        &["--iterations 1000 with --sizes 295000", "at most 338"],
        None,
    );
}

#[test]
fn a_picture_wider_than_its_bound_is_refused_and_the_widest_is_drawn() {
    let dir = TempDir::new("a_picture_wider_than_its_bound_is_refused");
    let structure = dir.join("structure");
    common::demo(&structure, &["--vertices", "200"]);
    let picture = dir.join("picture.png");
    for width in ["20000", "4294967295", "479"] {
        let a = args(&[&"render", &structure, &"--width", &width, &"-o", &picture]);
        let shown = format!("--width {width}: expected 480 to 8000 pixels");
        refused(&a, &[&shown], None);
        assert!(!picture.exists());
    }
    // The widest picture fits well within the limit the tests run under.
    let a = args(&[&"render", &structure, &"--width", &"8000", &"-o", &picture]);
    assert_success(&run_bounded(&a, 60), "render --width 8000");
    assert!(std::fs::metadata(&picture).unwrap().len() > 1_000_000);
}

#[test]
fn the_editor_bounds_its_parameters_as_the_cli_does() {
    let dir = TempDir::new("the_editor_bounds_its_parameters");
    let surface = saddle(&dir);
    let saves = dir.join("saves");
    let serve = |extra: &[&dyn AsRef<std::ffi::OsStr>]| {
        let mut a = args(&[&"serve", &"--port", &"0", &"--saves", &saves]);
        a.extend(args(extra));
        a
    };
    // Every offset coordinate was sent as null, and the save could not be loaded.
    for thickness in ["1e308", "1e30"] {
        let shown = format!("--thickness {thickness}: more than 1000 times");
        refused(
            &serve(&[&"--thickness", &thickness]),
            &[&shown],
            Some(&saves),
        );
    }
    refused(
        &serve(&[&surface, &"--cells", &"1000000"]),
        &["--cells 1000000", "at most 150000"],
        Some(&saves),
    );
}

#[cfg(unix)]
#[test]
fn a_fifo_as_input_is_refused_without_blocking() {
    let dir = TempDir::new("a_fifo_as_input_is_refused_without_blocking");
    let fifo = dir.join("surface.obj");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        println!("skipping: mkfifo is not available");
        return;
    }
    let out = dir.join("out");
    let base = dir.join("base.obj");
    for a in [
        args(&[&"optimize", &fifo, &"-o", &out]),
        args(&[&"init", &fifo, &"--cells", &"50", &"-o", &base]),
        args(&[&"pipeline", &fifo, &"--cells", &"50", &"-o", &out]),
    ] {
        // Opening a FIFO for reading waits for a writer, which never comes.
        refused(
            &a,
            &["surface.obj", "not a regular file (a FIFO"],
            Some(&out),
        );
    }
    assert!(!base.exists());
}
