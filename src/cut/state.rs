//! The model being cut: cutting it along a path or a set of edges (keeping the way back to the
//! input's vertices and the stiffness of every edge), the vertices no cut may pass, and seams as
//! 3D polylines.

use glam::DVec3;

use super::errors::CutError;
use super::options::NoCutRegion;
use super::paths::{path_edges, path_length};
use super::result::Seam;
use super::seam::SeamKind;
use super::split::split_along_edges;
use crate::flatten::Stiffness;
use crate::mesh::{FacetModel, NONE};

/// A point by the bits of its coordinates: copies of a vertex, and a section point on both
/// pieces it bounds, hold their position exactly, so equal keys are the same point.
pub(super) type PointKey = [u64; 3];

/// The exact key of a point ([`PointKey`]).
pub(super) fn point_key(p: DVec3) -> PointKey {
    p.to_array().map(f64::to_bits)
}

/// The model being cut, with its stiffness and the way back to the input's vertices.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct CutState {
    pub(super) model: FacetModel,
    pub(super) stiffness: Stiffness,
    pub(super) original_vertex: Vec<u32>,
}

impl CutState {
    /// The state after cutting along a vertex path, and for each of its vertices the vertex of
    /// `self` it copies.
    pub(super) fn cut_along(&self, path: &[u32]) -> Result<(CutState, Vec<u32>), CutError> {
        let edges = path_edges(&self.model, path).ok_or_else(|| {
            CutError::InvalidResult("a cut path skips from a vertex to a non-neighbour".into())
        })?;
        self.cut_edges(&edges)
    }

    /// The state after cutting along a set of edges, and for each of its vertices the vertex of
    /// `self` it copies.
    pub(super) fn cut_edges(&self, edges: &[usize]) -> Result<(CutState, Vec<u32>), CutError> {
        let split = split_along_edges(&self.model, edges)?;
        let factors = split
            .original_edge
            .iter()
            .map(|&e| self.stiffness.factors()[e])
            .collect();
        let original_vertex = split
            .original_vertex
            .iter()
            .map(|&v| self.original_vertex[v as usize])
            .collect();
        let state = CutState {
            model: split.model,
            stiffness: Stiffness::from_factors(factors),
            original_vertex,
        };
        Ok((state, split.original_vertex))
    }

    /// Vertices no cut may pass: the ends of fold-line edges and those in no-cut regions.
    pub(super) fn blocked(&self, regions: &[NoCutRegion]) -> Vec<bool> {
        let positions = self.model.positions();
        let mut blocked: Vec<bool> = positions
            .iter()
            .map(|&p| {
                regions
                    .iter()
                    .any(|region| p.distance(DVec3::from(region.center)) <= region.radius)
            })
            .collect();
        for (&[a, b], &line) in self.model.edges().iter().zip(self.model.edge_fold_lines()) {
            if line != NONE {
                blocked[a as usize] = true;
                blocked[b as usize] = true;
            }
        }
        blocked
    }
}

/// A seam of `kind` along the vertex path `path`.
pub(super) fn make_seam(model: &FacetModel, kind: SeamKind, path: &[u32]) -> Seam {
    Seam {
        kind,
        points: polyline(model, path),
        length: path_length(model, path),
    }
}

/// 3D positions of a vertex path (copies keep their original's position, so the path's indices
/// are valid in the cut model too).
pub(super) fn polyline(model: &FacetModel, path: &[u32]) -> Vec<DVec3> {
    path.iter()
        .map(|&v| model.positions()[v as usize])
        .collect()
}
