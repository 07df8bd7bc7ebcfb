//! Pieces (`--seams pieces`): a part that does not flatten within tolerance in one piece is cut
//! in two by a plane section, and each side is handled the same way, until every piece is
//! within tolerance. No crest-line cut is made: where the default cuts a dart, this cuts a
//! seam, which is what a scanned statue or a closed body needs (their crest-line cuts stall)
//! and what a pattern maker sews.
//!
//! Each section is a plane through the piece's interior vertex of largest angle deficit (so the
//! curvature concentrated there opens on the section) or through its area centroid, normal to
//! one of four directions in the plane of its two principal axes of largest spread (the axes
//! and their bisectors): of those leaving at least [`MIN_BALANCE`] of the area on either side,
//! those through the vertex first, then those through the centroid, each by shortest section
//! curve. A closed piece or one with handles is cut without being flattened first. Any
//! other piece is opened to a disk by seams (one per extra boundary loop, as in
//! [`super::cut_and_flatten`]) and flattened quickly (the fast solver's pattern, flips allowed);
//! over [`SCREEN_FACTOR`] times the tolerance it is cut without its valid flattening, which costs
//! far more. Its sides' errors are estimated at [`SECTION_ERROR_RATIO`] of its own; a side of
//! [`SKIP_MIN_TRIANGLES`] or more estimated over [`SKIP_FACTOR`] times the tolerance is cut
//! without being flattened at all (on a 320k-triangle scan, the quick flattenings of the first
//! few levels of halves took 10 s and kept nothing). Otherwise it is flattened validly (no
//! crest-line cut) and kept when it is within tolerance. A piece of fewer than
//! [`MIN_PIECE_TRIANGLES`] triangles, or one past [`MAX_SECTIONS`] sections deep, or one whose
//! part ran out of time, is kept as it is (rejected when over tolerance); one smaller than
//! [`SMALLEST_PIECE`] of the part's mean triangle is cut only through its vertex of largest angle
//! deficit, and kept as it is when it has none.
//!
//! Halving overshoots: the halves of a piece just over tolerance are often far within it. So
//! once every piece is made, neighbouring pieces are glued back together along the section they
//! share wherever a quick flattening of their union is valid and within the tolerance and its
//! valid flattening is within it too (`merge_neighbours`), each side's section edges first split
//! at the other side's points inside them (a later section crossed the curve on one side only:
//! [`super::t_junctions`]) so that the curve glues whole. The quick flattening of a large union
//! starts from the two pieces' patterns, fitted together along the curve
//! ([`super::union_start`]). Where the union closes around a cone point of the shared curve (a
//! spike of a noisy scan, which no flattening of the closed union keeps within tolerance), they
//! are glued with a slit instead: the shorter run of the curve from that point stays open, a dart
//! ending in it. A union that would enclose other pieces in a hole is not made, and two pieces
//! whose union is far over the tolerance ([`GIVE_UP_FACTOR`]) are not tried again inside larger
//! ones. Last, each sliver left (a piece of fewer than [`SLIVER_TRIANGLES`]: on a draped
//! garment, a corner of a face cut off where a section grazed a flap folded over) is glued into
//! a neighbour whose union is within tolerance, its union flattened validly even where its quick
//! pattern folds (`without_slivers`).
//!
//! Both stages use the threads without changing the result and without waiting for each other
//! at a barrier: the two sides of each section are cut in parallel, each on its own, and the
//! pieces kept in depth-first order; the gluing sends off each pair as soon as it shares no
//! piece with a pair being tried nor with a pair before it still to be tried, a few pairs per
//! thread at a time, which gives what trying them one by one in order gives.

use std::collections::{BTreeMap, BTreeSet};
use std::panic::{self, AssertUnwindSafe};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, mpsc};
use std::time::Duration;

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use super::cut_graph::RegionSigns;
use super::cut_loop::{converged_options, cut_opened};
use super::errors::CutError;
use super::opening::open_to_disk;
use super::options::{CutConstraints, CutOptions};
use super::piece::{Piece, SectionId, SideKey, side_key, side_length};
use super::result::{CutResult, CutStop, Seam};
use super::seam::{FLAT_DEFICIT, SeamKind, genus, hole_loops};
use super::state::CutState;
use super::t_junctions::conformed_pair;
use super::union_start::UnionStart;
use crate::flatten::{
    FlattenOptions, Flattened, Stiffness, boundary_comes_within, flatten, flatten_from,
    flatten_unrepaired, flatten_unrepaired_from, with_squeezed_triangles_opened,
};
use crate::geometry::bounding_box;
use crate::mesh::{
    EdgeOrigin, FacetModel, NONE, Plane, SectionPiece, chain_edges, principal_axes, section,
};
use crate::progress::{NoProgress, Progress};

/// Two runs of a piece's flat outline closer than this fraction of its size count as touching
/// (see `is_within`): far above the rounding of a turn of the pattern, far below any gap a
/// cutter keeps.
pub const TOUCHING_GAP: f64 = 1e-9;
/// A piece left after gluing with fewer triangles than this is a sliver, glued into a neighbour
/// where it can be (see `without_slivers`).
pub const SLIVER_TRIANGLES: usize = 8;

/// A piece with fewer triangles is not cut again.
pub const MIN_PIECE_TRIANGLES: usize = 2;

/// A piece whose quick flattening is over this many times the tolerance is cut without being
/// flattened validly (see [`cut_into_pieces`]).
pub const SCREEN_FACTOR: f64 = 2.0;

/// Two neighbouring pieces are glued back together only when a quick flattening of their union
/// is within this many times the tolerance (see `merge_neighbours`).
pub const GLUE_SCREEN_FACTOR: f64 = 1.0;

/// A piece smaller than this fraction of the part's mean triangle is not cut again by the usual
/// planes: a safety bound against cutting ever smaller pieces around one point. Over the
/// tolerance, it is still cut through its vertex of largest angle deficit (a spike's tip, which
/// the balanced planes around it missed), so that the point opens on the boundary.
pub const SMALLEST_PIECE: f64 = 1e-3;

/// A candidate plane is also tried shifted by this fraction of the mean edge length either way
/// (see `section_planes`).
pub const SHIFT: f64 = 0.37;

/// A piece this many sections deep is not cut again.
pub const MAX_SECTIONS: usize = 64;

/// A union of pieces of at least this many triangles starts its quick flattening from the
/// pieces' patterns ([`UnionStart`]); a smaller one grows its start, which costs little there
/// and more often ends without a fold (on the octopus, 230 pieces against 254).
pub const WARM_START_MIN_TRIANGLES: usize = 1_000;

/// A piece of at least [`SKIP_MIN_TRIANGLES`] triangles whose quick flattening's error is
/// estimated over this many times the tolerance is cut without being flattened (see
/// `is_far_over`).
pub const SKIP_FACTOR: f64 = 4.0 * SCREEN_FACTOR;

/// The smallest piece that may be cut without being flattened (see `is_far_over`).
pub const SKIP_MIN_TRIANGLES: usize = 10_000;

/// The estimate of a side's quick flattening error, as a fraction of its piece's: a section
/// halves the area, and roughly halves the curvature a side must flatten.
pub const SECTION_ERROR_RATIO: f64 = 0.5;

/// The smallest share of a piece's area a section leaves on either side, unless no candidate
/// plane does.
pub const MIN_BALANCE: f64 = 0.25;

/// Cuts the part into pieces by plane sections until each flattens within tolerance; see the
/// module documentation. The pieces come depth first, the positive side of each section first.
/// The two sides of each section are handled in parallel, each on its own, so the result does
/// not depend on the threads.
pub fn cut_into_pieces(
    model: &FacetModel,
    stiffness: &Stiffness,
    flatten_options: &FlattenOptions,
    progress: &dyn Progress,
) -> Result<Vec<CutResult>, CutError> {
    let cutting = Cutting {
        smallest_cut: SMALLEST_PIECE * model.area() / model.triangle_count() as f64,
        flatten_options,
        progress,
        made: AtomicUsize::new(0),
        to_go: AtomicUsize::new(1),
    };
    // One stage for the whole: each piece's own flattening is quick, and pieces run in parallel,
    // so the stage shows the pieces made and to go instead of their flattenings.
    progress.start("cutting into pieces", 0);
    // The whole part's quick flattening's error is not estimated (0).
    let done = cutting.pieces_of(Piece::whole(model, stiffness), 0.0)?;
    let merged = merge_neighbours(done, flatten_options, progress);
    let merged = without_slivers(merged, flatten_options);
    progress.finish();
    Ok((merged.into_iter())
        .map(|(piece, result)| finished(&piece, result, flatten_options))
        .collect())
}

/// What [`cut_into_pieces`] shares between the pieces it cuts, in parallel.
struct Cutting<'a> {
    /// The area under which a piece is not cut again.
    smallest_cut: f64,
    flatten_options: &'a FlattenOptions,
    progress: &'a dyn Progress,
    /// Pieces kept so far.
    made: AtomicUsize,
    /// Pieces being cut or waiting to be.
    to_go: AtomicUsize,
}

impl Cutting<'_> {
    /// The pieces `piece` ends in, depth first, with their patterns: itself when [`step`] keeps
    /// it, else the pieces of its sides, found in parallel. `estimate` is the estimate of its
    /// quick flattening's error. The error is the first in depth-first order, whatever thread
    /// met it first.
    fn pieces_of(&self, piece: Piece, estimate: f64) -> Result<Vec<(Piece, CutResult)>, CutError> {
        let step =
            step(piece, estimate, self.smallest_cut, self.flatten_options).inspect_err(|_| {
                self.to_go.fetch_sub(1, Ordering::Relaxed);
            })?;
        match step {
            Step::Kept(kept) => {
                self.made.fetch_add(1, Ordering::Relaxed);
                self.to_go.fetch_sub(1, Ordering::Relaxed);
                self.report();
                Ok(vec![*kept])
            }
            Step::Halved(sides, estimate) => {
                self.to_go.fetch_add(sides.len() - 1, Ordering::Relaxed);
                let sides: Vec<Result<Vec<(Piece, CutResult)>, CutError>> = (sides.into_par_iter())
                    .map(|side| self.pieces_of(side, estimate))
                    .collect();
                let mut pieces = Vec::new();
                for side in sides {
                    pieces.extend(side?);
                }
                Ok(pieces)
            }
        }
    }

    /// Shows the pieces made and to go.
    fn report(&self) {
        let (made, to_go) = (
            self.made.load(Ordering::Relaxed),
            self.to_go.load(Ordering::Relaxed),
        );
        self.progress.status(&format!("{made} made, {to_go} to go"));
    }
}

/// What one step of [`cut_into_pieces`] made of a piece.
enum Step {
    /// The piece is kept, with its pattern: within tolerance, or not to be cut again.
    Kept(Box<(Piece, CutResult)>),
    /// The piece is cut by a section into these sides, positive first, with the estimate of their
    /// quick flattenings' error.
    Halved(Vec<Piece>, f64),
}

/// One step of [`cut_into_pieces`] on `piece`: kept when it flattens within tolerance, else cut
/// in two by a section unless it is too small (`smallest_cut`, an area), too deep or out of
/// time, then kept as it is. A large piece whose quick flattening's error is `estimate`d far over
/// the tolerance ([`is_far_over`]) is cut without being flattened. Its flattenings report no
/// progress (the stage reports the pieces).
fn step(
    piece: Piece,
    estimate: f64,
    smallest_cut: f64,
    flatten_options: &FlattenOptions,
) -> Result<Step, CutError> {
    let progress = &NoProgress;
    let (flattened, error) = if must_cut(&piece) || is_far_over(&piece, estimate, flatten_options) {
        (None, estimate)
    } else {
        let screen = Screen {
            factor: SCREEN_FACTOR,
            repair: true,
            start: None,
        };
        match screened_flattening(&piece, screen, flatten_options, progress) {
            Ok(Screened::Flattened(result)) => {
                let error = result.flattened.stats.accuracy.larger_error();
                (Some(Ok(*result)), error)
            }
            Ok(Screened::Over { error }) => (None, error),
            Err(error) => (Some(Err(error)), 0.0),
        }
    };
    if let Some(Ok(result)) = &flattened
        && is_within(result, flatten_options.tolerance)
    {
        return Ok(Step::Kept(Box::new((piece, result.clone()))));
    }
    let cuttable = piece.model.triangle_count() >= MIN_PIECE_TRIANGLES
        && piece.depth < MAX_SECTIONS
        && !flatten_options.deadline.passed();
    let planes = if !cuttable {
        Vec::new()
    } else if piece.model.area() >= smallest_cut {
        section_planes(&piece.model)
    } else {
        planes_through_peak(&piece.model)
    };
    if let Some(sides) = halves(&piece, planes) {
        return Ok(Step::Halved(sides, error * SECTION_ERROR_RATIO));
    }
    let result = match flattened {
        Some(result) => result?,
        None => flatten_piece(&piece, flatten_options, progress)?,
    };
    Ok(Step::Kept(Box::new((piece, result))))
}

/// True for a piece of at least [`SKIP_MIN_TRIANGLES`] triangles whose quick flattening's error
/// is `estimate`d over [`SKIP_FACTOR`] times the tolerance: so far over that it is cut without
/// being flattened (a quick flattening of a large piece costs much, and would not keep it).
fn is_far_over(piece: &Piece, estimate: f64, options: &FlattenOptions) -> bool {
    piece.model.triangle_count() >= SKIP_MIN_TRIANGLES && estimate > SKIP_FACTOR * options.tolerance
}

/// True for a piece that is cut without being flattened: one with handles (a closed piece
/// without is opened by its seams like the default's, and may lie flat as its net).
fn must_cut(piece: &Piece) -> bool {
    genus(&piece.model) > 0
}

/// True for a union of pieces that may be flattened as one: one without handles
/// ([`must_cut`]) and without a hole bounded by sections alone, which would enclose other
/// pieces (a hole that small is not a pattern's hole, and may be too small to draw).
fn can_be_one_piece(union: &Piece) -> bool {
    if must_cut(union) {
        return false;
    }
    let sections = union.section_sides();
    let positions = union.model.positions();
    let on_section = |a: u32, b: u32| sections.contains_key(&side_key(positions, a, b));
    !(hole_loops(&union.model).into_iter()).any(|index| {
        let ring = &union.model.boundary_loops()[index];
        (0..ring.len()).all(|k| on_section(ring[k], ring[(k + 1) % ring.len()]))
    })
}

/// True when the flattened piece is within `tolerance` and valid: no flipped triangle and an
/// outline that does not cross itself, nor come within [`TOUCHING_GAP`] of its size of
/// itself. A piece holding a crack of no width (two runs of its boundary lying on each other in
/// the surface itself, where sections met) is within any tolerance, yet whether its outline
/// touches itself is decided by rounding, and may change when the pattern is turned into its
/// rest position: such a piece is cut further, and such a union not glued.
fn is_within(result: &CutResult, tolerance: f64) -> bool {
    let accuracy = result.flattened.stats.accuracy;
    accuracy.within(tolerance) && !accuracy.overlap && !touches_itself(result)
}

/// True when the piece's flat outline comes within [`TOUCHING_GAP`] of its size of itself
/// (see [`is_within`]).
fn touches_itself(result: &CutResult) -> bool {
    let positions = &result.flattened.positions;
    let (min, max) = bounding_box(positions);
    let gap = TOUCHING_GAP * (max - min).length();
    boundary_comes_within(&result.model, positions, gap)
}

/// The pieces with neighbours glued back together ([`Piece::glued`]) wherever their union
/// flattens within tolerance too: sections halve a piece, and the halves of neighbouring pieces
/// are often far within it (on the bust, half the pieces were under 0.04 % E_S). In rounds: each
/// round tries the pairs of pieces within tolerance that share a section curve, longest shared
/// curve first, each piece in at most one union per round and each pair once; the rounds end
/// when one glues nothing, or at the part's deadline. A pair whose union is not within tolerance
/// is tried once more glued with a slit ([`Piece::slit_glued`]): the small pieces left between
/// larger ones are most often sectors around a cone point, which a neighbour takes in only if
/// the cone stays open (on the 20k-triangle Hencky scan, 636 pieces became 572). A union takes
/// the place of the first of its two pieces; one that is not [`can_be_one_piece`] is not made.
/// A pair whose unions were over [`GIVE_UP_FACTOR`] times the tolerance is not tried again
/// inside any later pair ([`GluingLog`]).
fn merge_neighbours(
    pieces: Vec<(Piece, CutResult)>,
    options: &FlattenOptions,
    progress: &dyn Progress,
) -> Vec<(Piece, CutResult)> {
    let mut slots: Vec<Slot> = (pieces.into_iter().enumerate())
        .map(|(id, piece)| Some((id, Arc::new(piece))))
        .collect();
    let mut log = GluingLog::new(slots.len());
    loop {
        let glued_any = glue_round(&mut slots, &mut log, options, progress);
        slots.retain(Option::is_some);
        if !glued_any || options.deadline.passed() {
            break;
        }
    }
    (slots.into_iter().flatten())
        .map(|(_, piece)| Arc::unwrap_or_clone(piece))
        .collect()
}

/// One round of `merge_neighbours`: every pair of neighbouring pieces in `slots` still to be
/// tried ([`neighbour_pairs`], [`GluingLog::is_to_try`]), each piece in at most one union, sent
/// off to the pool as soon as it is ready ([`PairQueue::next_ready`]), at most
/// [`IN_FLIGHT_PER_THREAD`] pairs per thread at a time. A union takes the first piece's slot and
/// empties the second's. True when a pair glued.
fn glue_round(
    slots: &mut [Slot],
    log: &mut GluingLog,
    options: &FlattenOptions,
    progress: &dyn Progress,
) -> bool {
    let far_over = GIVE_UP_FACTOR * options.tolerance;
    let most_in_flight = IN_FLIGHT_PER_THREAD * rayon::current_num_threads();
    let mut busy = vec![false; slots.len()];
    let mut glued_any = false;
    let mut pairs = PairQueue::new(neighbour_pairs(slots, options.tolerance));
    rayon::in_place_scope(|scope| {
        let (sender, receiver) = mpsc::channel();
        // The pieces of the pairs in flight.
        let mut in_flight: BTreeSet<usize> = BTreeSet::new();
        loop {
            while in_flight.len() < 2 * most_in_flight && !options.deadline.passed() {
                let untried = |(i, j): (usize, usize)| {
                    !busy[i] && !busy[j] && ids(slots, i, j).is_some_and(|ids| log.is_to_try(ids))
                };
                let Some((i, j)) = pairs.next_ready(&in_flight, untried) else {
                    break;
                };
                let (Some(a), Some(b)) = (&slots[i], &slots[j]) else {
                    continue;
                };
                let (a, b) = (Arc::clone(&a.1), Arc::clone(&b.1));
                let sender = sender.clone();
                in_flight.extend([i, j]);
                progress.status(&format!("gluing neighbours, {} left", slots.len()));
                scope.spawn(move |_| {
                    let glued = panic::catch_unwind(AssertUnwindSafe(|| {
                        glued_within((&a.0, &a.1), (&b.0, &b.1), false, options)
                    }));
                    // The receiver waits for every pair it sent off.
                    let _ = sender.send(((i, j), glued));
                });
            }
            if in_flight.is_empty() {
                break;
            }
            let ((i, j), glued) = next_outcome(&receiver);
            let glued = glued.unwrap_or_else(|payload| panic::resume_unwind(payload));
            in_flight.remove(&i);
            in_flight.remove(&j);
            let Some(pair) = ids(slots, i, j) else {
                continue;
            };
            match glued {
                Glued::Union(union, result) => {
                    (busy[i], busy[j], glued_any) = (true, true, true);
                    slots[i] = Some((log.union(pair), Arc::new((*union, *result))));
                    slots[j] = None;
                }
                Glued::Not { error } => log.failure(pair, error > far_over),
            }
        }
    });
    glued_any
}

/// The glued pieces with each sliver among them (a piece of fewer than [`SLIVER_TRIANGLES`]: a
/// few faces a section cut off where it grazed a fold, or a sector around a cone point) glued
/// into a neighbour when their union is within tolerance, neighbours tried by decreasing shared
/// length ([`sliver_union`]). The slivers are tried in parallel, each against the pieces as
/// gluing left them; their unions are then taken in the pieces' order, each unless its
/// neighbour or the sliver is already in one taken before. Nothing is tried once the part is
/// out of time.
fn without_slivers(
    pieces: Vec<(Piece, CutResult)>,
    options: &FlattenOptions,
) -> Vec<(Piece, CutResult)> {
    if options.deadline.passed() {
        return pieces;
    }
    let slivers: Vec<usize> = (0..pieces.len())
        .filter(|&s| pieces[s].0.model.triangle_count() < SLIVER_TRIANGLES)
        .collect();
    if slivers.is_empty() {
        return pieces;
    }
    let sides: Vec<BTreeMap<SideKey, usize>> = (pieces.par_iter())
        .map(|(piece, _)| piece.section_sides())
        .collect();
    let unions: Vec<Option<(usize, Piece, CutResult)>> = (slivers.par_iter())
        .map(|&s| sliver_union(&pieces, &sides, s, options))
        .collect();
    let mut slots: Vec<Option<(Piece, CutResult)>> = pieces.into_iter().map(Some).collect();
    let mut taken = vec![false; slots.len()];
    for (&s, union) in slivers.iter().zip(unions) {
        if let Some((i, piece, result)) = union
            && !taken[i]
            && !taken[s]
        {
            (taken[i], taken[s]) = (true, true);
            slots[i] = Some((piece, result));
            slots[s] = None;
        }
    }
    slots.into_iter().flatten().collect()
}

/// The union of the sliver `pieces[s]` with the first of its neighbours (by decreasing length of
/// the curve they share, from the pieces' section `sides`) that it glues to within tolerance,
/// and that neighbour's index. Unlike
/// gluing's pairs, a union whose quick pattern folds is flattened validly all the same
/// ([`glued_within`] with `repair`): the fold is most often the sliver itself, a flap folded over
/// in the drape, which the flip-free repair opens; there are few slivers, so this costs little.
fn sliver_union(
    pieces: &[(Piece, CutResult)],
    sides: &[BTreeMap<SideKey, usize>],
    s: usize,
    options: &FlattenOptions,
) -> Option<(usize, Piece, CutResult)> {
    let (sliver, pattern) = &pieces[s];
    let shared_length = |i: usize| -> f64 {
        (sides[s].keys())
            .filter(|key| sides[i].contains_key(*key))
            .map(side_length)
            .sum()
    };
    let mut neighbours: Vec<(usize, f64)> = (0..pieces.len())
        .filter(|&i| i != s)
        .map(|i| (i, shared_length(i)))
        .filter(|&(_, length)| length > 0.0)
        .collect();
    neighbours.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
    neighbours.into_iter().find_map(|(i, _)| {
        let (piece, piece_pattern) = &pieces[i];
        match glued_within((piece, piece_pattern), (sliver, pattern), true, options) {
            Glued::Union(union, result) => Some((i, *union, *result)),
            Glued::Not { .. } => None,
        }
    })
}

/// The next outcome sent to `receiver`, running the pool's waiting work meanwhile (this thread
/// is most often one of the pool's, whose other threads run the pairs sent off).
fn next_outcome<T>(receiver: &mpsc::Receiver<T>) -> T {
    loop {
        if let Ok(outcome) = receiver.try_recv() {
            return outcome;
        }
        match rayon::yield_now() {
            Some(rayon::Yield::Executed) => {}
            Some(rayon::Yield::Idle) => std::thread::sleep(IDLE_WAIT),
            None => {
                return receiver
                    .recv()
                    .expect("every pair sent off sends its outcome");
            }
        }
    }
}

/// How long the gluing waits, when the pool has no work for it, before it looks again for an
/// outcome or for work.
const IDLE_WAIT: Duration = Duration::from_micros(50);

/// A union of two pieces whose flattenings, plain and with a slit, are over this many times the
/// tolerance (the smaller of their larger errors, [`Glued::Not`]) is tried in no larger union:
/// no later pair of pieces holding both is tried (a union holding one far over the tolerance
/// seldom comes within it; on the Hencky scan subdivided to 320k triangles, retrying such unions
/// took a sixth of the time, and it ends in fewer pieces without them).
pub const GIVE_UP_FACTOR: f64 = 2.0;

/// What gluing has tried, by piece ids (a union gets a new id).
struct GluingLog {
    /// For each piece id, the ids of the pieces glued into it and its own, sorted.
    lineage: Vec<Vec<usize>>,
    /// The pairs that did not glue.
    failed: BTreeSet<(usize, usize)>,
    /// For each piece id, the pieces its union with which was far over the tolerance.
    far_over: BTreeMap<usize, Vec<usize>>,
}

impl GluingLog {
    /// A log of `pieces` pieces (ids `0..pieces`) and no pair tried.
    fn new(pieces: usize) -> Self {
        Self {
            lineage: (0..pieces).map(|id| vec![id]).collect(),
            failed: BTreeSet::new(),
            far_over: BTreeMap::new(),
        }
    }

    /// Whether the pair of pieces `(a, b)` is to be tried: it did not fail, and no two pieces
    /// glued into them (or they themselves) made a union far over the tolerance.
    fn is_to_try(&self, (a, b): (usize, usize)) -> bool {
        let (within_a, within_b) = (&self.lineage[a], &self.lineage[b]);
        !self.failed.contains(&(a, b))
            && !within_a.iter().any(|p| {
                (self.far_over.get(p).into_iter().flatten())
                    .any(|q| within_b.binary_search(q).is_ok())
            })
    }

    /// Records that the pair glued, and returns the union's id.
    fn union(&mut self, (a, b): (usize, usize)) -> usize {
        let id = self.lineage.len();
        let mut lineage: Vec<usize> = (self.lineage[a].iter().chain(&self.lineage[b]))
            .copied()
            .chain([id])
            .collect();
        lineage.sort_unstable();
        self.lineage.push(lineage);
        id
    }

    /// Records that the pair did not glue, their union far over the tolerance or not.
    fn failure(&mut self, (a, b): (usize, usize), far_over: bool) {
        self.failed.insert((a, b));
        if far_over {
            self.far_over.entry(a).or_default().push(b);
            self.far_over.entry(b).or_default().push(a);
        }
    }
}

/// Pairs of pieces being tried at once per thread when gluing, at most (see `glue_round`):
/// more than one, so that a thread that finishes a pair finds the next one waiting.
const IN_FLIGHT_PER_THREAD: usize = 2;

/// The pairs of pieces a gluing round has yet to try, in order (longest shared curve first).
struct PairQueue {
    /// Pairs passed over because a piece of theirs was being tried, in order; they come before
    /// `rest`.
    waiting: Vec<(usize, usize)>,
    /// The pairs not looked at yet, in order.
    rest: std::vec::IntoIter<(usize, usize)>,
}

impl PairQueue {
    fn new(pairs: Vec<(usize, usize)>) -> Self {
        Self {
            waiting: Vec::new(),
            rest: pairs.into_iter(),
        }
    }

    /// The first of the pairs, in order, that is still to be tried (`untried`; the others are
    /// dropped) and shares no piece with a pair being tried (`in_flight`, their pieces) nor with
    /// a pair before it that waits; a pair passed over waits, in its place. Whether a pair glues
    /// never depends on a pair being tried at the same time or on a pair that waits, so trying
    /// the pairs as they come from here, and taking their outcomes in any order, gives what
    /// trying every pair one by one in order gives.
    fn next_ready(
        &mut self,
        in_flight: &BTreeSet<usize>,
        untried: impl Fn((usize, usize)) -> bool,
    ) -> Option<(usize, usize)> {
        let mut claimed = in_flight.clone();
        let mut k = 0;
        while k < self.waiting.len() {
            let pair = self.waiting[k];
            if !untried(pair) {
                self.waiting.remove(k);
            } else if claimed.contains(&pair.0) || claimed.contains(&pair.1) {
                claimed.extend([pair.0, pair.1]);
                k += 1;
            } else {
                return Some(self.waiting.remove(k));
            }
        }
        for pair in self.rest.by_ref() {
            if !untried(pair) {
                continue;
            }
            if !claimed.contains(&pair.0) && !claimed.contains(&pair.1) {
                return Some(pair);
            }
            claimed.extend([pair.0, pair.1]);
            self.waiting.push(pair);
        }
        None
    }
}

/// A place in the list of pieces being glued: a piece and its pattern under its id (shared with
/// the pairs being tried), or none once glued into another.
type Slot = Option<(usize, Arc<(Piece, CutResult)>)>;

/// The ids of the pieces in slots `i` and `j`, when both hold one.
fn ids(slots: &[Slot], i: usize, j: usize) -> Option<(usize, usize)> {
    Some((slots[i].as_ref()?.0, slots[j].as_ref()?.0))
}

/// What [`glued_within`] made of a pair of pieces.
enum Glued {
    /// Their union, with its valid flattening.
    Union(Box<Piece>, Box<CutResult>),
    /// Nothing, with the smaller error of the unions tried (the larger of a flattening's area
    /// and shape errors; 0 when no union was measured).
    Not {
        /// The smaller error of the unions tried.
        error: f64,
    },
}

/// Pieces `a` and `b` (with their patterns), their shared curve first given the same points on
/// both sides ([`conformed_pair`]), glued into one ([`Piece::glued`]), or with a slit where that
/// is not within tolerance ([`Piece::slit_glued`]), with its valid flattening when it is within
/// tolerance ([`flattened_within`], started from the two patterns: [`UnionStart`]; a union whose
/// quick pattern folds is flattened validly all the same when `repair`); not glued when neither
/// is, or when the union is not to be one piece ([`can_be_one_piece`]).
fn glued_within(
    (a, a_pattern): (&Piece, &CutResult),
    (b, b_pattern): (&Piece, &CutResult),
    repair: bool,
    options: &FlattenOptions,
) -> Glued {
    let triangles = a.model.triangle_count() + b.model.triangle_count();
    let start = (triangles >= WARM_START_MIN_TRIANGLES)
        .then(|| UnionStart::new((a, a_pattern), (b, b_pattern)))
        .flatten();
    let (a, b) = conformed_pair(a, b);
    let first_count = a.model.vertex_count();
    let within = |union: &Piece| {
        let positions = start.as_ref().and_then(|s| s.positions(union, first_count));
        flattened_within(union, positions.as_deref(), repair, options)
    };
    let Some(union) = a.glued(&b).filter(can_be_one_piece) else {
        return Glued::Not { error: 0.0 };
    };
    let error = match within(&union) {
        Ok(result) => return Glued::Union(Box::new(union), Box::new(result)),
        Err(error) => error,
    };
    let Some(slit) = a.slit_glued(&b, &union).filter(can_be_one_piece) else {
        return Glued::Not { error };
    };
    match within(&slit) {
        Ok(result) => Glued::Union(Box::new(slit), Box::new(result)),
        Err(slit_error) => Glued::Not {
            error: error.min(slit_error),
        },
    }
}

/// The valid flattening of a union of pieces when a quick one, from `start` when given (one
/// position per vertex of the union), is within the tolerance (and without a fold, unless
/// `repair`) and it is within it too (see `merge_neighbours`), reporting no progress (the stage
/// reports the gluing); else the error of the flattening that was not within it (the larger of
/// its area and shape errors; 0 when the flattening failed).
fn flattened_within(
    union: &Piece,
    start: Option<&[DVec2]>,
    repair: bool,
    options: &FlattenOptions,
) -> Result<CutResult, f64> {
    let screen = Screen {
        factor: GLUE_SCREEN_FACTOR,
        repair,
        start,
    };
    match screened_flattening(union, screen, options, &NoProgress) {
        Ok(Screened::Flattened(result)) if is_within(&result, options.tolerance) => Ok(*result),
        Ok(Screened::Flattened(result)) => Err(result.flattened.stats.accuracy.larger_error()),
        Ok(Screened::Over { error }) => Err(error),
        Err(_) => Err(0.0),
    }
}

/// The pairs of pieces within `tolerance` that share section edges, by the slots they are in,
/// longest shared curve first.
fn neighbour_pairs(slots: &[Slot], tolerance: f64) -> Vec<(usize, usize)> {
    let mut owners: BTreeMap<SideKey, Vec<usize>> = BTreeMap::new();
    for (i, slot) in slots.iter().enumerate() {
        if let Some((_, piece)) = slot
            && is_within(&piece.1, tolerance)
        {
            for key in piece.0.section_sides().into_keys() {
                owners.entry(key).or_default().push(i);
            }
        }
    }
    let mut shared: BTreeMap<(usize, usize), f64> = BTreeMap::new();
    for (key, owners) in &owners {
        if let [a, b] = owners[..] {
            *shared.entry((a, b)).or_default() += side_length(key);
        }
    }
    let mut pairs: Vec<((usize, usize), f64)> = shared.into_iter().collect();
    pairs.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
    pairs.into_iter().map(|(pair, _)| pair).collect()
}

/// What [`screened_flattening`] made of a piece.
enum Screened {
    /// Its valid flattening.
    Flattened(Box<CutResult>),
    /// Nothing: its quick flattening is over the screen, or folded (a flipped triangle, an
    /// overlap) where the screen does not repair, with this error (the larger of its area and
    /// shape errors).
    Over {
        /// The quick flattening's larger error.
        error: f64,
    },
}

/// How [`screened_flattening`] screens a piece.
#[derive(Debug, Clone, Copy)]
struct Screen<'a> {
    /// The quick flattening's errors may be this many times the tolerance at most.
    factor: f64,
    /// Whether a quick flattening with a flipped triangle or an overlap passes.
    repair: bool,
    /// Where the quick flattening starts, one position per vertex of the piece (else it grows
    /// its own start, as [`flatten_unrepaired`] does, and also when the pattern from this start
    /// has a fold but errors within the screen).
    start: Option<&'a [DVec2]>,
}

/// The piece's valid flattening ([`flatten_piece`]), or [`Screened::Over`] when a quick
/// flattening of the opened piece (the fast solver's pattern, flips allowed:
/// [`flatten_unrepaired`], or [`flatten_unrepaired_from`] the screen's start) is over the
/// screen's factor times the tolerance, or invalid (a flipped triangle, an overlap) unless the
/// screen repairs: the valid flattening, which costs far more, would not be within it.
fn screened_flattening(
    piece: &Piece,
    screen: Screen,
    options: &FlattenOptions,
    progress: &dyn Progress,
) -> Result<Screened, CutError> {
    let (opened, seams) = opened(piece)?;
    let limit = screen.factor * options.tolerance;
    let cold = || flatten_unrepaired(&opened.model, &opened.stiffness, options, &NoProgress);
    let invalid = |quick: &Flattened| {
        let accuracy = quick.stats.accuracy;
        accuracy.flipped > 0 || accuracy.overlap
    };
    let over = |quick: &Flattened| quick.stats.accuracy.larger_error() > limit;
    let quick = match screen.start {
        Some(start) => {
            let start: Vec<DVec2> = (opened.original_vertex.iter())
                .map(|&v| start[v as usize])
                .collect();
            let warm = flatten_unrepaired_from(&opened.model, &opened.stiffness, &start, options)?;
            // A start can hold the solver in a fold a grown start would not have: a folded
            // pattern the errors alone would pass is made again from a grown start (kept unless
            // it is over the screen where the folded one, which the screen repairs, is not).
            if invalid(&warm) && !over(&warm) {
                let grown = cold()?;
                if screen.repair && over(&grown) {
                    warm
                } else {
                    grown
                }
            } else {
                warm
            }
        }
        None => cold()?,
    };
    if over(&quick) || (invalid(&quick) && !screen.repair) {
        let error = quick.stats.accuracy.larger_error();
        return Ok(Screened::Over { error });
    }
    // Without a flipped triangle the quick pattern is the valid flattening's first pattern
    // itself: the flip-free repair is all that tells them apart.
    let first = (quick.stats.accuracy.flipped == 0).then_some(quick);
    flatten_opened(opened, seams, first, options, progress)
        .map(|result| Screened::Flattened(Box::new(result)))
}

/// The piece opened to a disk and flattened validly ([`flatten_opened`]).
fn flatten_piece(
    piece: &Piece,
    options: &FlattenOptions,
    progress: &dyn Progress,
) -> Result<CutResult, CutError> {
    let (opened, seams) = opened(piece)?;
    flatten_opened(opened, seams, None, options, progress)
}

/// The piece opened to a disk by seams, one per extra boundary loop (as in
/// [`super::cut_and_flatten`]), with those seams.
fn opened(piece: &Piece) -> Result<(CutState, Vec<Seam>), CutError> {
    let mut opened = CutState {
        model: piece.model.clone(),
        stiffness: piece.stiffness.clone(),
        original_vertex: (0..piece.model.vertex_count() as u32).collect(),
    };
    let mut seams = Vec::new();
    open_to_disk(
        &mut opened,
        &CutConstraints::default(),
        &mut seams,
        RegionSigns::Positive,
    )?;
    Ok((opened, seams))
}

/// The opened piece flattened validly with no crest-line cut, from `first`, its first pattern
/// as [`flatten`] makes it, when given (else made here), on to the cut loop's convergence when
/// that is over tolerance; its vertices numbered by the piece's and its opening seams first.
fn flatten_opened(
    opened: CutState,
    mut seams: Vec<Seam>,
    first: Option<Flattened>,
    options: &FlattenOptions,
    progress: &dyn Progress,
) -> Result<CutResult, CutError> {
    let no_cuts = CutOptions {
        max_cuts: Some(0),
        ..CutOptions::default()
    };
    let first = match first {
        Some(first) => first,
        None => flatten(&opened.model, &opened.stiffness, options, progress)?,
    };
    // The cut loop numbers the vertices of the opened model as they are.
    let disk = CutState {
        model: opened.model.clone(),
        stiffness: opened.stiffness.clone(),
        original_vertex: (0..opened.model.vertex_count() as u32).collect(),
    };
    let constraints = CutConstraints::default();
    let mut result = cut_opened(
        disk,
        Vec::new(),
        first,
        &constraints,
        options,
        &no_cuts,
        progress,
    )?;
    for v in &mut result.original_vertex {
        *v = opened.original_vertex[*v as usize];
    }
    seams.append(&mut result.seams);
    result.seams = seams;
    if !result.flattened.stats.accuracy.within(options.tolerance) {
        let converged = flatten_from(
            &result.model,
            &result.stiffness,
            &result.flattened.positions,
            &converged_options(options),
        )?;
        let better = converged.stats.accuracy.flipped == 0
            && !converged.stats.accuracy.overlap
            && converged.stats.energy < result.flattened.stats.energy;
        if better {
            result.flattened = with_squeezed_triangles_opened(
                &result.model,
                &result.stiffness,
                converged,
                options,
            );
        }
    }
    Ok(result)
}

/// A flattened piece as a result of the whole part: its vertices numbered by the part's, its
/// section curves among its seams, and why it was not cut further when it is over tolerance.
fn finished(piece: &Piece, mut result: CutResult, options: &FlattenOptions) -> CutResult {
    let mut seams = section_seams(piece);
    seams.append(&mut result.seams);
    result.seams = seams;
    for v in &mut result.original_vertex {
        *v = piece.part_vertex[*v as usize];
    }
    result.stop = if result.flattened.stats.accuracy.within(options.tolerance) {
        CutStop::ToleranceMet
    } else if options.deadline.passed() {
        CutStop::TimeLimit
    } else {
        CutStop::NoBetterCut
    };
    result
}

/// The piece's section curves on its boundary, as seams: one per run of one section's curve (where
/// the boundary passes from one section to another, at a corner of the piece, a seam ends and the
/// next begins).
fn section_seams(piece: &Piece) -> Vec<Seam> {
    let model = &piece.model;
    let edges: Vec<[u32; 2]> = (model.edges().iter().enumerate())
        .filter(|&(e, _)| piece.section_edges[e].is_some() && model.is_boundary_edge(e))
        .map(|(_, &edge)| edge)
        .collect();
    chain_edges(&edges)
        .into_iter()
        .flat_map(|path| runs_of_one_section(piece, &path))
        .map(|path| {
            let points: Vec<DVec3> = (path.iter())
                .map(|&v| model.positions()[v as usize])
                .collect();
            let length = points.windows(2).map(|w| w[0].distance(w[1])).sum();
            Seam {
                kind: SeamKind::Section,
                points,
                length,
            }
        })
        .collect()
}

/// A vertex path along section edges of the piece, split into runs that each lie on one section;
/// a closed path's last run and first run join when they lie on the same section.
fn runs_of_one_section(piece: &Piece, path: &[u32]) -> Vec<Vec<u32>> {
    let section_of =
        |a: u32, b: u32| (piece.model.find_edge(a, b)).and_then(|e| piece.section_edges[e]);
    let mut runs: Vec<(Option<SectionId>, Vec<u32>)> = Vec::new();
    for step in path.windows(2) {
        let section = section_of(step[0], step[1]);
        match runs.last_mut() {
            Some((run_section, run)) if *run_section == section => run.push(step[1]),
            _ => runs.push((section, step.to_vec())),
        }
    }
    let closed = path.len() > 2 && path.first() == path.last();
    if closed && runs.len() > 1 && runs[0].0 == runs[runs.len() - 1].0 {
        let (_, first) = runs.remove(0);
        if let Some((_, last)) = runs.last_mut() {
            last.extend_from_slice(&first[1..]);
        }
    }
    runs.into_iter().map(|(_, run)| run).collect()
}

/// The connected pieces of the piece's two sides along the first of the `planes` that makes
/// valid pieces, or `None` when none does.
fn halves(piece: &Piece, planes: Vec<Plane>) -> Option<Vec<Piece>> {
    let (plane, sides) =
        (planes.into_iter()).find_map(|plane| Some((plane, section(&piece.model, plane)?)))?;
    let section = SectionId::of(plane);
    Some(
        sides
            .into_iter()
            .map(|side| child(piece, side, section))
            .collect(),
    )
}

/// The planes the piece may be cut along, best first. Through two points: the interior vertex of
/// largest angle deficit (where the surface's curvature concentrates: on a section it is a
/// boundary vertex of both sides, free to open), and the area centroid. Of the planes through
/// either that leave at least [`MIN_BALANCE`] of the area on either side, those through the
/// vertex come first, each group by increasing section length; then the other planes by
/// decreasing balance; then all of them shifted by [`SHIFT`] of the mean edge length either
/// way, for a piece every one of those planes touches at a vertex.
fn section_planes(model: &FacetModel) -> Vec<Plane> {
    let (centroid, axes) = principal_axes(model);
    let normals = candidate_normals(axes);
    let peak = peak_vertex(model).map(|v| model.positions()[v]);
    let points = peak.into_iter().chain([centroid]);
    let mut candidates: Vec<(usize, Plane, f64, f64)> = points
        .enumerate()
        .flat_map(|(rank, point)| normals.map(|normal| (rank, Plane::through(point, normal))))
        .map(|(rank, plane)| {
            let (length, balance) = section_estimate(model, plane);
            (rank, plane, length, balance)
        })
        .filter(|&(_, _, _, balance)| balance > 0.0)
        .collect();
    let key = |&(rank, _, length, balance): &(usize, Plane, f64, f64)| {
        if balance >= MIN_BALANCE {
            (rank, length)
        } else {
            (2, -balance)
        }
    };
    candidates.sort_by(|a, b| {
        let (ka, kb) = (key(a), key(b));
        ka.0.cmp(&kb.0).then(ka.1.total_cmp(&kb.1))
    });
    let shift = SHIFT * mean_edge_length(model);
    let unshifted: Vec<Plane> = candidates
        .into_iter()
        .map(|(_, plane, _, _)| plane)
        .collect();
    let shifted = (unshifted.iter()).flat_map(|plane| {
        [shift, -shift].map(|by| Plane {
            offset: plane.offset + by,
            ..*plane
        })
    });
    unshifted.iter().copied().chain(shifted).collect()
}

/// The planes through the model's interior vertex of largest angle deficit along the candidate
/// normals of [`section_planes`] and along the spike there (from its neighbours' centroid to it),
/// by increasing section length, however little area they leave on a side; none when no
/// interior vertex holds curvature.
fn planes_through_peak(model: &FacetModel) -> Vec<Plane> {
    let Some(peak) = peak_vertex(model) else {
        return Vec::new();
    };
    let (_, axes) = principal_axes(model);
    let tip = model.positions()[peak];
    // A spike's tip lies beyond its neighbours along every axis of a small piece around it:
    // planes through it across those axes touch it, so planes along the spike are tried too.
    let neighbours: Vec<DVec3> = (model.vertex_faces(peak as u32).iter())
        .flat_map(|&f| model.triangles()[f as usize])
        .map(|w| model.positions()[w as usize])
        .collect();
    let spike = tip - neighbours.iter().sum::<DVec3>() / neighbours.len().max(1) as f64;
    let along_spike = axes.map(|axis| spike.cross(axis).normalize_or_zero());
    let mut planes: Vec<(f64, Plane)> = (candidate_normals(axes).into_iter())
        .chain(
            along_spike
                .into_iter()
                .filter(|normal| *normal != DVec3::ZERO),
        )
        .map(|normal| Plane::through(tip, normal))
        .map(|plane| (section_estimate(model, plane).0, plane))
        .collect();
    planes.sort_by(|a, b| a.0.total_cmp(&b.0));
    planes.into_iter().map(|(_, plane)| plane).collect()
}

/// The interior vertex of largest absolute angle deficit, if any holds curvature.
fn peak_vertex(model: &FacetModel) -> Option<usize> {
    let deficits = model.angle_deficits();
    (0..deficits.len())
        .max_by(|&a, &b| deficits[a].abs().total_cmp(&deficits[b].abs()))
        .filter(|&v| deficits[v].abs() > FLAT_DEFICIT)
}

/// The normals of the candidate planes of a piece with these principal axes: its two axes of
/// largest spread and their two bisectors.
fn candidate_normals(axes: [DVec3; 3]) -> [DVec3; 4] {
    [
        axes[0],
        axes[1],
        (axes[0] + axes[1]).normalize(),
        (axes[0] - axes[1]).normalize(),
    ]
}

/// The mean length of the model's edges.
fn mean_edge_length(model: &FacetModel) -> f64 {
    let positions = model.positions();
    let total: f64 = (model.edges().iter())
        .map(|&[a, b]| positions[a as usize].distance(positions[b as usize]))
        .sum();
    total / model.edges().len().max(1) as f64
}

/// The length of the section curve of `plane` (crossing points not snapped; an edge lying in the
/// plane counts half in each of its faces) and the smaller share of the area on one side (faces
/// counted by their centroid).
fn section_estimate(model: &FacetModel, plane: Plane) -> (f64, f64) {
    let positions = model.positions();
    let (mut length, mut positive, mut total) = (0.0, 0.0, 0.0);
    for (f, t) in model.triangles().iter().enumerate() {
        let corners = t.map(|v| positions[v as usize]);
        let d = corners.map(|p| plane.distance(p));
        let area = model.triangle_area(f);
        total += area;
        if d[0] + d[1] + d[2] > 0.0 {
            positive += area;
        }
        length += face_section_length(corners, d);
    }
    let balance = if total > 0.0 {
        positive.min(total - positive) / total
    } else {
        0.0
    };
    (length, balance)
}

/// The length of a plane's section of one face, from its corners' signed distances `d`: the
/// segment between its two crossing points (a corner on the plane is one), half an edge lying
/// in the plane (its other face has the other half), nothing else.
fn face_section_length(corners: [DVec3; 3], d: [f64; 3]) -> f64 {
    let on_plane: Vec<usize> = (0..3).filter(|&k| d[k] == 0.0).collect();
    if let [a, b] = on_plane[..] {
        return 0.5 * corners[a].distance(corners[b]);
    }
    let mut points: Vec<DVec3> = on_plane.iter().map(|&k| corners[k]).collect();
    for k in 0..3 {
        let j = (k + 1) % 3;
        if d[k] * d[j] < 0.0 {
            points.push(corners[k].lerp(corners[j], d[k] / (d[k] - d[j])));
        }
    }
    match points[..] {
        [a, b] => a.distance(b),
        _ => 0.0,
    }
}

/// One side's piece of `section`, its vertices, stiffness and section edges carried over from
/// its parent.
fn child(parent: &Piece, side: SectionPiece, section: SectionId) -> Piece {
    let part_vertex = (side.vertex_origins.iter())
        .map(|origin| parent.part_vertex[origin.nearer_vertex(&parent.model) as usize])
        .collect();
    let factors = parent.stiffness.factors();
    let factor_of = |e: u32| factors.get(e as usize).copied();
    let stiffness = (side.edge_origins.iter())
        .map(|origin| match *origin {
            EdgeOrigin::OnEdge(e) => factor_of(e).unwrap_or(1.0),
            EdgeOrigin::InFace(crossed) => (crossed.iter())
                .filter(|&&e| e != NONE)
                .filter_map(|&e| factor_of(e))
                .fold(1.0, f64::max),
        })
        .collect();
    let section_edges = (side.edge_origins.iter())
        .zip(&side.on_section)
        .map(|(origin, &on)| match *origin {
            _ if on => Some(section),
            EdgeOrigin::OnEdge(e) => parent.section_edges[e as usize],
            EdgeOrigin::InFace(_) => None,
        })
        .collect();
    Piece {
        model: side.model,
        stiffness: Stiffness::from_factors(stiffness),
        part_vertex,
        section_edges,
        depth: parent.depth + 1,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Plane;
    use crate::mesh::test_grid as grid;
    use crate::mesh::{TriangleSoup, validate};

    #[test]
    fn a_pair_waits_while_a_piece_of_it_or_of_a_waiting_pair_before_it_is_being_tried() {
        let mut queue = PairQueue::new(vec![(0, 1), (1, 2), (3, 4), (2, 5), (6, 7), (8, 9)]);
        let mut in_flight = BTreeSet::new();
        let mut next = |in_flight: &mut BTreeSet<usize>,
                        untried: &dyn Fn((usize, usize)) -> bool| {
            let pair = queue.next_ready(in_flight, untried);
            in_flight.extend(pair.iter().flat_map(|&(i, j)| [i, j]));
            pair
        };
        // (1, 2) shares piece 1 with (0, 1); (2, 5) shares piece 2 with the waiting (1, 2).
        let all = |_: (usize, usize)| true;
        assert_eq!(next(&mut in_flight, &all), Some((0, 1)));
        assert_eq!(next(&mut in_flight, &all), Some((3, 4)));
        assert_eq!(next(&mut in_flight, &all), Some((6, 7)));
        // Pieces 0 and 1 glued: (1, 2) is dropped, and (2, 5) comes before (8, 9).
        in_flight.retain(|&piece| piece > 1);
        let glued = [0, 1];
        let untried = |(i, j): (usize, usize)| !glued.contains(&i) && !glued.contains(&j);
        assert_eq!(next(&mut in_flight, &untried), Some((2, 5)));
        assert_eq!(next(&mut in_flight, &untried), Some((8, 9)));
        assert_eq!(next(&mut in_flight, &untried), None);
    }

    #[test]
    fn a_pair_after_a_waiting_pair_of_its_piece_waits_behind_it() {
        let mut queue = PairQueue::new(vec![(0, 1), (1, 2), (2, 3)]);
        assert_eq!(queue.next_ready(&BTreeSet::new(), |_| true), Some((0, 1)));
        // (1, 2) waits for (0, 1); (2, 3) shares piece 2 with it and waits behind it.
        assert_eq!(queue.next_ready(&BTreeSet::from([0, 1]), |_| true), None);
        assert_eq!(queue.next_ready(&BTreeSet::new(), |_| true), Some((1, 2)));
        assert_eq!(queue.next_ready(&BTreeSet::from([1, 2]), |_| true), None);
        assert_eq!(queue.next_ready(&BTreeSet::new(), |_| true), Some((2, 3)));
    }

    #[test]
    fn a_pair_far_over_the_tolerance_is_not_tried_again_inside_larger_pieces() {
        let mut log = GluingLog::new(5);
        log.failure((0, 1), true);
        log.failure((2, 3), false);
        assert!(!log.is_to_try((0, 1)) && !log.is_to_try((2, 3)));
        // Piece 5 holds 0, piece 6 holds 5 and 3: 6 with 1 holds the far pair (0, 1).
        assert_eq!(log.union((0, 4)), 5);
        assert_eq!(log.union((3, 5)), 6);
        assert!(!log.is_to_try((1, 5)) && !log.is_to_try((6, 1)));
        // A pair just over the tolerance is tried again inside a larger one.
        assert!(log.is_to_try((6, 2)));
    }

    #[test]
    fn a_strip_is_cut_across_its_middle_where_the_section_is_shortest() {
        let model = grid(20, 4);
        let plane = section_planes(&model)[0];
        assert!(plane.normal.dot(DVec3::X).abs() > 1.0 - 1e-9, "{plane:?}");
        assert!((plane.distance(DVec3::new(10.0, 2.0, 0.0))).abs() < 1e-9);
        let (length, balance) = section_estimate(&model, plane);
        assert!((length - 4.0).abs() < 1e-9, "{length}");
        assert!((balance - 0.5).abs() < 1e-9, "{balance}");
    }

    #[test]
    fn a_cone_is_cut_through_its_apex_where_its_curvature_is() {
        let ring = 12;
        let mut positions = vec![DVec3::new(0.1, 0.0, 1.0)];
        positions.extend((0..ring).map(|k| {
            let angle = std::f64::consts::TAU * k as f64 / ring as f64;
            DVec3::new(angle.cos(), angle.sin(), 0.0)
        }));
        let triangles = (0..ring).map(|k| [0, 1 + k, 1 + (k + 1) % ring]).collect();
        let model = validate(&TriangleSoup::new(positions.clone(), triangles))
            .unwrap()
            .components
            .remove(0);
        let plane = section_planes(&model)[0];
        assert_eq!(plane.distance(positions[0]), 0.0, "{plane:?}");
        let sides = section(&model, plane).expect("two sides");
        assert_eq!(sides.len(), 2);
        for side in &sides {
            let apex = (side.vertex_origins.iter())
                .position(|origin| *origin == crate::mesh::VertexOrigin::Vertex(0))
                .expect("the apex is on both sides");
            assert!(
                side.model.angle_deficits()[apex] == 0.0,
                "a boundary vertex"
            );
        }
    }

    #[test]
    fn a_flat_part_is_one_piece_and_keeps_its_vertices() {
        let model = grid(6, 3);
        let pieces = cut_into_pieces(
            &model,
            &Stiffness::uniform(&model),
            &FlattenOptions::default(),
            &NoProgress,
        )
        .expect("flattens");
        assert_eq!(pieces.len(), 1);
        assert_eq!(pieces[0].stop, CutStop::ToleranceMet);
        assert!(pieces[0].seams.is_empty());
        let identity: Vec<u32> = (0..model.vertex_count() as u32).collect();
        assert_eq!(pieces[0].original_vertex, identity);
    }

    /// The pieces of `piece` on either side of the plane through `point` with `normal`.
    fn across(piece: &Piece, point: DVec3, normal: DVec3) -> Vec<Piece> {
        let plane = Plane::through(point, normal);
        (section(&piece.model, plane).expect("two sides"))
            .into_iter()
            .map(|side| child(piece, side, SectionId::of(plane)))
            .collect()
    }

    #[test]
    fn a_section_crossing_the_shared_curve_on_one_side_still_glues_whole() {
        let model = grid(20, 4);
        let whole = Piece::whole(&model, &Stiffness::uniform(&model));
        let [right, left] =
            <[Piece; 2]>::try_from(across(&whole, DVec3::new(10.0, 0.0, 0.0), DVec3::X))
                .expect("two halves");
        // The right half alone is cut across the shared curve, inside its edge (10, 1)-(10, 2).
        let [upper, lower] =
            <[Piece; 2]>::try_from(across(&right, DVec3::new(0.0, 1.5, 0.0), DVec3::Y))
                .expect("two quarters");
        let perimeter = |piece: &Piece| -> f64 {
            let positions = piece.model.positions();
            (piece.model.boundary_sides())
                .map(|[a, b]| positions[a as usize].distance(positions[b as usize]))
                .sum()
        };
        let cracked = left.glued(&lower).expect("they share (10, 0)-(10, 1)");
        assert!(
            (perimeter(&cracked) - 49.0).abs() < 1e-9,
            "a crack: {}",
            perimeter(&cracked)
        );

        let (left_conformed, lower_conformed) = conformed_pair(&left, &lower);
        let union = left_conformed.glued(&lower_conformed).expect("glued");
        assert!(
            (perimeter(&union) - 48.0).abs() < 1e-9,
            "no crack: {}",
            perimeter(&union)
        );
        assert_eq!(union.model.boundary_loops().len(), 1);
        assert!((union.model.area() - 55.0).abs() < 1e-9);
        let (union, upper) = conformed_pair(&union, &upper);
        let all = union
            .glued(&upper)
            .expect("the rest of the curve matches the upper quarter");
        assert!(all.section_sides().is_empty(), "no section left");
        assert!((all.model.area() - 80.0).abs() < 1e-9);
        assert!((perimeter(&all) - 48.0).abs() < 1e-9);
    }

    #[test]
    fn a_sliver_cut_off_a_corner_is_glued_back_and_a_large_piece_is_not() {
        let model = grid(20, 4);
        let options = FlattenOptions::default();
        // The sides of a section of the whole strip, each with its valid flattening.
        let flattened_sides = |plane: Plane| -> Vec<(Piece, CutResult)> {
            let whole = Piece::whole(&model, &Stiffness::uniform(&model));
            (section(&model, plane).expect("two sides"))
                .into_iter()
                .map(|side| {
                    let piece = child(&whole, side, SectionId::of(plane));
                    let pattern = flatten_piece(&piece, &options, &NoProgress).expect("flat");
                    (piece, pattern)
                })
                .collect()
        };
        let corner = Plane::through(DVec3::new(0.4, 0.4, 0.0), DVec3::new(1.0, 1.0, 0.0));
        let pieces = flattened_sides(corner);
        let counts: Vec<usize> = (pieces.iter())
            .map(|(piece, _)| piece.model.triangle_count())
            .collect();
        assert_eq!(counts.len(), 2);
        assert!(
            counts.iter().any(|&count| count < SLIVER_TRIANGLES),
            "{counts:?}"
        );
        let glued = without_slivers(pieces, &options);
        assert_eq!(glued.len(), 1);
        assert!((glued[0].0.model.area() - 80.0).abs() < 1e-9);
        assert!(glued[0].0.section_sides().is_empty());
        assert!(is_within(&glued[0].1, options.tolerance));

        // Two large pieces are left as they are.
        let across = Plane::through(DVec3::new(10.0, 0.0, 0.0), DVec3::X);
        assert_eq!(without_slivers(flattened_sides(across), &options).len(), 2);
    }

    /// A strip cut across at x = 10, then its left half along y = 2: the lower left quarter's
    /// section boundary turns a corner where the two sections meet, and it is two seams, one
    /// per section, not one curve with a corner inside.
    #[test]
    fn a_piece_bounded_by_two_sections_has_a_seam_for_each() {
        let model = grid(20, 4);
        let whole = Piece::whole(&model, &Stiffness::uniform(&model));
        let halves = across(&whole, DVec3::new(10.0, 0.0, 0.0), DVec3::X);
        let left = (halves.iter())
            .find(|half| half.model.positions().iter().all(|p| p.x <= 10.0))
            .expect("a left half");
        let quarters = across(left, DVec3::new(0.0, 2.0, 0.0), DVec3::Y);
        let lower = (quarters.iter())
            .find(|quarter| quarter.model.positions().iter().all(|p| p.y <= 2.0))
            .expect("a lower quarter");
        let mut lengths: Vec<f64> = section_seams(lower).iter().map(|s| s.length).collect();
        lengths.sort_by(f64::total_cmp);
        assert_eq!(lengths.len(), 2, "{lengths:?}");
        assert!((lengths[0] - 2.0).abs() < 1e-9 && (lengths[1] - 10.0).abs() < 1e-9);
    }

    /// A needle (three long faces round a tip far above their base) smaller than any piece the
    /// usual planes cut: its tip, of angle sum far below 2π, would stay inside it whatever its
    /// size. The planes through the tip include one along the needle that opens it, leaving the
    /// tip on the boundary of both sides.
    #[test]
    fn a_spike_is_opened_by_a_plane_along_it() {
        let base = |k: f64| {
            let angle = std::f64::consts::TAU * k / 3.0 + 0.3;
            DVec3::new(angle.cos(), angle.sin(), 0.0)
        };
        let tip = DVec3::new(0.2, -0.1, 8.0);
        let soup = TriangleSoup::new(
            vec![tip, base(0.0), base(1.0), base(2.0)],
            vec![[0, 1, 2], [0, 2, 3], [0, 3, 1]],
        );
        let model = validate(&soup).unwrap().components.remove(0);
        let planes = planes_through_peak(&model);
        assert!(planes.iter().all(|plane| plane.distance(tip).abs() < 1e-12));
        let sides = (planes.into_iter())
            .find_map(|plane| section(&model, plane))
            .expect("a plane through the tip cuts the needle");
        assert_eq!(sides.len(), 2);
        for side in &sides {
            let m = &side.model;
            let at_tip = (m.positions().iter())
                .position(|&p| p == tip)
                .expect("each side holds the tip") as u32;
            assert!(
                m.boundary_flags()[at_tip as usize],
                "the tip is on the boundary"
            );
        }
    }

    #[test]
    fn the_halves_of_a_strip_carry_its_stiffness_and_mark_their_section_edges() {
        let model = grid(20, 4);
        let mut stiffness = Stiffness::uniform(&model);
        stiffness.raise_where(3.0, |_| true);
        let piece = Piece {
            part_vertex: (0..model.vertex_count() as u32).collect(),
            section_edges: vec![None; model.edges().len()],
            stiffness,
            model,
            depth: 0,
        };
        let halves = halves(&piece, section_planes(&piece.model)).expect("two halves");
        assert_eq!(halves.len(), 2);
        for half in &halves {
            assert!(half.stiffness.factors().iter().all(|&f| f == 3.0));
            let seams = section_seams(half);
            assert_eq!(seams.len(), 1);
            assert!((seams[0].length - 4.0).abs() < 1e-9);
            assert_eq!(half.depth, 1);
        }
    }
}
