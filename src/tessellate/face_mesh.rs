//! The mesh of one face, as every surface mesher produces it and [`super::weld`] joins them:
//! positions in part units, the parameter-domain coordinates of each vertex (patches), triangles
//! oriented alike, and the edges that lie on fold lines.

use glam::{DVec2, DVec3};

/// One mesh face: positions, triangles, the parameter of each vertex (for regions given in a
/// parameter domain) and the edges that lie on fold lines.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FaceMesh {
    /// Vertex positions (part units).
    pub positions: Vec<DVec3>,
    /// Parameter-domain coordinates of each vertex (patches; zero for structured meshes).
    pub parameters: Vec<DVec2>,
    /// Triangles, consistently oriented.
    pub triangles: Vec<[u32; 3]>,
    /// Edges on fold lines: the two vertices and the fold line's index.
    pub fold_edges: Vec<([u32; 2], u32)>,
}

impl FaceMesh {
    /// The total area of the triangles (part units squared).
    #[cfg(test)]
    pub fn area(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| self.positions[v as usize]);
                0.5 * (b - a).cross(c - a).length()
            })
            .sum()
    }

    /// Adds a vertex with a zero parameter and returns its index.
    pub fn add_vertex(&mut self, position: DVec3) -> u32 {
        self.positions.push(position);
        self.parameters.push(DVec2::ZERO);
        (self.positions.len() - 1) as u32
    }
}
