//! Summary statistics: mean, standard deviation and the medians every layer uses (the
//! quality report, the experiments, the real-data comparison).

/// Mean, population standard deviation and median of the finite values; `None` if there
/// are none.
pub fn summarize(values: &[f64]) -> Option<(f64, f64, f64)> {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    if v.is_empty() {
        return None;
    }
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n;
    v.sort_by(f64::total_cmp);
    Some((mean, var.sqrt(), median_sorted(&v)))
}

/// Median of an ascending slice (mean of the two middle values for even lengths).
pub fn median_sorted(v: &[f64]) -> f64 {
    let n = v.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Median of the finite values (NaN if none).
pub fn median(values: &[f64]) -> f64 {
    summarize(values).map(|s| s.2).unwrap_or(f64::NAN)
}

/// Upper median of the finite values: the middle one, the upper of the two middle ones for
/// an even count (always one of the values, never an average); `None` if there are none.
pub fn upper_median(values: impl IntoIterator<Item = f64>) -> Option<f64> {
    let mut v: Vec<f64> = values.into_iter().filter(|x| x.is_finite()).collect();
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_values() {
        let (m, s, med) = summarize(&[1.0, 2.0, 3.0, 4.0, f64::NAN]).unwrap();
        assert_eq!(m, 2.5);
        assert!((s - 1.25f64.sqrt()).abs() < 1e-15);
        assert_eq!(med, 2.5);
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), 2.5);
        assert!(median(&[]).is_nan());
        assert_eq!(upper_median([4.0, 1.0, 2.0, 3.0, f64::NAN]), Some(3.0));
        assert_eq!(upper_median([]), None);
        assert!(summarize(&[f64::NAN]).is_none());
    }
}
