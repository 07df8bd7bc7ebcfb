//! Sums over position arrays on rayon in chunks of a fixed size, added in chunk order, so the
//! results do not depend on the number of threads.

use glam::DVec2;
use rayon::prelude::*;

/// Springs or vertices per rayon task; the partial sums are added in chunk order.
pub(super) const CHUNK: usize = 4096;

/// Root-mean-square distance between two patterns.
pub(super) fn rms_distance(first: &[DVec2], second: &[DVec2]) -> f64 {
    let partial: Vec<f64> = first
        .par_chunks(CHUNK)
        .zip(second.par_chunks(CHUNK))
        .map(|(p, q)| p.iter().zip(q).map(|(&p, &q)| p.distance_squared(q)).sum())
        .collect();
    (partial.iter().sum::<f64>() / first.len().max(1) as f64).sqrt()
}

/// Dot product of two position arrays seen as vectors, summed in chunk order.
pub(super) fn dot(first: &[DVec2], second: &[DVec2]) -> f64 {
    let partial: Vec<f64> = first
        .par_chunks(CHUNK)
        .zip(second.par_chunks(CHUNK))
        .map(|(p, q)| p.iter().zip(q).map(|(&p, &q)| p.dot(q)).sum())
        .collect();
    partial.iter().sum()
}
