//! A tessellated part and the figures a user checks (mesh size, chord tolerance, worst angle).

use serde::Serialize;

use super::weld::Welded;
use crate::cad::TriangleSoup;

/// Figures of the tessellation a part came from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TessellationFigures {
    /// Target edge length used (part units).
    pub mesh_size: f64,
    /// Chord tolerance used (part units).
    pub chord: f64,
    /// Smallest triangle angle of the whole part's mesh, degrees.
    pub minimum_angle: f64,
}

/// A tessellated part: the soup with, per vertex, the faces it came from, and its figures.
#[derive(Debug, Clone)]
pub struct Tessellation {
    /// The welded soup.
    pub welded: Welded,
    /// The mesh size and chord used and the worst angle.
    pub figures: TessellationFigures,
}

impl Tessellation {
    /// A tessellation of `welded` meshed at `mesh_size` and `chord`, its worst angle measured.
    pub fn new(welded: Welded, mesh_size: f64, chord: f64) -> Self {
        let minimum_angle = minimum_angle(&welded.soup);
        Self {
            welded,
            figures: TessellationFigures {
                mesh_size,
                chord,
                minimum_angle,
            },
        }
    }

    /// The soup.
    pub fn soup(&self) -> &TriangleSoup {
        &self.welded.soup
    }
}

/// The smallest interior angle over all triangles, degrees.
pub fn minimum_angle(soup: &TriangleSoup) -> f64 {
    soup.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| soup.positions[v as usize]);
            [(a, b, c), (b, c, a), (c, a, b)]
                .iter()
                .map(|&(p, q, r)| (q - p).angle_between(r - p).to_degrees())
                .fold(180.0, f64::min)
        })
        .fold(180.0, f64::min)
}
