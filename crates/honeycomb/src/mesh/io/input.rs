//! Reading input files: only regular files (a FIFO or a device would block or never end), of a
//! bounded size, and text split into lines whatever the line ending (LF, CRLF or CR alone).

use crate::error::{Error, Result};
use std::path::Path;

/// Input files are read whole; a larger one is refused before it is read.
pub const MAX_INPUT_BYTES: u64 = 2 << 30;

/// The bytes of the regular file at `path`. A directory, a FIFO, a device or a socket is
/// refused without being opened, and so is a file over [`MAX_INPUT_BYTES`].
pub fn read_file(path: &Path) -> Result<Vec<u8>> {
    let io = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let refused = |message: String| Error::Parse {
        path: path.to_path_buf(),
        line: 0,
        message,
    };
    let meta = std::fs::metadata(path).map_err(io)?;
    if meta.is_dir() {
        return Err(refused("is a directory; expected a file".into()));
    }
    if !meta.is_file() {
        return Err(refused(
            "not a regular file (a FIFO, a device or a socket); expected a file".into(),
        ));
    }
    if meta.len() > MAX_INPUT_BYTES {
        return Err(refused(format!(
            "{} bytes; input files are read whole, up to {MAX_INPUT_BYTES} bytes (2 GiB)",
            meta.len()
        )));
    }
    std::fs::read(path).map_err(io)
}

/// The lines of `text`, each ended by LF, CRLF or a lone CR (old Mac files), without their
/// ending; like `str::lines`, no empty line after a final line ending. A byte order mark
/// before the first line is dropped.
pub fn text_lines(text: &str) -> TextLines<'_> {
    TextLines {
        rest: strip_bom(text),
    }
}

pub struct TextLines<'a> {
    rest: &'a str,
}

impl<'a> Iterator for TextLines<'a> {
    type Item = &'a str;

    fn next(&mut self) -> Option<&'a str> {
        if self.rest.is_empty() {
            return None;
        }
        let Some(end) = self.rest.find(['\r', '\n']) else {
            return Some(std::mem::take(&mut self.rest));
        };
        let line = &self.rest[..end];
        let ending = if self.rest[end..].starts_with("\r\n") {
            2
        } else {
            1
        };
        self.rest = &self.rest[end + ending..];
        Some(line)
    }
}

/// Drops a UTF-8 byte order mark, which some Windows tools write before the first keyword.
fn strip_bom(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// `strip_bom` for bytes.
pub fn strip_bom_bytes(bytes: &[u8]) -> &[u8] {
    bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_line_ending_splits_alike() {
        for text in [
            "a\nb\n\nc",
            "a\r\nb\r\n\r\nc\r\n",
            "a\rb\r\rc\r",
            "a\nb\r\n\rc",
        ] {
            let lines: Vec<&str> = text_lines(text).collect();
            assert_eq!(lines, ["a", "b", "", "c"], "{text:?}");
        }
        assert_eq!(text_lines("").count(), 0);
        assert_eq!(text_lines("\n").collect::<Vec<_>>(), [""]);
    }

    #[cfg(unix)]
    #[test]
    fn a_fifo_is_refused_without_blocking() {
        let dir = std::env::temp_dir().join(format!("honeycomb-input-fifo-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let fifo = dir.join("mesh.obj");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if !made.is_ok_and(|s| s.success()) {
            println!("skipping: mkfifo is not available");
            return;
        }
        // Opening a FIFO for reading blocks until a writer comes: this returns at once.
        let e = read_file(&fifo).unwrap_err().to_string();
        assert!(e.contains("mesh.obj: not a regular file (a FIFO"), "{e}");
        let e = read_file(Path::new("/dev/null")).unwrap_err().to_string();
        assert!(e.contains("/dev/null: not a regular file"), "{e}");
        let e = read_file(&dir).unwrap_err().to_string();
        assert!(e.contains("is a directory"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
