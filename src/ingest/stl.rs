//! STL, ASCII and binary. STL stores every triangle with its own three corners, so corners
//! closer than [`STL_WELD_TOLERANCE`] (relative to the bounding-box diagonal) are welded into
//! one vertex, the first one seen keeping its position.

use glam::DVec3;

use super::errors::FormatDefect;
use super::text::without_byte_order_mark;
use crate::cad::{SourceLines, SourceUnit, TriangleSoup};
use crate::geometry::tolerance::STL_WELD_TOLERANCE;
use crate::geometry::weld::{PointWelder, finite_bounds};

const BINARY_HEADER: usize = 80;
const BINARY_TRIANGLE: usize = 50;

/// True when the bytes are a binary STL (size matches the count) or start like an ASCII one.
pub(crate) fn looks_like_stl(bytes: &[u8]) -> bool {
    is_binary(bytes) || starts_like_ascii(bytes)
}

/// Whether the bytes start (after white space and a UTF-8 byte-order mark) with `solid`, in any
/// case.
fn starts_like_ascii(bytes: &[u8]) -> bool {
    let head = without_byte_order_mark(bytes).trim_ascii_start();
    head.get(..5)
        .is_some_and(|word| word.eq_ignore_ascii_case(b"solid"))
}

fn binary_count(bytes: &[u8]) -> Option<usize> {
    let count = bytes.get(BINARY_HEADER..BINARY_HEADER + 4)?;
    Some(u32::from_le_bytes(count.try_into().ok()?) as usize)
}

fn is_binary(bytes: &[u8]) -> bool {
    binary_count(bytes).is_some_and(|n| bytes.len() == BINARY_HEADER + 4 + n * BINARY_TRIANGLE)
}

/// Parses an STL file and welds its corners.
pub fn parse_stl(bytes: &[u8]) -> Result<TriangleSoup, FormatDefect> {
    let (corners, places, unit) = if is_binary(bytes) {
        let corners = parse_binary(bytes)?;
        let facets = (1..=corners.len() as u32).map(|f| (f, [f; 3])).collect();
        (corners, facets, SourceUnit::Facet)
    } else if starts_like_ascii(bytes) {
        let (corners, lines) = parse_ascii(without_byte_order_mark(bytes))?;
        (corners, lines, SourceUnit::Line)
    } else {
        let message = match binary_count(bytes) {
            Some(n) => format!(
                "not an ASCII STL, and as binary STL its header announces {n} triangles ({} bytes) but the file has {} bytes",
                BINARY_HEADER + 4 + n * BINARY_TRIANGLE,
                bytes.len()
            ),
            None => "not an STL file: too short for a binary header and not ASCII 'solid'".into(),
        };
        return Err(FormatDefect::Binary(message));
    };
    if corners.is_empty() {
        return Err(FormatDefect::Empty);
    }
    let mut soup = weld(&corners, &places);
    soup.source_lines.unit = unit;
    Ok(soup)
}

/// Where an STL's facet is: in an ASCII file its `facet` line (or its first `vertex` line when it
/// has none) and the line of each of its three corners; in a binary file its facet number, for
/// itself and each corner.
type FacetPlaces = (u32, [u32; 3]);

fn parse_binary(bytes: &[u8]) -> Result<Vec<[DVec3; 3]>, FormatDefect> {
    let count = binary_count(bytes).unwrap_or(0);
    let mut triangles = Vec::with_capacity(count);
    for t in 0..count {
        let record = &bytes[BINARY_HEADER + 4 + t * BINARY_TRIANGLE..][..BINARY_TRIANGLE];
        let read = |k: usize| -> f64 {
            let at = 12 + 4 * k;
            f32::from_le_bytes([record[at], record[at + 1], record[at + 2], record[at + 3]]) as f64
        };
        triangles
            .push([0, 1, 2].map(|c| DVec3::new(read(3 * c), read(3 * c + 1), read(3 * c + 2))));
    }
    Ok(triangles)
}

/// An ASCII STL's triangles, and the lines each was written on.
fn parse_ascii(bytes: &[u8]) -> Result<(Vec<[DVec3; 3]>, Vec<FacetPlaces>), FormatDefect> {
    let text = std::str::from_utf8(bytes)
        .map_err(|_| FormatDefect::Binary("ASCII STL holds non-UTF-8 bytes".into()))?;
    let mut triangles = Vec::new();
    let mut lines_of_triangles = Vec::new();
    let mut corners: Vec<DVec3> = Vec::with_capacity(3);
    let mut corner_lines: Vec<u32> = Vec::with_capacity(3);
    let mut facet_line = None;
    let mut ended = false;
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        let mut words = raw.split_whitespace();
        match words.next().map(str::to_ascii_lowercase).as_deref() {
            Some("vertex") => {
                let mut coordinate = || -> Result<f64, FormatDefect> {
                    let word = words.next().unwrap_or("");
                    word.parse().map_err(|_| FormatDefect::Line {
                        line,
                        message: format!("vertex coordinate '{word}' is not a number"),
                    })
                };
                corners.push(DVec3::new(coordinate()?, coordinate()?, coordinate()?));
                corner_lines.push(line as u32);
            }
            Some("facet") => facet_line = Some(line as u32),
            Some("endloop") => {
                let corners_found = std::mem::take(&mut corners);
                let triangle: [DVec3; 3] =
                    corners_found
                        .try_into()
                        .map_err(|found: Vec<DVec3>| FormatDefect::Line {
                            line,
                            message: format!("a facet needs 3 vertices, found {}", found.len()),
                        })?;
                let corner_lines = std::mem::take(&mut corner_lines);
                let facet = facet_line.take().unwrap_or(corner_lines[0]);
                lines_of_triangles
                    .push((facet, [corner_lines[0], corner_lines[1], corner_lines[2]]));
                triangles.push(triangle);
            }
            Some("endsolid") => ended = true,
            _ => {}
        }
    }
    let lines = text.lines().count();
    if !corners.is_empty() {
        return Err(FormatDefect::Line {
            line: lines,
            message: "the file ends inside a facet (no 'endloop'): it is truncated".into(),
        });
    }
    if !ended && !triangles.is_empty() {
        return Err(FormatDefect::Line {
            line: lines,
            message: "the ASCII STL has no 'endsolid' line: it is truncated".into(),
        });
    }
    Ok((triangles, lines_of_triangles))
}

/// Welds corners within the tolerance on a hash grid whose cell is the tolerance; each triangle
/// keeps its facet's place in the file (`places`) and each vertex the place of the first corner
/// welded into it, for messages.
fn weld(corners: &[[DVec3; 3]], places: &[FacetPlaces]) -> TriangleSoup {
    let (origin, diagonal) = finite_bounds(corners.iter().flatten())
        .map_or((DVec3::ZERO, 0.0), |(min, max)| (min, (max - min).length()));
    let tolerance = (STL_WELD_TOLERANCE * diagonal).max(f64::MIN_POSITIVE);
    let mut welder = PointWelder::new(origin, tolerance);
    let mut source_lines = SourceLines::default();
    let mut triangles = Vec::with_capacity(corners.len());
    for (t, triangle) in corners.iter().enumerate() {
        let welded = triangle.map(|p| welder.insert(p));
        let (facet, corner_places) = places[t];
        source_lines.triangles.push(facet);
        for (vertex, place) in welded.into_iter().zip(corner_places) {
            if vertex as usize == source_lines.vertices.len() {
                source_lines.vertices.push(place);
            }
        }
        triangles.push(welded);
    }
    TriangleSoup::new(welder.into_points(), triangles).with_lines(source_lines)
}

#[cfg(test)]
mod tests {
    use crate::ingest::stl::*;

    /// An ASCII STL's triangles keep their facet's line, and each welded vertex the line of the
    /// first corner at its point, so that a defect can say where it is in the file.
    #[test]
    fn an_ascii_stl_keeps_the_lines_of_its_facets_and_first_corners() {
        let text = "solid two\n\
            facet normal 0 0 1\n outer loop\n\
            vertex 0 0 0\n vertex 1 0 0\n vertex 0 1 0\n\
            endloop\n endfacet\n\
            facet normal 0 0 1\n outer loop\n\
            vertex 1 0 0\n vertex 1 1 0\n vertex 0 1 0\n\
            endloop\n endfacet\n\
            endsolid two\n";
        let soup = parse_stl(text.as_bytes()).expect("valid STL");
        assert_eq!(soup.triangles, [[0, 1, 2], [1, 3, 2]]);
        assert_eq!(soup.source_lines.triangles, [2, 9]);
        assert_eq!(soup.source_lines.vertices, [4, 5, 6, 12]);
        assert_eq!(soup.source_lines.unit, SourceUnit::Line);
    }

    /// A binary STL has no lines: its triangles keep their facet number, and each welded vertex
    /// the facet of the first corner at its point.
    #[test]
    fn a_binary_stl_keeps_the_facets_of_its_triangles_and_first_corners() {
        let binary = binary_stl(&[
            [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
        ]);
        let soup = parse_stl(&binary).expect("valid STL");
        assert_eq!(soup.triangles, [[0, 1, 2], [1, 3, 2]]);
        assert_eq!(soup.source_lines.triangles, [1, 2]);
        assert_eq!(soup.source_lines.vertices, [1, 1, 1, 2]);
        assert_eq!(soup.source_lines.unit, SourceUnit::Facet);
    }

    fn binary_stl(triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
        let mut bytes = vec![0u8; BINARY_HEADER];
        bytes.extend((triangles.len() as u32).to_le_bytes());
        for t in triangles {
            bytes.extend([0u8; 12]);
            for c in t {
                for x in c {
                    bytes.extend(x.to_le_bytes());
                }
            }
            bytes.extend([0u8; 2]);
        }
        bytes
    }

    #[test]
    fn binary_corners_are_welded() {
        let bytes = binary_stl(&[
            [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.]],
            [[0., 0., 0.], [1., 1., 0.], [0., 1., 0.]],
        ]);
        let soup = parse_stl(&bytes).expect("valid binary stl");
        assert_eq!(soup.positions.len(), 4);
        assert_eq!(soup.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn ascii_is_read_and_truncated_binary_is_refused() {
        let text = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
        assert_eq!(
            parse_stl(text.as_bytes()).expect("ascii").triangles.len(),
            1
        );
        for cut in [
            text.len() - 14,
            text.find("vertex 0 1 0").expect("third corner"),
        ] {
            let error = parse_stl(&text.as_bytes()[..cut]).expect_err("truncated ascii");
            assert!(error.to_string().contains("truncated"), "{error}");
        }
        let mut bytes = binary_stl(&[[[0., 0., 0.], [1., 0., 0.], [1., 1., 0.]]]);
        bytes.truncate(100);
        assert!(matches!(parse_stl(&bytes), Err(FormatDefect::Binary(_))));
    }
}
