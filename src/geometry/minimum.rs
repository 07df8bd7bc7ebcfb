//! One-dimensional minimisation.

/// The golden ratio's inverse, `(√5 − 1) / 2`: each step of the search keeps this much of the
/// interval.
const INVERSE_PHI: f64 = 0.618_033_988_749_894_8;

/// Where `f` is least in `[low, high]`, by `steps` steps of golden-section search (the interval
/// shrinks to `0.618^steps` of itself; one evaluation per step, two to start): the middle of the
/// last interval. For a unimodal `f`, its minimum; otherwise a local one.
pub fn golden_section_minimum(
    mut f: impl FnMut(f64) -> f64,
    mut low: f64,
    mut high: f64,
    steps: usize,
) -> f64 {
    let mut x1 = high - INVERSE_PHI * (high - low);
    let mut x2 = low + INVERSE_PHI * (high - low);
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..steps {
        if f1 <= f2 {
            high = x2;
            (x2, f2) = (x1, f1);
            x1 = high - INVERSE_PHI * (high - low);
            f1 = f(x1);
        } else {
            low = x1;
            (x1, f1) = (x2, f2);
            x2 = low + INVERSE_PHI * (high - low);
            f2 = f(x2);
        }
    }
    0.5 * (low + high)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_minimum_of_a_parabola_is_found_to_the_interval_left() {
        let found = golden_section_minimum(|x| (x - 0.3).powi(2), -1.0, 2.0, 40);
        assert!((found - 0.3).abs() < 3.0 * INVERSE_PHI.powi(40));
    }

    #[test]
    fn a_minimum_at_an_end_is_approached_from_inside() {
        let found = golden_section_minimum(|x| x, 0.0, 1.0, 30);
        assert!(found > 0.0 && found < INVERSE_PHI.powi(30));
    }
}
