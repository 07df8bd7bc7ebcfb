//! The defects a mesh check finds, each naming the element (vertex or triangle index, 0-based
//! here; printed 1-based, in the file's order, as OBJ numbers its vertices), and whether it was
//! repaired.

use std::fmt;

use crate::cad::{SourceLines, SourceUnit};

/// Largest coordinate magnitude accepted, in the mesh's units (1e9 mm is 1,000 km): beyond it a
/// coordinate is a unit or exporter error, and squared lengths lose their precision.
pub const MAXIMUM_COORDINATE: f64 = 1e9;

/// One defect of an input mesh.
#[derive(Debug, Clone, PartialEq)]
pub enum Defect {
    /// The mesh has no triangles at all.
    NoTriangles,
    /// A vertex has a NaN or infinite coordinate.
    NonFiniteVertex {
        /// Vertex index.
        vertex: usize,
    },
    /// A vertex has a coordinate larger in magnitude than
    /// [`MAXIMUM_COORDINATE`] (a unit or exporter error).
    TooLargeVertex {
        /// Vertex index.
        vertex: usize,
        /// The largest coordinate magnitude of the vertex.
        value: f64,
    },
    /// A triangle references a vertex that does not exist.
    IndexOutOfRange {
        /// Triangle index.
        triangle: usize,
        /// The offending vertex index.
        index: u32,
        /// Number of vertices in the mesh.
        vertex_count: usize,
    },
    /// A triangle uses the same vertex twice (dropped, with a warning).
    RepeatedVertex {
        /// Triangle index.
        triangle: usize,
    },
    /// A triangle with three distinct vertices but (nearly) no area.
    ZeroArea {
        /// Triangle index.
        triangle: usize,
        /// Its area in model units squared.
        area: f64,
    },
    /// A triangle with the same three vertices as an earlier one: a duplicate face (its edges
    /// would each be shared by three triangles; `--repair` drops it).
    RepeatedTriangle {
        /// Triangle index.
        triangle: usize,
        /// The earlier triangle it repeats.
        of: usize,
    },
    /// An edge shared by more than two triangles.
    NonManifoldEdge {
        /// The edge's vertices.
        vertices: [u32; 2],
        /// How many triangles share it.
        faces: usize,
    },
    /// A vertex whose triangles form several fans touching only at the vertex (a bow-tie).
    NonManifoldVertex {
        /// Vertex index.
        vertex: usize,
        /// Number of separate fans.
        fans: usize,
    },
    /// A Möbius-like surface whose triangles cannot all be oriented the same way.
    NonOrientable {
        /// An edge where the orientations conflict.
        vertices: [u32; 2],
    },
    /// Triangles whose orientation disagreed with their neighbours (reoriented, with a warning).
    Reoriented {
        /// How many triangles were flipped.
        count: usize,
    },
    /// Most triangles share no edge with another though their corners lie on other triangles'
    /// vertices: a file that gives each triangle vertices of its own (as STL converters write
    /// them), which would otherwise come out as one part per triangle.
    Unwelded {
        /// How many triangles are so.
        isolated: usize,
        /// How many triangles the mesh has.
        triangles: usize,
        /// The first of them.
        first: usize,
    },
    /// Vertices no triangle uses (dropped, with a warning).
    UnreferencedVertices {
        /// How many.
        count: usize,
        /// The first one.
        first: usize,
    },
    /// A vertex at the same point as an earlier one, welded into it (`--repair`).
    WeldedVertex {
        /// Vertex index.
        vertex: usize,
        /// The earlier vertex it was welded into.
        into: usize,
    },
    /// More vertices welded than are named one by one ([`Defect::WeldedVertex`]), `--repair`.
    MoreWelded {
        /// How many.
        count: usize,
    },
    /// An edge shared by more than two triangles, split apart (`--repair`).
    SplitEdge {
        /// The edge's vertices.
        vertices: [u32; 2],
        /// How many triangles shared it.
        faces: usize,
        /// How many of them stay neighbours in pairs, the file's texture layout continuing one
        /// into the other across the edge.
        kept: usize,
    },
    /// A vertex joining several fans of triangles, given one copy per fan (`--repair`).
    SplitVertex {
        /// Vertex index.
        vertex: usize,
        /// Number of copies (fans).
        copies: usize,
    },
    /// A non-orientable surface (a Möbius strip) cut open along the edges where its
    /// orientations conflicted (`--repair`).
    CutOpen {
        /// The first edge cut.
        vertices: [u32; 2],
        /// How many edges were cut.
        edges: usize,
    },
    /// A triangle with the same three vertices as an earlier one, dropped (`--repair`).
    DuplicateTriangle {
        /// Triangle index.
        triangle: usize,
        /// The earlier triangle.
        of: usize,
    },
    /// A zero-area triangle whose third vertex lies on its longest edge, that edge flipped with
    /// the triangle across it (`--repair`).
    FlippedEdge {
        /// Triangle index.
        triangle: usize,
        /// The edge's vertices.
        vertices: [u32; 2],
    },
    /// A zero-area triangle whose longest edge is on the boundary, dropped (`--repair`).
    DroppedSliver {
        /// Triangle index.
        triangle: usize,
    },
    /// A zero-area triangle whose shortest edge was collapsed into its lower-numbered end
    /// (`--repair`).
    CollapsedEdge {
        /// Triangle index.
        triangle: usize,
        /// The edge's vertices.
        vertices: [u32; 2],
    },
}

impl Defect {
    /// True for defects that were repaired (a warning), false for those that stop the run.
    pub fn is_repaired(&self) -> bool {
        matches!(
            self,
            Defect::RepeatedVertex { .. }
                | Defect::Reoriented { .. }
                | Defect::UnreferencedVertices { .. }
                | Defect::WeldedVertex { .. }
                | Defect::MoreWelded { .. }
                | Defect::SplitEdge { .. }
                | Defect::SplitVertex { .. }
                | Defect::CutOpen { .. }
                | Defect::DuplicateTriangle { .. }
                | Defect::FlippedEdge { .. }
                | Defect::DroppedSliver { .. }
                | Defect::CollapsedEdge { .. }
        )
    }
}

impl Defect {
    /// The defect with the file's line of its vertex or triangle, where `lines` knows it:
    /// `triangle 5 has zero area (...) [line 12]`; in a binary STL its facet (`[facet 7]`; the
    /// two ends of an edge first seen in one facet name it once).
    pub fn located(&self, lines: &SourceLines) -> String {
        let vertex_lines = |vertices: &[usize]| -> Option<String> {
            let mut found: Vec<u32> = vertices
                .iter()
                .map(|&v| lines.vertex(v))
                .collect::<Option<_>>()?;
            found.dedup();
            let found: Vec<String> = found.iter().map(u32::to_string).collect();
            Some(found.join(" and "))
        };
        let line = match *self {
            Defect::NonFiniteVertex { vertex }
            | Defect::TooLargeVertex { vertex, .. }
            | Defect::NonManifoldVertex { vertex, .. }
            | Defect::SplitVertex { vertex, .. }
            | Defect::UnreferencedVertices { first: vertex, .. } => vertex_lines(&[vertex]),
            Defect::WeldedVertex { vertex, into } => vertex_lines(&[vertex, into]),
            Defect::IndexOutOfRange { triangle, .. }
            | Defect::RepeatedVertex { triangle }
            | Defect::ZeroArea { triangle, .. }
            | Defect::Unwelded {
                first: triangle, ..
            }
            | Defect::DuplicateTriangle { triangle, .. }
            | Defect::RepeatedTriangle { triangle, .. }
            | Defect::FlippedEdge { triangle, .. }
            | Defect::DroppedSliver { triangle }
            | Defect::CollapsedEdge { triangle, .. } => {
                lines.triangle(triangle).map(|line| line.to_string())
            }
            Defect::NonManifoldEdge {
                vertices: [a, b], ..
            }
            | Defect::SplitEdge {
                vertices: [a, b], ..
            }
            | Defect::NonOrientable { vertices: [a, b] }
            | Defect::CutOpen {
                vertices: [a, b], ..
            } => vertex_lines(&[a as usize, b as usize]),
            Defect::NoTriangles | Defect::Reoriented { .. } | Defect::MoreWelded { .. } => None,
        };
        let unit = match lines.unit {
            SourceUnit::Line => "line",
            SourceUnit::Facet => "facet",
        };
        match line {
            Some(line) if line.contains(' ') => format!("{self} [{unit}s {line}]"),
            Some(line) => format!("{self} [{unit} {line}]"),
            None => self.to_string(),
        }
    }
}

impl fmt::Display for Defect {
    /// Vertices and triangles are numbered from 1, as in the file.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let n = |index: usize| index + 1;
        match self {
            Defect::NoTriangles => write!(f, "the mesh has no triangles"),
            Defect::NonFiniteVertex { vertex } => {
                write!(f, "vertex {} has a NaN or infinite coordinate", n(*vertex))
            }
            Defect::TooLargeVertex { vertex, value } => write!(
                f,
                "vertex {} has a coordinate too large ({value:e}, above {:e}): check the \
                 file's units and the exporter",
                n(*vertex),
                MAXIMUM_COORDINATE
            ),
            Defect::IndexOutOfRange {
                triangle,
                index,
                vertex_count,
            } => write!(
                f,
                "triangle {} references vertex {}, but there are only {vertex_count} vertices",
                n(*triangle),
                n(*index as usize)
            ),
            Defect::RepeatedVertex { triangle } => {
                write!(
                    f,
                    "triangle {} uses the same vertex twice (dropped)",
                    n(*triangle)
                )
            }
            Defect::ZeroArea { triangle, area } => write!(
                f,
                "triangle {} has zero area ({area:.3e}): its vertices are collinear; \
                 --repair flips or collapses it where it can",
                n(*triangle)
            ),
            Defect::RepeatedTriangle { triangle, of } => write!(
                f,
                "triangle {} has the same three vertices as triangle {} (a duplicate face)",
                n(*triangle),
                n(*of)
            ),
            Defect::NonManifoldEdge {
                vertices: [a, b],
                faces,
            } => write!(
                f,
                "edge {}-{} is shared by {faces} triangles (non-manifold; at most 2 allowed)",
                n(*a as usize),
                n(*b as usize)
            ),
            Defect::NonManifoldVertex { vertex, fans } => write!(
                f,
                "vertex {} joins {fans} separate fans of triangles (non-manifold vertex)",
                n(*vertex)
            ),
            Defect::NonOrientable { vertices: [a, b] } => write!(
                f,
                "the surface is not orientable (orientations conflict at edge {}-{})",
                n(*a as usize),
                n(*b as usize)
            ),
            Defect::Reoriented { count } => {
                write!(
                    f,
                    "{count} triangles had the opposite orientation and were flipped"
                )
            }
            Defect::Unwelded {
                isolated,
                triangles,
                first,
            } => write!(
                f,
                "{isolated} of the {triangles} triangles (first: {}) share no edge with another \
                 though their corners lie on other triangles' vertices: the file gives each \
                 triangle vertices of its own; --repair welds vertices at the same point",
                n(*first)
            ),
            Defect::UnreferencedVertices { count, first } => {
                write!(
                    f,
                    "{count} vertices are used by no triangle (first: {}); dropped",
                    n(*first)
                )
            }
            Defect::WeldedVertex { vertex, into } => write!(
                f,
                "vertex {} lies on vertex {}: welded into it (--repair)",
                n(*vertex),
                n(*into)
            ),
            Defect::MoreWelded { count } => write!(
                f,
                "{count} more vertices lay on earlier vertices: welded into them (--repair)"
            ),
            Defect::SplitEdge {
                vertices: [a, b],
                faces,
                kept: 0,
            } => write!(
                f,
                "edge {}-{} was shared by {faces} triangles: split apart (--repair)",
                n(*a as usize),
                n(*b as usize)
            ),
            Defect::SplitEdge {
                vertices: [a, b],
                faces,
                kept,
            } => write!(
                f,
                "edge {}-{} was shared by {faces} triangles: split apart, keeping the {kept} \
                 that the texture layout (vt) continues across it together in pairs (--repair)",
                n(*a as usize),
                n(*b as usize)
            ),
            Defect::SplitVertex { vertex, copies } => write!(
                f,
                "vertex {} joined {copies} separate fans of triangles: one copy per fan \
                 (--repair)",
                n(*vertex)
            ),
            Defect::CutOpen {
                vertices: [a, b],
                edges,
            } => write!(
                f,
                "the surface was not orientable (a Möbius strip): cut open along {edges} edge(s) \
                 where its orientations conflicted, from edge {}-{} (--repair)",
                n(*a as usize),
                n(*b as usize)
            ),
            Defect::DuplicateTriangle { triangle, of } => write!(
                f,
                "triangle {} repeats triangle {}: dropped (--repair)",
                n(*triangle),
                n(*of)
            ),
            Defect::FlippedEdge {
                triangle,
                vertices: [a, b],
            } => write!(
                f,
                "triangle {} had zero area (its third vertex on its edge {}-{}): that edge \
                 flipped (--repair)",
                n(*triangle),
                n(*a as usize),
                n(*b as usize)
            ),
            Defect::DroppedSliver { triangle } => write!(
                f,
                "triangle {} had zero area along the boundary: dropped (--repair)",
                n(*triangle)
            ),
            Defect::CollapsedEdge {
                triangle,
                vertices: [a, b],
            } => write!(
                f,
                "triangle {} had zero area: its shortest edge {}-{} collapsed (--repair)",
                n(*triangle),
                n(*a as usize),
                n(*b as usize)
            ),
        }
    }
}

/// The defects that stop a mesh from being used, all of them, with the lines of the file they
/// are on where it has lines.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshDefects {
    /// The defects.
    pub defects: Vec<Defect>,
    /// The file's lines of the mesh's vertices and triangles.
    pub lines: SourceLines,
}

impl fmt::Display for MeshDefects {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        const SHOWN: usize = 20;
        write!(f, "{} defect(s)", self.defects.len())?;
        for defect in self.defects.iter().take(SHOWN) {
            write!(f, "\n  - {}", defect.located(&self.lines))?;
        }
        if self.defects.len() > SHOWN {
            write!(f, "\n  - ... and {} more", self.defects.len() - SHOWN)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A defect names the lines of a text file, or a binary STL's facets; an edge whose two ends
    /// were first seen in one facet names that facet once.
    #[test]
    fn a_defect_names_the_lines_or_facets_it_is_at() {
        let edge = Defect::NonManifoldEdge {
            vertices: [0, 1],
            faces: 3,
        };
        let message = "edge 1-2 is shared by 3 triangles (non-manifold; at most 2 allowed)";
        let lines = SourceLines {
            vertices: vec![4, 5],
            triangles: vec![2],
            unit: SourceUnit::Line,
        };
        assert_eq!(edge.located(&lines), format!("{message} [lines 4 and 5]"));
        let facets = SourceLines {
            vertices: vec![1, 1, 3],
            triangles: vec![1, 2, 3],
            unit: SourceUnit::Facet,
        };
        assert_eq!(edge.located(&facets), format!("{message} [facet 1]"));
        let across = Defect::NonManifoldEdge {
            vertices: [0, 2],
            faces: 3,
        };
        assert!(across.located(&facets).ends_with("[facets 1 and 3]"));
        let triangle = Defect::RepeatedVertex { triangle: 1 };
        assert!(triangle.located(&facets).ends_with("[facet 2]"));
    }
}
