//! The global step's linear system: the spring Laplacian (weights `C_ij`) without the held
//! vertex's row and column, factored once by faer's sparse Cholesky.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    LltRef, SymbolicCholesky, SymmetricOrdering, factorize_symbolic_cholesky,
};
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

/// A fill-reducing elimination order of a model's vertices (faer's AMD on its spring graph), to
/// factor the Laplacians of the models made from it by appending vertices (a cut inserts and
/// copies vertices after the model's own) without ordering each afresh: each appended vertex is
/// eliminated right after its earliest neighbour among the model's vertices.
#[derive(Debug, Clone, PartialEq)]
pub struct FillOrder {
    /// Each vertex's place in the order (the held vertex's is unused).
    rank: Vec<u32>,
}

impl FillOrder {
    /// The order faer's AMD gives the spring Laplacian of `springs` over `vertex_count` vertices.
    pub fn of(vertex_count: usize, springs: &SpringSystem) -> Result<Self, FastError> {
        let matrix = reduced_laplacian(vertex_count, springs)?;
        let symbolic = factorize_symbolic_cholesky(
            matrix.symbolic(),
            Side::Lower,
            SymmetricOrdering::Amd,
            Default::default(),
        )
        .map_err(factorisation_error)?;
        let mut rank = vec![0; vertex_count];
        match symbolic.perm() {
            Some(perm) => {
                for (place, &unknown) in perm.arrays().0.iter().enumerate() {
                    rank[unknown_vertex(unknown as usize)] = place as u32;
                }
            }
            None => (1..vertex_count).for_each(|v| rank[v] = (v - 1) as u32),
        }
        Ok(Self { rank })
    }

    /// The elimination order of the unknowns of a model of `vertex_count` vertices made from this
    /// order's model by appending vertices, joined by `springs`: forward (unknown eliminated at
    /// each place) and inverse. `None` when the model has fewer vertices than the order's.
    fn unknowns_in_order(
        &self,
        vertex_count: usize,
        springs: &SpringSystem,
    ) -> Option<(Vec<u32>, Vec<u32>)> {
        let known = self.rank.len();
        if vertex_count < known {
            return None;
        }
        // (place of the earliest old neighbour, 1 for an appended vertex, vertex).
        let mut key: Vec<(u32, u8, u32)> = (0..vertex_count as u32)
            .map(|v| match self.rank.get(v as usize) {
                Some(&rank) => (rank, 0, v),
                None => (u32::MAX, 1, v),
            })
            .collect();
        for &[a, b] in &springs.edges {
            for (new, old) in [(a, b), (b, a)] {
                let (new, old) = (new as usize, old as usize);
                if new >= known && old < known && old != HELD_VERTEX {
                    key[new].0 = key[new].0.min(self.rank[old]);
                }
            }
        }
        key.remove(HELD_VERTEX);
        key.sort_unstable();
        let forward: Vec<u32> = key.iter().map(|&(_, _, v)| v - 1).collect();
        let mut inverse = vec![0; forward.len()];
        for (place, &unknown) in forward.iter().enumerate() {
            inverse[unknown as usize] = place as u32;
        }
        Some((forward, inverse))
    }
}

/// The spring Laplacian (weights `C_ij`) without the held vertex's row and column, its lower
/// triangle.
fn reduced_laplacian(
    vertex_count: usize,
    springs: &SpringSystem,
) -> Result<SparseColMat<u32, f64>, FastError> {
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
    SparseColMat::<u32, f64>::try_new_from_triplets(unknowns, unknowns, &entries)
        .map_err(factorisation_error)
}

/// The fast solver's error for what faer reported.
fn factorisation_error(error: impl std::fmt::Debug) -> FastError {
    FastError::Factorisation {
        reason: format!("{error:?}"),
    }
}

/// Factors the spring Laplacian (weights `C_ij`) without the held vertex's row and column, in the
/// elimination order `order` gives it when given (see [`FillOrder`]), else in faer's AMD order.
pub(super) fn factor_laplacian(
    vertex_count: usize,
    springs: &SpringSystem,
    order: Option<&FillOrder>,
) -> Result<LaplacianFactor, FastError> {
    let matrix = reduced_laplacian(vertex_count, springs)?;
    let places = order.and_then(|order| order.unknowns_in_order(vertex_count, springs));
    let ordering = match &places {
        Some((forward, inverse)) => {
            SymmetricOrdering::Custom(PermRef::new_checked(forward, inverse, vertex_count - 1))
        }
        None => SymmetricOrdering::Amd,
    };
    let symbolic =
        factorize_symbolic_cholesky(matrix.symbolic(), Side::Lower, ordering, Default::default())
            .map_err(factorisation_error)?;
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
        .map_err(factorisation_error)?;
    Ok(LaplacianFactor { symbolic, values })
}

#[cfg(test)]
mod tests {
    use faer::Mat;

    use crate::flatten::fast::laplacian::*;
    use crate::flatten::samples::{sample, uniform_springs};

    /// The hemisphere's springs, and those among its vertices but the last `appended`: the
    /// model an order is made for, and the hemisphere as a model made from it by appending them.
    fn hemisphere_and_parent(appended: usize) -> (usize, SpringSystem, usize, SpringSystem) {
        let model = sample("hemisphere.obj");
        let springs = uniform_springs(&model);
        let count = model.vertex_count();
        let known = count - appended;
        let kept: Vec<usize> = (0..springs.len())
            .filter(|&e| springs.edges[e].iter().all(|&v| (v as usize) < known))
            .collect();
        let parent = SpringSystem {
            edges: kept.iter().map(|&e| springs.edges[e]).collect(),
            rest_lengths: kept.iter().map(|&e| springs.rest_lengths[e]).collect(),
            constants: kept.iter().map(|&e| springs.constants[e]).collect(),
        };
        (count, springs, known, parent)
    }

    #[test]
    fn appended_vertices_follow_their_earliest_neighbour() {
        let (count, springs, known, parent) = hemisphere_and_parent(12);
        let order = FillOrder::of(known, &parent).expect("orders");
        let (forward, inverse) = order.unknowns_in_order(count, &springs).expect("extends");
        let mut sorted = forward.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..count as u32 - 1).collect::<Vec<_>>());
        for (place, &unknown) in forward.iter().enumerate() {
            assert_eq!(inverse[unknown as usize], place as u32);
        }
        let place_of = |v: u32| inverse[v as usize - 1] as usize;
        for new in known as u32..count as u32 {
            let anchor = (springs.edges.iter())
                .filter_map(|&[a, b]| match (a == new, b == new) {
                    (true, _) => Some(b),
                    (_, true) => Some(a),
                    _ => None,
                })
                .filter(|&v| (v as usize) < known && v as usize != HELD_VERTEX)
                .min_by_key(|&v| order.rank[v as usize]);
            if let Some(anchor) = anchor {
                let between = &forward[place_of(anchor) + 1..place_of(new)];
                assert!(
                    between.iter().all(|&u| u as usize + 1 >= known),
                    "vertex {new} waits for old vertices after its neighbour {anchor}"
                );
            }
        }
        assert_eq!(order.unknowns_in_order(known - 1, &parent), None);
    }

    #[test]
    fn a_factor_in_an_extended_order_solves_as_the_amd_one_does() {
        let (count, springs, known, parent) = hemisphere_and_parent(40);
        let order = FillOrder::of(known, &parent).expect("orders");
        let rhs = Mat::from_fn(count - 1, 2, |i, axis| ((3 * i + axis) % 7) as f64 - 3.0);
        let solved = |order: Option<&FillOrder>| {
            let mut x = rhs.clone();
            factor_laplacian(count, &springs, order)
                .expect("factors")
                .solve_in_place(x.as_mut());
            x
        };
        let (amd, extended) = (solved(None), solved(Some(&order)));
        let scale = amd.norm_max();
        assert!((&amd - &extended).norm_max() <= 1e-9 * scale);
    }
}
