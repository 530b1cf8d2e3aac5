//! The page's files, embedded at build time (see build.rs). Only these paths are served: a
//! request for anything else, `..` included, is a 404, never a file read.

mod embedded {
    include!(concat!(env!("OUT_DIR"), "/assets.rs"));
}

pub enum Asset {
    Found {
        mime: &'static str,
        bytes: &'static [u8],
    },
    /// A module the build could not install (npm missing).
    Missing,
    NotFound,
}

pub fn lookup(path: &str) -> Asset {
    let path = if path == "/index.html" { "/" } else { path };
    match embedded::ASSETS.iter().find(|(url, _, _)| *url == path) {
        Some((_, mime, Some(bytes))) => Asset::Found { mime, bytes },
        Some((_, _, None)) => Asset::Missing,
        None => Asset::NotFound,
    }
}

/// What to tell a user whose build had no three.js.
pub const MISSING_HINT: &str =
    "three.js was not installed when honeycomb was built: run `npm ci --prefix web`, then `cargo build --release` again";
