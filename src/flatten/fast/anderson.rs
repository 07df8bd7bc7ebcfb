//! Anderson acceleration (type II, depth `m`, Walker and Ni 2011) of the fast solver's plain
//! iteration.

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};
use glam::DVec2;
use rayon::prelude::*;

use super::chunked::dot;

/// Tikhonov term added to the diagonal of the Anderson least-squares problem, relative to its
/// trace: bounds its condition number, so a nearly dependent history still gives finite weights.
const ANDERSON_REGULARISATION: f64 = 1e-10;

/// Anderson acceleration (type II) of the fixed-point map `G`: from the last iterates `x_k`
/// and their images `g_k = G(x_k)`, the next iterate is `g_k − ΔG γ` with `γ` minimising
/// `|f_k − ΔF γ|`, `f = g − x`, `ΔF` and `ΔG` the differences of successive `f` and `g`.
pub(super) struct Anderson {
    depth: usize,
    /// Differences of residuals and of images, oldest first.
    residual_differences: Vec<Vec<DVec2>>,
    image_differences: Vec<Vec<DVec2>>,
    /// Dot products of the residual differences with each other, in the same order.
    gram: Vec<Vec<f64>>,
    /// The last residual and image.
    residual: Vec<DVec2>,
    image: Vec<DVec2>,
    has_last: bool,
}

impl Anderson {
    pub(super) fn new(depth: usize, size: usize) -> Self {
        Self {
            depth,
            residual_differences: Vec::with_capacity(depth),
            image_differences: Vec::with_capacity(depth),
            gram: Vec::with_capacity(depth),
            residual: vec![DVec2::ZERO; size],
            image: vec![DVec2::ZERO; size],
            has_last: false,
        }
    }

    /// Forgets the history (after a rejected accelerated step).
    pub(super) fn clear(&mut self) {
        self.residual_differences.clear();
        self.image_differences.clear();
        self.gram.clear();
        self.has_last = false;
    }

    /// Records the iterate `x` and its image `g`.
    pub(super) fn push(&mut self, x: &[DVec2], g: &[DVec2]) {
        if self.depth == 0 {
            return;
        }
        if self.has_last {
            let (mut residual_difference, mut image_difference) =
                if self.residual_differences.len() == self.depth {
                    self.gram.remove(0);
                    for row in &mut self.gram {
                        row.remove(0);
                    }
                    (
                        self.residual_differences.remove(0),
                        self.image_differences.remove(0),
                    )
                } else {
                    (vec![DVec2::ZERO; x.len()], vec![DVec2::ZERO; x.len()])
                };
            residual_difference
                .par_iter_mut()
                .zip(image_difference.par_iter_mut())
                .enumerate()
                .for_each(|(i, (df, dg))| {
                    *df = (g[i] - x[i]) - self.residual[i];
                    *dg = g[i] - self.image[i];
                });
            let mut row: Vec<f64> = self
                .residual_differences
                .iter()
                .map(|other| dot(other, &residual_difference))
                .collect();
            row.push(dot(&residual_difference, &residual_difference));
            for (existing, &value) in self.gram.iter_mut().zip(&row) {
                existing.push(value);
            }
            self.gram.push(row);
            self.residual_differences.push(residual_difference);
            self.image_differences.push(image_difference);
        }
        self.residual
            .par_iter_mut()
            .zip(self.image.par_iter_mut())
            .enumerate()
            .for_each(|(i, (f, image))| {
                *f = g[i] - x[i];
                *image = g[i];
            });
        self.has_last = true;
    }

    /// Writes the accelerated iterate into `out`; false when there is no history or the
    /// least-squares problem is singular (then `out` is not meaningful).
    pub(super) fn extrapolate(&self, image: &[DVec2], out: &mut [DVec2]) -> bool {
        let m = self.residual_differences.len();
        if m == 0 {
            return false;
        }
        let gram = Mat::from_fn(m, m, |i, j| self.gram[i][j]);
        let trace: f64 = (0..m).map(|i| gram[(i, i)]).sum();
        let regularised = Mat::from_fn(m, m, |i, j| {
            gram[(i, j)]
                + if i == j {
                    ANDERSON_REGULARISATION * trace
                } else {
                    0.0
                }
        });
        let mut gamma = Mat::from_fn(m, 1, |i, _| {
            dot(&self.residual_differences[i], &self.residual)
        });
        let Ok(factor) = regularised.llt(Side::Lower) else {
            return false;
        };
        factor.solve_in_place(gamma.as_mut());
        if !(0..m).all(|i| gamma[(i, 0)].is_finite()) {
            return false;
        }
        out.par_iter_mut().enumerate().for_each(|(v, x)| {
            let mut value = image[v];
            for (k, difference) in self.image_differences.iter().enumerate() {
                value -= difference[v] * gamma[(k, 0)];
            }
            *x = value;
        });
        true
    }
}
