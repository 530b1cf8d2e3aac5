//! The editor server over real sockets: what it serves, what it refuses, how it streams.

use honeycomb::generate::Shape;
use honeycomb::structure::quad_planarity;
use honeycomb::{Options, Variant};
use honeycomb_serve::latency::Client;
use honeycomb_serve::{start, ServeOptions, Server, Source};
use serde_json::{json, Value};
use std::io::{Read, Write};
use std::net::TcpStream;
use std::path::PathBuf;

fn server(tag: &str) -> (Server, PathBuf) {
    let saves = std::env::temp_dir().join(format!("honeycomb-serve-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&saves);
    let source = Source::Demo {
        shape: Shape::Dome,
        vertices: 400,
    };
    let options = ServeOptions {
        port: 0,
        save_root: saves.clone(),
        ..ServeOptions::default()
    };
    (start(&source, options).unwrap(), saves)
}

/// A raw HTTP/1.1 GET with the path exactly as given (no client-side normalization).
fn get(server: &Server, path: &str) -> (u16, Vec<u8>) {
    let mut s = TcpStream::connect(server.addr).unwrap();
    write!(
        s,
        "GET {path} HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n\r\n"
    )
    .unwrap();
    let mut response = Vec::new();
    s.read_to_end(&mut response).unwrap();
    let text = String::from_utf8_lossy(&response);
    let status = text
        .split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or(0);
    let body = match response.windows(4).position(|w| w == b"\r\n\r\n") {
        Some(i) => response[i + 4..].to_vec(),
        None => Vec::new(),
    };
    (status, body)
}

fn connect(server: &Server) -> (Client, Value, Value) {
    let (c, _, mesh, state) = connect_page(server);
    (c, mesh, state)
}

/// A page and its number (a state's `undo_page` names the page whose gesture undo takes back).
fn connect_page(server: &Server) -> (Client, Value, Value, Value) {
    let mut c = Client::connect(&format!("ws://{}/ws", server.addr)).unwrap();
    // Updates of other pages' edits may come first.
    let hello = c.until("hello", |_| true).unwrap();
    let mesh = c.until("mesh", |_| true).unwrap();
    let state = c.until("state", |_| true).unwrap();
    (c, hello["page"].clone(), mesh, state)
}

#[test]
fn serves_its_assets_and_nothing_else() {
    let (server, _) = server("assets");
    let (status, body) = get(&server, "/");
    assert_eq!(status, 200);
    assert!(String::from_utf8_lossy(&body).contains("importmap"));
    for path in [
        "/app.js",
        "/style.css",
        "/vendor/three.module.js",
        "/vendor/OrbitControls.js",
    ] {
        let (status, body) = get(&server, path);
        assert_eq!(status, 200, "{path}");
        assert!(body.len() > 100, "{path}");
    }
    // Browsers ask for an icon: no icon, but no 404 either.
    assert_eq!(get(&server, "/favicon.ico").0, 204);
    for path in [
        "/../Cargo.toml",
        "/vendor/../../Cargo.toml",
        "/%2e%2e/%2e%2e/Cargo.toml",
        "/..%2f..%2fCargo.toml",
        "/etc/passwd",
        "//etc/passwd",
        "/node_modules/three/package.json",
        "/web/app.js",
        "/app.js/../../README.md",
    ] {
        let (status, body) = get(&server, path);
        assert_eq!(status, 404, "{path}");
        let body = String::from_utf8_lossy(&body);
        assert!(
            !body.contains("[package]") && !body.contains("root:"),
            "{path}"
        );
    }
    server.stop();
}

#[test]
fn malformed_messages_get_an_error_and_change_nothing() {
    let (server, _) = server("malformed");
    let (mut c, mesh, first) = connect(&server);
    let nv = mesh["vertices"].as_u64().unwrap();
    let bad = [
        "not json".to_string(),
        "{}".to_string(),
        json!({"type": "explode"}).to_string(),
        json!({"type": "drag_axis", "vertex": "seven", "direction": [0, 0, 1], "radius": 2})
            .to_string(),
        json!({"type": "drag_axis", "vertex": 1, "direction": [0, 0], "radius": 2}).to_string(),
        json!({"type": "drag_vertex", "vertex": 1, "target": [0, 0, 1], "extra": true}).to_string(),
        json!({"type": "undo", "steps": 3}).to_string(),
        json!({"type": "slide", "vertex": -1, "distance": 0.1}).to_string(),
        r#"{"type":"slide","vertex":1,"distance":1e999}"#.to_string(),
        json!({"type": "save", "name": "x".repeat(70 * 1024)}).to_string(),
    ];
    for text in &bad {
        c.send_text(text).unwrap();
        let e = c.until("error", |_| true).unwrap();
        assert!(!e["message"].as_str().unwrap().is_empty(), "{text:.80}");
    }
    // Well-formed but impossible: the editor says why.
    let impossible = [
        json!({"type": "drag_axis", "vertex": nv, "direction": [0, 0, 1], "radius": 2}),
        json!({"type": "drag_axis", "vertex": 0, "direction": [0, 0, 0], "radius": 2}),
        json!({"type": "drag_axis", "vertex": 0, "direction": [0, 0, 1], "radius": 100000}),
        json!({"type": "save", "name": "../outside"}),
        json!({"type": "load", "name": "never-saved"}),
    ];
    for m in &impossible {
        c.send(m).unwrap();
        let e = c.until("error", |_| true).unwrap();
        assert!(!e["message"].as_str().unwrap().is_empty(), "{m}");
    }
    // A binary frame.
    c.send_binary(&[1, 2, 3]).unwrap();
    let e = c.until("error", |_| true).unwrap();
    assert!(e["message"].as_str().unwrap().contains("binary"));
    // The last good state is kept: a cancel shows the geometry the page started with.
    c.send(&json!({"type": "cancel"})).unwrap();
    let now = c.until("state", |_| true).unwrap();
    assert!(
        now["base"] == first["base"] && now["offset"] == first["offset"],
        "state changed"
    );
    assert!(!std::path::Path::new("../outside").exists());
    server.stop();
}

#[test]
fn a_drag_streams_every_step_and_a_newer_one_wins() {
    let (server, saves) = server("drag");
    let (mut c, page, mesh, first) = connect_page(&server);
    let nv = mesh["vertices"].as_u64().unwrap() as usize;
    let p = |s: &Value, key: &str, v: usize| {
        let f = |k: usize| s[key][3 * v + k].as_f64().unwrap();
        [f(0), f(1), f(2)]
    };
    let v = nv / 2;
    let (b, o) = (p(&first, "base", v), p(&first, "offset", v));
    let axis = [o[0] - b[0], o[1] - b[1], o[2] - b[2]];
    let turned = |s: f64| [axis[0] + s * axis[2], axis[1], axis[2] - s * axis[0]];
    // Two gestures back to back: the second replaces the first while it solves.
    c.send(&json!({"type": "drag_axis", "vertex": v, "direction": turned(0.1), "radius": 2, "stroke": 1}))
        .unwrap();
    c.send(&json!({"type": "drag_axis", "vertex": v, "direction": turned(-0.1), "radius": 2, "stroke": 2}))
        .unwrap();
    let mut steps = Vec::new();
    let last = loop {
        let s = c.until("state", |_| true).unwrap();
        if s["stroke"] == 2 {
            steps.push(s["iteration"].as_u64().unwrap());
            if s["done"] == true {
                break s;
            }
        } else {
            // Once the newer gesture is read, the older one gets no more steps.
            assert!(
                steps.is_empty(),
                "a step of the replaced gesture came after the newer one"
            );
        }
    };
    assert!(
        steps.len() >= 2 && steps.windows(2).all(|w| w[1] == w[0] + 1),
        "{steps:?}"
    );
    let omega = last["measures"]["omega_max_deg"].as_f64().unwrap();
    assert!(omega < 0.05, "omega {omega}");
    assert!(
        last["offset"] != first["offset"],
        "the drag changed nothing"
    );
    assert_eq!(last["undo_page"], page);

    // Undo, one step per gesture: back to the start.
    c.send(&json!({"type": "undo"})).unwrap();
    c.until("state", |_| true).unwrap();
    c.send(&json!({"type": "undo"})).unwrap();
    let undone = c.until("state", |_| true).unwrap();
    assert!(
        undone["base"] == first["base"],
        "two undos did not restore the start"
    );
    assert_eq!(undone["undo_page"], Value::Null);
    assert_eq!(undone["redo_page"], page);

    // Save, then load it back: the same geometry, written as a structure directory.
    c.send(&json!({"type": "redo"})).unwrap();
    c.until("state", |_| true).unwrap();
    c.send(&json!({"type": "redo"})).unwrap();
    let redone = c.until("state", |_| true).unwrap();
    assert!(
        redone["base"] == last["base"],
        "redo did not restore the drag"
    );
    c.send(&json!({"type": "save", "name": "after-drag"}))
        .unwrap();
    let saved = c.until("saved", |_| true).unwrap();
    let dir = PathBuf::from(saved["dir"].as_str().unwrap());
    assert_eq!(dir, saves.join("after-drag"));
    for f in [
        "base.obj",
        "offset.obj",
        "walls.obj",
        "structure.json",
        "report.json",
        "surface.obj",
    ] {
        assert!(dir.join(f).exists(), "{f} missing");
    }
    c.send(&json!({"type": "load", "name": "after-drag"}))
        .unwrap();
    let mesh2 = c.until("mesh", |_| true).unwrap();
    assert_eq!(mesh2["vertices"], mesh["vertices"]);
    let loaded = c.until("state", |_| true).unwrap();
    let max_diff = (0..3 * nv)
        .map(|i| (loaded["base"][i].as_f64().unwrap() - redone["base"][i].as_f64().unwrap()).abs())
        .fold(0.0, f64::max);
    // A load solves once more: the saved compromise with the wished axes (omega a few
    // hundredths of a degree) settles into an exact honeycomb close by.
    let edge = redone["measures"]["mean_edge_length"].as_f64().unwrap();
    assert!(
        max_diff < 0.05 * edge,
        "loaded geometry differs by {max_diff}"
    );
    let omega = loaded["measures"]["omega_max_deg"].as_f64().unwrap();
    assert!(omega < 0.01, "loaded omega {omega}");
    server.stop();
    let _ = std::fs::remove_dir_all(&saves);
}

/// `serve SURFACE`: a design surface gets init's hex mesh, solved into a honeycomb.
#[test]
fn a_design_surface_gets_a_hex_mesh_first() {
    let dir = std::env::temp_dir().join(format!("honeycomb-serve-surface-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (_, surface) = honeycomb::generate::lifted_hex_patch(Shape::Saddle, 600);
    let path = dir.join("saddle.obj");
    honeycomb::mesh::write_mesh(&path, &surface).unwrap();
    let options = ServeOptions {
        port: 0,
        save_root: dir.join("saves"),
        ..ServeOptions::default()
    };
    let server = start(&Source::from_path(&path, 200, Options::default()), options).unwrap();
    let (_, mesh, state) = connect(&server);
    let nv = mesh["vertices"].as_u64().unwrap();
    assert!((300..600).contains(&nv), "{nv} vertices for 200 cells");
    assert!(mesh["source"].as_str().unwrap().contains("saddle.obj"));
    let omega = state["measures"]["omega_max_deg"].as_f64().unwrap();
    assert!(omega < 0.01, "omega {omega}");
    // The page may make it again with another cell count, within the library's bounds.
    assert_eq!(mesh["remake"]["cells"], 200);
    let mut c = Client::connect(&format!("ws://{}/ws", server.addr)).unwrap();
    c.until("state", |_| true).unwrap();
    for (cells, says) in [(0, "cells 0"), (10_000_000, "cells 10000000")] {
        c.send(&json!({"type": "remake", "cells": cells})).unwrap();
        let e = c.until("error", |_| true).unwrap();
        let text = e["message"].as_str().unwrap();
        assert!(
            text.starts_with("remake failed") && text.contains(says),
            "{text}"
        );
    }
    c.send(&json!({"type": "remake", "cells": 120})).unwrap();
    let remade = c.until("mesh", |_| true).unwrap();
    assert_eq!(remade["remake"]["cells"], 120);
    let fewer = remade["vertices"].as_u64().unwrap();
    assert!(fewer < nv, "{fewer} vertices for 120 cells, {nv} for 200");
    assert!(remade["source"].as_str().unwrap().contains("120 cells"));
    server.stop();
    // A missing file is an error before anything is served.
    let missing = Source::from_path(&dir.join("missing.obj"), 200, Options::default());
    assert!(start(
        &missing,
        ServeOptions {
            port: 0,
            ..ServeOptions::default()
        }
    )
    .is_err());
    let _ = std::fs::remove_dir_all(&dir);
}

/// The status code of a WebSocket handshake to `/ws` with `host` and `origin` (none: a client
/// that is not a browser).
fn handshake(server: &Server, host: &str, origin: Option<&str>) -> u16 {
    let mut s = TcpStream::connect(server.addr).unwrap();
    let origin = origin.map_or(String::new(), |o| format!("Origin: {o}\r\n"));
    write!(
        s,
        "GET /ws HTTP/1.1\r\nHost: {host}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n\
         Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n{origin}\r\n"
    )
    .unwrap();
    let mut head = [0u8; 12];
    s.read_exact(&mut head).unwrap();
    String::from_utf8_lossy(&head[9..12]).parse().unwrap()
}

#[test]
fn only_its_own_page_may_open_the_websocket() {
    // A browser lets any site open a WebSocket to 127.0.0.1; that site could edit and
    // overwrite saves. The page itself comes from the server's own address.
    let (server, _) = server("origin");
    let own = server.addr.to_string();
    assert_eq!(handshake(&server, &own, Some("https://evil.example")), 403);
    assert_eq!(handshake(&server, &own, Some("null")), 403);
    assert_eq!(
        handshake(&server, &own, Some(&format!("http://{own}"))),
        101
    );
    assert_eq!(handshake(&server, &own, None), 101);
    let port = server.addr.port();
    let local = format!("localhost:{port}");
    assert_eq!(
        handshake(&server, &local, Some(&format!("http://{local}"))),
        101
    );
    // A site whose name resolves to 127.0.0.1 (DNS rebinding) is the same origin as itself,
    // but not a loopback name.
    let rebound = format!("evil.example:{port}");
    assert_eq!(
        handshake(&server, &rebound, Some(&format!("http://{rebound}"))),
        403
    );
    server.stop();
}

#[test]
fn two_pages_gestures_are_two_undo_steps() {
    // Each page numbers its gestures from 1: page B's gesture 1 is not page A's.
    let (server, _) = server("two-pages");
    let (mut a, page_a, _, first) = connect_page(&server);
    let (mut b, page_b, _, _) = connect_page(&server);
    assert_ne!(page_a, page_b);
    let z = |s: &Value, v: usize| s["base"][3 * v + 2].as_f64().unwrap();
    let moved = |s: &Value, v: usize| (z(s, v) - z(&first, v)).abs() > 1e-6;
    a.send(&json!({"type": "slide", "vertex": 0, "distance": 0.1, "stroke": 1}))
        .unwrap();
    a.until("state", |s| moved(s, 0)).unwrap();
    b.send(&json!({"type": "slide", "vertex": 5, "distance": 0.1, "stroke": 1}))
        .unwrap();
    let both = b.until("state", |s| moved(s, 5)).unwrap();
    assert!(moved(&both, 0), "B's gesture undid A's");
    b.send(&json!({"type": "undo"})).unwrap();
    let undone = b.until("state", |s| !moved(s, 5)).unwrap();
    assert!(moved(&undone, 0), "one undo took both pages' gestures");
    assert_eq!(undone["undo_page"], page_a);
    // A's gesture is A's to undo: B hears so, and nothing changes.
    b.send(&json!({"type": "undo"})).unwrap();
    let e = b.until("error", |_| true).unwrap();
    assert!(
        e["message"].as_str().unwrap().contains("another page's"),
        "{e}"
    );
    a.send(&json!({"type": "undo"})).unwrap();
    a.until("state", |s| !moved(s, 0)).unwrap();
    server.stop();
}

/// A page opened after another page's edits shows them, but has nothing to undo.
#[test]
fn a_new_page_starts_from_the_shared_state_without_its_undo_history() {
    let (server, _) = server("new-page");
    let (mut a, page_a, _, _) = connect_page(&server);
    a.send(&json!({"type": "slide", "vertex": 2, "distance": 0.05, "stroke": 1}))
        .unwrap();
    let edited = a.until("state", |s| s["undo_page"] == page_a).unwrap();
    let (mut b, page_b, _, shown) = connect_page(&server);
    assert_eq!(shown["base"], edited["base"], "the new page shows the edit");
    assert_eq!(shown["undo_page"], page_a);
    assert_ne!(shown["undo_page"], page_b, "the new page could undo");
    b.send(&json!({"type": "undo"})).unwrap();
    let e = b.until("error", |_| true).unwrap();
    assert!(e["message"]
        .as_str()
        .unwrap()
        .contains("nothing of this page's to undo"));
    b.send(&json!({"type": "redo"})).unwrap();
    let e = b.until("error", |_| true).unwrap();
    assert!(
        e["message"].as_str().unwrap().contains("nothing to redo"),
        "{e}"
    );
    server.stop();
}

/// The warning a page is told and the state all pages are sent after it, in either order: the
/// two travel different ways and may arrive crossed.
fn warning_and_state(c: &mut Client) -> (Value, Value) {
    let (mut warning, mut state) = (None, None);
    while warning.is_none() || state.is_none() {
        let m = c.receive().unwrap();
        match m["type"].as_str() {
            Some("warning") => warning = Some(m),
            Some("state") if state.is_none() => state = Some(m),
            Some("error") => panic!("the editor says: {}", m["message"]),
            _ => {}
        }
    }
    (warning.unwrap(), state.unwrap())
}

/// A slide stops at `MAX_SLIDE_OFF_S` mean edge lengths from S, and the page hears why; a
/// small one that stays on S goes through without a word.
#[test]
fn a_slide_off_s_is_stopped_at_the_limit_with_a_warning() {
    use honeycomb::interactive::MAX_SLIDE_OFF_S;
    let (server, _) = server("slide-limit");
    let (mut c, _, first) = connect(&server);
    let edge = first["measures"]["mean_edge_length"].as_f64().unwrap();
    let v = 7;
    // What a 48-pixel drag asked for: several edge lengths away from S.
    c.send(&json!({"type": "slide", "vertex": v, "distance": -5.0 * edge, "stroke": 1}))
        .unwrap();
    let (w, s) = warning_and_state(&mut c);
    let text = w["message"].as_str().unwrap();
    assert!(
        text.contains(&format!("slide of vertex {v} stopped")) && text.contains("off S"),
        "{text}"
    );
    assert!(text.contains("model units"), "{text}");
    let off = s["measures"]["closeness_max"].as_f64().unwrap();
    assert!(
        (off - MAX_SLIDE_OFF_S).abs() < 5e-3,
        "the vertex ended {off} edge lengths off S"
    );
    // Further out: refused, the vertex stays at the limit.
    c.send(&json!({"type": "slide", "vertex": v, "distance": -edge, "stroke": 1}))
        .unwrap();
    let (_, s) = warning_and_state(&mut c);
    assert!(s["measures"]["closeness_max"].as_f64().unwrap() < MAX_SLIDE_OFF_S + 5e-3);
    // Back towards S is always allowed.
    c.send(&json!({"type": "slide", "vertex": v, "distance": 0.1 * edge, "stroke": 1}))
        .unwrap();
    let s = c.until("state", |_| true).unwrap();
    assert!(s["measures"]["closeness_max"].as_f64().unwrap() < MAX_SLIDE_OFF_S - 0.05);
    // A slide that stays on S (a hundredth of an edge): no warning before its state.
    c.send(&json!({"type": "undo"})).unwrap();
    c.until("state", |_| true).unwrap();
    c.send(&json!({"type": "slide", "vertex": v, "distance": 0.01 * edge, "stroke": 2}))
        .unwrap();
    let next = c.receive().unwrap();
    assert_eq!(next["type"], "state", "{next}");
    server.stop();
}

/// A raw GET's status, headers and body.
fn get_with_headers(server: &Server, path: &str) -> (u16, String, Vec<u8>) {
    let mut s = TcpStream::connect(server.addr).unwrap();
    write!(
        s,
        "GET {path} HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n\r\n"
    )
    .unwrap();
    let mut response = Vec::new();
    s.read_to_end(&mut response).unwrap();
    let split = response.windows(4).position(|w| w == b"\r\n\r\n").unwrap();
    let head = String::from_utf8_lossy(&response[..split]).to_lowercase();
    let status = head.split_whitespace().nth(1).unwrap().parse().unwrap();
    // Chunked or not, the first bytes of the body tell the format.
    (status, head, response[split + 4..].to_vec())
}

#[test]
fn downloads_are_the_export_files_of_the_current_state() {
    let (server, _) = server("downloads");
    let (mut c, _, _) = connect(&server);
    let found = |body: &[u8], what: &[u8]| body.windows(what.len()).any(|w| w == what);
    for (file, mime, inside) in [
        ("structure.glb", "model/gltf-binary", &b"glTF"[..]),
        ("structure.obj", "model/obj", b"\nv "),
        ("structure.mtl", "model/mtl", b"newmtl"),
        ("panels.dxf", "image/vnd.dxf", b"SECTION"),
        ("panels.svg", "image/svg+xml", b"<svg"),
        ("walls.csv", "text/csv", b"\n"),
        ("nodes.csv", "text/csv", b"\n"),
        ("bom.csv", "text/csv", b"\n"),
    ] {
        let (status, head, body) = get_with_headers(&server, &format!("/download/{file}"));
        assert_eq!(status, 200, "{file}: {}", String::from_utf8_lossy(&body));
        assert!(
            head.contains(&format!("content-type: {mime}")),
            "{file}: {head}"
        );
        assert!(
            head.contains(&format!("attachment; filename=\"{file}\"")),
            "{file}: {head}"
        );
        assert!(body.len() > 100 && found(&body, inside), "{file}");
    }
    // Units as `honeycomb export --units` takes them: the glTF (metres) of a model in mm is a
    // thousandth of the one in m; nonsense is refused.
    let glb_m = get_with_headers(&server, "/download/structure.glb").2;
    let glb_mm = get_with_headers(&server, "/download/structure.glb?units=mm").2;
    assert!(!glb_mm.is_empty() && glb_mm != glb_m);
    let (status, _, body) = get_with_headers(&server, "/download/structure.glb?units=furlong");
    assert_eq!(status, 400);
    assert!(String::from_utf8_lossy(&body).contains("expected mm, cm, m, in or ft"));
    let (status, _, body) = get_with_headers(&server, "/download/export.json");
    assert_eq!(status, 404);
    assert!(String::from_utf8_lossy(&body).contains("the downloads are structure.glb"));
    // Mid-edit: a vertex dragged and the solve stopped before it re-solved is no honeycomb.
    // The cancel races the solve (on a busy machine the drag may finish first, and then the
    // state is a honeycomb the downloads serve), so the drag is tried a few times.
    let mut mid_edit = false;
    for stroke in 1..=10 {
        let target = [0.0, 0.0, 100.0 * stroke as f64];
        c.send(&json!({"type": "drag_vertex", "vertex": 7, "target": target, "radius": 3, "stroke": stroke}))
            .unwrap();
        c.send(&json!({"type": "cancel"})).unwrap();
        let s = c
            .until("state", |s| s["done"] == true && s["stroke"].is_null())
            .unwrap();
        if s["measures"]["omega_max_deg"].as_f64().unwrap() > 0.1 {
            mid_edit = true;
            break;
        }
        let (status, _, _) = get_with_headers(&server, "/download/structure.glb");
        assert_eq!(status, 200, "a honeycomb is served");
    }
    assert!(mid_edit, "every drag re-solved before its cancel");
    let (status, _, body) = get_with_headers(&server, "/download/structure.glb");
    let body = String::from_utf8_lossy(&body);
    assert_eq!(status, 409, "{body}");
    assert!(
        body.contains("not a honeycomb") && body.contains("omega_max"),
        "{body}"
    );
    server.stop();
}

#[test]
fn remake_refuses_what_its_input_cannot_take() {
    let (server, _) = server("remake");
    let (mut c, mesh, first) = connect(&server);
    assert_eq!(
        mesh["remake"]["cells"],
        Value::Null,
        "the demo has no cell count"
    );
    assert_eq!(mesh["remake"]["thickness"], true);
    let edge = first["measures"]["mean_edge_length"].as_f64().unwrap();
    for (m, says) in [
        (json!({"type": "remake"}), "give cells or thickness"),
        (json!({"type": "remake", "cells": 300}), "cells: the demo"),
        (
            json!({"type": "remake", "thickness": -1.0}),
            "thickness -1: expected a positive length",
        ),
        (
            json!({"type": "remake", "thickness": 0.0}),
            "thickness 0: expected a positive length",
        ),
        (
            json!({"type": "remake", "thickness": 1e30}),
            "thickness 1e30: more than 1000 times",
        ),
    ] {
        c.send(&m).unwrap();
        let e = c.until("error", |_| true).unwrap();
        let text = e["message"].as_str().unwrap();
        assert!(
            text.starts_with("remake failed") && text.contains(says),
            "{m}: {text}"
        );
    }
    for bad in [
        r#"{"type":"remake","cells":-3}"#,
        r#"{"type":"remake","thickness":"thick"}"#,
        r#"{"type":"remake","thickness":0.1,"depth":2}"#,
    ] {
        c.send_text(bad).unwrap();
        let e = c.until("error", |_| true).unwrap();
        assert!(
            e["message"]
                .as_str()
                .unwrap()
                .starts_with("malformed message"),
            "{bad}"
        );
    }
    // A good thickness: a new mesh at that thickness, and a fresh undo history.
    c.send(&json!({"type": "slide", "vertex": 1, "distance": 0.01 * edge, "stroke": 1}))
        .unwrap();
    c.until("state", |s| !s["undo_page"].is_null()).unwrap();
    c.send(&json!({"type": "remake", "thickness": 0.5 * edge}))
        .unwrap();
    let mesh = c.until("mesh", |_| true).unwrap();
    let t = mesh["thickness"].as_f64().unwrap();
    assert!((t - 0.5 * edge).abs() < 1e-9 * edge, "thickness {t}");
    let s = c.until("state", |_| true).unwrap();
    assert_eq!(s["undo_page"], Value::Null);
    server.stop();
}

#[test]
fn a_flood_of_messages_is_turned_away_not_queued() {
    let (server, _) = server("flood");
    let (mut a, _, _) = connect(&server);
    for _ in 0..5000 {
        a.send(&json!({"type": "undo"})).unwrap();
    }
    // Among the replies ("nothing to undo or redo" to the undos that got in), a busy one.
    let busy = |m: &Value| {
        m["message"]
            .as_str()
            .is_some_and(|t| t.contains("the editor is busy"))
    };
    let reply = loop {
        let m = a.receive().unwrap();
        if busy(&m) {
            break m;
        }
    };
    // It says which message it dropped.
    assert!(
        reply["message"]
            .as_str()
            .unwrap()
            .starts_with("the editor is busy: message undo dropped"),
        "{reply}"
    );
    // Another page still gets in, and the editor still edits.
    let (mut c, _, first) = connect(&server);
    c.send(&json!({"type": "slide", "vertex": 3, "distance": 0.1, "stroke": 1}))
        .unwrap();
    c.until("state", |s| s["base"][11] != first["base"][11])
        .unwrap();
    server.stop();
}

#[test]
fn parameters_beyond_the_bounds_are_refused_before_serving() {
    let demo = |vertices| Source::Demo {
        shape: Shape::Dome,
        vertices,
    };
    // With 1e308 every offset coordinate was sent as null, and saves could not be loaded.
    for (thickness, shown) in [(1e308, "1e308"), (1e30, "1e30")] {
        let options = ServeOptions {
            port: 0,
            thickness: Some(thickness),
            ..ServeOptions::default()
        };
        let Err(e) = start(&demo(400), options) else {
            panic!("thickness {shown} was accepted");
        };
        let e = e.to_string();
        assert!(
            e.contains(&format!("thickness {shown}: more than 1000 times")),
            "{e}"
        );
    }
    let options = ServeOptions {
        port: 0,
        ..ServeOptions::default()
    };
    let Err(e) = start(&demo(5_000_000), options) else {
        panic!("5000000 vertices were accepted");
    };
    assert!(
        e.to_string()
            .contains("--vertices 5000000: a solve of about"),
        "{e}"
    );
}

/// A design surface made with a variant: the page hears its name (and the quads that cap the
/// cells), and after every edit the variant's measure taken from the edited meshes.
#[test]
fn a_design_surface_keeps_its_variant_in_view() {
    let dir = std::env::temp_dir().join(format!("honeycomb-serve-variant-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let surface = honeycomb::generate::design_surface(Shape::Dome);
    let path = dir.join("dome.obj");
    honeycomb::mesh::write_mesh(&path, &surface).unwrap();
    let start_with = |variant: Variant, cells: usize| {
        let options = ServeOptions {
            port: 0,
            save_root: dir.join("saves"),
            ..ServeOptions::default()
        };
        let made = Options {
            variant,
            ..Options::default()
        };
        start(&Source::from_path(&path, cells, made), options).unwrap()
    };
    // Quads: the planarity of the quads, as the page can measure it from the state.
    let server = start_with(
        Variant::Quads {
            pattern: honeycomb::structure::QuadPattern::Alternating,
            quad_direction: None,
            w_cons_faces: None,
            w_fair_zig: None,
            w_fair_str: None,
            quads_reshape: None,
            quads_whole_pattern: false,
        },
        200,
    );
    let (mut c, mesh, first) = connect(&server);
    assert_eq!(mesh["variant"]["name"], "quads alternating");
    assert!(mesh["source"]
        .as_str()
        .unwrap()
        .contains("quads alternating"));
    let quads: Vec<[usize; 4]> = serde_json::from_value(mesh["variant"]["quads"].clone()).unwrap();
    assert!(quads.len() > 150, "{} quads for 200 cells", quads.len());
    // The quads' planarity on the page's coordinates, against what the page is told.
    let planarity = |state: &Value| {
        let p = |v: usize| {
            let f = |k: usize| state["base"][3 * v + k].as_f64().unwrap();
            honeycomb::Vec3::new(f(0), f(1), f(2))
        };
        let worst = (quads.iter()).fold(0.0f64, |worst, q| worst.max(quad_planarity(q.map(p))));
        (worst, state["variant"]["delta_face_max"].as_f64().unwrap())
    };
    // The page's coordinates are single precision.
    let close = |(measured, shown): (f64, f64)| (measured - shown).abs() < 1e-3 * shown.max(1e-4);
    let (measured, shown) = planarity(&first);
    assert_eq!(first["variant"]["variant"], "quads");
    assert!(close((measured, shown)), "{measured} vs {shown}");
    assert!(shown <= 0.01, "the capped dome's quads: {shown}");
    // Turning an axis moves vertices: the quads' planarity is measured again on the result.
    let v = mesh["vertices"].as_u64().unwrap() as usize / 2;
    let axis = |s: &Value, k: usize| {
        s["offset"][3 * v + k].as_f64().unwrap() - s["base"][3 * v + k].as_f64().unwrap()
    };
    let turned = [
        axis(&first, 0) + 0.3 * axis(&first, 2),
        axis(&first, 1),
        axis(&first, 2),
    ];
    c.send(
        &json!({"type": "drag_axis", "vertex": v, "direction": turned, "radius": 2, "stroke": 1}),
    )
    .unwrap();
    let done = c
        .until("state", |s| s["done"] == true && s["stroke"] == 1)
        .unwrap();
    let (measured, after) = planarity(&done);
    assert!(close((measured, after)), "{measured} vs {after}");
    assert!(
        after != shown,
        "the quads' planarity was not measured again"
    );
    assert!(done["base"] != first["base"], "the edit moved no vertex");
    server.stop();

    // Shading: the light share before and after, through the walls as they stand.
    let server = start_with(
        Variant::Shading {
            light: honeycomb::analysis::sun_light(45.0, 200.0),
            sun_path: Vec::new(),
            w_axes: None,
        },
        500,
    );
    let (_, mesh, first) = connect(&server);
    assert_eq!(mesh["variant"]["name"], "shading");
    let shading = &first["variant"]["light"];
    let (before, after) = (
        shading["before"].as_f64().unwrap(),
        shading["after"].as_f64().unwrap(),
    );
    assert!(after <= 0.5 * before, "{before} -> {after}");
    server.stop();

    // Parallel meshes: each edge's angle to its twin.
    let server = start_with(
        Variant::Parallel {
            depth: None,
            w_parallel: None,
            w_depth: None,
        },
        200,
    );
    let (_, mesh, first) = connect(&server);
    assert_eq!(mesh["variant"]["name"], "parallel meshes");
    let beta = first["variant"]["beta_max_deg"].as_f64().unwrap();
    assert!(beta < 0.5, "beta {beta}");
    server.stop();
    let _ = std::fs::remove_dir_all(&dir);
}
