//! Writing a honeycomb structure directory: `base.obj`, `offset.obj`, `walls.obj`,
//! `structure.json`, `report.json`. Every file is written to a temporary name and renamed, so a
//! reader never sees a half-written file.

use crate::error::{Error, Result};
use crate::mesh::{write_atomically, write_mesh};
use crate::report::Report;
use crate::structure::Honeycomb;
use std::path::Path;

pub fn write_json(path: &Path, value: &impl serde::Serialize) -> Result<()> {
    write_atomically(path, |w| {
        serde_json::to_writer_pretty(&mut *w, value).map_err(std::io::Error::other)?;
        writeln!(w)
    })
}

pub fn write_structure(dir: &Path, honeycomb: &Honeycomb, report: &Report) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|source| Error::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    write_mesh(&dir.join("base.obj"), &honeycomb.base)?;
    write_mesh(&dir.join("offset.obj"), &honeycomb.offset)?;
    write_mesh(&dir.join("walls.obj"), &honeycomb.walls())?;
    write_json(&dir.join("structure.json"), &honeycomb.to_json())?;
    write_json(&dir.join("report.json"), report)
}
