//! The local repair of a folded pattern: when the fast solver's pattern has a few flipped
//! triangles (phase one folded the part there), only the vertices near them are placed afresh,
//! the rest of the pattern held where it is, instead of flattening the whole part again from a
//! Tutte start ([`flip_free_flatten`](super::flip_free_flatten), hundreds of Newton iterations
//! over every vertex: 26 s on a 20k-triangle hemisphere with 18 flipped triangles).
//!
//! The vertices within a few rings of the flipped triangles (the free ones) are put at the
//! weighted means of their neighbours, the others held: the Tutte embedding of that region with
//! its surroundings as its boundary ([`solve_interior`], the same clamped cotangent weights).
//! Outline vertices in the region are free too: a fold most often reaches the outline (where
//! phase one's growth ends), and held there it stays folded (on the pieces of the dress, the cow
//! head, the horse and the spot head, 3 of 31 folds were repaired with them held, 27 of 33 with
//! them free).
//! Nothing guarantees the new region no flipped triangle (its surroundings need not be convex,
//! and an outline vertex has neighbours on one side only), so it is checked; when one is
//! flipped the region grows ([`REPAIR_RINGS`]) until it holds more than [`LOCAL_REPAIR_SHARE`]
//! of the vertices, and the repair gives up. The region is then
//! relaxed by the flip-free minimiser on its free vertices alone ([`flip_free_solve_moving`],
//! [`ORIENTATION_BARRIER`], at most [`LOCAL_ITERATIONS`] Newton iterations): every triangle stays
//! positively oriented, so the fast solver can then converge the whole pattern from it without
//! flipping any.

use glam::DVec2;

use super::barrier::ORIENTATION_BARRIER;
use super::solver::{FlipFreeSettings, Outline, flip_free_solve_moving};
use super::tutte::solve_interior;
use crate::flatten::accuracy::{flipped_triangles, signed_area};
use crate::flatten::springs::SpringSystem;
use crate::mesh::FacetModel;
use crate::progress::Deadline;

/// The rings of neighbours around the flipped triangles that the repaired region takes, tried in
/// turn until one comes out without a flipped triangle.
pub const REPAIR_RINGS: [usize; 4] = [2, 4, 8, 16];
/// The local repair gives up when its region would hold more than this fraction of the part's
/// vertices (the whole part is then flattened again without flips).
pub const LOCAL_REPAIR_SHARE: f64 = 0.25;
/// Newton iterations at most of the relaxation of the repaired region.
pub const LOCAL_ITERATIONS: usize = 50;

/// The pattern `positions` with its flipped triangles repaired locally (see the module
/// documentation), and the Newton iterations the region's relaxation took; `None` when no region
/// up to [`LOCAL_REPAIR_SHARE`] of the vertices comes out without a flipped triangle, or the
/// deadline passed. Every triangle of the returned pattern is positively oriented.
pub fn repaired_locally(
    model: &FacetModel,
    springs: &SpringSystem,
    positions: &[DVec2],
    deadline: Deadline,
) -> Option<(Vec<DVec2>, usize)> {
    let flipped: Vec<usize> = (model.triangles().iter().enumerate())
        .filter(|(_, t)| {
            let [a, b, c] = t.map(|v| positions[v as usize]);
            signed_area(a, b, c) <= 0.0
        })
        .map(|(f, _)| f)
        .collect();
    if flipped.is_empty() {
        return Some((positions.to_vec(), 0));
    }
    let largest = LOCAL_REPAIR_SHARE * model.vertex_count() as f64;
    for rings in REPAIR_RINGS {
        if deadline.passed() {
            return None;
        }
        let free = near_triangles(model, &flipped, rings);
        let count = free.iter().filter(|&&f| f).count();
        if count as f64 > largest {
            return None;
        }
        if let Some(repaired) = repaired_region(model, springs, positions, &free, deadline) {
            return Some(repaired);
        }
    }
    None
}

/// The pattern with the `free` vertices placed afresh ([`solve_interior`]) and relaxed, when
/// that leaves no triangle flipped (see the module documentation).
fn repaired_region(
    model: &FacetModel,
    springs: &SpringSystem,
    positions: &[DVec2],
    free: &[bool],
    deadline: Deadline,
) -> Option<(Vec<DVec2>, usize)> {
    let mut unknown = vec![u32::MAX; model.vertex_count()];
    let mut count = 0;
    for (slot, _) in unknown.iter_mut().zip(free).filter(|(_, f)| **f) {
        *slot = count;
        count += 1;
    }
    if count == 0 {
        return None;
    }
    let mut repaired = positions.to_vec();
    solve_interior(model, &unknown, count as usize, &[], &mut repaired).ok()?;
    if flipped_triangles(model, &repaired) > 0 {
        return None;
    }
    let settings = FlipFreeSettings {
        barrier: ORIENTATION_BARRIER,
        max_iterations: LOCAL_ITERATIONS,
        deadline,
        outline: Outline::Free,
    };
    let outcome = flip_free_solve_moving(model, springs, &mut repaired, free, settings).ok()?;
    Some((repaired, outcome.iterations))
}

/// Per vertex, whether it is a corner of one of `triangles` or within `rings` rings of one.
pub fn near_triangles(model: &FacetModel, triangles: &[usize], rings: usize) -> Vec<bool> {
    let mut near = vec![false; model.vertex_count()];
    let mut front: Vec<u32> = triangles
        .iter()
        .flat_map(|&f| model.triangles()[f])
        .collect();
    for &v in &front {
        near[v as usize] = true;
    }
    for _ in 0..rings {
        let mut next = Vec::new();
        for v in front {
            for &f in model.vertex_faces(v) {
                for w in model.triangles()[f as usize] {
                    if !near[w as usize] {
                        near[w as usize] = true;
                        next.push(w);
                    }
                }
            }
        }
        front = next;
    }
    near
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use crate::flatten::fast::{FastOptions, fast_solve};
    use crate::flatten::init_flatten::{InitRelease, NEIGHBOURHOOD_SWEEPS, init_flatten};
    use crate::flatten::injective::local::*;
    use crate::flatten::samples::{deep_bowl, sample};
    use crate::flatten::springs::PAPER_SPRING_CONSTANT;
    use crate::progress::NoProgress;

    fn springs(model: &FacetModel) -> SpringSystem {
        SpringSystem::new(
            model,
            &vec![1.0; model.edges().len()],
            PAPER_SPRING_CONSTANT,
        )
    }

    /// The fast solver's pattern of `model` from phase one.
    fn fast_pattern(model: &FacetModel, springs: &SpringSystem) -> Vec<DVec2> {
        let release = InitRelease::Neighbourhood {
            sweeps: NEIGHBOURHOOD_SWEEPS,
        };
        let mut pattern = init_flatten(model, springs, release, &NoProgress);
        fast_solve(model, springs, &mut pattern, FastOptions::default()).expect("factors");
        pattern
    }

    fn flipped(model: &FacetModel, pattern: &[DVec2]) -> Vec<usize> {
        (0..model.triangle_count())
            .filter(|&f| {
                let [a, b, c] = model.triangles()[f].map(|v| pattern[v as usize]);
                signed_area(a, b, c) <= 0.0
            })
            .collect()
    }

    /// The hemisphere sample's pattern with one interior vertex (all of whose neighbours are
    /// interior too) pushed out past its neighbours, folding part of its fan over.
    fn folded_hemisphere() -> (FacetModel, SpringSystem, Vec<DVec2>) {
        let model = sample("hemisphere.obj");
        let springs = springs(&model);
        let mut pattern = fast_pattern(&model, &springs);
        assert!(flipped(&model, &pattern).is_empty());
        let mut on_outline = vec![false; model.vertex_count()];
        for &v in model.boundary_loops().iter().flatten() {
            on_outline[v as usize] = true;
        }
        let neighbours = |v: u32| {
            let mut around: Vec<u32> = (model.vertex_faces(v).iter())
                .flat_map(|&f| model.triangles()[f as usize])
                .filter(|&w| w != v)
                .collect();
            around.sort_unstable();
            around.dedup();
            around
        };
        let v = (0..model.vertex_count() as u32)
            .find(|&v| {
                !on_outline[v as usize] && neighbours(v).iter().all(|&w| !on_outline[w as usize])
            })
            .expect("a vertex well inside");
        let around = neighbours(v);
        let centre =
            around.iter().map(|&w| pattern[w as usize]).sum::<DVec2>() / around.len() as f64;
        pattern[v as usize] = centre + 3.0 * (pattern[around[0] as usize] - centre);
        (model, springs, pattern)
    }

    #[test]
    fn a_fold_is_repaired_near_its_flips_and_the_rest_held() {
        let (model, springs, folded) = folded_hemisphere();
        let flips = flipped(&model, &folded);
        assert!(!flips.is_empty(), "the pushed vertex folds its fan");
        let (repaired, _) =
            repaired_locally(&model, &springs, &folded, Deadline::NONE).expect("repaired");
        assert!(flipped(&model, &repaired).is_empty());
        let widest = near_triangles(&model, &flips, REPAIR_RINGS[REPAIR_RINGS.len() - 1]);
        let moved: Vec<usize> = (0..model.vertex_count())
            .filter(|&v| repaired[v] != folded[v])
            .collect();
        assert!(!moved.is_empty());
        assert!(
            moved.iter().all(|&v| widest[v]),
            "a vertex far from the fold moved"
        );
        assert!((moved.len() as f64) <= LOCAL_REPAIR_SHARE * model.vertex_count() as f64);
    }

    #[test]
    fn a_pattern_without_flips_is_left_as_it_is() {
        let model = sample("hemisphere.obj");
        let springs = springs(&model);
        let pattern = fast_pattern(&model, &springs);
        let (again, iterations) =
            repaired_locally(&model, &springs, &pattern, Deadline::NONE).expect("nothing to do");
        assert_eq!((again, iterations), (pattern, 0));
    }

    #[test]
    fn a_fold_across_a_deep_bowls_rim_is_left_to_the_whole_flattening() {
        // Phase one folds a bowl of 0.85 pi: placed afresh, the vertices near its flips come out
        // folded too, however far the region reaches within its share.
        let model = deep_bowl(0.85 * PI, 16, 48);
        let springs = springs(&model);
        let pattern = fast_pattern(&model, &springs);
        assert!(
            !flipped(&model, &pattern).is_empty(),
            "the fast solver folds this bowl"
        );
        assert!(repaired_locally(&model, &springs, &pattern, Deadline::NONE).is_none());
    }
}
