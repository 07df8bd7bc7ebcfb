//! Wavefront OBJ: `v` positions and `f` faces (forms `i`, `i/t`, `i/t/n`, `i//n`, negative
//! indices relative to the end); polygons are fan-triangulated from their first corner. Other
//! statements (`vt`, `vn`, `g`, `o`, `s`, `usemtl`, `mtllib`, ...) are ignored.

use glam::DVec3;

use super::errors::FormatDefect;
use crate::cad::{SourceLines, TriangleSoup};

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
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        let content = raw.split('#').next().unwrap_or("").trim();
        let mut words = content.split_whitespace();
        match words.next() {
            Some("v") => {
                positions.push(parse_position(words, line)?);
                lines.vertices.push(line as u32);
            }
            Some("f") => {
                let corners = words
                    .map(|word| parse_corner(word, positions.len(), line))
                    .collect::<Result<Vec<u32>, _>>()?;
                if corners.len() < 3 {
                    return Err(FormatDefect::Line {
                        line,
                        message: format!(
                            "a face needs at least 3 vertices, found {}",
                            corners.len()
                        ),
                    });
                }
                for k in 1..corners.len() - 1 {
                    triangles.push([corners[0], corners[k], corners[k + 1]]);
                    lines.triangles.push(line as u32);
                }
            }
            _ => {}
        }
    }
    if triangles.is_empty() {
        return Err(FormatDefect::Empty);
    }
    Ok(TriangleSoup::new(positions, triangles).with_lines(lines))
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

/// The 0-based vertex index of one face corner, resolving negative (relative) indices.
fn parse_corner(word: &str, vertex_count: usize, line: usize) -> Result<u32, FormatDefect> {
    let index_text = word.split('/').next().unwrap_or("");
    let bad = |message: String| FormatDefect::Line { line, message };
    let index: i64 = index_text
        .parse()
        .map_err(|_| bad(format!("face corner '{word}' is not a vertex index")))?;
    let resolved = match index {
        0 => {
            return Err(bad(
                "face index 0 is invalid (OBJ indices start at 1)".into()
            ));
        }
        i if i > 0 => i - 1,
        i => vertex_count as i64 + i,
    };
    if resolved < 0 || resolved >= vertex_count as i64 {
        return Err(bad(format!(
            "face index {index} is out of range: {vertex_count} vertices defined so far"
        )));
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
