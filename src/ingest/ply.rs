//! PLY (Stanford polygon files), ASCII and binary of either byte order, as scanners and
//! photogrammetry tools write them: the `vertex` element's `x`, `y`, `z` and the `face`
//! element's index list (`vertex_indices` or `vertex_index`); polygons are made into triangles by
//! `triangulate_polygon` (a convex one fanned from its first corner). A `tristrips` element's index
//! lists are triangle strips (`-1` starts a
//! new strip; every other triangle of a strip is turned so all face the same way). Every other
//! element and property (normals, colours, edges, materials) is read past and ignored.

use glam::DVec3;

use super::errors::FormatDefect;
use super::polygon::triangulate_polygon;
use crate::cad::TriangleSoup;

/// True when the bytes start like a PLY file.
pub(crate) fn looks_like_ply(bytes: &[u8]) -> bool {
    bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r\n")
}

/// Parses a PLY file into a triangle soup.
pub fn parse_ply(bytes: &[u8]) -> Result<TriangleSoup, FormatDefect> {
    let header = Header::parse(bytes)?;
    let mut body = match header.format {
        Format::Ascii => Body::Ascii(AsciiBody::new(bytes, header.body_start, header.body_line)?),
        Format::Binary(order) => Body::Binary {
            bytes: &bytes[header.body_start..],
            at: 0,
            order,
        },
    };
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for element in &header.elements {
        match element.role {
            Role::Vertices(axes) => {
                positions = read_vertices(&mut body, element, axes)?;
            }
            Role::Faces(list) => {
                let faces = read_faces(&mut body, element, list, &positions, face_corners)?;
                triangles.extend(faces);
            }
            Role::Strips(list) => {
                let strips = read_faces(&mut body, element, list, &positions, strip_triangles)?;
                triangles.extend(strips);
            }
            Role::Other => skip_element(&mut body, element)?,
        }
    }
    if triangles.is_empty() {
        return Err(FormatDefect::Empty);
    }
    Ok(TriangleSoup::new(positions, triangles))
}

/// How the body is stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Ascii,
    Binary(ByteOrder),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ByteOrder {
    Little,
    Big,
}

/// A scalar type of a property.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
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
    fn parse(word: &str) -> Option<Self> {
        Some(match word {
            "char" | "int8" => Self::I8,
            "uchar" | "uint8" => Self::U8,
            "short" | "int16" => Self::I16,
            "ushort" | "uint16" => Self::U16,
            "int" | "int32" => Self::I32,
            "uint" | "uint32" => Self::U32,
            "float" | "float32" => Self::F32,
            "double" | "float64" => Self::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Self::I8 | Self::U8 => 1,
            Self::I16 | Self::U16 => 2,
            Self::I32 | Self::U32 | Self::F32 => 4,
            Self::F64 => 8,
        }
    }
}

/// A property: one scalar, or a list of scalars preceded by its length.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Property {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

/// What an element is to flatcut.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Role {
    /// `vertex`, with the indices of its `x`, `y` and `z` properties.
    Vertices([usize; 3]),
    /// `face`, with the index of its vertex list property.
    Faces(usize),
    /// `tristrips`, with the index of its vertex list property.
    Strips(usize),
    Other,
}

#[derive(Debug, Clone, PartialEq)]
struct Element {
    name: String,
    count: usize,
    properties: Vec<(String, Property)>,
    role: Role,
}

struct Header {
    format: Format,
    elements: Vec<Element>,
    /// Byte offset of the body.
    body_start: usize,
    /// 1-based line number of the body's first line (ASCII).
    body_line: usize,
}

fn header_error(line: usize, message: impl Into<String>) -> FormatDefect {
    FormatDefect::Line {
        line,
        message: message.into(),
    }
}

impl Header {
    fn parse(bytes: &[u8]) -> Result<Self, FormatDefect> {
        if !looks_like_ply(bytes) {
            return Err(header_error(1, "not a PLY file: it must start with 'ply'"));
        }
        let mut format = None;
        let mut elements: Vec<Element> = Vec::new();
        let mut at = 0;
        let mut line = 0;
        loop {
            let Some(length) = bytes[at..].iter().position(|&b| b == b'\n') else {
                return Err(header_error(
                    line + 1,
                    "the header has no 'end_header' line",
                ));
            };
            line += 1;
            let raw = &bytes[at..at + length];
            at += length + 1;
            let text = std::str::from_utf8(raw)
                .map_err(|_| header_error(line, "the header is not ASCII text"))?
                .trim();
            let words: Vec<&str> = text.split_whitespace().collect();
            match words.as_slice() {
                ["ply"] if line == 1 => {}
                ["end_header"] => break,
                ["comment" | "obj_info", ..] | [] => {}
                ["format", kind, "1.0"] => {
                    format = Some(match *kind {
                        "ascii" => Format::Ascii,
                        "binary_little_endian" => Format::Binary(ByteOrder::Little),
                        "binary_big_endian" => Format::Binary(ByteOrder::Big),
                        other => {
                            return Err(header_error(line, format!("unknown format '{other}'")));
                        }
                    })
                }
                ["element", name, count] => {
                    let count = count.parse::<usize>().map_err(|_| {
                        header_error(line, format!("element count '{count}' is not a number"))
                    })?;
                    elements.push(Element {
                        name: (*name).to_string(),
                        count,
                        properties: Vec::new(),
                        role: Role::Other,
                    });
                }
                ["property", ..] => {
                    let element = elements
                        .last_mut()
                        .ok_or_else(|| header_error(line, "a property before any element"))?;
                    element.properties.push(parse_property(&words, line)?);
                }
                _ => return Err(header_error(line, format!("unknown header line '{text}'"))),
            }
        }
        let format = format.ok_or_else(|| header_error(line, "the header has no format line"))?;
        for element in &mut elements {
            element.role = role_of(element, line)?;
        }
        Ok(Self {
            format,
            elements,
            body_start: at,
            body_line: line + 1,
        })
    }
}

fn parse_property(words: &[&str], line: usize) -> Result<(String, Property), FormatDefect> {
    let scalar = |word: &str| {
        Scalar::parse(word)
            .ok_or_else(|| header_error(line, format!("unknown property type '{word}'")))
    };
    match words {
        ["property", "list", count, item, name] => Ok((
            (*name).to_string(),
            Property::List {
                count: scalar(count)?,
                item: scalar(item)?,
            },
        )),
        ["property", kind, name] => Ok(((*name).to_string(), Property::Scalar(scalar(kind)?))),
        _ => Err(header_error(
            line,
            format!("malformed property line '{}'", words.join(" ")),
        )),
    }
}

/// The role of an element: `vertex` needs scalar `x`, `y`, `z`; `face` needs an index list.
fn role_of(element: &Element, line: usize) -> Result<Role, FormatDefect> {
    let find = |wanted: &[&str]| {
        element
            .properties
            .iter()
            .position(|(name, _)| wanted.contains(&name.as_str()))
    };
    match element.name.as_str() {
        "vertex" => {
            let mut axes = [0; 3];
            for (axis, name) in axes.iter_mut().zip(["x", "y", "z"]) {
                let index = find(&[name]).ok_or_else(|| {
                    header_error(line, format!("the vertex element has no '{name}' property"))
                })?;
                if !matches!(element.properties[index].1, Property::Scalar(_)) {
                    return Err(header_error(line, format!("vertex '{name}' is a list")));
                }
                *axis = index;
            }
            Ok(Role::Vertices(axes))
        }
        name @ ("face" | "tristrips") => {
            let index = find(&["vertex_indices", "vertex_index"]).ok_or_else(|| {
                header_error(
                    line,
                    format!("the {name} element has no 'vertex_indices' list"),
                )
            })?;
            match element.properties[index].1 {
                Property::List { item, .. } if !matches!(item, Scalar::F32 | Scalar::F64) => {
                    Ok(if name == "face" {
                        Role::Faces(index)
                    } else {
                        Role::Strips(index)
                    })
                }
                _ => Err(header_error(
                    line,
                    format!("{name} 'vertex_indices' must be a list of integers"),
                )),
            }
        }
        _ => Ok(Role::Other),
    }
}

/// The body being read: ASCII words, or binary bytes with a cursor.
enum Body<'a> {
    Ascii(AsciiBody<'a>),
    Binary {
        bytes: &'a [u8],
        at: usize,
        order: ByteOrder,
    },
}

/// An ASCII body: its words, each with its 1-based line.
struct AsciiBody<'a> {
    text: &'a str,
    at: usize,
    line: usize,
}

impl<'a> AsciiBody<'a> {
    fn new(bytes: &'a [u8], start: usize, line: usize) -> Result<Self, FormatDefect> {
        let text = std::str::from_utf8(&bytes[start..])
            .map_err(|_| header_error(line, "the ASCII body is not text"))?;
        Ok(Self { text, at: 0, line })
    }

    /// The next word and its line.
    fn word(&mut self) -> Option<(&'a str, usize)> {
        let rest = &self.text[self.at..];
        let start = rest.find(|c: char| !c.is_ascii_whitespace())?;
        self.line += rest[..start].matches('\n').count();
        let word = &rest[start..];
        let end = word
            .find(|c: char| c.is_ascii_whitespace())
            .unwrap_or(word.len());
        self.at += start + end;
        Some((&word[..end], self.line))
    }
}

impl Body<'_> {
    /// The next value of type `scalar`, as a float.
    /// `what` names the record in an error (made only then: values are read in the millions).
    fn value(&mut self, scalar: Scalar, what: &dyn Fn() -> String) -> Result<f64, FormatDefect> {
        match self {
            Body::Ascii(ascii) => {
                let line = ascii.line;
                let (word, line) = ascii.word().ok_or_else(|| {
                    header_error(line, format!("the file ends inside {}", what()))
                })?;
                word.parse::<f64>()
                    .ok()
                    .filter(|value| {
                        matches!(scalar, Scalar::F32 | Scalar::F64) || value.fract() == 0.0
                    })
                    .ok_or_else(|| {
                        header_error(
                            line,
                            format!("'{word}' in {} is not a number of its type", what()),
                        )
                    })
            }
            Body::Binary { bytes, at, order } => {
                let size = scalar.size();
                let raw = bytes.get(*at..*at + size).ok_or_else(|| {
                    FormatDefect::Binary(format!(
                        "the file ends inside {} (byte {} of the body)",
                        what(),
                        *at
                    ))
                })?;
                *at += size;
                Ok(decode(raw, scalar, *order))
            }
        }
    }

    /// Bytes (binary) or words (ASCII) left, a bound on the records still to come.
    fn remaining(&self) -> usize {
        match self {
            Body::Ascii(ascii) => (ascii.text.len() - ascii.at).div_ceil(2),
            Body::Binary { bytes, at, .. } => bytes.len() - at,
        }
    }
}

fn decode(raw: &[u8], scalar: Scalar, order: ByteOrder) -> f64 {
    macro_rules! number {
        ($type:ty) => {{
            let array = raw.try_into().expect("sized by the scalar");
            match order {
                ByteOrder::Little => <$type>::from_le_bytes(array) as f64,
                ByteOrder::Big => <$type>::from_be_bytes(array) as f64,
            }
        }};
    }
    match scalar {
        Scalar::I8 => raw[0] as i8 as f64,
        Scalar::U8 => raw[0] as f64,
        Scalar::I16 => number!(i16),
        Scalar::U16 => number!(u16),
        Scalar::I32 => number!(i32),
        Scalar::U32 => number!(u32),
        Scalar::F32 => number!(f32),
        Scalar::F64 => number!(f64),
    }
}

/// Reads a record's properties, calling `keep` with each scalar's property index and value and
/// `list` with each list's property index and items.
fn read_record(
    body: &mut Body<'_>,
    element: &Element,
    record: usize,
    mut keep: impl FnMut(usize, f64),
    mut list: impl FnMut(usize, &[f64]) -> Result<(), FormatDefect>,
) -> Result<(), FormatDefect> {
    let what = || format!("{} {}", element.name, record + 1);
    let mut items = Vec::new();
    for (index, (_, property)) in element.properties.iter().enumerate() {
        match *property {
            Property::Scalar(scalar) => keep(index, body.value(scalar, &what)?),
            Property::List { count, item } => {
                let length = body.value(count, &what)?;
                if !(0.0..=u32::MAX as f64).contains(&length) || length > body.remaining() as f64 {
                    return Err(FormatDefect::Binary(format!(
                        "{} has a list of {length} items, more than the file holds",
                        what()
                    )));
                }
                items.clear();
                for _ in 0..length as usize {
                    items.push(body.value(item, &what)?);
                }
                list(index, &items)?;
            }
        }
    }
    Ok(())
}

/// Refuses an element count the rest of the file cannot hold (each record takes at least a
/// byte, or a word and a separator).
fn check_count(body: &Body<'_>, element: &Element) -> Result<(), FormatDefect> {
    if !element.properties.is_empty() && element.count > body.remaining() {
        return Err(FormatDefect::Binary(format!(
            "the header announces {} {} records, more than the rest of the file can hold",
            element.count, element.name
        )));
    }
    Ok(())
}

fn read_vertices(
    body: &mut Body<'_>,
    element: &Element,
    axes: [usize; 3],
) -> Result<Vec<DVec3>, FormatDefect> {
    check_count(body, element)?;
    let mut positions = Vec::with_capacity(element.count);
    for record in 0..element.count {
        let mut point = DVec3::ZERO;
        read_record(
            body,
            element,
            record,
            |index, value| {
                for (axis, &at) in axes.iter().enumerate() {
                    if at == index {
                        point[axis] = value;
                    }
                }
            },
            |_, _| Ok(()),
        )?;
        positions.push(point);
    }
    Ok(positions)
}

/// Makes one record's index list into triangles, given the vertex count and the record's index.
type Triangulate = fn(&[f64], &[DVec3], usize) -> Result<Vec<[u32; 3]>, FormatDefect>;

/// The triangles of a `face` or `tristrips` element, each record's index list made into
/// triangles by `triangulate` (given the list, the vertices and the record).
fn read_faces(
    body: &mut Body<'_>,
    element: &Element,
    list_property: usize,
    vertices: &[DVec3],
    triangulate: Triangulate,
) -> Result<Vec<[u32; 3]>, FormatDefect> {
    check_count(body, element)?;
    let mut triangles = Vec::with_capacity(element.count);
    for record in 0..element.count {
        read_record(
            body,
            element,
            record,
            |_, _| {},
            |index, items| {
                if index != list_property {
                    return Ok(());
                }
                triangles.extend(triangulate(items, vertices, record)?);
                Ok(())
            },
        )?;
    }
    Ok(triangles)
}

/// A polygon's triangles ([`triangulate_polygon`]: a convex one fanned from its first corner).
fn face_corners(
    items: &[f64],
    vertices: &[DVec3],
    record: usize,
) -> Result<Vec<[u32; 3]>, FormatDefect> {
    let corners = polygon_corners(items, vertices.len(), record)?;
    let mut triangles = Vec::with_capacity(corners.len() - 2);
    let corner = |k: usize| vertices[corners[k] as usize];
    triangulate_polygon(corners.len(), corner, |triangle| {
        triangles.push(triangle.map(|k| corners[k]));
    });
    Ok(triangles)
}

/// The triangles of a record of triangle strips: `-1` ends a strip; in each strip, triangle `k`
/// is `(s[k], s[k+1], s[k+2])`, its two first corners swapped for odd `k` so that every triangle
/// keeps the strip's orientation. A strip of fewer than 3 indices makes no triangle.
fn strip_triangles(
    items: &[f64],
    vertices: &[DVec3],
    record: usize,
) -> Result<Vec<[u32; 3]>, FormatDefect> {
    let mut triangles = Vec::new();
    for strip in items.split(|&index| index == -1.0) {
        let corners = checked_indices(strip, vertices.len(), record, "triangle strip")?;
        for k in 0..corners.len().saturating_sub(2) {
            let [a, b, c] = [corners[k], corners[k + 1], corners[k + 2]];
            triangles.push(if k % 2 == 0 { [a, b, c] } else { [b, a, c] });
        }
    }
    Ok(triangles)
}

/// A face's corners as vertex indices, checked against the vertex count.
fn polygon_corners(
    items: &[f64],
    vertices: usize,
    record: usize,
) -> Result<Vec<u32>, FormatDefect> {
    if items.len() < 3 {
        return Err(FormatDefect::Binary(format!(
            "face {} has {} vertices; a face needs at least 3",
            record + 1,
            items.len()
        )));
    }
    checked_indices(items, vertices, record, "face")
}

/// The indices of a record, each checked against the vertex count.
fn checked_indices(
    items: &[f64],
    vertices: usize,
    record: usize,
    what: &str,
) -> Result<Vec<u32>, FormatDefect> {
    items
        .iter()
        .map(|&index| {
            if index >= 0.0 && index < vertices as f64 {
                Ok(index as u32)
            } else {
                Err(FormatDefect::Binary(format!(
                    "{what} {} refers to vertex {index}, but the file has {vertices} vertices (numbered from 0)",
                    record + 1
                )))
            }
        })
        .collect()
}

fn skip_element(body: &mut Body<'_>, element: &Element) -> Result<(), FormatDefect> {
    check_count(body, element)?;
    for record in 0..element.count {
        read_record(body, element, record, |_, _| {}, |_, _| Ok(()))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::ingest::ply::*;

    const SQUARE_ASCII: &str = "ply\nformat ascii 1.0\ncomment two triangles\nelement vertex 4\n\
        property float x\nproperty float y\nproperty float z\nproperty uchar red\n\
        element face 1\nproperty list uchar int vertex_indices\nend_header\n\
        0 0 0 255\n1 0 0 0\n1 1 0 0\n0 1 0 9\n4 0 1 2 3\n";

    fn binary_square(order: ByteOrder) -> Vec<u8> {
        let name = match order {
            ByteOrder::Little => "binary_little_endian",
            ByteOrder::Big => "binary_big_endian",
        };
        let mut bytes = format!(
            "ply\r\nformat {name} 1.0\r\nelement vertex 4\r\nproperty double x\r\n\
             property double y\r\nproperty double z\r\nelement edge 1\r\n\
             property list uchar uint vertex_pair\r\nelement face 2\r\n\
             property list uchar uint vertex_indices\r\nend_header\r\n"
        )
        .into_bytes();
        let f64_bytes = |v: f64| match order {
            ByteOrder::Little => v.to_le_bytes(),
            ByteOrder::Big => v.to_be_bytes(),
        };
        let u32_bytes = |v: u32| match order {
            ByteOrder::Little => v.to_le_bytes(),
            ByteOrder::Big => v.to_be_bytes(),
        };
        for [x, y] in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] {
            for v in [x, y, 0.5] {
                bytes.extend(f64_bytes(v));
            }
        }
        bytes.push(2);
        bytes.extend(u32_bytes(0));
        bytes.extend(u32_bytes(2));
        for face in [[0, 1, 2], [0, 2, 3]] {
            bytes.push(3);
            for v in face {
                bytes.extend(u32_bytes(v));
            }
        }
        bytes
    }

    #[test]
    fn ascii_polygons_are_fanned_and_other_properties_skipped() {
        let soup = parse_ply(SQUARE_ASCII.as_bytes()).expect("parses");
        assert_eq!(soup.positions.len(), 4);
        assert_eq!(soup.positions[2], DVec3::new(1.0, 1.0, 0.0));
        assert_eq!(soup.triangles, [[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn triangle_strips_are_split_at_minus_one_and_keep_one_orientation() {
        let text = "ply\nformat ascii 1.0\nelement vertex 7\nproperty float x\nproperty float y\n\
                    property float z\nelement tristrips 1\nproperty list int int vertex_indices\n\
                    end_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n5 0 0\n6 0 0\n5 1 0\n\
                    8 0 1 2 3 -1 4 5 6\n";
        let soup = parse_ply(text.as_bytes()).expect("parses");
        assert_eq!(soup.triangles, [[0, 1, 2], [2, 1, 3], [4, 5, 6]]);
        // Every triangle faces +z: counter-clockwise in the plane.
        for t in &soup.triangles {
            let [a, b, c] = t.map(|v| soup.positions[v as usize]);
            assert!((b - a).cross(c - a).z > 0.0, "{t:?}");
        }
        let bad = text.replace("-1 4 5 6", "-1 4 5 9");
        let error = parse_ply(bad.as_bytes())
            .expect_err("out of range")
            .to_string();
        assert!(error.contains("triangle strip 1"), "{error}");
    }

    #[test]
    fn binary_files_of_both_byte_orders_read_the_same() {
        for order in [ByteOrder::Little, ByteOrder::Big] {
            let soup = parse_ply(&binary_square(order)).expect("parses");
            assert_eq!(soup.triangles, [[0, 1, 2], [0, 2, 3]], "{order:?}");
            assert_eq!(soup.positions[3], DVec3::new(0.0, 1.0, 0.5), "{order:?}");
        }
    }

    #[test]
    fn bad_files_are_refused_with_the_place() {
        let refused = |bytes: &[u8]| parse_ply(bytes).expect_err("refused").to_string();
        let truncated = binary_square(ByteOrder::Little);
        assert!(refused(&truncated[..truncated.len() - 3]).contains("ends inside face 2"));
        let bad_index = SQUARE_ASCII.replace("4 0 1 2 3", "3 0 1 7");
        assert!(refused(bad_index.as_bytes()).contains("face 1 refers to vertex 7"));
        let bad_number = SQUARE_ASCII.replace("1 1 0 0", "1 x 0 0");
        assert_eq!(
            refused(bad_number.as_bytes()),
            "line 14: 'x' in vertex 3 is not a number of its type"
        );
        let huge = SQUARE_ASCII.replace("element vertex 4", "element vertex 4000000000");
        assert!(refused(huge.as_bytes()).contains("more than the rest of the file can hold"));
        assert!(refused(b"ply\nformat ascii 1.0\n").contains("no 'end_header'"));
        let no_z = SQUARE_ASCII.replace("property float z\n", "");
        assert!(refused(no_z.as_bytes()).contains("no 'z' property"));
    }
}
