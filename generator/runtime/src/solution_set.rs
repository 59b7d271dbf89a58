//! A fixed-capacity list on the stack.

use std::fmt;
use std::ops::Index;

/// A list of at most `N` values of `T`, stored inline (array + length); no heap.
///
/// Emitted solvers return their real solutions in a `SolutionSet<Solution, MAX>`.
/// Slots beyond [`len`](Self::len) hold a filler value (`T::default()` for
/// [`new`](Self::new), the given one for [`filled_with`](Self::filled_with)) and are never
/// exposed. Only `T: Copy` is required, so that types without `Default` (such as
/// `nalgebra::SVector<f64, N>` for generic `N`) can be stored; no `unsafe` code.
#[derive(Clone, Copy)]
pub struct SolutionSet<T: Copy, const N: usize> {
    data: [T; N],
    len: usize,
}

impl<T: Copy + Default, const N: usize> SolutionSet<T, N> {
    /// An empty set.
    #[inline]
    pub fn new() -> Self {
        Self::filled_with(T::default())
    }
}

impl<T: Copy, const N: usize> SolutionSet<T, N> {
    /// An empty set whose unused slots hold `fill` (never observable).
    #[inline]
    pub fn filled_with(fill: T) -> Self {
        SolutionSet {
            data: [fill; N],
            len: 0,
        }
    }
    /// Appends `value`; returns `false` (and drops it) when the set is full.
    #[inline]
    pub fn push(&mut self, value: T) -> bool {
        if self.len < N {
            self.data[self.len] = value;
            self.len += 1;
            true
        } else {
            false
        }
    }
    /// Number of stored values.
    #[inline]
    pub fn len(&self) -> usize {
        self.len
    }
    /// Whether no value is stored.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
    /// Whether the set holds `N` values.
    #[inline]
    pub fn is_full(&self) -> bool {
        self.len == N
    }
    /// The capacity `N`.
    #[inline]
    pub const fn capacity(&self) -> usize {
        N
    }
    /// Removes every value.
    #[inline]
    pub fn clear(&mut self) {
        self.len = 0;
    }
    /// Keeps the first `len` values (no effect if `len >= self.len()`).
    #[inline]
    pub fn truncate(&mut self, len: usize) {
        if len < self.len {
            self.len = len;
        }
    }
    /// The value at `i`, if any.
    #[inline]
    pub fn get(&self, i: usize) -> Option<&T> {
        self.as_slice().get(i)
    }
    /// The stored values.
    #[inline]
    pub fn as_slice(&self) -> &[T] {
        &self.data[..self.len]
    }
    /// The stored values, mutably.
    #[inline]
    pub fn as_mut_slice(&mut self) -> &mut [T] {
        &mut self.data[..self.len]
    }
    /// Iterates over the stored values.
    #[inline]
    pub fn iter(&self) -> std::slice::Iter<'_, T> {
        self.as_slice().iter()
    }
    /// Keeps only the values for which `keep` returns true (order preserved).
    pub fn retain(&mut self, mut keep: impl FnMut(&T) -> bool) {
        let mut w = 0;
        for r in 0..self.len {
            if keep(&self.data[r]) {
                self.data[w] = self.data[r];
                w += 1;
            }
        }
        self.len = w;
    }
}

impl<T: Copy + Default, const N: usize> Default for SolutionSet<T, N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Copy + fmt::Debug, const N: usize> fmt::Debug for SolutionSet<T, N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.as_slice()).finish()
    }
}

impl<T: Copy + PartialEq, const N: usize> PartialEq for SolutionSet<T, N> {
    fn eq(&self, other: &Self) -> bool {
        self.as_slice() == other.as_slice()
    }
}

impl<T: Copy, const N: usize> AsRef<[T]> for SolutionSet<T, N> {
    #[inline]
    fn as_ref(&self) -> &[T] {
        self.as_slice()
    }
}

impl<T: Copy, const N: usize> Index<usize> for SolutionSet<T, N> {
    type Output = T;
    /// Panics if `i >= len()`, like slice indexing.
    #[inline]
    fn index(&self, i: usize) -> &T {
        &self.as_slice()[i]
    }
}

impl<'a, T: Copy, const N: usize> IntoIterator for &'a SolutionSet<T, N> {
    type Item = &'a T;
    type IntoIter = std::slice::Iter<'a, T>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

impl<T: Copy, const N: usize> IntoIterator for SolutionSet<T, N> {
    type Item = T;
    type IntoIter = std::iter::Take<std::array::IntoIter<T, N>>;
    fn into_iter(self) -> Self::IntoIter {
        self.data.into_iter().take(self.len)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn push_until_full() {
        let mut s: SolutionSet<[f64; 2], 3> = SolutionSet::new();
        assert!(s.is_empty());
        assert!(s.push([1.0, 2.0]));
        assert!(s.push([3.0, 4.0]));
        assert!(s.push([5.0, 6.0]));
        assert!(!s.push([7.0, 8.0]));
        assert_eq!(s.len(), 3);
        assert!(s.is_full());
        assert_eq!(s[1], [3.0, 4.0]);
        assert_eq!(s.get(3), None);
        let firsts: Vec<f64> = (&s).into_iter().map(|v| v[0]).collect();
        assert_eq!(firsts, [1.0, 3.0, 5.0]);
        s.retain(|v| v[0] != 3.0);
        assert_eq!(s.as_slice(), &[[1.0, 2.0], [5.0, 6.0]]);
        assert_eq!(format!("{s:?}"), "[[1.0, 2.0], [5.0, 6.0]]");
        let owned: Vec<[f64; 2]> = s.into_iter().collect();
        assert_eq!(owned.len(), 2);
        let t = s;
        assert_eq!(t, s);
        s.clear();
        assert!(s.is_empty());
        assert_eq!(SolutionSet::<u8, 4>::default().capacity(), 4);
    }

    #[test]
    fn zero_capacity() {
        let mut s: SolutionSet<f64, 0> = SolutionSet::new();
        assert!(!s.push(1.0));
        assert!(s.is_empty());
    }
}
