//! Plane geometry shared by every stage.

use glam::DVec2;

/// Signed area of a closed ring (positive when counter-clockwise), by the shoelace formula. The
/// ring's last point may or may not repeat its first.
pub fn signed_area(ring: &[DVec2]) -> f64 {
    let count = ring.len();
    0.5 * (0..count)
        .map(|index| ring[index].perp_dot(ring[(index + 1) % count]))
        .sum::<f64>()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_square_both_ways() {
        let square = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
        assert!((signed_area(&square) - 1.0).abs() < 1e-15);
        let mut reversed = square;
        reversed.reverse();
        assert!((signed_area(&reversed) + 1.0).abs() < 1e-15);
    }
}
