//! Support of the table form of large emitted solvers.
//!
//! A solver whose coefficient code would be tens of thousands of lines (templates of
//! hundreds of rows) is emitted in table form: the coefficient statements write one array
//! `c` from a few functions of bounded size, and the template is filled from `c` through a
//! constant table of `(entry, coefficient)` pairs by [`fill_template`]. The arithmetic is
//! the same, operation for operation, as in the straight-line form; only where the values
//! live changes, so both forms compute the same bits.

/// A zeroed `[f64; N]` on the heap (a coefficient array too large for the stack).
#[must_use]
pub fn zeroed_coefficients<const N: usize>() -> Box<[f64; N]> {
    let v: Box<[f64]> = vec![0.0; N].into_boxed_slice();
    match v.try_into() {
        Ok(b) => b,
        // The slice has length N by construction.
        Err(_) => unreachable!("a vec of length N converts to [f64; N]"),
    }
}

/// Writes `m[entry] = ±c[k]` for every `[entry, code]` of `table`, where
/// `code = 2 k + negated`. Entries or coefficients out of range are skipped (the generator
/// never emits them; skipping keeps the never-panics contract).
#[inline]
pub fn fill_template(m: &mut [f64], c: &[f64], table: &[[u32; 2]]) {
    for &[entry, code] in table {
        let (Some(&v), Some(slot)) = (c.get((code >> 1) as usize), m.get_mut(entry as usize))
        else {
            continue;
        };
        *slot = if code & 1 == 0 { v } else { -v };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fills_signed_entries_and_skips_out_of_range_codes() {
        let c = [1.5, -2.0, 4.0];
        let mut m = [0.0; 6];
        fill_template(&mut m, &c, &[[0, 0], [3, 3], [5, 4], [2, 7], [9, 0]]);
        assert_eq!(m, [1.5, 0.0, 0.0, 2.0, 0.0, 4.0]);
        let z = zeroed_coefficients::<5000>();
        assert!(z.iter().all(|&x| x == 0.0));
    }
}
