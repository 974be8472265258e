//! Order-preserving maps over `0..n`, on rayon's pool with the `parallel` feature and
//! sequential without it, so that callers need no `cfg` of their own.

/// `(0..n).map(f)`, collected in order. `min_len` is the least number of items a
/// parallel task takes (small items want large tasks).
pub(crate) fn map_range<T: Send>(
    n: usize,
    min_len: usize,
    f: impl Fn(usize) -> T + Sync + Send,
) -> Vec<T> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        (0..n)
            .into_par_iter()
            .with_min_len(min_len)
            .map(f)
            .collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        let _ = min_len;
        (0..n).map(f).collect()
    }
}

/// `(0..n).map(f).unzip()`: two vectors filled in order in one pass.
pub(crate) fn unzip_range<A: Send, B: Send>(
    n: usize,
    min_len: usize,
    f: impl Fn(usize) -> (A, B) + Sync + Send,
) -> (Vec<A>, Vec<B>) {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        (0..n).into_par_iter().with_min_len(min_len).map(f).unzip()
    }
    #[cfg(not(feature = "parallel"))]
    {
        let _ = min_len;
        (0..n).map(f).unzip()
    }
}

/// `(0..n).filter_map(f)`, collected in order.
pub(crate) fn filter_map_range<T: Send>(
    n: usize,
    min_len: usize,
    f: impl Fn(usize) -> Option<T> + Sync + Send,
) -> Vec<T> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        (0..n)
            .into_par_iter()
            .with_min_len(min_len)
            .filter_map(f)
            .collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        let _ = min_len;
        (0..n).filter_map(f).collect()
    }
}

/// `(a(), b())`, the two run side by side on rayon's pool (one after the other
/// without the `parallel` feature).
pub(crate) fn join<A: Send, B: Send>(
    a: impl FnOnce() -> A + Send,
    b: impl FnOnce() -> B + Send,
) -> (A, B) {
    #[cfg(feature = "parallel")]
    {
        rayon::join(a, b)
    }
    #[cfg(not(feature = "parallel"))]
    {
        (a(), b())
    }
}
