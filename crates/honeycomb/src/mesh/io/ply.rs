//! PLY (Stanford polygon format), ASCII or binary in either byte order. The mesh is the `vertex`
//! element's x, y, z and the `face` element's `vertex_indices` (or `vertex_index`) lists; every
//! other element and property is read past and dropped.

use super::{
    capacity, check_face_range, check_finite, parse_error, strip_bom_bytes, text_lines,
    write_counted_body, LoadedMesh, TextLines,
};
use crate::error::{short_number, Error, Result};
use crate::geometry::Vec3;
use crate::mesh::PolyMesh;
use std::io::Write;
use std::path::Path;

#[derive(Clone, Copy, Debug, PartialEq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    /// Accepts the original type names and their sized aliases.
    fn from_name(name: &str) -> Option<Scalar> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }
}

#[derive(Debug)]
enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

#[derive(Debug)]
struct Property {
    name: String,
    kind: Kind,
}

#[derive(Debug)]
struct Element {
    name: String,
    count: usize,
    /// Header line of the `element` record, for messages about its properties.
    line: usize,
    properties: Vec<Property>,
}

#[derive(Clone, Copy, Debug)]
enum Encoding {
    Ascii,
    Binary { big_endian: bool },
}

struct Header {
    encoding: Encoding,
    elements: Vec<Element>,
    /// Byte offset of the first data byte.
    data_start: usize,
    /// Number of header lines, so that ASCII data lines get their numbers in the file.
    lines: usize,
}

/// Where the mesh sits among the header's elements and properties.
struct Layout {
    vertex: usize,
    xyz: [usize; 3],
    /// The face element and its index-list property.
    face: Option<(usize, usize)>,
}

/// Parses PLY bytes; `path` only names the file in messages.
pub fn parse_ply(bytes: &[u8], path: &Path) -> Result<LoadedMesh> {
    let bytes = strip_bom_bytes(bytes);
    if bytes.iter().all(u8::is_ascii_whitespace) {
        return Err(parse_error(path, 0, "empty file"));
    }
    let header = parse_header(bytes, path)?;
    let layout = find_layout(&header, path)?;
    let data = bytes.get(header.data_start..).unwrap_or_default();
    match header.encoding {
        Encoding::Ascii => {
            let text = String::from_utf8_lossy(data);
            let mut source = AsciiData {
                lines: text_lines(&text),
                line: header.lines,
                tokens: "".split_whitespace(),
            };
            read_data(&header, &layout, &mut source, data.len(), path)
        }
        Encoding::Binary { big_endian } => {
            let mut source = BinaryData {
                data,
                pos: 0,
                big_endian,
            };
            read_data(&header, &layout, &mut source, data.len(), path)
        }
    }
}

fn parse_header(bytes: &[u8], path: &Path) -> Result<Header> {
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut pos = 0;
    let mut line = 0;
    // The header's lines end as its first line does (LF, CRLF or CR alone): binary data may
    // begin with either byte, so the ending is not guessed line by line.
    let first_end = bytes
        .iter()
        .position(|&b| b == b'\n' || b == b'\r')
        .unwrap_or(bytes.len());
    let ending: &[u8] = match &bytes[first_end..] {
        [b'\r', b'\n', ..] => b"\r\n",
        [b'\r', ..] => b"\r",
        _ => b"\n",
    };
    loop {
        let Some(rest) = bytes.get(pos..).filter(|rest| !rest.is_empty()) else {
            return Err(parse_error(
                path,
                line,
                "the header has no 'end_header' line",
            ));
        };
        let len = rest
            .windows(ending.len())
            .position(|w| w == ending)
            .unwrap_or(rest.len());
        pos += len + ending.len();
        line += 1;
        let text = std::str::from_utf8(&rest[..len])
            .map_err(|_| parse_error(path, line, "the header line is not text"))?;
        let err = |message: String| parse_error(path, line, message);
        let mut tokens = text.split_whitespace();
        let keyword = tokens.next();
        if line == 1 {
            if keyword != Some("ply") || tokens.next().is_some() {
                return Err(err(
                    "not a PLY file: the first line must be 'ply'".to_string()
                ));
            }
            continue;
        }
        match keyword {
            None | Some("comment") | Some("obj_info") => {}
            Some("format") => {
                encoding = Some(match tokens.next() {
                    Some("ascii") => Encoding::Ascii,
                    Some("binary_little_endian") => Encoding::Binary { big_endian: false },
                    Some("binary_big_endian") => Encoding::Binary { big_endian: true },
                    other => {
                        return Err(err(format!(
                            "unknown PLY format '{}': expected ascii, binary_little_endian \
                             or binary_big_endian",
                            other.unwrap_or("")
                        )))
                    }
                });
            }
            Some("element") => {
                let name = tokens.next().unwrap_or("");
                let count = tokens
                    .next()
                    .and_then(|t| t.parse().ok())
                    .ok_or_else(|| err(format!("element '{name}' needs a name and a count")))?;
                elements.push(Element {
                    name: name.to_string(),
                    count,
                    line,
                    properties: Vec::new(),
                });
            }
            Some("property") => {
                let element = elements
                    .last_mut()
                    .ok_or_else(|| err("a property before any element".to_string()))?;
                let scalar = |t: Option<&str>| {
                    let t = t.unwrap_or("");
                    Scalar::from_name(t).ok_or_else(|| err(format!("unknown property type '{t}'")))
                };
                let kind = match tokens.next() {
                    Some("list") => Kind::List {
                        count: scalar(tokens.next())?,
                        item: scalar(tokens.next())?,
                    },
                    t => Kind::Scalar(scalar(t)?),
                };
                let name = tokens
                    .next()
                    .ok_or_else(|| err("a property without a name".to_string()))?;
                element.properties.push(Property {
                    name: name.to_string(),
                    kind,
                });
            }
            Some("end_header") => break,
            Some(other) => {
                return Err(err(format!(
                    "unexpected header line starting with '{other}'"
                )))
            }
        }
    }
    let encoding =
        encoding.ok_or_else(|| parse_error(path, 0, "the header has no 'format' line"))?;
    Ok(Header {
        encoding,
        elements,
        data_start: pos.min(bytes.len()),
        lines: line,
    })
}

fn find_layout(header: &Header, path: &Path) -> Result<Layout> {
    let find = |name: &str| header.elements.iter().position(|e| e.name == name);
    let vertex =
        find("vertex").ok_or_else(|| parse_error(path, 0, "the header has no 'vertex' element"))?;
    let element = &header.elements[vertex];
    let mut xyz = [0; 3];
    for (slot, name) in xyz.iter_mut().zip(["x", "y", "z"]) {
        let p = element
            .properties
            .iter()
            .position(|p| p.name == name)
            .ok_or_else(|| {
                parse_error(
                    path,
                    element.line,
                    format!("the vertex element has no '{name}' property"),
                )
            })?;
        if matches!(element.properties[p].kind, Kind::List { .. }) {
            return Err(parse_error(
                path,
                element.line,
                format!("vertex property '{name}' is a list; expected a number"),
            ));
        }
        *slot = p;
    }
    let face = match find("face") {
        None => None,
        Some(f) => {
            let element = &header.elements[f];
            let p = element
                .properties
                .iter()
                .position(|p| {
                    matches!(p.kind, Kind::List { .. })
                        && (p.name == "vertex_indices" || p.name == "vertex_index")
                })
                .ok_or_else(|| {
                    parse_error(
                        path,
                        element.line,
                        "the face element has no 'vertex_indices' list property",
                    )
                })?;
            Some((f, p))
        }
    };
    Ok(Layout { vertex, xyz, face })
}

/// Why a value could not be read; turned into a message by the caller, which knows where.
enum ReadError {
    /// The data ended.
    Eof,
    /// An ASCII line has fewer values than the header's properties.
    Short,
    /// An ASCII line has this many values more than the header's properties.
    Extra(usize),
    NotANumber(String),
}

/// The data section as a sequence of element instances, each a sequence of values.
trait Source {
    /// Moves to the next element instance.
    fn begin(&mut self) -> std::result::Result<(), ReadError>;
    fn value(&mut self, ty: Scalar) -> std::result::Result<f64, ReadError>;
    /// Ends the current instance, failing if it holds more values than were read.
    fn end(&mut self) -> std::result::Result<(), ReadError>;
    /// The line of the current instance in the file; 0 for binary data.
    fn line(&self) -> usize;
    /// Describes any data left after the last element.
    fn leftover(&mut self) -> Option<String>;
}

/// ASCII data: one element instance per line.
struct AsciiData<'a> {
    lines: TextLines<'a>,
    line: usize,
    tokens: std::str::SplitWhitespace<'a>,
}

impl Source for AsciiData<'_> {
    fn begin(&mut self) -> std::result::Result<(), ReadError> {
        loop {
            let text = self.lines.next().ok_or(ReadError::Eof)?;
            self.line += 1;
            self.tokens = text.split_whitespace();
            if self.tokens.clone().next().is_some() {
                return Ok(());
            }
        }
    }

    // Every type is read as f64, which holds all PLY scalars exactly; integer-ness is checked
    // where it matters (list lengths, indices).
    fn value(&mut self, _: Scalar) -> std::result::Result<f64, ReadError> {
        let token = self.tokens.next().ok_or(ReadError::Short)?;
        token
            .parse()
            .map_err(|_| ReadError::NotANumber(token.to_string()))
    }

    fn end(&mut self) -> std::result::Result<(), ReadError> {
        match self.tokens.clone().count() {
            0 => Ok(()),
            extra => Err(ReadError::Extra(extra)),
        }
    }

    fn line(&self) -> usize {
        self.line
    }

    fn leftover(&mut self) -> Option<String> {
        let lines = self.lines.by_ref().filter(|l| !l.trim().is_empty()).count();
        (lines > 0).then(|| format!("{lines} lines after the last element ignored"))
    }
}

struct BinaryData<'a> {
    data: &'a [u8],
    pos: usize,
    big_endian: bool,
}

impl BinaryData<'_> {
    fn take<const N: usize>(&mut self) -> std::result::Result<[u8; N], ReadError> {
        let bytes = self
            .data
            .get(self.pos..self.pos + N)
            .ok_or(ReadError::Eof)?;
        self.pos += N;
        bytes.try_into().map_err(|_| ReadError::Eof)
    }
}

impl Source for BinaryData<'_> {
    fn begin(&mut self) -> std::result::Result<(), ReadError> {
        Ok(())
    }

    fn value(&mut self, ty: Scalar) -> std::result::Result<f64, ReadError> {
        macro_rules! read {
            ($t:ty) => {{
                let bytes = self.take()?;
                f64::from(if self.big_endian {
                    <$t>::from_be_bytes(bytes)
                } else {
                    <$t>::from_le_bytes(bytes)
                })
            }};
        }
        Ok(match ty {
            Scalar::I8 => read!(i8),
            Scalar::U8 => read!(u8),
            Scalar::I16 => read!(i16),
            Scalar::U16 => read!(u16),
            Scalar::I32 => read!(i32),
            Scalar::U32 => read!(u32),
            Scalar::F32 => read!(f32),
            Scalar::F64 => read!(f64),
        })
    }

    fn end(&mut self) -> std::result::Result<(), ReadError> {
        Ok(())
    }

    fn line(&self) -> usize {
        0
    }

    fn leftover(&mut self) -> Option<String> {
        let bytes = self.data.len().saturating_sub(self.pos);
        (bytes > 0).then(|| format!("{bytes} bytes after the last element ignored"))
    }
}

/// A list length or vertex index read as a number: it must be a non-negative integer.
fn as_index(v: f64) -> Option<usize> {
    (v >= 0.0 && v.fract() == 0.0 && v < usize::MAX as f64).then_some(v as usize)
}

/// "1 vertex", "4 faces", "2 'edge' elements".
fn counted(count: usize, name: &str) -> String {
    match (name, count) {
        ("vertex", 1) | ("face", 1) => format!("1 {name}"),
        ("vertex", _) => format!("{count} vertices"),
        ("face", _) => format!("{count} faces"),
        (other, 1) => format!("1 '{other}' element"),
        (other, _) => format!("{count} '{other}' elements"),
    }
}

fn read_data(
    header: &Header,
    layout: &Layout,
    source: &mut impl Source,
    available: usize,
    path: &Path,
) -> Result<LoadedMesh> {
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    let mut face_lines = Vec::new();
    for (e, element) in header.elements.iter().enumerate() {
        // Instances without properties occupy no data; skipping them also avoids spinning
        // through a bogus count.
        if element.properties.is_empty() {
            continue;
        }
        let is_vertex = e == layout.vertex;
        let index_list = layout.face.filter(|&(f, _)| f == e).map(|(_, p)| p);
        let reserve = capacity(element.count, available, element.properties.len());
        if is_vertex {
            vertices.reserve(reserve);
        }
        if index_list.is_some() {
            faces.reserve(reserve);
            face_lines.reserve(reserve);
        }
        for i in 0..element.count {
            let fail = |error: ReadError, line: usize| -> Error {
                let name = &element.name;
                match error {
                    ReadError::Eof => parse_error(
                        path,
                        0,
                        format!(
                            "truncated file: the header says {}, but only {i} were found",
                            counted(element.count, name)
                        ),
                    ),
                    ReadError::Short => parse_error(
                        path,
                        line,
                        format!("{name} {i} has fewer values than the header declares"),
                    ),
                    ReadError::Extra(n) => parse_error(
                        path,
                        line,
                        format!("{name} {i} has {n} more values than the header declares"),
                    ),
                    ReadError::NotANumber(token) => {
                        parse_error(path, line, format!("{name} {i}: '{token}' is not a number"))
                    }
                }
            };
            source.begin().map_err(|error| fail(error, 0))?;
            let line = source.line();
            let mut xyz = [0.0; 3];
            let mut face = Vec::new();
            for (p, property) in element.properties.iter().enumerate() {
                match property.kind {
                    Kind::Scalar(ty) => {
                        let v = source.value(ty).map_err(|error| fail(error, line))?;
                        if let Some(k) = layout.xyz.iter().position(|&q| is_vertex && q == p) {
                            xyz[k] = v;
                        }
                    }
                    Kind::List { count, item } => {
                        let n = source.value(count).map_err(|error| fail(error, line))?;
                        let n = as_index(n).ok_or_else(|| {
                            parse_error(
                                path,
                                line,
                                format!(
                                    "{} {i}: invalid list length {}",
                                    element.name,
                                    short_number(n)
                                ),
                            )
                        })?;
                        if index_list != Some(p) {
                            for _ in 0..n {
                                source.value(item).map_err(|error| fail(error, line))?;
                            }
                            continue;
                        }
                        if n < 3 {
                            return Err(parse_error(
                                path,
                                line,
                                format!("face {i} has {n} vertices; a face needs at least 3"),
                            ));
                        }
                        for _ in 0..n {
                            let v = source.value(item).map_err(|error| fail(error, line))?;
                            face.push(as_index(v).ok_or_else(|| {
                                parse_error(
                                    path,
                                    line,
                                    format!("face {i}: {} is not a vertex index", short_number(v)),
                                )
                            })?);
                        }
                    }
                }
            }
            source.end().map_err(|error| fail(error, line))?;
            if is_vertex {
                let p = Vec3::new(xyz[0], xyz[1], xyz[2]);
                check_finite(p, i, path, line)?;
                vertices.push(p);
            }
            if index_list.is_some() {
                faces.push(face);
                face_lines.push(line);
            }
        }
    }
    // The vertex element may follow the face element, so indices are checked at the end.
    check_face_range(&faces, &face_lines, vertices.len(), 0, path)?;
    let warnings = source
        .leftover()
        .map(|w| format!("{}: {w}", path.display()))
        .into_iter()
        .collect();
    Ok(LoadedMesh {
        mesh: PolyMesh::new(vertices, faces),
        warnings,
    })
}

/// Writes ASCII PLY with double coordinates in full precision.
pub fn write_ply(w: &mut dyn Write, mesh: &PolyMesh) -> std::io::Result<()> {
    // A uchar count is what most readers expect, but it caps faces at 255 vertices.
    let count_type = if mesh.faces.iter().all(|f| f.len() <= 255) {
        "uchar"
    } else {
        "int"
    };
    write!(
        w,
        "ply\n\
         format ascii 1.0\n\
         comment written by honeycomb\n\
         element vertex {}\n\
         property double x\n\
         property double y\n\
         property double z\n\
         element face {}\n\
         property list {count_type} int vertex_indices\n\
         end_header\n",
        mesh.vertices.len(),
        mesh.faces.len()
    )?;
    write_counted_body(w, mesh)
}

#[cfg(test)]
mod tests {
    use super::super::sample_mesh;
    use super::*;

    fn parse(bytes: &[u8]) -> Result<LoadedMesh> {
        parse_ply(bytes, Path::new("test.ply"))
    }

    fn error(bytes: &[u8]) -> String {
        parse(bytes).unwrap_err().to_string()
    }

    /// The unit square as one quad, z = 0.25, with extra properties and an extra element
    /// carrying a list, in the given byte order.
    fn binary_square(big_endian: bool) -> Vec<u8> {
        let order = if big_endian { "big" } else { "little" };
        let mut b = format!(
            "ply\r\nformat binary_{order}_endian 1.0\r\n\
             comment vertex types differ on purpose\r\n\
             element vertex 4\r\n\
             property float x\r\n\
             property float32 y\r\n\
             property uchar red\r\n\
             property float64 z\r\n\
             element face 1\r\n\
             property list uint8 int32 vertex_indices\r\n\
             property int16 flags\r\n\
             element edge 1\r\n\
             property list uchar uint ends\r\n\
             end_header\r\n"
        )
        .into_bytes();
        macro_rules! put {
            ($v:expr) => {
                if big_endian {
                    b.extend_from_slice(&$v.to_be_bytes())
                } else {
                    b.extend_from_slice(&$v.to_le_bytes())
                }
            };
        }
        for (x, y) in [(0.0f32, 0.0f32), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
            put!(x);
            put!(y);
            put!(200u8);
            put!(0.25f64);
        }
        put!(4u8);
        for i in [0i32, 1, 2, 3] {
            put!(i);
        }
        put!(-7i16);
        put!(2u8);
        put!(0u32);
        put!(1u32);
        b
    }

    fn square() -> PolyMesh {
        PolyMesh::new(
            vec![
                Vec3::new(0.0, 0.0, 0.25),
                Vec3::new(1.0, 0.0, 0.25),
                Vec3::new(1.0, 1.0, 0.25),
                Vec3::new(0.0, 1.0, 0.25),
            ],
            vec![vec![0, 1, 2, 3]],
        )
    }

    #[test]
    fn ascii_round_trip_keeps_every_bit() {
        let mesh = sample_mesh();
        let mut bytes = Vec::new();
        write_ply(&mut bytes, &mesh).unwrap();
        let loaded = parse(&bytes).unwrap();
        assert_eq!(loaded.mesh, mesh);
        assert!(loaded.warnings.is_empty());
    }

    #[test]
    fn faces_longer_than_255_get_an_int_count() {
        let n = 300;
        let mesh = PolyMesh::new(
            (0..n).map(|k| Vec3::new(k as f64, 0.0, 0.0)).collect(),
            vec![(0..n).collect()],
        );
        let mut bytes = Vec::new();
        write_ply(&mut bytes, &mesh).unwrap();
        assert_eq!(parse(&bytes).unwrap().mesh, mesh);
    }

    #[test]
    fn binary_both_byte_orders() {
        for big_endian in [false, true] {
            let loaded = parse(&binary_square(big_endian)).unwrap();
            assert_eq!(loaded.mesh, square(), "big endian: {big_endian}");
            assert!(loaded.warnings.is_empty());
        }
    }

    #[test]
    fn no_prefix_of_a_binary_file_is_accepted_or_panics() {
        let bytes = binary_square(false);
        for end in 0..bytes.len() {
            assert!(parse(&bytes[..end]).is_err(), "prefix of {end} bytes");
        }
    }

    #[test]
    fn a_byte_order_mark_and_every_line_ending_read_alike() {
        let mut lf = Vec::new();
        write_ply(&mut lf, &square()).unwrap();
        let lf = String::from_utf8(lf).unwrap();
        for text in [
            format!("\u{feff}{lf}"),
            lf.replace('\n', "\r\n"),
            lf.replace('\n', "\r"),
        ] {
            assert_eq!(parse(text.as_bytes()).unwrap().mesh, square(), "{text:?}");
        }
        // Binary data after a header of CR endings, beginning with a LF byte (x = 10 as u8
        // would be one): the header's own ending decides where the data starts.
        let header = "ply\rformat binary_little_endian 1.0\relement vertex 3\r\
                      property uchar x\rproperty uchar y\rproperty uchar z\r\
                      element face 1\rproperty list uchar uchar vertex_indices\rend_header\r";
        let mut bytes = header.as_bytes().to_vec();
        bytes.extend_from_slice(&[10, 0, 0, 0, 13, 0, 0, 0, 1, 3, 0, 1, 2]);
        let mesh = parse(&bytes).unwrap().mesh;
        assert_eq!(mesh.vertices[0], Vec3::new(10.0, 0.0, 0.0));
        assert_eq!(mesh.vertices[1], Vec3::new(0.0, 13.0, 0.0));
    }

    #[test]
    fn truncated_binary_face() {
        let mut bytes = binary_square(true);
        bytes.truncate(bytes.len() - 9 - 4);
        let err = error(&bytes);
        assert!(
            err.contains("truncated file: the header says 1 face, but only 0 were found"),
            "{err}"
        );
    }

    #[test]
    fn ascii_with_skipped_elements_hexagon_and_alias_names() {
        let text = "ply\n\
                    format ascii 1.0\n\
                    element material 2\n\
                    property list uchar float coefficients\n\
                    property int id\n\
                    element vertex 6\n\
                    property int32 x\n\
                    property int32 y\n\
                    property int32 z\n\
                    property list uchar uchar tags\n\
                    element face 2\n\
                    property uchar flag\n\
                    property list int uint vertex_index\n\
                    end_header\n\
                    3 0.5 0.25 1 7\n\
                    0 8\n\
                    0 0 0 0\n\
                    1 0 0 2 1 2\n\
                    2 1 0 0\n\
                    1 2 0 0\n\
                    0 2 0 0\n\
                    -1 1 0 0\n\
                    1 6 0 1 2 3 4 5\n\
                    \n\
                    0 4 0 1 3 4\n";
        let loaded = parse(text.as_bytes()).unwrap();
        assert_eq!(loaded.mesh.vertices[5], Vec3::new(-1.0, 1.0, 0.0));
        assert_eq!(
            loaded.mesh.faces,
            vec![vec![0, 1, 2, 3, 4, 5], vec![0, 1, 3, 4]]
        );
    }

    const ASCII_HEADER: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n\
                                property float y\nproperty float z\nelement face 1\n\
                                property list uchar int vertex_indices\nend_header\n";

    fn ascii(data: &str) -> Vec<u8> {
        format!("{ASCII_HEADER}{data}").into_bytes()
    }

    #[test]
    fn empty_file() {
        assert!(error(b"").contains("empty file"));
        assert!(error(b"\n  \n").contains("empty file"));
    }

    #[test]
    fn truncated_ascii_vertices() {
        let err = error(&ascii("0 0 0\n1 0 0\n"));
        assert!(
            err.contains("truncated file: the header says 3 vertices, but only 2 were found"),
            "{err}"
        );
    }

    #[test]
    fn value_errors_name_element_and_line() {
        let err = error(&ascii("0 0 0\n1 0 0\n0 one 0\n3 0 1 2\n"));
        assert!(err.contains("test.ply:12:"), "{err}");
        assert!(err.contains("vertex 2: 'one' is not a number"), "{err}");
        let err = error(&ascii("0 0 0\n1 0 0\n0 1\n3 0 1 2\n"));
        assert!(
            err.contains(":12:") && err.contains("vertex 2 has fewer values"),
            "{err}"
        );
        let err = error(&ascii("0 0 0\n1 0 0 5\n0 1 0\n3 0 1 2\n"));
        assert!(
            err.contains(":11:") && err.contains("vertex 1 has 1 more values"),
            "{err}"
        );
        let err = error(&ascii("0 0 0\n1 0 0\n0 1 0\n3 0 1 -2\n"));
        assert!(
            err.contains(":13:") && err.contains("face 0: -2 is not a vertex index"),
            "{err}"
        );
        let err = error(&ascii("0 0 0\n1 0 0\n0 1 0\n2 0 1\n"));
        assert!(err.contains("face 0 has 2 vertices"), "{err}");
        let err = error(&ascii("0 0 0\n1 0 0\n0 1 0\n2.5 0 1\n"));
        assert!(err.contains("face 0: invalid list length 2.5"), "{err}");
    }

    #[test]
    fn non_finite_coordinate_names_vertex_and_line() {
        let err = error(&ascii("0 0 0\n1 0 inf\n0 1 0\n3 0 1 2\n"));
        assert!(err.contains("test.ply:11:"), "{err}");
        assert!(
            err.contains("vertex 1 has a non-finite coordinate"),
            "{err}"
        );

        let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 1\n\
                          property double x\nproperty double y\nproperty double z\nend_header\n"
            .to_vec();
        for v in [0.0, f64::NAN, 0.0] {
            bytes.extend_from_slice(&f64::to_le_bytes(v));
        }
        let err = error(&bytes);
        assert!(
            err.contains("vertex 0 has a non-finite coordinate: (0, NaN, 0)"),
            "{err}"
        );
    }

    #[test]
    fn out_of_range_index_names_face_and_line() {
        let err = error(&ascii("0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"));
        assert!(err.contains("test.ply:13:"), "{err}");
        assert!(
            err.contains("face 0: vertex index 3 is out of range (the file has 3 vertices)"),
            "{err}"
        );
    }

    #[test]
    fn bad_headers() {
        assert!(error(b"OFF\n3 1 0\n").contains("the first line must be 'ply'"));
        assert!(error(b"ply\nformat ascii 1.0\n").contains("no 'end_header'"));
        assert!(error(b"ply\nformat utf8 1.0\nend_header\n").contains("unknown PLY format 'utf8'"));
        assert!(error(b"ply\nend_header\n").contains("no 'format' line"));
        assert!(error(b"ply\nformat ascii 1.0\nend_header\n").contains("no 'vertex' element"));
        let err = error(b"ply\nformat ascii 1.0\nelement vertex 1\nproperty half x\nend_header\n");
        assert!(
            err.contains(":4:") && err.contains("unknown property type 'half'"),
            "{err}"
        );
        let err = error(b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n");
        assert!(
            err.contains(":3:") && err.contains("no 'y' property"),
            "{err}"
        );
        let err = error(
            &ASCII_HEADER
                .replace("vertex_indices", "corners")
                .into_bytes(),
        );
        assert!(err.contains("no 'vertex_indices' list property"), "{err}");
        let err = error(b"ply\nformat ascii 1.0\nproperty float x\n");
        assert!(err.contains("a property before any element"), "{err}");
    }

    #[test]
    fn bogus_counts_do_not_allocate_or_spin() {
        let header = "ply\nformat binary_little_endian 1.0\nelement vertex 18446744073709551615\n\
                      property float x\nproperty float y\nproperty float z\n\
                      element nothing 18446744073709551615\nend_header\n";
        let err = error(header.as_bytes());
        assert!(
            err.contains("the header says 18446744073709551615 vertices"),
            "{err}"
        );
        let mut bytes = ascii("0 0 0\n1 0 0\n0 1 0\n");
        bytes.extend_from_slice(b"4000000000 0 1 2\n");
        assert!(error(&bytes).contains("face 0 has fewer values"));
    }

    #[test]
    fn trailing_data_is_reported() {
        let mut bytes = binary_square(false);
        bytes.extend_from_slice(&[0, 0, 0]);
        let loaded = parse(&bytes).unwrap();
        assert_eq!(
            loaded.warnings,
            ["test.ply: 3 bytes after the last element ignored"]
        );
    }
}
