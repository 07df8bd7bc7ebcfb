//! The stage's entry points: phase one (the initial pattern) then phase two (the energy
//! minimised by the chosen solver), the pattern moved to the origin, and its figures.

use std::time::Instant;

use glam::DVec2;

use super::accuracy::{
    Accuracy, DEGENERATE_AREA_RATIO, boundary_self_intersects, flipped_triangles,
    squeezed_triangles,
};
use super::energy_release::{EnergyRelease, ReleaseOutcome, ReleaseParameters, StopReason};
use super::errors::FlattenError;
use super::fast::{FastOptions, FastSolver};
use super::flattened::{FlattenStats, Flattened};
use super::init_flatten::{InitRelease, NEIGHBOURHOOD_SWEEPS, init_flatten};
use super::injective::{
    Barrier, FlipFreeSettings, OPENING_BARRIER, Outline, SLIVER_BARRIER, flip_free_flatten,
    flip_free_solve_moving, near_triangles, repaired_locally,
};
use super::options::{FlattenOptions, Solver};
use super::orient::move_to_origin;
use super::springs::SpringSystem;
use super::stiffness::Stiffness;
use crate::mesh::FacetModel;
use crate::progress::Progress;

/// Flattens a facet model with per-edge stiffness factors.
pub fn flatten(
    model: &FacetModel,
    stiffness: &Stiffness,
    options: &FlattenOptions,
    progress: &dyn Progress,
) -> Result<Flattened, FlattenError> {
    flatten_cold(model, stiffness, options, progress, Repair::FlipFree)
}

/// [`flatten`] without the flip-free repair: the fast solver's pattern as it comes, flipped
/// triangles and all. For a cold re-flattening tried beside a valid warm one, where a flipped
/// result is discarded anyway and the repair (a Newton solve from a Tutte start) would be
/// wasted.
pub fn flatten_unrepaired(
    model: &FacetModel,
    stiffness: &Stiffness,
    options: &FlattenOptions,
    progress: &dyn Progress,
) -> Result<Flattened, FlattenError> {
    flatten_cold(model, stiffness, options, progress, Repair::None)
}

/// Vertices this many rings around a squeezed triangle move when it is opened
/// ([`open_squeezed_triangles`]).
pub const OPENING_RINGS: usize = 3;
/// Newton iterations at most of opening squeezed triangles ([`open_squeezed_triangles`]).
pub const OPENING_ITERATIONS: usize = 50;

/// Whether a fast-solver pattern with flipped triangles is made again without any.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Repair {
    /// By [`flip_free_flatten`].
    FlipFree,
    /// Not at all.
    None,
}

/// Phase one, then [`finish`] with `repair`.
fn flatten_cold(
    model: &FacetModel,
    stiffness: &Stiffness,
    options: &FlattenOptions,
    progress: &dyn Progress,
    repair: Repair,
) -> Result<Flattened, FlattenError> {
    let started = Instant::now();
    check_input(model, stiffness)?;
    let springs = SpringSystem::new(model, stiffness.factors(), options.spring_constant);
    let release = match options.solver {
        Solver::Paper => InitRelease::WholeSystem {
            steps: options.init_release_steps,
            time_step: options.time_step,
        },
        Solver::Fast => InitRelease::Neighbourhood {
            sweeps: NEIGHBOURHOOD_SWEEPS,
        },
    };
    let positions = init_flatten(model, &springs, release, progress);
    finish(model, &springs, positions, options, repair, started)
}

/// Flattens a facet model from given flat positions (a warm start: phase one is skipped), for
/// the cut → re-flatten loop, where the pattern before a cut is a good start for the cut model.
/// `initial[v]` is the start of vertex `v`; a missing or extra entry is an error.
pub fn flatten_from(
    model: &FacetModel,
    stiffness: &Stiffness,
    initial: &[DVec2],
    options: &FlattenOptions,
) -> Result<Flattened, FlattenError> {
    flatten_warm(model, stiffness, initial, options, Repair::FlipFree)
}

/// As [`flatten_from`], but a fast-solver pattern with flipped triangles is kept as it is (as
/// [`flatten_unrepaired`] keeps it): a quick look at how flat the model lies from a start.
pub fn flatten_unrepaired_from(
    model: &FacetModel,
    stiffness: &Stiffness,
    initial: &[DVec2],
    options: &FlattenOptions,
) -> Result<Flattened, FlattenError> {
    flatten_warm(model, stiffness, initial, options, Repair::None)
}

/// Phase two from `initial`, then [`finish`] with `repair`.
fn flatten_warm(
    model: &FacetModel,
    stiffness: &Stiffness,
    initial: &[DVec2],
    options: &FlattenOptions,
    repair: Repair,
) -> Result<Flattened, FlattenError> {
    let started = Instant::now();
    check_input(model, stiffness)?;
    if initial.len() != model.vertex_count() {
        return Err(FlattenError::InitialMismatch {
            expected: model.vertex_count(),
            found: initial.len(),
        });
    }
    let springs = SpringSystem::new(model, stiffness.factors(), options.spring_constant);
    finish(model, &springs, initial.to_vec(), options, repair, started)
}

/// The flip-free flattening with the outline kept from crossing itself: a Tutte start (no
/// flipped triangle, no crossing), then the shaping and orientation stages of
/// [`flip_free_flatten`] with the boundary barrier ([`Outline::Kept`]). For a part whose pattern
/// overlaps itself; `None` when the minimiser cannot run (a system that does not factor).
pub fn overlap_free_flatten(
    model: &FacetModel,
    stiffness: &Stiffness,
    options: &FlattenOptions,
) -> Result<Option<Flattened>, FlattenError> {
    let started = Instant::now();
    check_input(model, stiffness)?;
    let springs = SpringSystem::new(model, stiffness.factors(), options.spring_constant);
    let Ok((mut positions, outcome)) = flip_free_flatten(
        model,
        &springs,
        options.fast.max_iterations,
        options.deadline,
        Outline::Kept,
    ) else {
        return Ok(None);
    };
    move_to_origin(&mut positions);
    let accuracy = Accuracy::measure(model, &positions);
    let stats = FlattenStats {
        accuracy,
        initial_accuracy: accuracy,
        energy: springs.energy(&positions),
        iterations: outcome.iterations,
        stop_reason: outcome.stop_reason,
        seconds: started.elapsed().as_secs_f64(),
    };
    Ok(Some(Flattened { positions, stats }))
}

/// Refuses closed surfaces and stiffness maps of another model.
fn check_input(model: &FacetModel, stiffness: &Stiffness) -> Result<(), FlattenError> {
    if model.is_closed() {
        return Err(FlattenError::ClosedSurface);
    }
    if stiffness.factors().len() != model.edges().len() {
        return Err(FlattenError::StiffnessMismatch {
            expected: model.edges().len(),
            found: stiffness.factors().len(),
        });
    }
    Ok(())
}

/// Phase two from the initial pattern `positions` (with `repair` of a flipped fast-solver
/// pattern), then the figures.
fn finish(
    model: &FacetModel,
    springs: &SpringSystem,
    mut positions: Vec<DVec2>,
    options: &FlattenOptions,
    repair: Repair,
    started: Instant,
) -> Result<Flattened, FlattenError> {
    let initial_accuracy = Accuracy::measure(model, &positions);
    let (iterations, stop_reason) = match options.solver {
        Solver::Paper => {
            let outcome = relax(model, springs, &mut positions, options);
            (outcome.steps, outcome.stop_reason)
        }
        Solver::Fast => minimise(model, springs, &mut positions, options, repair)?,
    };
    move_to_origin(&mut positions);
    let stats = FlattenStats {
        accuracy: Accuracy::measure(model, &positions),
        initial_accuracy,
        energy: springs.energy(&positions),
        iterations,
        stop_reason,
        seconds: started.elapsed().as_secs_f64(),
    };
    Ok(Flattened { positions, stats })
}

/// Phase two of the paper's solver: EnergyRelease over the whole model.
fn relax(
    model: &FacetModel,
    springs: &SpringSystem,
    positions: &mut [DVec2],
    options: &FlattenOptions,
) -> ReleaseOutcome {
    let energy = EnergyRelease::new(model, springs);
    let system = energy.whole_system();
    let parameters = ReleaseParameters {
        time_step: options.time_step,
        energy_variation: options.energy_variation,
        tolerance: options.tolerance,
        max_steps: options.max_steps,
        deadline: options.deadline,
    };
    energy.release(&system, positions, &parameters, true)
}

/// Phase two of the fast solver: the spring energy minimised by
/// [`FastSolver`](super::fast::FastSolver); returns the iterations and why it stopped.
///
/// The fast solver never flips a triangle that is positive in its start, but it keeps the flips
/// of a start that has them (phase one folds strongly curved parts). When its pattern has a
/// flipped triangle, the vertices near the flips are placed afresh and relaxed, the rest held
/// ([`repaired_locally`]), and the fast solver goes on from there, which keeps every triangle
/// positive. When that region cannot be made without flips and the model has a boundary, the
/// pattern is made again by the flip-free flattening ([`flip_free_flatten`]: a Tutte embedding,
/// then the spring energy with a barrier on triangle orientation, minimised by projected Newton
/// with flip-free steps, at most the fast solver's iteration budget per stage), which has none;
/// the iterations then count every solver's.
/// A pattern without flipped triangles is kept as it is, so good results do not change. When the
/// flip-free flattening cannot run (a closed model, a system that does not factor) the fast solver's
/// pattern stays, flips and all, and the part is judged by it.
fn minimise(
    model: &FacetModel,
    springs: &SpringSystem,
    positions: &mut Vec<DVec2>,
    options: &FlattenOptions,
    repair: Repair,
) -> Result<(usize, StopReason), FlattenError> {
    let fast_options = FastOptions {
        deadline: options.deadline,
        ..options.fast
    };
    let solver = FastSolver::in_order(model, springs, fast_options, options.fill_order.as_deref())?;
    let fast = solver.solve(positions);
    if repair == Repair::None || flipped_triangles(model, positions) == 0 {
        return Ok((fast.iterations, fast.stop_reason));
    }
    if let Some((mut repaired, newton)) =
        repaired_locally(model, springs, positions, options.deadline)
    {
        let again = solver.solve(&mut repaired);
        // The fast solver keeps positive triangles positive; checked all the same.
        if flipped_triangles(model, &repaired) == 0 {
            *positions = repaired;
            let iterations = fast.iterations + newton + again.iterations;
            return Ok((iterations, again.stop_reason));
        }
    }
    Ok(
        match flip_free_flatten(
            model,
            springs,
            options.fast.max_iterations,
            options.deadline,
            Outline::Free,
        ) {
            Ok((pattern, injective)) => {
                *positions = pattern;
                (
                    fast.iterations + injective.iterations,
                    injective.stop_reason,
                )
            }
            Err(_) => (fast.iterations, fast.stop_reason),
        },
    )
}

/// A finished pattern with its squeezed triangles opened (`open_squeezed_triangles`), its
/// figures measured again. The solvers' patterns can hold triangles squeezed to slivers (they
/// keep triangles from flipping, not from collapsing), which leave a notch in the outline and are
/// degenerate at worst; the cut stage opens its final patterns. Triangles below half their area
/// are opened first ([`OPENING_BARRIER`]); when that does not pay (`opening_pays`: it would
/// leave the tolerance, `options.tolerance`, that the pattern met, or raise its errors), only
/// slivers below a hundredth of their area are ([`SLIVER_BARRIER`], moving their corners only),
/// and when that does not pay either, the pattern stays as it is.
pub fn with_squeezed_triangles_opened(
    model: &FacetModel,
    stiffness: &Stiffness,
    flattened: Flattened,
    options: &FlattenOptions,
) -> Flattened {
    // The opening barrier acts above the sliver barrier: nothing squeezed for it, nothing to do.
    if squeezed_triangles(model, &flattened.positions, OPENING_BARRIER.threshold).is_empty() {
        return flattened;
    }
    let springs = SpringSystem::new(model, stiffness.factors(), options.spring_constant);
    let before = Squeezed::measure(model, &flattened.positions);
    for (barrier, rings) in [(OPENING_BARRIER, OPENING_RINGS), (SLIVER_BARRIER, 0)] {
        let mut positions = flattened.positions.clone();
        let opening = Opening { barrier, rings };
        let iterations = open_squeezed_triangles(model, &springs, &mut positions, opening, options);
        if iterations == 0 {
            continue;
        }
        move_to_origin(&mut positions);
        let opened = Squeezed::measure(model, &positions);
        if !opening_pays(&before, &opened, options.tolerance) {
            continue;
        }
        let accuracy = opened.accuracy;
        let stats = FlattenStats {
            accuracy,
            energy: springs.energy(&positions),
            iterations: flattened.stats.iterations + iterations,
            ..flattened.stats
        };
        return Flattened { positions, stats };
    }
    flattened
}

/// Whether an opened pattern (`after`) replaces the pattern it was opened from (`before`): when
/// it is valid and within `tolerance`, or valid where `before` is not (a degenerate triangle
/// makes a pattern invalid here), or when neither is within it and its larger error is no
/// larger.
fn opening_pays(before: &Squeezed, after: &Squeezed, tolerance: f64) -> bool {
    let valid = |s: &Squeezed| s.accuracy.flipped == 0 && !s.accuracy.overlap && s.degenerate == 0;
    let within = |s: &Squeezed| valid(s) && s.accuracy.within(tolerance);
    within(after)
        || (valid(after) && !valid(before))
        || (valid(after)
            && !within(before)
            && after.accuracy.larger_error() <= before.accuracy.larger_error())
}

/// A pattern's figures and its degenerate triangles (at most [`DEGENERATE_AREA_RATIO`] of their
/// 3D area: slivers the metrics count apart from the flipped ones).
struct Squeezed {
    accuracy: Accuracy,
    degenerate: usize,
}

impl Squeezed {
    fn measure(model: &FacetModel, positions: &[DVec2]) -> Self {
        let degenerate = squeezed_triangles(model, positions, DEGENERATE_AREA_RATIO).len()
            - flipped_triangles(model, positions);
        Self {
            accuracy: Accuracy::measure(model, positions),
            degenerate,
        }
    }
}

/// How squeezed triangles are opened: the barrier (its threshold says which are squeezed) and
/// how many rings of vertices around them move.
#[derive(Debug, Clone, Copy)]
struct Opening {
    barrier: Barrier,
    rings: usize,
}

/// Opens the triangles of a pattern without flipped triangles that are squeezed below the
/// threshold of `opening`'s barrier: the fast solver keeps triangles from flipping, not from
/// collapsing into slivers, which it approaches as closely as rounding allows where the springs
/// hardly resist (an obtuse boundary triangle whose corner moves onto its opposite side), and the
/// flip-free flattening's own barrier is weak. The spring energy plus the barrier is minimised by
/// the flip-free solver moving only the vertices within `opening`'s rings of the squeezed
/// triangles (the rest of the pattern, which the solvers settled, stays), with the outline kept
/// from crossing itself when it does not already. Returns the Newton iterations taken; the
/// pattern is left as it is when it has a flipped triangle or none squeezed, or the solver cannot
/// run.
fn open_squeezed_triangles(
    model: &FacetModel,
    springs: &SpringSystem,
    positions: &mut [DVec2],
    opening: Opening,
    options: &FlattenOptions,
) -> usize {
    let Opening { barrier, rings } = opening;
    let squeezed = squeezed_triangles(model, positions, barrier.threshold);
    if squeezed.is_empty() || flipped_triangles(model, positions) > 0 {
        return 0;
    }
    let outline = if boundary_self_intersects(model, positions) {
        Outline::Free
    } else {
        Outline::Kept
    };
    let moving = near_triangles(model, &squeezed, rings);
    let mut opened = positions.to_vec();
    let settings = FlipFreeSettings {
        barrier,
        max_iterations: OPENING_ITERATIONS,
        deadline: options.deadline,
        outline,
    };
    match flip_free_solve_moving(model, springs, &mut opened, &moving, settings) {
        Ok(outcome) => {
            positions.copy_from_slice(&opened);
            outcome.iterations
        }
        Err(_) => 0,
    }
}

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3};

    use crate::cad::TriangleSoup;
    use crate::flatten::accuracy::{Accuracy, DEGENERATE_AREA_RATIO, squeezed_triangles};
    use crate::flatten::energy_release::StopReason;
    use crate::flatten::entry::{flatten, overlap_free_flatten, with_squeezed_triangles_opened};
    use crate::flatten::flattened::{FlattenStats, Flattened};
    use crate::flatten::options::{FlattenOptions, Solver};
    use crate::flatten::samples::{deep_bowl, sample};
    use crate::flatten::stiffness::Stiffness;
    use crate::mesh::{FacetModel, validate};
    use crate::progress::NoProgress;

    #[test]
    fn fast_ends_at_or_below_the_paper_solvers_energy() {
        for name in ["hemisphere.obj", "saddle.obj"] {
            let model = sample(name);
            let stiffness = Stiffness::uniform(&model);
            let run = |solver| {
                let options = FlattenOptions {
                    solver,
                    ..FlattenOptions::default()
                };
                flatten(&model, &stiffness, &options, &NoProgress).expect("flattens")
            };
            let (fast, paper) = (run(Solver::Fast).stats, run(Solver::Paper).stats);
            assert!(fast.energy <= paper.energy, "{name}: {fast:?} {paper:?}");
            assert!(
                fast.accuracy.shape_error <= paper.accuracy.shape_error,
                "{name}: {fast:?} {paper:?}"
            );
            assert_eq!(fast.accuracy.flipped + paper.accuracy.flipped, 0, "{name}");
        }
    }

    #[test]
    fn a_folded_fast_pattern_of_a_disk_is_made_again_without_flips() {
        let model = deep_bowl(0.85 * std::f64::consts::PI, 16, 48);
        let stiffness = Stiffness::uniform(&model);
        let flattened =
            flatten(&model, &stiffness, &FlattenOptions::default(), &NoProgress).expect("flattens");
        let accuracy = Accuracy::measure(&model, &flattened.positions);
        assert_eq!(accuracy.flipped, 0, "{:?}", flattened.stats);
        assert!(
            flattened.stats.initial_accuracy.flipped > 0,
            "phase one folds the bowl"
        );
    }

    /// A fan of 16 triangles around a saddle vertex (the rim waves up and down three times), slit
    /// along one spoke: its angles at the centre add up to more than a full turn, so any
    /// near-isometric flattening lays the slit's two sides over each other.
    fn slit_saddle_fan() -> (FacetModel, f64) {
        let n = 16;
        let mut positions = vec![DVec3::ZERO];
        for i in 0..=n {
            let angle = std::f64::consts::TAU * i as f64 / n as f64;
            positions.push(DVec3::new(
                angle.cos(),
                angle.sin(),
                0.7 * (3.0 * angle).cos(),
            ));
        }
        let triangles: Vec<[u32; 3]> = (1..=n as u32).map(|i| [0, i, i + 1]).collect();
        let model = validate(&TriangleSoup::new(positions, triangles))
            .expect("valid")
            .components
            .remove(0);
        let turn: f64 = (1..=n)
            .map(|i| {
                let (a, b) = (model.positions()[i], model.positions()[i + 1]);
                (a.dot(b) / (a.length() * b.length())).acos()
            })
            .sum();
        (model, turn)
    }

    /// True if two boundary edges that share no vertex cross (checked pair by pair).
    fn outline_crosses(model: &FacetModel, pattern: &[DVec2]) -> bool {
        let edges: Vec<[u32; 2]> = model
            .boundary_loops()
            .iter()
            .flat_map(|ring| (0..ring.len()).map(move |i| [ring[i], ring[(i + 1) % ring.len()]]))
            .collect();
        let side = |a: DVec2, b: DVec2, c: DVec2| (b - a).perp_dot(c - a);
        edges.iter().enumerate().any(|(i, &[a, b])| {
            edges[i + 1..].iter().any(|&[c, d]| {
                if [c, d].contains(&a) || [c, d].contains(&b) {
                    return false;
                }
                let [p, q, r, s] = [a, b, c, d].map(|v| pattern[v as usize]);
                side(p, q, r) * side(p, q, s) <= 0.0 && side(r, s, p) * side(r, s, q) <= 0.0
            })
        })
    }

    #[test]
    fn the_overlap_free_flattening_keeps_a_slit_saddle_from_overlapping() {
        let (model, turn) = slit_saddle_fan();
        assert!(turn > 1.15 * std::f64::consts::TAU, "a saddle: {turn}");
        let stiffness = Stiffness::uniform(&model);
        let options = FlattenOptions::default();
        let plain = flatten(&model, &stiffness, &options, &NoProgress).expect("flattens");
        assert!(
            outline_crosses(&model, &plain.positions),
            "the plain flattening overlaps: the test means something"
        );
        let kept = overlap_free_flatten(&model, &stiffness, &options)
            .expect("flattens")
            .expect("the minimiser runs");
        assert!(!outline_crosses(&model, &kept.positions));
        assert!(!kept.stats.accuracy.overlap && kept.stats.accuracy.flipped == 0);
        let recomputed = Accuracy::measure(&model, &kept.positions);
        assert_eq!(recomputed, kept.stats.accuracy);
        assert!(kept.stats.accuracy.area_error < 0.5, "{:?}", kept.stats);
    }

    /// A flat 5 × 5 grid of unit squares (each split along its rising diagonal) and its exact
    /// development, but for the bottom edge's vertex at x = 2, moved up to `1 − squeeze`: its two
    /// triangles that reach the vertex above are squeezed to `squeeze` of their area, still
    /// positively oriented.
    fn grid_with_a_squeezed_corner(squeeze: f64) -> (FacetModel, Vec<DVec2>) {
        let index = |i: u32, j: u32| j * 6 + i;
        let positions = (0..6)
            .flat_map(|j| (0..6).map(move |i| DVec3::new(f64::from(i), f64::from(j), 0.0)))
            .collect();
        let triangles = (0..5)
            .flat_map(|j| {
                (0..5).flat_map(move |i| {
                    let [a, b, c, d] = [
                        index(i, j),
                        index(i + 1, j),
                        index(i + 1, j + 1),
                        index(i, j + 1),
                    ];
                    [[a, b, c], [a, c, d]]
                })
            })
            .collect();
        let model = validate(&TriangleSoup::new(positions, triangles))
            .expect("valid")
            .components
            .remove(0);
        let mut pattern: Vec<DVec2> = model.positions().iter().map(|p| p.truncate()).collect();
        let moved = model
            .positions()
            .iter()
            .position(|p| *p == DVec3::new(2.0, 0.0, 0.0))
            .expect("the vertex");
        pattern[moved].y = 1.0 - squeeze;
        (model, pattern)
    }

    /// A flattening of `positions` with the figures `accuracy`, as a solver would return it.
    fn squeezed_flattening(positions: Vec<DVec2>, accuracy: Accuracy) -> Flattened {
        Flattened {
            positions,
            stats: FlattenStats {
                accuracy,
                initial_accuracy: accuracy,
                energy: 0.0,
                iterations: 0,
                stop_reason: StopReason::Converged,
                seconds: 0.0,
            },
        }
    }

    #[test]
    fn squeezed_triangles_are_opened_back_to_the_development() {
        let (model, pattern) = grid_with_a_squeezed_corner(1e-7);
        let stiffness = Stiffness::uniform(&model);
        let before = Accuracy::measure(&model, &pattern);
        assert_eq!(before.flipped, 0, "squeezed, not flipped");
        assert_eq!(squeezed_triangles(&model, &pattern, 1e-6).len(), 2);
        let options = FlattenOptions::default();
        let squeezed = squeezed_flattening(pattern, before);
        let opened = with_squeezed_triangles_opened(&model, &stiffness, squeezed, &options);
        assert_eq!(squeezed_triangles(&model, &opened.positions, 0.45).len(), 0);
        let recomputed = Accuracy::measure(&model, &opened.positions);
        assert_eq!(recomputed, opened.stats.accuracy);
        assert!(recomputed.area_error < 1e-3, "{recomputed:?}");
        assert!(
            recomputed.area_error < before.area_error / 10.0,
            "{before:?}"
        );
    }

    #[test]
    fn a_degenerate_triangle_is_opened_even_out_of_tolerance() {
        let (model, pattern) = grid_with_a_squeezed_corner(1e-12);
        assert_eq!(
            squeezed_triangles(&model, &pattern, DEGENERATE_AREA_RATIO).len(),
            2
        );
        let stiffness = Stiffness::uniform(&model);
        let accuracy = Accuracy::measure(&model, &pattern);
        let options = FlattenOptions {
            tolerance: 1e-6,
            ..FlattenOptions::default()
        };
        let opened = with_squeezed_triangles_opened(
            &model,
            &stiffness,
            squeezed_flattening(pattern, accuracy),
            &options,
        );
        assert_eq!(squeezed_triangles(&model, &opened.positions, 1e-3).len(), 0);
    }
}
