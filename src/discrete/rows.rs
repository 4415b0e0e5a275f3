//! Row-by-row work on a row-major field (rows of `width` values, like a level's node fields or
//! a kernel), serially or on the rayon pool: the rows are independent, so the result is the
//! same either way.

/// `f(j, row)` for every row j of `data` (rows of `width` values), on the rayon pool when
/// `parallel`.
pub fn for_each_row<T: Send>(
    parallel: bool,
    data: &mut [T],
    width: usize,
    f: impl Fn(usize, &mut [T]) + Sync + Send,
) {
    if parallel {
        use rayon::prelude::*;
        data.par_chunks_mut(width)
            .enumerate()
            .for_each(|(j, row)| f(j, row));
    } else {
        for (j, row) in data.chunks_mut(width).enumerate() {
            f(j, row);
        }
    }
}
