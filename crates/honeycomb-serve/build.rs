//! Embeds the editor's page and the three.js modules it imports into the binary.
//!
//! The page is plain ES modules (no bundler): `web/index.html`, `web/app.js`, `web/style.css`,
//! and three.js from `web/node_modules` (pinned by `web/package-lock.json`). When three.js is
//! not installed yet, this runs `npm ci` in `web/` once; without npm the server still builds and
//! its page says which command installs the modules. Set HONEYCOMB_NO_NPM=1 to skip npm.

use std::path::{Path, PathBuf};
use std::process::Command;

/// (URL path, file under web/, content type)
const ASSETS: &[(&str, &str, &str)] = &[
    ("/", "index.html", "text/html; charset=utf-8"),
    ("/app.js", "app.js", "text/javascript; charset=utf-8"),
    ("/style.css", "style.css", "text/css; charset=utf-8"),
    (
        "/vendor/three.module.js",
        "node_modules/three/build/three.module.js",
        "text/javascript; charset=utf-8",
    ),
    (
        "/vendor/three.core.js",
        "node_modules/three/build/three.core.js",
        "text/javascript; charset=utf-8",
    ),
    (
        "/vendor/OrbitControls.js",
        "node_modules/three/examples/jsm/controls/OrbitControls.js",
        "text/javascript; charset=utf-8",
    ),
];

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap());
    let web = manifest
        .join("../../web")
        .canonicalize()
        .expect("web/ beside crates/");
    for f in [
        "index.html",
        "app.js",
        "style.css",
        "package.json",
        "package-lock.json",
    ] {
        println!("cargo:rerun-if-changed={}", web.join(f).display());
    }
    let three = web.join("node_modules/three/build/three.module.js");
    println!("cargo:rerun-if-changed={}", three.display());
    println!("cargo:rerun-if-env-changed=HONEYCOMB_NO_NPM");
    if !three.exists() && std::env::var_os("HONEYCOMB_NO_NPM").is_none() {
        npm_ci(&web);
    }
    let mut code = String::from("pub static ASSETS: &[(&str, &str, Option<&[u8]>)] = &[\n");
    for (url, file, mime) in ASSETS {
        let path = web.join(file);
        let bytes = if path.exists() {
            format!("Some(include_bytes!({:?}))", path.display().to_string())
        } else {
            "None".to_string()
        };
        code += &format!("    ({url:?}, {mime:?}, {bytes}),\n");
    }
    code += "];\n";
    let out = PathBuf::from(std::env::var("OUT_DIR").unwrap()).join("assets.rs");
    std::fs::write(out, code).unwrap();
}

fn npm_ci(web: &Path) {
    let status = Command::new("npm")
        .args(["ci", "--no-audit", "--no-fund", "--loglevel=error"])
        .current_dir(web)
        .status();
    match status {
        Ok(s) if s.success() => {}
        Ok(s) => println!(
            "cargo:warning=`npm ci` in {} failed ({s}); the editor page will say so",
            web.display()
        ),
        Err(e) => println!(
            "cargo:warning=npm not found ({e}); run `npm ci --prefix web` for the editor page"
        ),
    }
}
