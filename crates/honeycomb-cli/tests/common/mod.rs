//! Helpers shared by the end-to-end tests of the `honeycomb` binary.

#![allow(dead_code)] // each test file uses a different subset

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A fresh, empty directory under the system temporary directory, removed on drop.
pub struct TempDir {
    pub path: PathBuf,
}

impl TempDir {
    /// `name` must be unique among the tests of one binary (the test's own name is).
    pub fn new(name: &str) -> TempDir {
        let path =
            std::env::temp_dir().join(format!("honeycomb-cli-test-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&path);
        std::fs::create_dir_all(&path).expect("create the test directory");
        TempDir { path }
    }

    pub fn join(&self, name: &str) -> PathBuf {
        self.path.join(name)
    }

    /// Writes `text` to `name` in the directory and returns its path.
    pub fn write(&self, name: &str, text: &str) -> PathBuf {
        let path = self.join(name);
        std::fs::write(&path, text).expect("write a test input");
        path
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.path);
    }
}

/// Runs the `honeycomb` binary with `args`.
pub fn run<I, S>(args: I) -> Output
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    Command::new(env!("CARGO_BIN_EXE_honeycomb"))
        .args(args)
        .output()
        .expect("run the honeycomb binary")
}

/// Address space a bounded run may take: ten times what the small inputs of the tests need,
/// well below the machine, so that a regression to an unbounded allocation aborts the run
/// (and fails its test) instead of eating the machine.
pub const ADDRESS_SPACE_LIMIT_KIB: u64 = 2 << 20;

/// Runs the `honeycomb` binary with `args` under [`ADDRESS_SPACE_LIMIT_KIB`] (`ulimit -v`),
/// killing it if it has not ended within `seconds`: the test then fails as a hang.
pub fn run_bounded<I, S>(args: I, seconds: u64) -> Output
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v {ADDRESS_SPACE_LIMIT_KIB} && exec \"$0\" \"$@\""
        ))
        .arg(env!("CARGO_BIN_EXE_honeycomb"))
        .args(args)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("run the honeycomb binary under sh");
    // Read both streams while waiting, so that a full pipe cannot stall the child.
    fn drain(mut stream: impl std::io::Read + Send + 'static) -> std::thread::JoinHandle<Vec<u8>> {
        std::thread::spawn(move || {
            let mut bytes = Vec::new();
            let _ = stream.read_to_end(&mut bytes);
            bytes
        })
    }
    let streams = [
        drain(child.stdout.take().expect("piped")),
        drain(child.stderr.take().expect("piped")),
    ];
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(seconds);
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait for the binary") {
            break status;
        }
        if std::time::Instant::now() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            panic!("still running after {seconds} s: a hang");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    let [stdout, stderr] = streams.map(|t| t.join().expect("read a stream"));
    Output {
        status,
        stdout,
        stderr,
    }
}

pub fn stdout(output: &Output) -> String {
    String::from_utf8_lossy(&output.stdout).into_owned()
}

pub fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// Fails with the command's streams when it did not exit with 0.
pub fn assert_success(output: &Output, what: &str) {
    assert!(
        output.status.success(),
        "{what}: exit {:?}\nstdout:\n{}\nstderr:\n{}",
        output.status.code(),
        stdout(output),
        stderr(output)
    );
    assert!(
        !stderr(output).contains("panicked"),
        "{what}: {}",
        stderr(output)
    );
}

/// The names in `dir` (empty when it does not exist).
pub fn entries(dir: &Path) -> Vec<String> {
    let Ok(list) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut names: Vec<String> = list
        .map(|e| {
            e.expect("directory entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    names.sort();
    names
}

/// Checks a clean failure: a non-zero exit code, exactly one `error:` line on stderr that
/// contains every one of `keywords`, no panic, and nothing written to `out_dir` (absent or
/// empty, so no stray temporary files either). Returns the error line.
pub fn assert_clean_failure(output: &Output, keywords: &[&str], out_dir: Option<&Path>) -> String {
    let err = stderr(output);
    let context = format!(
        "exit {:?}\nstdout:\n{}\nstderr:\n{err}",
        output.status.code(),
        stdout(output)
    );
    assert!(!output.status.success(), "expected a failure\n{context}");
    assert!(
        output.status.code().is_some(),
        "killed by a signal\n{context}"
    );
    assert!(!err.contains("panicked"), "panic\n{context}");
    assert!(!err.contains("RUST_BACKTRACE"), "panic\n{context}");
    let error_lines: Vec<&str> = err.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(error_lines.len(), 1, "expected one error line\n{context}");
    let line = error_lines[0];
    println!("{line}");
    for keyword in keywords {
        assert!(
            line.contains(keyword),
            "the error line does not name {keyword:?}\n{context}"
        );
    }
    if let Some(dir) = out_dir {
        assert_eq!(
            entries(dir),
            Vec::<String>::new(),
            "files left in {}\n{context}",
            dir.display()
        );
    }
    line.to_string()
}

/// Where a run asked for `-o out` put its outputs: `out`, or `out.failed` when the result
/// failed its verdict (no honeycomb).
pub fn written(output: &Output, out: &Path) -> PathBuf {
    if output.status.success() {
        return out.to_path_buf();
    }
    let mut failed = out.as_os_str().to_os_string();
    failed.push(".failed");
    PathBuf::from(failed)
}

/// The `../shared/data` directory next to the workspace, if present.
pub fn shared_data() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data");
    dir.is_dir().then(|| dir.canonicalize().unwrap_or(dir))
}

/// A report (or `--json` output) parsed as JSON.
pub fn parse_json(text: &str, what: &str) -> serde_json::Value {
    serde_json::from_str(text).unwrap_or_else(|e| panic!("{what} is not JSON ({e}):\n{text}"))
}

/// `report[key]` as a number, failing with the key's name when missing or not a number.
pub fn number(report: &serde_json::Value, key: &str) -> f64 {
    report[key]
        .as_f64()
        .unwrap_or_else(|| panic!("report key {key:?} missing or not a number: {report}"))
}

/// The keys every report has (report.json and `optimize --json`).
pub const REPORT_KEYS: [&str; 10] = [
    "vertices",
    "edges",
    "iterations",
    "omega_max_deg",
    "omega_avg_deg",
    "delta_max",
    "delta_avg",
    "closeness_max",
    "closeness_avg",
    "seconds",
];

/// `honeycomb demo EXTRA... -q -o DIR`, which must succeed.
pub fn demo(dir: &Path, extra: &[&str]) {
    let out = run_demo(dir, extra);
    assert!(out.status.success(), "demo {extra:?}: {}", stderr(&out));
}

/// `honeycomb demo EXTRA... -q -o DIR`.
pub fn run_demo(dir: &Path, extra: &[&str]) -> Output {
    let mut args: Vec<&str> = vec!["demo"];
    args.extend_from_slice(extra);
    args.extend(["-q", "-o", dir.to_str().expect("utf-8 path")]);
    run(&args)
}

/// `DIR/NAME` parsed as JSON.
pub fn read_json(dir: &Path, name: &str) -> serde_json::Value {
    let text = std::fs::read_to_string(dir.join(name))
        .unwrap_or_else(|e| panic!("{}: {e}", dir.join(name).display()));
    parse_json(&text, name)
}

/// A mesh the binary wrote, which must read back without a warning.
pub fn read_written_mesh(path: &Path) -> honeycomb::mesh::PolyMesh {
    let loaded =
        honeycomb::mesh::read_mesh(path).unwrap_or_else(|e| panic!("read {}: {e}", path.display()));
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    loaded.mesh
}

/// The undirected edges of a polygon mesh, each once as (low, high), sorted.
pub fn mesh_edges(mesh: &honeycomb::mesh::PolyMesh) -> Vec<[usize; 2]> {
    let mut set = std::collections::BTreeSet::new();
    for face in &mesh.faces {
        for k in 0..face.len() {
            let (a, b) = (face[k], face[(k + 1) % face.len()]);
            set.insert([a.min(b), a.max(b)]);
        }
    }
    set.into_iter().collect()
}

/// Distance between the diagonals of a quad over its mean edge length (DESIGN.md section 3),
/// computed here from the corners, independently of the library.
pub fn quad_delta(p: [honeycomb::geometry::Vec3; 4]) -> f64 {
    let (d1, d2) = (p[2] - p[0], p[3] - p[1]);
    let n = d1.cross(d2);
    let distance = (p[1] - p[0]).dot(n).abs() / n.norm();
    let mean_edge = (0..4).map(|k| (p[(k + 1) % 4] - p[k]).norm()).sum::<f64>() / 4.0;
    distance / mean_edge
}

/// A design surface as a file: the surface of a small demo on the built-in `shape`.
pub fn surface_file(tmp: &TempDir, shape: &str) -> PathBuf {
    let dir = tmp.join(&format!("demo-{shape}"));
    demo(&dir, &["--vertices", "600", "--shape", shape]);
    dir.join("surface.obj")
}

/// `pipeline SURFACE --cells 300 -o DIR` with `extra` options.
pub fn pipeline(surface: &Path, dir: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "pipeline",
        surface.to_str().unwrap(),
        "--cells",
        "300",
        "-o",
    ];
    args.push(dir.to_str().unwrap());
    args.extend(extra);
    run(args)
}

/// A steep bowl, `z = 1.7 r^2` over the unit square (slopes up to 67 degrees), written as an
/// OBJ of 60 x 60 squares each cut in two.
pub fn bowl_file(tmp: &TempDir) -> PathBuf {
    paraboloid_file(tmp, 1.7, "bowl.obj")
}

/// The bowl `z = k r^2` over the unit square (`r` from its centre), written as `name`: an OBJ
/// of 60 x 60 squares each cut in two.
pub fn paraboloid_file(tmp: &TempDir, k: f64, name: &str) -> PathBuf {
    let n = 60;
    let mut text = String::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
            let z = k * ((x - 0.5).powi(2) + (y - 0.5).powi(2));
            text += &format!("v {x} {y} {z}\n");
        }
    }
    let id = |i: usize, j: usize| j * (n + 1) + i + 1;
    for j in 0..n {
        for i in 0..n {
            text += &format!("f {} {} {}\n", id(i, j), id(i + 1, j), id(i + 1, j + 1));
            text += &format!("f {} {} {}\n", id(i, j), id(i + 1, j + 1), id(i, j + 1));
        }
    }
    let surface = tmp.join(name);
    std::fs::write(&surface, text).unwrap();
    surface
}
