//! The local repair of a folded pattern: when the fast solver's pattern has a few flipped
//! triangles (phase one folded the part there), only the vertices near them are placed afresh,
//! the rest of the pattern held where it is, instead of flattening the whole part again from a
//! Tutte start ([`flip_free_flatten`](super::flip_free_flatten), hundreds of Newton iterations
//! over every vertex: 26 s on a 20k-triangle hemisphere with 17 flipped triangles).
//!
//! The vertices within a few rings of the flipped triangles (the free ones) are put at the
//! weighted means of their neighbours, the others held: the Tutte embedding of that region with
//! its surroundings as its boundary ([`solve_interior`], the same clamped cotangent weights).
//! Outline vertices in the region are free too: a fold most often reaches the outline (where
//! phase one's growth ends), and held there it stays folded. They are placed in one of two ways
//! ([`OutlinePlacement`]), the second tried when the first leaves a flip: like the others, at the
//! weighted mean of their neighbours (which all lie on one side, so the outline is pulled in), or
//! along the chord between the held outline vertices at the ends of their run, the other free
//! vertices then placed inside. On the pieces of the dress, the cow head, the horse and the spot
//! head, 3 of 31 folds were repaired with the outline held, 27 of 33 with the mean alone, 25 of
//! 31 with the chord alone, and 28 of 32 with both.
//!
//! Nothing guarantees the new region no flipped triangle (its surroundings need not be convex),
//! so it is checked; when one is flipped the region grows ([`REPAIR_RINGS`]) until it holds more
//! than [`LOCAL_REPAIR_SHARE`] of the vertices, and the repair gives up. The region is then
//! relaxed by the flip-free minimiser on its free vertices alone ([`flip_free_solve_moving`],
//! [`ORIENTATION_BARRIER`], at most [`LOCAL_ITERATIONS`] Newton iterations): every triangle stays
//! positively oriented, so the fast solver can then converge the whole pattern from it without
//! flipping any.

use glam::DVec2;

use super::barrier::ORIENTATION_BARRIER;
use super::solver::{FlipFreeSettings, Outline, flip_free_solve_moving};
use super::tutte::solve_interior;
use crate::flatten::accuracy::{flipped_faces, flipped_triangles};
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
    let flipped = flipped_faces(model, positions);
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

/// How the free vertices of the outline are placed afresh.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum OutlinePlacement {
    /// Like the others, at the weighted mean of their neighbours (which all lie on one side).
    Mean,
    /// On the chord between the held outline vertices at the ends of their run
    /// ([`place_on_chords`]), before the other free vertices are placed.
    Chord,
}

/// The pattern with the `free` vertices placed afresh ([`placed_afresh`], the outline's by
/// [`OutlinePlacement::Mean`], else by [`OutlinePlacement::Chord`]) and relaxed, when that
/// leaves no triangle flipped (see the module documentation).
fn repaired_region(
    model: &FacetModel,
    springs: &SpringSystem,
    positions: &[DVec2],
    free: &[bool],
    deadline: Deadline,
) -> Option<(Vec<DVec2>, usize)> {
    let mut repaired = [OutlinePlacement::Mean, OutlinePlacement::Chord]
        .into_iter()
        .filter_map(|placement| placed_afresh(model, positions, free, placement))
        .find(|placed| flipped_triangles(model, placed) == 0)?;
    let settings = FlipFreeSettings {
        barrier: ORIENTATION_BARRIER,
        max_iterations: LOCAL_ITERATIONS,
        deadline,
        outline: Outline::Free,
    };
    let outcome = flip_free_solve_moving(model, springs, &mut repaired, free, settings).ok()?;
    Some((repaired, outcome.iterations))
}

/// The pattern with the `free` vertices placed afresh: those of the outline by `placement`, the
/// others at the weighted means of their neighbours ([`solve_interior`]); `None` when the system
/// does not solve or a whole outline loop is free with [`OutlinePlacement::Chord`].
fn placed_afresh(
    model: &FacetModel,
    positions: &[DVec2],
    free: &[bool],
    placement: OutlinePlacement,
) -> Option<Vec<DVec2>> {
    let mut placed = positions.to_vec();
    let mut held = vec![false; model.vertex_count()];
    if placement == OutlinePlacement::Chord {
        for ring in model.boundary_loops() {
            place_on_chords(model, ring, free, &mut placed)?;
            for &v in ring {
                held[v as usize] = true;
            }
        }
    }
    let mut unknown = vec![u32::MAX; model.vertex_count()];
    let mut count = 0;
    for (v, slot) in unknown.iter_mut().enumerate() {
        if free[v] && !held[v] {
            *slot = count;
            count += 1;
        }
    }
    if count > 0 {
        solve_interior(model, &unknown, count as usize, &[], &mut placed).ok()?;
    }
    Some(placed)
}

/// Places each run of `free` vertices of the outline loop `ring` on the straight segment
/// between the held vertices at its ends, in the order and at the spacing of their rest lengths
/// (see the module documentation); `None` when the whole loop is free (no end to hold it by).
fn place_on_chords(
    model: &FacetModel,
    ring: &[u32],
    free: &[bool],
    positions: &mut [DVec2],
) -> Option<()> {
    let is_free = |k: usize| free[ring[k % ring.len()] as usize];
    let held = (0..ring.len()).find(|&k| !is_free(k))?;
    let rest = |a: u32, b: u32| {
        model
            .find_edge(a, b)
            .map_or(0.0, |e| model.rest_lengths()[e])
    };
    let mut k = held;
    while k < held + ring.len() {
        if !is_free(k + 1) {
            k += 1;
            continue;
        }
        // A run of free vertices from k + 1 to end − 1, between the held k and end.
        let mut end = k + 1;
        while is_free(end) {
            end += 1;
        }
        let run: Vec<u32> = (k..=end).map(|j| ring[j % ring.len()]).collect();
        let lengths: Vec<f64> = run.windows(2).map(|pair| rest(pair[0], pair[1])).collect();
        let total: f64 = lengths.iter().sum();
        let (from, to) = (
            positions[run[0] as usize],
            positions[run[run.len() - 1] as usize],
        );
        let mut travelled = 0.0;
        for (j, &v) in run.iter().enumerate().skip(1).take(run.len() - 2) {
            travelled += lengths[j - 1];
            let fraction = if total > 0.0 { travelled / total } else { 0.5 };
            positions[v as usize] = from.lerp(to, fraction);
        }
        k = end;
    }
    Some(())
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

    use glam::DVec3;

    use crate::cad::TriangleSoup;
    use crate::flatten::fast::{FastOptions, fast_solve};
    use crate::flatten::init_flatten::{InitRelease, NEIGHBOURHOOD_SWEEPS, init_flatten};
    use crate::flatten::injective::local::*;
    use crate::flatten::samples::{deep_bowl, sample, uniform_springs};
    use crate::mesh::validate;
    use crate::progress::NoProgress;

    /// The fast solver's pattern of `model` from phase one.
    fn fast_pattern(model: &FacetModel, springs: &SpringSystem) -> Vec<DVec2> {
        let release = InitRelease::Neighbourhood {
            sweeps: NEIGHBOURHOOD_SWEEPS,
        };
        let mut pattern = init_flatten(model, springs, release, &NoProgress);
        fast_solve(model, springs, &mut pattern, FastOptions::default()).expect("factors");
        pattern
    }

    /// The hemisphere sample's pattern with one interior vertex (all of whose neighbours are
    /// interior too) pushed out past its neighbours, folding part of its fan over.
    fn folded_hemisphere() -> (FacetModel, SpringSystem, Vec<DVec2>) {
        let model = sample("hemisphere.obj");
        let springs = uniform_springs(&model);
        let mut pattern = fast_pattern(&model, &springs);
        assert!(flipped_faces(&model, &pattern).is_empty());
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
        let flips = flipped_faces(&model, &folded);
        assert!(!flips.is_empty(), "the pushed vertex folds its fan");
        let (repaired, _) =
            repaired_locally(&model, &springs, &folded, Deadline::NONE).expect("repaired");
        assert!(flipped_faces(&model, &repaired).is_empty());
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
    fn a_free_run_of_the_outline_goes_onto_the_chord_between_its_held_ends() {
        // A 2 x 2 square of unit cells: 8 outline vertices, 1 mm apart along the outline.
        let positions: Vec<DVec3> = (0..9)
            .map(|i| DVec3::new((i % 3) as f64, (i / 3) as f64, 0.0))
            .collect();
        let mut triangles = Vec::new();
        for y in 0..2u32 {
            for x in 0..2u32 {
                let v = 3 * y + x;
                triangles.extend([[v, v + 1, v + 4], [v, v + 4, v + 3]]);
            }
        }
        let model = validate(&TriangleSoup::new(positions, triangles))
            .expect("valid")
            .components
            .remove(0);
        let ring = model.boundary_loops()[0].clone();
        let start: Vec<DVec2> = model.positions().iter().map(|p| p.truncate()).collect();
        // Three consecutive outline vertices free, held ends 4 mm apart along the outline.
        let mut free = vec![false; model.vertex_count()];
        for &v in &ring[1..4] {
            free[v as usize] = true;
        }
        let mut placed = start.clone();
        place_on_chords(&model, &ring, &free, &mut placed).expect("held ends");
        let (from, to) = (start[ring[0] as usize], start[ring[4] as usize]);
        for (k, &v) in ring[1..4].iter().enumerate() {
            let expected = from.lerp(to, (k + 1) as f64 / 4.0);
            assert!(placed[v as usize].distance(expected) < 1e-12, "{k}");
        }
        let untouched = |v: &u32| placed[*v as usize] == start[*v as usize];
        assert!(ring[4..].iter().chain(&ring[..1]).all(untouched));
        let all_free = vec![true; model.vertex_count()];
        assert!(place_on_chords(&model, &ring, &all_free, &mut placed).is_none());
    }

    #[test]
    fn a_pattern_without_flips_is_left_as_it_is() {
        let model = sample("hemisphere.obj");
        let springs = uniform_springs(&model);
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
        let springs = uniform_springs(&model);
        let pattern = fast_pattern(&model, &springs);
        assert!(
            !flipped_faces(&model, &pattern).is_empty(),
            "the fast solver folds this bowl"
        );
        assert!(repaired_locally(&model, &springs, &pattern, Deadline::NONE).is_none());
    }
}
