//! The global step's linear system: the spring Laplacian (weights `C_ij`) without the held
//! vertex's row and column, factored once by faer's sparse Cholesky.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{LltRef, SymbolicCholesky, factorize_symbolic_cholesky};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Conj, Par, Side};

use crate::flatten::springs::SpringSystem;

/// Errors of the fast solver's precomputation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FastError {
    /// The spring Laplacian could not be factored: a constant is not positive or not finite.
    #[error(
        "the spring system could not be factored ({reason}): every spring constant must be \
         positive and finite"
    )]
    Factorisation {
        /// What faer reported.
        reason: String,
    },
}

/// The vertex whose position the global step holds (the energy is translation invariant).
pub(super) const HELD_VERTEX: usize = 0;

/// The model vertex of unknown `i` of the reduced system (every vertex but the held one).
pub(super) fn unknown_vertex(i: usize) -> usize {
    i + 1
}

/// The Cholesky factor `L = U Uᵀ` of the reduced spring Laplacian.
#[derive(Debug)]
pub(super) struct LaplacianFactor {
    symbolic: SymbolicCholesky<u32>,
    values: Vec<f64>,
}

impl LaplacianFactor {
    /// Solves `L X = B` in place for the columns of `rhs`, in one pass over the factor.
    /// Sequential: the substitutions are bound by reading the factor from memory (at 400k
    /// triangles, two columns in one pass took as long as one column per thread), and faer's
    /// fine-grained parallel substitution spent most of its time waiting on rayon latches.
    pub(super) fn solve_in_place(&self, rhs: faer::MatMut<'_, f64>) {
        let factor = LltRef::new(&self.symbolic, &self.values);
        let scratch = self
            .symbolic
            .solve_in_place_scratch::<f64>(rhs.ncols(), Par::Seq);
        let mut buffer = MemBuffer::new(scratch);
        factor.solve_in_place_with_conj(Conj::No, rhs, Par::Seq, MemStack::new(&mut buffer));
    }
}

/// Factors the spring Laplacian (weights `C_ij`) without the held vertex's row and column; the
/// lower triangle is given.
pub(super) fn factor_laplacian(
    vertex_count: usize,
    springs: &SpringSystem,
) -> Result<LaplacianFactor, FastError> {
    let unknown = |v: u32| (v as usize).checked_sub(1);
    let mut entries = Vec::with_capacity(3 * springs.len());
    for (&[a, b], &constant) in springs.edges.iter().zip(&springs.constants) {
        let (ia, ib) = (unknown(a), unknown(b));
        for i in [ia, ib].into_iter().flatten() {
            entries.push(Triplet::new(i as u32, i as u32, constant));
        }
        if let (Some(i), Some(j)) = (ia, ib) {
            entries.push(Triplet::new(i.max(j) as u32, i.min(j) as u32, -constant));
        }
    }
    let unknowns = vertex_count - 1;
    let failure = |reason: String| FastError::Factorisation { reason };
    let matrix = SparseColMat::<u32, f64>::try_new_from_triplets(unknowns, unknowns, &entries)
        .map_err(|error| failure(format!("{error:?}")))?;
    let symbolic = factorize_symbolic_cholesky(
        matrix.symbolic(),
        Side::Lower,
        Default::default(),
        Default::default(),
    )
    .map_err(|error| failure(format!("{error:?}")))?;
    let mut values = vec![0.0; symbolic.len_val()];
    // Sequential, as the substitutions: on 2 shared cores faer's rayon factorisation was slower
    // (400k fender, whole flatten: 3.4-4.0 s sequential against 3.4-4.3 s with rayon).
    let parallelism = Par::Seq;
    let scratch = symbolic.factorize_numeric_llt_scratch::<f64>(parallelism, Default::default());
    symbolic
        .factorize_numeric_llt(
            &mut values,
            matrix.as_ref(),
            Side::Lower,
            Default::default(),
            parallelism,
            MemStack::new(&mut MemBuffer::new(scratch)),
            Default::default(),
        )
        .map_err(|error| failure(format!("{error:?}")))?;
    Ok(LaplacianFactor { symbolic, values })
}
