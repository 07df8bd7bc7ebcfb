//! A raw triangle soup as read from a file or produced by a tessellator, before validation.
//!
//! Nothing is assumed about a soup: it may be non-manifold, hold NaNs or degenerate triangles, or
//! reference vertices that do not exist. `crate::mesh::validate` turns it into checked
//! facet models, one per connected component, or lists every defect.

use glam::{DVec2, DVec3};

/// Tag of a face that came from a plain mesh file (no CAD face behind it).
pub const NO_SOURCE_FACE: u32 = 0;

/// An indexed triangle soup in model units (millimetres unless the part says otherwise).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriangleSoup {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Triangles as indices into `positions`, counter-clockwise seen from the front.
    pub triangles: Vec<[u32; 3]>,
    /// Per-triangle tag of the CAD face the triangle was tessellated from
    /// ([`NO_SOURCE_FACE`] for mesh files). Same length as `triangles`.
    pub face_sources: Vec<u32>,
    /// Mesh edges, as vertex index pairs, that lie on a fold line, with the fold line's index.
    pub fold_edges: Vec<FoldEdge>,
    /// Where each vertex and triangle was written in its text file, for messages; empty for
    /// binary files and tessellations.
    pub source_lines: SourceLines,
    /// The texture coordinates of every triangle corner, when the file gives them for every face
    /// (an OBJ's `vt`: a garment's sewing pattern, a scan's atlas).
    pub texture: Option<TextureCorners>,
}

/// Texture coordinates (`u`, `v`) of the corners of a soup's triangles: where each triangle lies
/// in the file's texture layout. A corner's texture point is independent of its vertex: a vertex
/// on a chart boundary of the layout has one texture point per chart.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TextureCorners {
    /// The texture points.
    pub points: Vec<DVec2>,
    /// Per triangle, the index into `points` of each corner, in the triangle's corner order.
    pub corners: Vec<[u32; 3]>,
}

/// The 1-based line of each vertex and triangle in the text file a soup was read from (a
/// polygon's triangles share its line), or in a binary STL the 1-based facet of each triangle
/// and of the first corner welded into each vertex ([`SourceUnit`]). Either list is empty when
/// the file has neither.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct SourceLines {
    /// Line (or facet) of each vertex.
    pub vertices: Vec<u32>,
    /// Line (or facet) of each triangle.
    pub triangles: Vec<u32>,
    /// What the numbers count.
    pub unit: SourceUnit,
}

/// What the numbers of [`SourceLines`] count.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum SourceUnit {
    /// Lines of a text file.
    #[default]
    Line,
    /// Facets (triangle records) of a binary STL, in file order.
    Facet,
}

impl SourceLines {
    /// The line of vertex `index`, if known.
    pub fn vertex(&self, index: usize) -> Option<u32> {
        self.vertices.get(index).copied()
    }

    /// The line of triangle `index`, if known.
    pub fn triangle(&self, index: usize) -> Option<u32> {
        self.triangles.get(index).copied()
    }
}

/// One mesh edge that lies on a user fold line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FoldEdge {
    /// The edge's two vertices (order irrelevant).
    pub vertices: [u32; 2],
    /// Index of the fold line in the part's list of fold lines.
    pub fold_line: u32,
}

impl TriangleSoup {
    /// A soup from positions and triangles, every face tagged [`NO_SOURCE_FACE`].
    pub fn new(positions: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Self {
        let face_sources = vec![NO_SOURCE_FACE; triangles.len()];
        Self {
            positions,
            triangles,
            face_sources,
            fold_edges: Vec::new(),
            source_lines: SourceLines::default(),
            texture: None,
        }
    }

    /// The soup with the texture coordinates of its triangles' corners.
    pub fn with_texture(self, texture: TextureCorners) -> Self {
        Self {
            texture: Some(texture),
            ..self
        }
    }

    /// The soup with the lines its vertices and triangles were read from.
    pub fn with_lines(self, source_lines: SourceLines) -> Self {
        Self {
            source_lines,
            ..self
        }
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// The same soup moved by a rigid motion (or any affine map given as a closure).
    pub fn transformed(&self, map: impl Fn(DVec3) -> DVec3) -> Self {
        Self {
            positions: self.positions.iter().map(|&p| map(p)).collect(),
            ..self.clone()
        }
    }

    /// The soup scaled by `factor` (a unit conversion).
    pub fn scaled(&self, factor: f64) -> Self {
        self.transformed(|p| p * factor)
    }
}
