//! Opening a part to a disk: the user's seams first, then automatic seams (a cut graph on a
//! closed surface, one seam per extra boundary loop, handle or corner), and the opened part's
//! first flattening.

use glam::DVec3;

use super::cut_graph::{self, RegionSigns};
use super::errors::CutError;
use super::options::CutConstraints;
use super::paths::Adjacency;
use super::result::Seam;
use super::seam::{self, SeamKind};
use super::state::{CutState, make_seam};
use super::trials::is_better;
use crate::flatten::{FlattenOptions, Flattened, flatten};
use crate::progress::Progress;

/// Cuts the user's seams, in order.
pub(super) fn lay_user_seams(
    state: &mut CutState,
    constraints: &CutConstraints,
    seams: &mut Vec<Seam>,
) -> Result<(), CutError> {
    for (index, points) in constraints.seams.iter().enumerate() {
        let points: Vec<DVec3> = points.iter().map(|&p| DVec3::from(p)).collect();
        let adjacency = Adjacency::new(&state.model);
        let blocked = state.blocked(&constraints.no_cut_regions);
        let path = seam::lay_polyline(&state.model, &adjacency, &blocked, &points, index)?;
        (*state, _) = state.cut_along(&path).map_err(|error| match error {
            CutError::Disconnects => CutError::SeamNotLaid {
                seam: index,
                from: 0,
                to: points.len() - 1,
            },
            other => other,
        })?;
        seams.push(make_seam(&state.model, SeamKind::User, &path));
    }
    Ok(())
}

/// Opens the part to a disk with automatic seams after `seams` (the user's) and flattens it. A
/// closed surface without handles whose curvature regions have both signs is opened both ways,
/// with seams through the regions of either sign and through the positive ones only
/// ([`RegionSigns`]), and the better pattern is kept ([`is_better`]: an overlapping
/// pattern is worse than any other): on a box with a pocket, the seam around the pocket's rim
/// lets the pocket develop exactly. On a surface with handles the negative curvature is the
/// inside of the handles, which their cut graph already follows: only positive regions are cut
/// (seams through a torus's inside cut thin strips off it).
pub(super) fn open_and_flatten(
    state: &CutState,
    constraints: &CutConstraints,
    seams: Vec<Seam>,
    flatten_options: &FlattenOptions,
    progress: &dyn Progress,
) -> Result<(CutState, Vec<Seam>, Flattened), CutError> {
    let variants: &[RegionSigns] = if state.model.is_closed() && seam::genus(&state.model) == 0 {
        &[RegionSigns::Both, RegionSigns::Positive]
    } else {
        &[RegionSigns::Positive]
    };
    let mut best: Option<(CutState, Vec<Seam>, Flattened)> = None;
    for &signs in variants {
        let mut opened = state.clone();
        let mut opened_seams = seams.clone();
        open_to_disk(&mut opened, constraints, &mut opened_seams, signs)?;
        if best
            .as_ref()
            .is_some_and(|(_, known, _)| *known == opened_seams)
        {
            continue;
        }
        let flattened = flatten(&opened.model, &opened.stiffness, flatten_options, progress)?;
        if best
            .as_ref()
            .is_none_or(|(_, _, known)| is_better(&flattened.stats.accuracy, &known.stats.accuracy))
        {
            best = Some((opened, opened_seams, flattened));
        }
    }
    best.ok_or(CutError::NoSeam)
}

/// Cuts automatic seams until the model is a disk; `signs` says which curvature regions the
/// seams of a closed surface run through.
pub(super) fn open_to_disk(
    state: &mut CutState,
    constraints: &CutConstraints,
    seams: &mut Vec<Seam>,
    signs: RegionSigns,
) -> Result<(), CutError> {
    let was_closed = state.model.is_closed();
    if was_closed && seam::genus(&state.model) > 0 {
        let graph = cut_graph::tree_cotree_cut_graph(&state.model, &Adjacency::new(&state.model));
        (*state, _) = state.cut_edges(&graph.edges)?;
        for chain in &graph.chains {
            seams.push(make_seam(&state.model, SeamKind::Handle, chain));
        }
    }
    if was_closed {
        let blocked = state.blocked(&constraints.no_cut_regions);
        let adjacency = Adjacency::new(&state.model);
        let graph = cut_graph::curvature_cut_graph(&state.model, &adjacency, &blocked, signs)
            .map(|graph| (SeamKind::Curvature, graph))
            .or_else(|| {
                cut_graph::bisector_cut_graph(&state.model, &adjacency, &blocked)
                    .map(|graph| (SeamKind::Bisector, graph))
            });
        if let Some((kind, graph)) = graph {
            (*state, _) = state.cut_edges(&graph.edges)?;
            for chain in &graph.chains {
                seams.push(make_seam(&state.model, kind, chain));
            }
        }
    }
    // Every seam removes a boundary loop, a handle or a corner, so this bounds the count.
    for _ in 0..=state.model.vertex_count() {
        let adjacency = Adjacency::new(&state.model);
        let blocked = state.blocked(&constraints.no_cut_regions);
        let Some((kind, path)) = seam::next_seam(&state.model, &adjacency, &blocked, was_closed)?
        else {
            return Ok(());
        };
        (*state, _) = state.cut_along(&path)?;
        seams.push(make_seam(&state.model, kind, &path));
    }
    Err(CutError::NoSeam)
}
