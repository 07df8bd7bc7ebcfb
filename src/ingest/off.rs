//! OFF (Object File Format, as Geomview, CGAL and many mesh datasets write it): an `OFF` line,
//! the counts `vertices faces edges`, the vertices `x y z`, then the faces `n i₁ … iₙ` with
//! 0-based indices; polygons are made into triangles by `triangulate_polygon` (a convex one fanned
//! from its first corner), colours after a
//! face's indices and `#` comments are ignored. The `COFF` and `NOFF` variants read the same
//! (their extra numbers per vertex are ignored).

use glam::DVec3;

use super::errors::FormatDefect;
use super::polygon::triangulate_polygon;
use crate::cad::{SourceLines, TriangleSoup};

/// True when the bytes start like an OFF file.
pub(crate) fn looks_like_off(bytes: &[u8]) -> bool {
    let head = bytes.trim_ascii_start();
    ["OFF", "COFF", "NOFF", "CNOFF"].iter().any(|keyword| {
        head.strip_prefix(keyword.as_bytes())
            .is_some_and(|rest| rest.first().is_none_or(u8::is_ascii_whitespace))
    })
}

/// Parses an OFF file into a triangle soup.
pub fn parse_off(bytes: &[u8]) -> Result<TriangleSoup, FormatDefect> {
    let text = std::str::from_utf8(bytes).map_err(|_| FormatDefect::Line {
        line: 1,
        message: "not UTF-8 text".into(),
    })?;
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(index, line)| (index + 1, line.split('#').next().unwrap_or("").trim()))
        .filter(|(_, line)| !line.is_empty());
    let error = |line: usize, message: String| FormatDefect::Line { line, message };
    let (mut line, mut first) = lines
        .next()
        .ok_or_else(|| error(1, "the file is empty".into()))?;
    if let Some(rest) = ["CNOFF", "COFF", "NOFF", "OFF"]
        .iter()
        .find_map(|keyword| first.strip_prefix(keyword))
    {
        first = rest.trim();
        if first.is_empty() {
            (line, first) = lines
                .next()
                .ok_or_else(|| error(line, "no counts line after OFF".into()))?;
        }
    }
    let counts = numbers::<usize>(first, line, "count")?;
    let [vertices, faces] = [0, 1].map(|i| counts.get(i).copied());
    let (Some(vertices), Some(faces)) = (vertices, faces) else {
        return Err(error(
            line,
            "the counts line needs 'vertices faces edges'".into(),
        ));
    };
    // Each vertex and face takes a line of at least two bytes.
    if vertices.saturating_add(faces) > bytes.len() / 2 {
        return Err(error(
            line,
            format!(
                "the counts announce {vertices} vertices and {faces} faces, more than the file can hold"
            ),
        ));
    }
    let mut source_lines = SourceLines::default();
    let mut positions = Vec::with_capacity(vertices);
    for _ in 0..vertices {
        let (line, text) = lines.next().ok_or_else(|| {
            error(
                line,
                format!("the file ends before its {vertices} vertices"),
            )
        })?;
        let coordinates = numbers::<f64>(text, line, "coordinate")?;
        let [Some(x), Some(y), Some(z)] = [0, 1, 2].map(|i| coordinates.get(i).copied()) else {
            return Err(error(line, "a vertex needs x, y and z".into()));
        };
        positions.push(DVec3::new(x, y, z));
        source_lines.vertices.push(line as u32);
    }
    let mut triangles = Vec::with_capacity(faces);
    for _ in 0..faces {
        let (line, text) = lines
            .next()
            .ok_or_else(|| error(line, format!("the file ends before its {faces} faces")))?;
        let mut words = text.split_whitespace();
        let count = words
            .next()
            .and_then(|word| word.parse::<usize>().ok())
            .filter(|&count| count >= 3)
            .ok_or_else(|| {
                error(
                    line,
                    "a face starts with its vertex count, at least 3".into(),
                )
            })?;
        let corners = words
            .take(count)
            .map(|word| match word.parse::<u32>() {
                Ok(index) if (index as usize) < vertices => Ok(index),
                _ => Err(error(
                    line,
                    format!("'{word}' is not a vertex index below {vertices} (numbered from 0)"),
                )),
            })
            .collect::<Result<Vec<u32>, _>>()?;
        if corners.len() < count {
            return Err(error(
                line,
                format!("the face lists fewer than its {count} vertices"),
            ));
        }
        let corner = |k: usize| positions[corners[k] as usize];
        triangulate_polygon(count, corner, |triangle| {
            triangles.push(triangle.map(|k| corners[k]));
            source_lines.triangles.push(line as u32);
        });
    }
    if triangles.is_empty() {
        return Err(FormatDefect::Empty);
    }
    Ok(TriangleSoup::new(positions, triangles).with_lines(source_lines))
}

/// The numbers of a line.
fn numbers<T: std::str::FromStr>(
    text: &str,
    line: usize,
    what: &str,
) -> Result<Vec<T>, FormatDefect> {
    text.split_whitespace()
        .map(|word| {
            word.parse::<T>().map_err(|_| FormatDefect::Line {
                line,
                message: format!("{what} '{word}' is not a number"),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::ingest::off::*;

    #[test]
    fn a_square_of_one_quad_is_two_triangles() {
        let text = "OFF\n# a square\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3 255 0 0\n";
        assert!(looks_like_off(text.as_bytes()));
        let soup = parse_off(text.as_bytes()).expect("parses");
        assert_eq!(soup.positions.len(), 4);
        assert_eq!(soup.triangles, [[0, 1, 2], [0, 2, 3]]);
        let same_line = "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        assert_eq!(
            parse_off(same_line.as_bytes())
                .expect("parses")
                .triangles
                .len(),
            1
        );
    }

    #[test]
    fn bad_files_are_refused_with_the_line() {
        let refused = |text: &str| parse_off(text.as_bytes()).expect_err("refused").to_string();
        assert_eq!(
            refused("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
            "line 6: '3' is not a vertex index below 3 (numbered from 0)"
        );
        assert_eq!(
            refused("OFF\n3 1 0\n0 0 0\n1 zero 0\n"),
            "line 4: coordinate 'zero' is not a number"
        );
        assert!(refused("OFF\n99999999 1 0\n0 0 0\n").contains("more than the file can hold"));
        assert!(refused("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n").contains("ends before its 1 faces"));
    }
}
