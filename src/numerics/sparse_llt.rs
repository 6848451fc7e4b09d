//! Sparse Cholesky factorisation `A = L Lᵀ` of a symmetric matrix given by its lower-triangle
//! pattern (faer): the symbolic analysis once per pattern (AMD ordering, the supernodal
//! threshold of [`SUPERNODAL_THRESHOLD`]), then numeric factorisations and solves of values in
//! pattern order, sequential, in double or single precision. The stable Newton minimiser's
//! direct path factorises its Hessians with it, and the Schur-condensation bench its bulk.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{LltParams, LltRegularization};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LltRef, SymbolicCholesky, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat};
use faer::{Conj, Par, Side, Spec};

/// faer's choice between its simplicial and supernodal sparse Cholesky, scaled: the supernodal
/// factorisation is taken from a quarter of faer's default ratio of flops to factor entries.
/// The Hessian of a finite-element mesh (fill in dense blocks) then factorises supernodally,
/// 2.5 times faster than simplicially (22 000 unknowns: 10.7 ms against 26.9 ms), while the
/// chains and arrays of springs keep the simplicial one.
pub const SUPERNODAL_THRESHOLD: f64 = 0.25;

/// The symbolic Cholesky analysis of one n × n lower-triangle pattern, for numeric
/// factorisations of values given in the pattern's order.
pub struct SparseLlt {
    n: usize,
    symbolic: SymbolicSparseColMat<usize>,
    argsort: Argsort<usize>,
    llt: SymbolicCholesky<usize>,
}

impl SparseLlt {
    /// Analyse the lower-triangle `pattern` (entries (row, column), row ≥ column; repeated
    /// entries are summed) of an n × n matrix.
    ///
    /// # Errors
    /// A one-line reason if the pattern is out of bounds or the symbolic factorisation fails.
    pub fn analyse(n: usize, pattern: &[(usize, usize)]) -> Result<Self, String> {
        let pairs: Vec<Pair<usize, usize>> = pattern.iter().map(|&(r, c)| Pair::new(r, c)).collect();
        let (symbolic, argsort) = SymbolicSparseColMat::try_new_from_indices(n, n, &pairs)
            .map_err(|e| format!("sparsity pattern: {e:?}"))?;
        let llt = factorize_symbolic_cholesky(
            symbolic.as_ref(),
            Side::Lower,
            SymmetricOrdering::Amd,
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold(SUPERNODAL_THRESHOLD),
                ..Default::default()
            },
        )
        .map_err(|e| format!("symbolic factorisation: {e:?}"))?;
        Ok(Self {
            n,
            symbolic,
            argsort,
            llt,
        })
    }

    /// Entries of a numeric factor.
    pub fn factor_len(&self) -> usize {
        self.llt.len_val()
    }

    /// The numeric factorisation (sequential) of the matrix with `values` in pattern order,
    /// into `storage` where it is large enough: `Ok(Ok(factor))`, `Ok(Err(storage))` when the
    /// matrix is not positive definite (in the precision of `T`), `Err` when the values do not
    /// fit the pattern.
    ///
    /// # Errors
    /// A one-line reason if the matrix cannot be assembled from `values`.
    pub fn factorise<T: faer::traits::RealField + Copy>(
        &self,
        values: &[T],
        storage: Option<Vec<T>>,
    ) -> Result<Result<Vec<T>, Vec<T>>, String> {
        let mat = SparseColMat::<usize, T>::new_from_argsort(self.symbolic.clone(), &self.argsort, values)
            .map_err(|e| format!("assembling the matrix: {e:?}"))?;
        let len = self.llt.len_val();
        let mut factor = match storage {
            Some(mut v) if v.capacity() >= len => {
                v.resize(len, T::zero_impl());
                v
            }
            _ => vec![T::zero_impl(); len],
        };
        let params: Spec<LltParams, T> = Default::default();
        let mut buf = MemBuffer::new(self.llt.factorize_numeric_llt_scratch::<T>(Par::Seq, params));
        let ok = self
            .llt
            .factorize_numeric_llt(
                &mut factor,
                mat.as_ref(),
                Side::Lower,
                LltRegularization::default(),
                Par::Seq,
                MemStack::new(&mut buf),
                params,
            )
            .is_ok();
        Ok(if ok { Ok(factor) } else { Err(factor) })
    }

    /// Overwrite the columns of `rhs` (n × k, column-major) with `(L Lᵀ)⁻¹ rhs` for the numeric
    /// `factor` of [`Self::factorise`], sequentially.
    pub fn solve<T: faer::traits::RealField>(&self, factor: &[T], rhs: &mut [T]) {
        let k = rhs.len() / self.n;
        let m = faer::MatMut::from_column_major_slice_mut(rhs, self.n, k);
        let mut buf = MemBuffer::new(self.llt.solve_in_place_scratch::<T>(k, Par::Seq));
        LltRef::new(&self.llt, factor).solve_in_place_with_conj(
            Conj::No,
            m,
            Par::Seq,
            MemStack::new(&mut buf),
        );
    }
}
