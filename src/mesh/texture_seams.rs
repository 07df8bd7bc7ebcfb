//! Seams from a mesh's texture layout (`--seams from-uv`): a garment exported with its sewing
//! pattern as texture coordinates has one texture chart per pattern piece. Every vertex is split
//! into one copy per texture point its corners use, so the soup falls apart along the chart
//! boundaries; validation then makes one part per piece.

use std::collections::{BTreeMap, BTreeSet};

use glam::DVec2;
use serde::{Deserialize, Serialize};

use crate::cad::{SourceLines, TextureCorners, TriangleSoup};

/// Where a mesh file's pieces and seams come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum SeamSource {
    /// The whole connected mesh is one part; the cut stage lays its seams and cuts it along
    /// crest lines, and a part still over tolerance after them (or one with handles) is cut into
    /// pieces as `pieces` does.
    #[default]
    Auto,
    /// As `auto`, but the part stays whole: over tolerance after its cuts, it is rejected.
    Whole,
    /// Every chart of the file's texture layout (OBJ `vt`) is one part: its boundaries are the
    /// seams, as a garment's sewing pattern has them.
    FromUv,
    /// The cut stage makes no crest-line cut: a part that does not flatten within tolerance
    /// is cut into pieces by plane sections until each does (docs/cutting.md, "Pieces").
    Pieces,
}

impl SeamSource {
    /// True for the default.
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }
}

/// The soup cut apart along the boundaries of its texture charts, or `None` when it has no
/// texture coordinates. Each vertex of the result is one (vertex, texture point) pair of the
/// input, in that order; its texture point is `texture.points[v]` (the result's texture corners
/// are its triangles).
pub fn split_at_texture_seams(soup: &TriangleSoup) -> Option<TriangleSoup> {
    let texture = soup.texture.as_ref()?;
    let pairs: BTreeSet<(u32, u32)> = corner_pairs(soup, texture).collect();
    let index: BTreeMap<(u32, u32), u32> = pairs
        .iter()
        .enumerate()
        .map(|(i, &pair)| (pair, i as u32))
        .collect();
    let triangles: Vec<[u32; 3]> = soup
        .triangles
        .iter()
        .zip(&texture.corners)
        .map(|(vertices, points)| [0, 1, 2].map(|k| index[&(vertices[k], points[k])]))
        .collect();
    let original: Vec<u32> = pairs.iter().map(|&(vertex, _)| vertex).collect();
    let points: Vec<DVec2> = pairs
        .iter()
        .map(|&(_, point)| {
            texture
                .points
                .get(point as usize)
                .copied()
                .unwrap_or(DVec2::NAN)
        })
        .collect();
    Some(TriangleSoup {
        positions: original
            .iter()
            .map(|&v| soup.positions.get(v as usize).copied().unwrap_or_default())
            .collect(),
        // Mesh files, the only soups with texture points, have no fold lines.
        fold_edges: Vec::new(),
        face_sources: soup.face_sources.clone(),
        source_lines: SourceLines {
            vertices: original
                .iter()
                .filter_map(|&v| soup.source_lines.vertex(v as usize))
                .collect(),
            triangles: soup.source_lines.triangles.clone(),
            unit: soup.source_lines.unit,
        },
        texture: Some(TextureCorners {
            points,
            corners: triangles.clone(),
        }),
        triangles,
    })
}

/// Every triangle corner's (vertex, texture point).
fn corner_pairs<'a>(
    soup: &'a TriangleSoup,
    texture: &'a TextureCorners,
) -> impl Iterator<Item = (u32, u32)> + 'a {
    soup.triangles
        .iter()
        .zip(&texture.corners)
        .flat_map(|(vertices, points)| (0..3).map(move |k| (vertices[k], points[k])))
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::mesh::validate;

    /// A unit square of two triangles whose texture layout puts each triangle in its own chart
    /// (the diagonal is a seam), plus a third triangle sharing the first one's chart.
    fn two_chart_soup() -> TriangleSoup {
        let positions = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(1.0, -1.0, 0.0),
        ];
        let triangles = vec![[0, 1, 2], [0, 2, 3], [0, 4, 1]];
        let texture = TextureCorners {
            points: (0..8)
                .map(|i| DVec2::new(i as f64, 0.5 * i as f64))
                .collect(),
            corners: vec![[0, 1, 2], [3, 4, 5], [0, 6, 1]],
        };
        TriangleSoup::new(positions, triangles).with_texture(texture)
    }

    #[test]
    fn charts_become_components_and_vertices_keep_their_texture_points() {
        let soup = two_chart_soup();
        let split = split_at_texture_seams(&soup).expect("textured");
        // Vertices 0 and 2 are in both charts: 5 + 2 vertices.
        assert_eq!(split.positions.len(), 7);
        let texture = split.texture.as_ref().expect("texture kept");
        assert_eq!(texture.corners, split.triangles);
        for (t, split_triangle) in split.triangles.iter().enumerate() {
            for (k, &v) in split_triangle.iter().enumerate() {
                let v = v as usize;
                let input = soup.triangles[t][k] as usize;
                assert_eq!(split.positions[v], soup.positions[input]);
                let point = soup.texture.as_ref().unwrap().corners[t][k] as usize;
                assert_eq!(
                    texture.points[v],
                    soup.texture.as_ref().unwrap().points[point]
                );
            }
        }
        let components = validate(&split).expect("valid").components;
        let sizes: Vec<usize> = components.iter().map(|m| m.triangle_count()).collect();
        assert_eq!(sizes, vec![2, 1]);
    }

    #[test]
    fn a_soup_without_texture_is_not_split() {
        let mut soup = two_chart_soup();
        soup.texture = None;
        assert_eq!(split_at_texture_seams(&soup), None);
    }
}
