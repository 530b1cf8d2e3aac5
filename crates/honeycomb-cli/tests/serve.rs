//! `honeycomb serve` as a user meets it: the binary started on a free port, the page driven in
//! real headless Chromium (playwright-core), and the command's own refusals.
//!
//! The browser test needs Debian's chromium, node and `web/node_modules/playwright-core`
//! (`npm ci --prefix web`). Without them it prints why and passes, unless HONEYCOMB_E2E=1
//! (CI sets it), where a missing piece is a failure.

mod common;

use common::{assert_clean_failure, run, TempDir};
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Kills the server when the test ends, however it ends.
struct Running(Child);

impl Drop for Running {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// `honeycomb` with `args`, then `more`, its stdout and stderr piped; the stdout to read the
/// address from.
fn serve(args: &[&str], more: &[&std::ffi::OsStr]) -> (Child, std::process::ChildStdout) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_honeycomb"))
        .args(args)
        .args(more)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let stdout = child.stdout.take().unwrap();
    (child, stdout)
}

fn missing_piece() -> Option<String> {
    let chromium = std::env::var("CHROMIUM").unwrap_or_else(|_| "/usr/bin/chromium".into());
    if !Path::new(&chromium).exists() {
        return Some(format!(
            "no Chromium at {chromium} (apt-get install chromium)"
        ));
    }
    if Command::new("node").arg("--version").output().is_err() {
        return Some("no node".into());
    }
    if !repo().join("web/node_modules/playwright-core").exists() {
        return Some("no web/node_modules/playwright-core (npm ci --prefix web)".into());
    }
    None
}

/// Whether the browser tests can run; else why not is printed, and with HONEYCOMB_E2E=1 (CI)
/// that is a failure.
fn browser_at_hand() -> bool {
    let Some(why) = missing_piece() else {
        return true;
    };
    if std::env::var("HONEYCOMB_E2E").as_deref() == Ok("1") {
        panic!("HONEYCOMB_E2E=1 but the browser test cannot run: {why}");
    }
    println!("skipped: {why}");
    false
}

/// The findings of `web/e2e/SCRIPT` run on the page at `url`, its screenshots into `shots`
/// (emptied first; they stay after the test, to look at). A failed check fails the test.
fn browse(script: &str, url: &str, shots: &Path) -> serde_json::Value {
    let _ = std::fs::remove_dir_all(shots);
    std::fs::create_dir_all(shots).unwrap();
    println!("screenshots in {}", shots.display());
    let out = Command::new("node")
        .arg(Path::new("e2e").join(script))
        .arg(url)
        .arg(shots)
        .current_dir(repo().join("web"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    println!("{stdout}{stderr}");
    assert!(out.status.success(), "the browser test failed: {stderr}");
    serde_json::from_str(stdout.trim()).unwrap()
}

#[test]
fn browser_drags_a_node_axis_and_sees_a_honeycomb() {
    if !browser_at_hand() {
        return;
    }
    let dir = TempDir::new("serve-browser");
    let mut child = Command::new(env!("CARGO_BIN_EXE_honeycomb"))
        .args(["serve", "--port", "0", "--quiet", "--saves"])
        .arg(dir.join("saves"))
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let stdout = child.stdout.take().unwrap();
    let _server = Running(child);
    let mut url = String::new();
    BufReader::new(stdout).read_line(&mut url).unwrap();
    let url = url.trim().to_string();
    assert!(
        url.starts_with("http://127.0.0.1:"),
        "serve printed {url:?}"
    );

    // The screenshots stay after the test, to look at: editor.png, drag-axis.png and
    // slide-warning.png in the system's temporary folder.
    let shots = std::env::temp_dir().join("honeycomb-e2e-serve");
    let findings = browse("drag-axis.mjs", &url, &shots);
    assert!(findings["omega_after"].as_f64().unwrap() < 0.05);
    assert!(findings["moved"].as_f64().unwrap() > 1e-3);
    assert!(findings["error_shown"]
        .as_str()
        .unwrap()
        .contains("malformed message"));
    assert_eq!(findings["undo_restored"], true);
    assert!(findings["vertex_drag_omega"].as_f64().unwrap() < 0.05);
    // The page says what it shows, and a second page cannot undo the first one's drag.
    let legend = findings["shown"]["legend"].as_str().unwrap();
    assert!(
        legend.contains("omega") && legend.contains("M: base mesh"),
        "{legend}"
    );
    assert_eq!(findings["shown"]["help"].as_array().unwrap().len(), 3);
    assert_eq!(findings["second_page_undo_disabled"], true);
    let warning = findings["slide_warning"].as_str().unwrap();
    assert!(
        warning.contains("stopped") && warning.contains("off S"),
        "{warning}"
    );
    assert_eq!(findings["download"]["ok"], true);
    assert_eq!(findings["failed_requests"], serde_json::json!([]));
    for shot in ["editor.png", "drag-axis.png", "slide-warning.png"] {
        assert!(
            std::fs::metadata(shots.join(shot)).unwrap().len() > 10_000,
            "{shot}"
        );
    }
}

/// A design surface served with quads: the page's panel names the variant and shows the
/// quads' planarity, and shows it measured again after an edit.
#[test]
fn browser_shows_the_variant_of_a_design_surface() {
    if !browser_at_hand() {
        return;
    }
    let dir = TempDir::new("serve-variant");
    let surface = dir.join("dome.obj");
    let dome = honeycomb::generate::design_surface(honeycomb::generate::Shape::Dome);
    honeycomb::mesh::write_mesh(&surface, &dome).unwrap();
    let args = ["serve", "--port", "0", "--quiet", "--cells", "200"];
    let saves = dir.join("saves");
    let more = [
        surface.as_os_str(),
        "--quads".as_ref(),
        "alternating".as_ref(),
        "--saves".as_ref(),
        saves.as_os_str(),
    ];
    let (child, stdout) = serve(&args, &more);
    let _server = Running(child);
    let mut url = String::new();
    BufReader::new(stdout).read_line(&mut url).unwrap();
    let shots = std::env::temp_dir().join("honeycomb-e2e-serve-variant");
    let findings = browse("variant.mjs", url.trim(), &shots);
    for row in [&findings["first"], &findings["after"]] {
        assert_eq!(row["hidden"], false);
        assert_eq!(row["name"], "quads alternating");
        assert!(
            row["unit"].as_str().unwrap().contains("delta_face max"),
            "{row}"
        );
        let max = row["text"].as_str().unwrap().split(" / ").next().unwrap();
        assert!(max.parse::<f64>().unwrap() < 0.01, "{row}");
    }
    assert_ne!(findings["first"]["text"], findings["after"]["text"]);
}

#[test]
fn serve_refuses_what_it_cannot_open() {
    let dir = TempDir::new("serve-refusals");
    let empty = dir.write("empty.obj", "");
    let missing = dir.join("no-such-file.obj");
    // A mesh that reads but is not acceptable: the message names the file too.
    let isolated = dir.write(
        "isolated.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\n",
    );
    let saves = dir.join("saves");
    let s = |p: &Path| p.to_str().unwrap().to_string();
    let cases: [(Vec<String>, &[&str]); 6] = [
        (vec![s(&missing)], &["no-such-file.obj"]),
        (vec![s(&empty)], &["empty.obj"]),
        (vec![s(&isolated)], &["isolated.obj", "isolated vertex"]),
        (vec!["--vertices".into(), "10".into()], &["--vertices"]),
        // A variant shapes the honeycomb made on a design surface, one at a time.
        (
            vec!["--quads".into(), "zigzag".into()],
            &["--quads", "design surface"],
        ),
        (
            vec![
                s(&isolated),
                "--parallel".into(),
                "--light".into(),
                "0,0,-1".into(),
            ],
            &["--parallel and --light", "one variant at a time"],
        ),
    ];
    for (args, keywords) in cases {
        let mut all = vec!["serve".to_string(), "--port".into(), "0".into()];
        all.extend(args);
        all.extend(["--saves".to_string(), s(&saves)]);
        assert_clean_failure(&run(&all), keywords, Some(&saves));
    }
    let file = dir.write("saves.txt", "not a directory");
    let out = run(["serve", "--port", "0", "--saves", &s(&file)]);
    assert_clean_failure(&out, &["--saves", "saves.txt", "not a directory"], None);
}

#[test]
fn serve_json_prints_its_address_as_json() {
    let dir = TempDir::new("serve-json");
    let saves = dir.join("saves");
    let args = [
        "serve",
        "--port",
        "0",
        "--json",
        "--vertices",
        "300",
        "--saves",
    ];
    let (child, stdout) = serve(&args, &[saves.as_os_str()]);
    let _server = Running(child);
    let mut line = String::new();
    BufReader::new(stdout).read_line(&mut line).unwrap();
    let v: serde_json::Value = serde_json::from_str(line.trim()).unwrap();
    let url = v["url"].as_str().unwrap();
    assert!(url.starts_with("http://127.0.0.1:"), "{url}");
    assert!(v["source"].as_str().unwrap().contains("300 vertices"));
    // The page is there.
    let addr = url.trim_start_matches("http://").trim_end_matches('/');
    let mut s = std::net::TcpStream::connect(addr).unwrap();
    use std::io::{Read, Write};
    write!(s, "GET / HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n").unwrap();
    let mut page = String::new();
    s.read_to_string(&mut page).unwrap();
    assert!(page.starts_with("HTTP/1.1 200") && page.contains("honeycomb"));
}

/// What `serve` with `args` on `surface` says on stderr until it is listening (its first
/// line of stdout is its address), then stopped.
fn said_on_start(args: &[&str], surface: &Path, saves: &Path) -> String {
    let more = [surface.as_os_str(), "--saves".as_ref(), saves.as_os_str()];
    let (mut child, stdout) = serve(args, &more);
    let mut stderr = child.stderr.take().unwrap();
    let mut line = String::new();
    BufReader::new(stdout).read_line(&mut line).unwrap();
    assert!(line.starts_with("http://"), "{line}");
    drop(Running(child));
    let mut said = String::new();
    std::io::Read::read_to_string(&mut stderr, &mut said).unwrap();
    said
}

/// A surface's notes (here: uniform walls on a vault that folds over seen along its mean
/// normal) go to stderr, and not with --quiet.
#[test]
fn serve_says_what_the_pipeline_changed_unless_quiet() {
    let dir = TempDir::new("serve-notes");
    // A vault over 216 degrees of arc.
    let (n, m) = (36, 6);
    let mut obj = String::new();
    for j in 0..=n {
        let a = std::f64::consts::PI * (-0.1 + 1.2 * j as f64 / n as f64);
        for i in 0..=m {
            obj += &format!("v {} {} {}\n", 3.0 * a.cos(), i as f64, 3.0 * a.sin());
        }
    }
    let v = |i: usize, j: usize| j * (m + 1) + i + 1;
    for j in 0..n {
        for i in 0..m {
            let (a, b, c, d) = (v(i, j), v(i, j + 1), v(i + 1, j + 1), v(i + 1, j));
            obj += &format!("f {a} {b} {c} {d}\n");
        }
    }
    let vault = dir.write("vault.obj", &obj);
    for quiet in [false, true] {
        let mut args = vec![
            "serve", "--port", "0", "--cells", "150", "--walls", "uniform",
        ];
        if quiet {
            args.push("--quiet");
        }
        let said = said_on_start(&args, &vault, &dir.join("saves"));
        assert_eq!(
            said.contains("note: seen along its mean normal"),
            !quiet,
            "quiet {quiet}: {said}"
        );
    }
}

/// `serve SURFACE` starts from the pipeline's honeycomb with its cells evened, as `pipeline`
/// does by default (a steep bowl, whose walls across leave them uneven): the note says so.
/// Without a design surface `--even-cells` and `--no-even-cells` are refused by name.
#[test]
fn serve_evens_the_cells_of_a_surface() {
    let dir = TempDir::new("serve-even-cells");
    let bowl = common::bowl_file(&dir);
    let said = said_on_start(&["serve", "--port", "0"], &bowl, &dir.join("saves"));
    assert!(said.contains("note: the cells were evened"), "{said}");
    for flag in ["--even-cells", "--no-even-cells"] {
        let demo = run(["serve", "--port", "0", flag]);
        assert_clean_failure(&demo, &[flag, "design surface"], None);
    }
}
