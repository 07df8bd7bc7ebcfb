//! Wavefront OBJ: `v` positions, `vt` texture points and `f` faces (forms `i`, `i/t`, `i/t/n`,
//! `i//n`, negative indices relative to the end); polygons are made into triangles by
//! [`triangulate_polygon`] (a convex one fanned from its first corner). The texture points are
//! kept when every face gives one per corner (a garment's sewing
//! pattern). Other statements (`vn`, `g`, `o`, `s`, `usemtl`, `mtllib`, ...) are ignored.

use glam::{DVec2, DVec3};

use super::errors::FormatDefect;
use super::polygon::triangulate_polygon;
use crate::cad::{SourceLines, TextureCorners, TriangleSoup};

/// True when the bytes look like an OBJ file: text whose statements start with `v ` or `f `.
pub(crate) fn looks_like_obj(bytes: &[u8]) -> bool {
    let head = &bytes[..bytes.len().min(4096)];
    std::str::from_utf8(head).is_ok_and(|text| {
        text.lines()
            .any(|line| line.starts_with("v ") || line.starts_with("f "))
    })
}

/// Parses OBJ text into a triangle soup.
pub fn parse_obj(bytes: &[u8]) -> Result<TriangleSoup, FormatDefect> {
    let text = std::str::from_utf8(bytes).map_err(|e| FormatDefect::Line {
        line: line_of_offset(bytes, e.valid_up_to()),
        message: "not UTF-8 text".into(),
    })?;
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    let mut lines = SourceLines::default();
    let mut texture = TextureCorners::default();
    let mut every_corner_textured = true;
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        let content = raw.split('#').next().unwrap_or("").trim();
        let mut words = content.split_whitespace();
        match words.next() {
            Some("v") => {
                positions.push(parse_position(words, line)?);
                lines.vertices.push(line as u32);
            }
            Some("vt") => texture.points.push(parse_texture_point(words, line)?),
            Some("f") => {
                let corners = words
                    .map(|word| parse_corner(word, positions.len(), texture.points.len(), line))
                    .collect::<Result<Vec<Corner>, _>>()?;
                if corners.len() < 3 {
                    return Err(FormatDefect::Line {
                        line,
                        message: format!(
                            "a face needs at least 3 vertices, found {}",
                            corners.len()
                        ),
                    });
                }
                every_corner_textured &= corners.iter().all(|c| c.texture.is_some());
                let corner = |k: usize| positions[corners[k].vertex as usize];
                triangulate_polygon(corners.len(), corner, |triangle| {
                    let corners = triangle.map(|k| &corners[k]);
                    triangles.push(corners.map(|c| c.vertex));
                    if every_corner_textured {
                        texture
                            .corners
                            .push(corners.map(|c| c.texture.unwrap_or(0)));
                    }
                    lines.triangles.push(line as u32);
                });
            }
            _ => {}
        }
    }
    if triangles.is_empty() {
        return Err(FormatDefect::Empty);
    }
    let soup = TriangleSoup::new(positions, triangles).with_lines(lines);
    Ok(if every_corner_textured {
        soup.with_texture(texture)
    } else {
        soup
    })
}

/// A `vt` statement's `u` and `v` (`v` is 0 when the file gives only `u`; a `w` is ignored).
fn parse_texture_point<'a>(
    mut words: impl Iterator<Item = &'a str>,
    line: usize,
) -> Result<DVec2, FormatDefect> {
    let mut coordinate = |axis: &str, default: Option<f64>| -> Result<f64, FormatDefect> {
        match (words.next(), default) {
            (None, Some(value)) => Ok(value),
            (None, None) => Err(FormatDefect::Line {
                line,
                message: format!("texture point has no {axis} coordinate"),
            }),
            (Some(word), _) => word.parse::<f64>().map_err(|_| FormatDefect::Line {
                line,
                message: format!("texture {axis} coordinate '{word}' is not a number"),
            }),
        }
    };
    Ok(DVec2::new(
        coordinate("u", None)?,
        coordinate("v", Some(0.0))?,
    ))
}

fn parse_position<'a>(
    mut words: impl Iterator<Item = &'a str>,
    line: usize,
) -> Result<DVec3, FormatDefect> {
    let mut coordinate = |axis: &str| -> Result<f64, FormatDefect> {
        let word = words.next().ok_or_else(|| FormatDefect::Line {
            line,
            message: format!("vertex has no {axis} coordinate"),
        })?;
        word.parse::<f64>().map_err(|_| FormatDefect::Line {
            line,
            message: format!("vertex {axis} coordinate '{word}' is not a number"),
        })
    };
    Ok(DVec3::new(
        coordinate("x")?,
        coordinate("y")?,
        coordinate("z")?,
    ))
}

/// One face corner: its vertex and, when given, its texture point (0-based).
struct Corner {
    vertex: u32,
    texture: Option<u32>,
}

/// The 0-based vertex and texture indices of one face corner (`i`, `i/t`, `i/t/n` or `i//n`),
/// resolving negative (relative) indices.
fn parse_corner(
    word: &str,
    vertex_count: usize,
    texture_count: usize,
    line: usize,
) -> Result<Corner, FormatDefect> {
    let mut parts = word.split('/');
    let bad = |message: String| FormatDefect::Line { line, message };
    let index_text = parts.next().unwrap_or("");
    let index: i64 = index_text
        .parse()
        .map_err(|_| bad(format!("face corner '{word}' is not a vertex index")))?;
    let vertex = resolve_index(index, vertex_count, "vertices").map_err(bad)?;
    let texture = match parts.next() {
        None | Some("") => None,
        Some(text) => {
            let index: i64 = text
                .parse()
                .map_err(|_| bad(format!("face corner '{word}' has a bad texture index")))?;
            Some(resolve_index(index, texture_count, "texture points").map_err(bad)?)
        }
    };
    Ok(Corner { vertex, texture })
}

/// A 1-based (or negative, relative) OBJ index as a 0-based one, checked against the `count`
/// elements (`what`) defined so far.
fn resolve_index(index: i64, count: usize, what: &str) -> Result<u32, String> {
    let resolved = match index {
        0 => return Err("face index 0 is invalid (OBJ indices start at 1)".into()),
        i if i > 0 => i - 1,
        i => count as i64 + i,
    };
    if resolved < 0 || resolved >= count as i64 {
        return Err(format!(
            "face index {index} is out of range: {count} {what} defined so far"
        ));
    }
    Ok(resolved as u32)
}

/// 1-based line number of a byte offset.
fn line_of_offset(bytes: &[u8], offset: usize) -> usize {
    bytes[..offset].iter().filter(|&&b| b == b'\n').count() + 1
}

#[cfg(test)]
mod tests {
    use crate::ingest::obj::*;

    #[test]
    fn quad_with_texture_and_normal_indices_is_fanned() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3//1 -1\n";
        let soup = parse_obj(text.as_bytes()).expect("valid obj");
        assert_eq!(soup.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(soup.texture, None, "the third corner has no texture point");
    }

    #[test]
    fn texture_points_are_kept_per_corner() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 0.5 0\nvt 0.5 0.5 0\nvt 0\n\
                    f 1/1 2/2 3/3 4/-1\n";
        let soup = parse_obj(text.as_bytes()).expect("valid obj");
        let texture = soup.texture.expect("every corner has a texture point");
        assert_eq!(texture.corners, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(texture.points[2], DVec2::new(0.5, 0.5));
        assert_eq!(texture.points[3], DVec2::ZERO);
        let error = parse_obj(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n")
            .expect_err("texture index out of range");
        assert!(
            error.to_string().contains("line 5") && error.to_string().contains("texture points"),
            "{error}"
        );
    }

    #[test]
    fn errors_name_the_line() {
        let error = parse_obj(b"v 0 0 0\nv 1 0 x\n").expect_err("bad number");
        assert!(error.to_string().contains("line 2"), "{error}");
        let error = parse_obj(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n").expect_err("out of range");
        assert!(
            error.to_string().contains("line 4") && error.to_string().contains("out of range"),
            "{error}"
        );
        assert_eq!(parse_obj(b"# nothing\n"), Err(FormatDefect::Empty));
    }
}
