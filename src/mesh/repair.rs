//! Repairs of real exports' connectivity (`--repair`), each reported as a warning that names
//! what it changed: vertices at the same point welded into one, edges shared by more than
//! two triangles and vertices joining separate fans split apart, so that every edge has at most
//! two triangles and every vertex one fan, and a non-orientable surface (a Möbius strip) cut open
//! where its orientations conflict. Positions never move.

use super::defects::Defect;
use super::validate::{
    HalfEdge, PointsNearlyEqual, breadth_first_orientation, corner, corner_fans, edge_groups,
    is_usable, manifold_pairs, orientations_agree, sorted_half_edges,
};
use crate::cad::TriangleSoup;

/// Welded vertices named one by one in the warnings; the rest are counted in one
/// ([`Defect::MoreWelded`]), since a triangle soup welds every vertex it has.
pub const NAMED_WELDS: usize = 10;

/// The soup with every vertex that lies on an earlier one (within
/// [`MESH_WELD_RATIO`](crate::geometry::tolerance::MESH_WELD_RATIO) of the bounding diagonal)
/// replaced by it in the triangles (the duplicate is then used by no triangle and dropped by
/// validation), and one [`Defect::WeldedVertex`] per duplicate for the first [`NAMED_WELDS`], one
/// [`Defect::MoreWelded`] for the others. Vertex numbers and positions do not change.
pub fn weld_duplicates(soup: &TriangleSoup) -> (TriangleSoup, Vec<Defect>) {
    let mut points = PointsNearlyEqual::new(&soup.positions);
    let mut representative: Vec<u32> = (0..soup.positions.len() as u32).collect();
    let mut warnings = Vec::new();
    for (v, slot) in representative.iter_mut().enumerate() {
        let first = points.first_at(v as u32);
        if first != v as u32 {
            *slot = first;
            warnings.push(Defect::WeldedVertex {
                vertex: v,
                into: first as usize,
            });
        }
    }
    if warnings.len() > NAMED_WELDS {
        let count = warnings.len() - NAMED_WELDS;
        warnings.truncate(NAMED_WELDS);
        warnings.push(Defect::MoreWelded { count });
    }
    let mut welded = soup.clone();
    for triangle in &mut welded.triangles {
        *triangle = triangle.map(|v| representative.get(v as usize).copied().unwrap_or(v));
    }
    for edge in &mut welded.fold_edges {
        edge.vertices = edge
            .vertices
            .map(|v| representative.get(v as usize).copied().unwrap_or(v));
    }
    (welded, warnings)
}

/// The soup with its non-manifold edges and vertices split: at an edge that more than two
/// triangles share, only the triangles that the file's texture layout continues across it stay
/// neighbours (`continued_pairs`; none without texture coordinates), and each vertex gets one
/// copy per fan of triangles that meet there (`corner_fans`; fans ordered by their lowest
/// triangle, the first keeping the vertex). Copies keep their vertex's position and file line. A
/// triangle that repeats a vertex or names a missing one is left as it is, for validation.
/// Returns the warnings, one [`Defect::SplitEdge`] per edge and one [`Defect::SplitVertex`] per
/// vertex split.
pub fn split_non_manifold(soup: &TriangleSoup) -> (TriangleSoup, Vec<Defect>) {
    let (usable, triangles) = usable_triangles(soup);
    let texture: Option<Vec<[u32; 3]>> = soup
        .texture
        .as_ref()
        .map(|texture| usable.iter().map(|&t| texture.corners[t]).collect());
    let half_edges = sorted_half_edges(&triangles);
    let shared: Vec<&[HalfEdge]> = edge_groups(&half_edges)
        .filter(|group| group.len() > 2)
        .collect();
    let (kept, fans) = kept_pairs(&triangles, &half_edges, &shared, texture.as_deref());
    let mut warnings: Vec<Defect> = shared
        .iter()
        .zip(&kept)
        .map(|(group, pairs)| Defect::SplitEdge {
            vertices: [group[0].0, group[0].1],
            faces: group.len(),
            kept: 2 * pairs.len(),
        })
        .collect();
    let (split, splits) = split_vertices_by_fan(soup, &usable, &triangles, &fans);
    warnings.extend(splits);
    (split, warnings)
}

/// The indices of the soup's usable triangles ([`is_usable`]: validation drops or refuses the
/// others), and those triangles.
fn usable_triangles(soup: &TriangleSoup) -> (Vec<usize>, Vec<[u32; 3]>) {
    let vertex_count = soup.positions.len();
    let usable: Vec<usize> = (0..soup.triangles.len())
        .filter(|&t| is_usable(soup.triangles[t], vertex_count))
        .collect();
    let triangles = usable.iter().map(|&t| soup.triangles[t]).collect();
    (usable, triangles)
}

/// The soup with each vertex given one copy per fan of its corners (`fans`, one representative
/// corner per corner of the `usable` triangles, listed in `triangles`; fans ordered by their
/// lowest triangle, the first keeping the vertex), and one [`Defect::SplitVertex`] per vertex
/// split. Copies keep their vertex's position and file line.
fn split_vertices_by_fan(
    soup: &TriangleSoup,
    usable: &[usize],
    triangles: &[[u32; 3]],
    fans: &[u32],
) -> (TriangleSoup, Vec<Defect>) {
    let vertex_count = soup.positions.len();
    let mut warnings = Vec::new();
    // Per vertex, its fans in the order of their lowest triangle, each with its corners.
    let mut fans_of_vertex: Vec<Vec<(u32, Vec<usize>)>> = vec![Vec::new(); vertex_count];
    for (corner, &fan) in fans.iter().enumerate() {
        let vertex = triangles[corner / 3][corner % 3] as usize;
        let groups = &mut fans_of_vertex[vertex];
        match groups.iter_mut().find(|(known, _)| *known == fan) {
            Some((_, corners)) => corners.push(corner),
            None => groups.push((fan, vec![corner])),
        }
    }
    let mut split = soup.clone();
    for (vertex, groups) in fans_of_vertex.iter().enumerate() {
        if groups.len() < 2 {
            continue;
        }
        warnings.push(Defect::SplitVertex {
            vertex,
            copies: groups.len(),
        });
        for (_, corners) in &groups[1..] {
            let copy = split.positions.len() as u32;
            split.positions.push(soup.positions[vertex]);
            if let Some(line) = soup.source_lines.vertex(vertex) {
                split.source_lines.vertices.push(line);
            }
            for &corner in corners {
                split.triangles[usable[corner / 3]][corner % 3] = copy;
            }
        }
    }
    (split, warnings)
}

/// The soup cut open where its orientations conflict, so that a non-orientable surface (a Möbius
/// strip) becomes orientable: each connected part is oriented breadth first from its lowest
/// triangle across its manifold edges (as validation does), the edges whose two triangles then
/// disagree stop joining them, and each vertex on them gets one copy per fan left
/// ([`Defect::SplitVertex`]). Returns one [`Defect::CutOpen`] naming the first edge and counting
/// them, or no warning and the soup as it is when its orientations agree (every orientable
/// surface). Run after [`split_non_manifold`]: edges of more than two triangles are not crossed.
pub fn cut_open_non_orientable(soup: &TriangleSoup) -> (TriangleSoup, Vec<Defect>) {
    let (usable, triangles) = usable_triangles(soup);
    let half_edges = sorted_half_edges(&triangles);
    let pairs: Vec<[HalfEdge; 2]> = manifold_pairs(&half_edges).collect();
    let (flipped, _) = breadth_first_orientation(triangles.len(), &pairs);
    let agree = |pair: &[HalfEdge; 2]| orientations_agree(pair, &flipped);
    let conflicts: Vec<[u32; 2]> = (pairs.iter())
        .filter(|pair| !agree(pair))
        .map(|[x, _]| [x.0, x.1])
        .collect();
    let Some(&first) = conflicts.first() else {
        return (soup.clone(), Vec::new());
    };
    let fans = corner_fans(&triangles, pairs.iter().copied().filter(|pair| agree(pair)));
    let (cut, splits) = split_vertices_by_fan(soup, &usable, &triangles, &fans);
    let mut warnings = vec![Defect::CutOpen {
        vertices: first,
        edges: conflicts.len(),
    }];
    warnings.extend(splits);
    (cut, warnings)
}

/// Per non-manifold edge (`shared`), the pairs of its triangles that stay neighbours, and the
/// corner fans (`corner_fans`) they make: an edge keeps its continued pairs as long as the split
/// still leaves it with at most two triangles on each copy. An edge whose triangles stay joined
/// around its ends by other ways loses its pairs, and the others are checked again.
fn kept_pairs(
    triangles: &[[u32; 3]],
    half_edges: &[HalfEdge],
    shared: &[&[HalfEdge]],
    texture: Option<&[[u32; 3]]>,
) -> (Vec<Vec<[HalfEdge; 2]>>, Vec<u32>) {
    let mut kept: Vec<Vec<[HalfEdge; 2]>> = shared
        .iter()
        .map(|group| texture.map_or_else(Vec::new, |t| continued_pairs(group, triangles, t)))
        .collect();
    loop {
        let neighbours = manifold_pairs(half_edges).chain(kept.iter().flatten().copied());
        let fans = corner_fans(triangles, neighbours);
        let mut dropped = false;
        for (group, pairs) in shared.iter().zip(&mut kept) {
            if !pairs.is_empty() && !split_apart(group, triangles, &fans) {
                pairs.clear();
                dropped = true;
            }
        }
        if !dropped {
            return (kept, fans);
        }
    }
}

/// Disjoint pairs of an edge's half-edges, running opposite ways, whose triangles give both of
/// the edge's ends the same texture point: the file's texture layout continues one triangle into
/// the other there (a garment's panel goes on across a seam that another panel is sewn onto).
fn continued_pairs(
    group: &[HalfEdge],
    triangles: &[[u32; 3]],
    texture: &[[u32; 3]],
) -> Vec<[HalfEdge; 2]> {
    let ends = |half: &HalfEdge| {
        [half.0, half.1].map(|vertex| texture.as_flattened()[corner(triangles, half, vertex)])
    };
    let mut pairs = Vec::new();
    let mut taken = vec![false; group.len()];
    for i in 0..group.len() {
        for j in i + 1..group.len() {
            let (x, y) = (&group[i], &group[j]);
            if !taken[i] && !taken[j] && x.3 != y.3 && ends(x) == ends(y) {
                taken[i] = true;
                taken[j] = true;
                pairs.push([*x, *y]);
            }
        }
    }
    pairs
}

/// True when the fans leave no more than two of an edge's triangles on any one copy of it.
fn split_apart(group: &[HalfEdge], triangles: &[[u32; 3]], fans: &[u32]) -> bool {
    let mut copies: Vec<[u32; 2]> = group
        .iter()
        .map(|half| [half.0, half.1].map(|vertex| fans[corner(triangles, half, vertex)]))
        .collect();
    copies.sort_unstable();
    copies.chunk_by(|a, b| a == b).all(|same| same.len() <= 2)
}

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3};

    use super::*;
    use crate::cad::{NO_SOURCE_FACE, TextureCorners};
    use crate::mesh::validate::{check_welded, validate};

    /// Three triangles on one edge (0-1), like three panels sewn along one seam.
    fn three_panels() -> TriangleSoup {
        let positions = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.5, 1.0, 0.0),
            DVec3::new(0.5, -1.0, 0.0),
            DVec3::new(0.5, 0.0, 1.0),
        ];
        TriangleSoup::new(positions, vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]])
    }

    /// The soup split ([`split_non_manifold`]) and its warnings, the first of which says that
    /// edge 0-1 of [`three_panels`] was split keeping `kept` of its triangles together.
    fn split_edge_keeping(soup: &TriangleSoup, kept: usize) -> (TriangleSoup, Vec<Defect>) {
        let (split, warnings) = split_non_manifold(soup);
        assert_eq!(
            warnings[0],
            Defect::SplitEdge {
                vertices: [0, 1],
                faces: 3,
                kept
            }
        );
        (split, warnings)
    }

    /// Texture points 0 to 6, one per corner as `corners` gives them.
    fn texture(corners: Vec<[u32; 3]>) -> Option<TextureCorners> {
        Some(TextureCorners {
            points: (0..7).map(|i| DVec2::new(i as f64, 0.0)).collect(),
            corners,
        })
    }

    /// A strip of `segments` quads around a circle, its ends glued with a half twist.
    fn mobius_strip(segments: u32) -> TriangleSoup {
        let positions: Vec<DVec3> = (0..segments)
            .flat_map(|i| {
                let angle = std::f64::consts::TAU * i as f64 / segments as f64;
                let twist = angle / 2.0;
                let (radial, height) = (0.3 * twist.cos(), 0.3 * twist.sin());
                [-1.0, 1.0].map(|side| {
                    let radius = 1.0 + side * radial;
                    DVec3::new(radius * angle.cos(), radius * angle.sin(), side * height)
                })
            })
            .collect();
        let mut triangles = Vec::new();
        for i in 0..segments {
            let (a, b) = (2 * i, 2 * i + 1);
            let (c, d) = if i + 1 == segments {
                (1, 0)
            } else {
                (2 * i + 2, 2 * i + 3)
            };
            triangles.extend([[a, c, b], [b, c, d]]);
        }
        TriangleSoup::new(positions, triangles)
    }

    #[test]
    fn a_mobius_strip_is_cut_open_across_and_then_validates() {
        let strip = mobius_strip(12);
        assert!(validate(&strip).is_err());
        let (cut, warnings) = cut_open_non_orientable(&strip);
        assert!(
            matches!(warnings[0], Defect::CutOpen { edges: 1, .. }),
            "{warnings:?}"
        );
        // The edge across the strip is cut: its two ends get a copy each.
        let copies = (warnings.iter())
            .filter(|w| matches!(w, Defect::SplitVertex { copies: 2, .. }))
            .count();
        assert_eq!(copies, 2, "{warnings:?}");
        assert_eq!(cut.positions.len(), strip.positions.len() + 2);
        let model = validate(&cut).expect("orientable once cut").components;
        assert_eq!(model.len(), 1);
        assert_eq!(model[0].triangle_count(), strip.triangles.len());
    }

    #[test]
    fn an_orientable_surface_is_not_cut() {
        let mut strip = mobius_strip(12);
        // Without the twist where the ends meet, the band is an annulus: orientable.
        let last = strip.triangles.len() - 2;
        strip.triangles[last] = [22, 0, 23];
        strip.triangles[last + 1] = [23, 0, 1];
        let (cut, warnings) = cut_open_non_orientable(&strip);
        assert!(warnings.is_empty(), "{warnings:?}");
        assert_eq!(cut.triangles, strip.triangles);
        assert!(validate(&cut).is_ok());
    }

    #[test]
    fn a_non_manifold_edge_is_split_and_the_mesh_then_validates() {
        let soup = three_panels();
        assert!(validate(&soup).is_err());
        let (split, warnings) = split_edge_keeping(&soup, 0);
        assert!(warnings.iter().all(Defect::is_repaired));
        let validated = validate(&split).expect("valid after the split");
        assert_eq!(validated.components.len(), 3, "three separate panels");
        for (v, p) in split
            .positions
            .iter()
            .enumerate()
            .skip(soup.positions.len())
        {
            assert!(soup.positions[..2].contains(p), "copy {v} of an edge end");
        }
    }

    #[test]
    fn the_two_triangles_the_texture_continues_across_a_split_edge_stay_neighbours() {
        let mut soup = three_panels();
        // The first two panels are one chart across the edge; the third is a chart of its own.
        soup.texture = texture(vec![[0, 1, 2], [1, 0, 3], [4, 5, 6]]);
        let (split, _) = split_edge_keeping(&soup, 2);
        let validated = validate(&split).expect("valid after the split");
        let mut sizes: Vec<usize> = validated
            .components
            .iter()
            .map(|c| c.triangles().len())
            .collect();
        sizes.sort_unstable();
        assert_eq!(sizes, vec![1, 2], "the chart's two panels stay one piece");
    }

    #[test]
    fn a_continued_pair_is_not_kept_where_the_split_would_leave_the_edge_shared_by_three() {
        let mut soup = three_panels();
        // The third panel is joined to the first around both ends of the edge by two more
        // triangles, so the edge keeps three triangles unless the continued pair is parted.
        soup.triangles.extend([[0, 4, 2], [1, 2, 4]]);
        soup.face_sources.extend([NO_SOURCE_FACE; 2]);
        soup.texture = texture(vec![[0, 1, 2], [1, 0, 3], [4, 5, 6], [0, 4, 2], [1, 2, 4]]);
        let (split, _) = split_edge_keeping(&soup, 0);
        assert!(
            validate(&split).is_ok(),
            "every edge has at most two triangles"
        );
    }

    #[test]
    fn a_bow_tie_vertex_gets_one_copy_per_fan() {
        let positions = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(-1.0, 0.0, 0.0),
            DVec3::new(-1.0, -1.0, 0.0),
        ];
        let soup = TriangleSoup::new(positions, vec![[0, 1, 2], [0, 3, 4]]);
        let (split, warnings) = split_non_manifold(&soup);
        assert_eq!(
            warnings,
            vec![Defect::SplitVertex {
                vertex: 0,
                copies: 2
            }]
        );
        assert_eq!(split.triangles, vec![[0, 1, 2], [5, 3, 4]]);
        assert_eq!(validate(&split).expect("valid").components.len(), 2);
    }

    #[test]
    fn a_triangle_naming_a_missing_vertex_is_left_for_validation_to_refuse() {
        let mut soup = three_panels();
        soup.triangles.push([0, 1, 99]);
        let (split, _) = split_non_manifold(&soup);
        assert_eq!(split.triangles[3], [0, 1, 99], "left as it was");
        assert!(
            validate(&split).is_err(),
            "the missing vertex is still refused"
        );
    }

    /// Two triangles with vertices of their own, one corner off its twin by rounding noise
    /// (1e-9 of the size): refused as a soup, welded by `--repair`.
    #[test]
    fn duplicates_are_welded_into_the_first_vertex_at_their_point() {
        let positions = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(1.0 + 1e-9, 0.0, -1e-9),
            DVec3::new(1.0, 1.0, -0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        let soup = TriangleSoup::new(positions, vec![[0, 1, 2], [3, 4, 5]]);
        let refused = check_welded(&soup).expect_err("a triangle soup is refused");
        assert_eq!(
            refused.defects,
            vec![Defect::Unwelded {
                isolated: 2,
                triangles: 2,
                first: 0
            }]
        );
        let (welded, warnings) = weld_duplicates(&soup);
        assert_eq!(welded.triangles, vec![[0, 1, 2], [1, 4, 2]]);
        assert_eq!(
            warnings,
            vec![
                Defect::WeldedVertex { vertex: 3, into: 1 },
                Defect::WeldedVertex { vertex: 5, into: 2 }
            ]
        );
        assert_eq!(validate(&welded).expect("valid").components.len(), 1);
        let mut apart = soup.clone();
        apart.positions[3].x = 1.0 + 1e-5;
        assert_eq!(
            weld_duplicates(&apart).0.triangles,
            vec![[0, 1, 2], [3, 4, 2]]
        );
    }

    /// A strip of unwelded triangles, each with vertices of its own: the first welds are named,
    /// the rest counted in one warning, and the strip validates as one part.
    #[test]
    fn a_soup_names_its_first_welds_and_counts_the_rest() {
        let strip = 20;
        let corner = |i: u32, top: bool| DVec3::new(f64::from(i), f64::from(u8::from(top)), 0.0);
        let mut positions = Vec::new();
        let mut triangles = Vec::new();
        for i in 0..strip {
            let base = positions.len() as u32;
            positions.extend([corner(i, false), corner(i + 1, false), corner(i, true)]);
            positions.extend([corner(i + 1, false), corner(i + 1, true), corner(i, true)]);
            triangles.extend([[base, base + 1, base + 2], [base + 3, base + 4, base + 5]]);
        }
        let soup = TriangleSoup::new(positions, triangles);
        let (welded, warnings) = weld_duplicates(&soup);
        // 6 × 20 corners at 2 × 21 points.
        let duplicates = 6 * strip as usize - 2 * (strip as usize + 1);
        assert_eq!(warnings.len(), NAMED_WELDS + 1);
        assert_eq!(
            warnings[NAMED_WELDS],
            Defect::MoreWelded {
                count: duplicates - NAMED_WELDS
            }
        );
        assert!(
            warnings[..NAMED_WELDS]
                .iter()
                .all(|w| matches!(w, Defect::WeldedVertex { .. }))
        );
        assert_eq!(validate(&welded).expect("valid").components.len(), 1);
    }
}
