//! Symmetric positive definite sparse systems with a fixed pattern, factored by faer's sparse
//! Cholesky: the pattern and its fill-reducing symbolic factorisation are computed once, the
//! values refactored as often as they change (every Newton iteration).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{LltRef, SymbolicCholesky, factorize_symbolic_cholesky};
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat};
use faer::{Conj, Par, Side};

use super::errors::InjectiveError;

/// The lower triangle of a sparse symmetric matrix given as a list of positions, and its
/// symbolic Cholesky factorisation. Values are given in the order of the positions (repeated
/// positions are summed).
#[derive(Debug)]
pub(super) struct SparsePattern {
    matrix: SymbolicSparseColMat<u32>,
    order: Argsort<u32>,
    cholesky: SymbolicCholesky<u32>,
}

/// The numeric Cholesky factor of a [`SparsePattern`] with given values.
pub(super) struct Factor<'a> {
    pattern: &'a SparsePattern,
    values: Vec<f64>,
}

impl SparsePattern {
    /// The pattern of an `n × n` matrix whose lower triangle has entries at `positions`
    /// (`(row, column)`, `row ≥ column`).
    pub(super) fn new(n: usize, positions: &[(u32, u32)]) -> Result<Self, InjectiveError> {
        let pairs: Vec<Pair<u32, u32>> = positions
            .iter()
            .map(|&(row, col)| Pair { row, col })
            .collect();
        let (matrix, order) = SymbolicSparseColMat::try_new_from_indices(n, n, &pairs)
            .map_err(|error| InjectiveError::factorisation(format!("{error:?}")))?;
        let cholesky = factorize_symbolic_cholesky(
            matrix.as_ref(),
            Side::Lower,
            Default::default(),
            Default::default(),
        )
        .map_err(|error| InjectiveError::factorisation(format!("{error:?}")))?;
        Ok(Self {
            matrix,
            order,
            cholesky,
        })
    }

    /// Factors the matrix with `values` (one per position given to [`SparsePattern::new`]);
    /// an error if it is not numerically positive definite.
    pub(super) fn factor(&self, values: &[f64]) -> Result<Factor<'_>, InjectiveError> {
        let matrix = SparseColMat::new_from_argsort(self.matrix.clone(), &self.order, values)
            .map_err(|error| InjectiveError::factorisation(format!("{error:?}")))?;
        let mut factor_values = vec![0.0; self.cholesky.len_val()];
        let scratch = self
            .cholesky
            .factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default());
        self.cholesky
            .factorize_numeric_llt(
                &mut factor_values,
                matrix.as_ref(),
                Side::Lower,
                Default::default(),
                Par::Seq,
                MemStack::new(&mut MemBuffer::new(scratch)),
                Default::default(),
            )
            .map_err(|error| InjectiveError::factorisation(format!("{error:?}")))?;
        Ok(Factor {
            pattern: self,
            values: factor_values,
        })
    }
}

impl Factor<'_> {
    /// Solves `M X = B` in place for the columns of `rhs`.
    pub(super) fn solve_in_place(&self, rhs: faer::MatMut<'_, f64>) {
        let cholesky = &self.pattern.cholesky;
        let factor = LltRef::new(cholesky, &self.values);
        let scratch = cholesky.solve_in_place_scratch::<f64>(rhs.ncols(), Par::Seq);
        let mut buffer = MemBuffer::new(scratch);
        factor.solve_in_place_with_conj(Conj::No, rhs, Par::Seq, MemStack::new(&mut buffer));
    }
}
