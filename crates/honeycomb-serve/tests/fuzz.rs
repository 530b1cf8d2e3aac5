//! Property-based fuzzing of what reads untrusted bytes: the OBJ, OFF and PLY readers (with the
//! checks every command runs on a mesh it read) and the editor's message parser. Inputs are
//! arbitrary bytes and valid files or messages mutated the way files get broken (bytes
//! flipped, inserted, dropped, lines cut, numbers swapped for extreme ones). Every input must
//! give a value or an error: no panic, no hang (each case runs under a watchdog), and no
//! allocation beyond a bound proportional to its size (counted by the allocator below).
//!
//! CI runs a fixed number of cases from a fixed seed (a few seconds); for a longer run:
//! `HONEYCOMB_FUZZ_CASES=100000 cargo test --release -p honeycomb-serve --test fuzz`, and
//! `HONEYCOMB_FUZZ_SEED=N` for other inputs than CI's.

use honeycomb::generate::hex_disk;
use honeycomb::mesh::io::{parse_obj, parse_off, parse_ply, write_obj, write_off, write_ply};
use honeycomb::mesh::{validate_base_mesh, validate_surface_mesh, LoadedMesh};
use honeycomb_serve::protocol::ClientMessage;
use proptest::prelude::*;
use proptest::sample::Index;
use proptest::test_runner::{Config, RngSeed, TestRunner};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::path::Path;
use std::time::Duration;

/// Counts each thread's live heap bytes and their peak, so that a case (run on a thread of
/// its own) knows the most it held at once.
struct Counting;

thread_local! {
    static LIVE: Cell<usize> = const { Cell::new(0) };
    static PEAK: Cell<usize> = const { Cell::new(0) };
}

fn note(grown: usize, shrunk: usize) {
    // `try_with`: the allocator also runs while a thread's locals are being torn down.
    let _ = LIVE.try_with(|live| {
        let now = (live.get() + grown).saturating_sub(shrunk);
        live.set(now);
        let _ = PEAK.try_with(|peak| peak.set(peak.get().max(now)));
    });
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = System.alloc(layout);
        if !p.is_null() {
            note(layout.size(), 0);
        }
        p
    }

    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        System.dealloc(p, layout);
        note(0, layout.size());
    }

    unsafe fn realloc(&self, p: *mut u8, layout: Layout, size: usize) -> *mut u8 {
        let q = System.realloc(p, layout, size);
        if !q.is_null() {
            note(size, layout.size());
        }
        q
    }
}

#[global_allocator]
static COUNTING: Counting = Counting;

/// A case that runs longer than this hangs.
const WATCHDOG: Duration = Duration::from_secs(10);

/// Heap a case may hold at once: a fixed allowance plus this many bytes per input byte (a
/// mesh read keeps a lossy copy of the text, 24 bytes per vertex of at least 6 characters,
/// a vector per face, and the validation's adjacency).
const BYTES_PER_INPUT_BYTE: usize = 96;
const ALLOWANCE: usize = 1 << 20;

/// Runs `case` on `input` on a thread of its own and fails on a panic, a hang or a peak of
/// live heap beyond the bound for `input`'s size.
fn bounded(input: Vec<u8>, case: Reader) -> Result<(), TestCaseError> {
    let (done, outcome) = std::sync::mpsc::channel();
    let len = input.len();
    std::thread::spawn(move || {
        let _ = PEAK.try_with(|p| p.set(0));
        let _ = LIVE.try_with(|l| l.set(0));
        let result = std::panic::catch_unwind(|| case(&input));
        let peak = PEAK.try_with(Cell::get).unwrap_or(0);
        let _ = done.send(result.map(|()| peak));
    });
    let peak = match outcome.recv_timeout(WATCHDOG) {
        Ok(Ok(peak)) => peak,
        Ok(Err(_)) => return Err(TestCaseError::fail("panicked")),
        Err(_) => return Err(TestCaseError::fail(format!("no answer in {WATCHDOG:?}"))),
    };
    let bound = ALLOWANCE + BYTES_PER_INPUT_BYTE * len;
    if peak > bound {
        return Err(TestCaseError::fail(format!(
            "held {peak} bytes for an input of {len} (bound {bound})"
        )));
    }
    Ok(())
}

/// Cases per property: few in CI, as many as `HONEYCOMB_FUZZ_CASES` asks otherwise.
fn runner() -> TestRunner {
    let number = |name: &str, default: u64| {
        std::env::var(name)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    TestRunner::new(Config {
        cases: number("HONEYCOMB_FUZZ_CASES", 1000) as u32,
        rng_seed: RngSeed::Fixed(number("HONEYCOMB_FUZZ_SEED", 22)),
        failure_persistence: None,
        ..Config::default()
    })
}

/// A mesh read from the bytes as every command reads one, then checked as every command
/// checks one; its only outcomes are a mesh or an error.
fn read_and_check(parse: fn(&[u8]) -> honeycomb::Result<LoadedMesh>, bytes: &[u8]) {
    if let Ok(loaded) = parse(bytes) {
        let _ = validate_surface_mesh(&loaded.mesh);
        let _ = validate_base_mesh(&loaded.mesh);
    }
}

fn obj(bytes: &[u8]) {
    let parse = |b: &[u8]| parse_obj(&String::from_utf8_lossy(b), Path::new("fuzz.obj"));
    read_and_check(parse, bytes)
}

fn off(bytes: &[u8]) {
    let parse = |b: &[u8]| parse_off(&String::from_utf8_lossy(b), Path::new("fuzz.off"));
    read_and_check(parse, bytes)
}

fn ply(bytes: &[u8]) {
    read_and_check(|b| parse_ply(b, Path::new("fuzz.ply")), bytes)
}

fn message(bytes: &[u8]) {
    if let Ok(m) = ClientMessage::parse(&String::from_utf8_lossy(bytes)) {
        let _ = (m.edit(), m.label());
    }
}

/// What reads an input: a reader and the checks after it, or the message parser.
type Reader = fn(&[u8]);

/// Valid inputs of each reader: a hexagon disk in the format, and a binary PLY.
fn valid_files() -> Vec<(Reader, Vec<u8>)> {
    let mesh = hex_disk(1.0);
    let mut files: Vec<(Reader, Vec<u8>)> = Vec::new();
    let mut text = Vec::new();
    write_obj(&mut text, &mesh).unwrap();
    files.push((obj, text));
    let mut text = Vec::new();
    write_off(&mut text, &mesh).unwrap();
    files.push((off, text));
    let mut text = Vec::new();
    write_ply(&mut text, &mesh).unwrap();
    files.push((ply, text));
    let mut binary = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {}\nproperty float x\n\
         property float y\nproperty double z\nelement face {}\n\
         property list uchar int vertex_indices\nend_header\n",
        mesh.vertices.len(),
        mesh.faces.len()
    )
    .into_bytes();
    for p in &mesh.vertices {
        binary.extend((p.x as f32).to_le_bytes());
        binary.extend((p.y as f32).to_le_bytes());
        binary.extend(p.z.to_le_bytes());
    }
    for f in &mesh.faces {
        binary.push(f.len() as u8);
        for &v in f {
            binary.extend((v as i32).to_le_bytes());
        }
    }
    files.push((ply, binary));
    files
}

/// Valid editor messages, one of each type.
fn valid_messages() -> Vec<Vec<u8>> {
    [
        r#"{"type": "drag_vertex", "vertex": 1, "target": [0, 0, 1], "radius": 2, "stroke": 1}"#,
        r#"{"type": "slide", "vertex": 1, "distance": 0.1, "stroke": 2}"#,
        r#"{"type": "drag_axis", "vertex": 1, "direction": [0, 0, 1], "radius": 2}"#,
        r#"{"type": "undo"}"#,
        r#"{"type": "redo"}"#,
        r#"{"type": "cancel"}"#,
        r#"{"type": "save", "name": "a"}"#,
        r#"{"type": "load", "name": "a"}"#,
    ]
    .map(|m| m.as_bytes().to_vec())
    .to_vec()
}

/// Numbers and marks that readers mistake: overflowing, non-finite, negative, subnormal,
/// beyond u32 and u64, a byte order mark, line endings.
const EXTREMES: [&str; 16] = [
    "1e308",
    "-1e308",
    "NaN",
    "inf",
    "-1",
    "0",
    "4294967296",
    "18446744073709551616",
    "99999999999999999999",
    "1e-320",
    "-0",
    "3.5",
    "\u{feff}",
    "\r",
    "\r\n",
    "",
];

/// One way a file gets broken.
#[derive(Clone, Debug)]
enum Mutation {
    Flip(Index, u8),
    Insert(Index, u8),
    Delete(Index),
    Truncate(Index),
    /// The token around a position replaced by one of [`EXTREMES`].
    Number(Index, Index),
    /// A stretch of the file repeated (a line twice, a count doubled).
    Repeat(Index, Index),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<Index>(), any::<u8>()).prop_map(|(i, b)| Mutation::Flip(i, b)),
        (any::<Index>(), any::<u8>()).prop_map(|(i, b)| Mutation::Insert(i, b)),
        any::<Index>().prop_map(Mutation::Delete),
        any::<Index>().prop_map(Mutation::Truncate),
        (any::<Index>(), any::<Index>()).prop_map(|(i, k)| Mutation::Number(i, k)),
        (any::<Index>(), any::<Index>()).prop_map(|(i, k)| Mutation::Repeat(i, k)),
    ]
}

fn apply(bytes: &mut Vec<u8>, m: &Mutation) {
    if bytes.is_empty() {
        return;
    }
    let at = |i: &Index| i.index(bytes.len());
    match m {
        Mutation::Flip(i, b) => {
            let k = at(i);
            bytes[k] = *b;
        }
        Mutation::Insert(i, b) => {
            let k = at(i);
            bytes.insert(k, *b);
        }
        Mutation::Delete(i) => {
            let k = at(i);
            bytes.remove(k);
        }
        Mutation::Truncate(i) => {
            let k = at(i);
            bytes.truncate(k);
        }
        Mutation::Number(i, k) => {
            let k = k.index(EXTREMES.len());
            let i = at(i);
            let space = |b: &u8| b.is_ascii_whitespace();
            let start = bytes[..i].iter().rposition(space).map_or(0, |s| s + 1);
            let end = bytes[i..]
                .iter()
                .position(space)
                .map_or(bytes.len(), |e| i + e);
            bytes.splice(start..end.max(start), EXTREMES[k].bytes());
        }
        Mutation::Repeat(i, k) => {
            let (a, b) = (at(i), at(k));
            let stretch = bytes[a.min(b)..a.max(b)].to_vec();
            bytes.splice(a.max(b)..a.max(b), stretch);
        }
    }
}

#[test]
fn arbitrary_bytes_never_break_a_reader_or_the_message_parser() {
    let readers: [(&str, Reader); 4] = [
        ("obj", obj),
        ("off", off),
        ("ply", ply),
        ("message", message),
    ];
    for (name, reader) in readers {
        runner()
            .run(&proptest::collection::vec(any::<u8>(), 0..2048), |bytes| {
                bounded(bytes, reader)
            })
            .unwrap_or_else(|e| panic!("{name}: {e}"));
    }
    // A plausible start makes the bytes after it reach deeper.
    for (name, start, reader) in [
        ("ply", "ply\nformat ascii 1.0\n", ply as Reader),
        (
            "ply",
            "ply\nformat binary_big_endian 1.0\nelement vertex 3\n",
            ply,
        ),
        ("off", "OFF\n", off),
        ("message", r#"{"type": "drag_vertex", "#, message),
    ] {
        runner()
            .run(&proptest::collection::vec(any::<u8>(), 0..512), |tail| {
                bounded([start.as_bytes(), &tail].concat(), reader)
            })
            .unwrap_or_else(|e| panic!("{name} after {start:?}: {e}"));
    }
}

#[test]
fn broken_valid_files_and_messages_give_a_value_or_an_error() {
    let mut inputs: Vec<(Reader, Vec<u8>)> = valid_files();
    inputs.extend(valid_messages().into_iter().map(|m| (message as Reader, m)));
    // Unbroken, each reads.
    for (reader, bytes) in &inputs {
        bounded(bytes.clone(), *reader).unwrap();
    }
    let cases = (any::<Index>(), proptest::collection::vec(mutation(), 1..8));
    runner()
        .run(&cases, |(which, mutations)| {
            let (reader, bytes) = &inputs[which.index(inputs.len())];
            let mut bytes = bytes.clone();
            for m in &mutations {
                apply(&mut bytes, m);
            }
            bounded(bytes, *reader)
        })
        .unwrap();
}

#[test]
fn the_allocation_bound_would_catch_a_count_taken_from_a_header() {
    // The bound holds a reader that trusts a header's count to it: a case must fail.
    fn trusting(bytes: &[u8]) {
        let count = bytes.len() * 100_000;
        let v: Vec<u64> = Vec::with_capacity(count);
        std::hint::black_box(v);
    }
    assert!(bounded(vec![b'x'; 100], trusting).is_err());
    fn panicking(_: &[u8]) {
        panic!("a reader that panics");
    }
    assert!(bounded(Vec::new(), panicking).is_err());
}
