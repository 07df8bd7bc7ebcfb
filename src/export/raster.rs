//! A barycentric triangle rasteriser with a scalar interpolated linearly over each triangle
//! (Gouraud shading of a field, the paper's Eq. 16), coloured per pixel, written straight into a
//! tiny-skia pixmap (tiny-skia has no per-vertex colour fill).
//!
//! Input: corner positions in pixel coordinates (x right, y down, pixel `(i, j)` covers
//! `[i, i + 1) × [j, j + 1)`), triangles as index triples, one value per corner, and a colour
//! function of the interpolated value. A pixel is covered when its centre is inside the triangle.
//!
//! Seamless and without double cover: corners are snapped to a grid of 1/256 pixel and the edge
//! tests run in exact integer arithmetic, with a tie rule that gives a pixel centre on an edge
//! shared by two triangles to exactly one of them. No anti-aliasing: a stroked outline drawn
//! afterwards smooths the pattern's border.

use glam::DVec2;
use tiny_skia::{Pixmap, PremultipliedColorU8};

/// Sub-pixel steps per pixel of the snapped corner coordinates.
const SUBPIXELS: f64 = 256.0;

/// Largest coordinate magnitude accepted, in pixels; triangles reaching further are skipped so
/// the integer edge tests cannot overflow.
const COORDINATE_LIMIT: f64 = 1.0e6;

/// A triangle with its corners snapped to the sub-pixel grid and its values, corners in an order
/// that makes its doubled area positive.
struct SnappedTriangle {
    corners: [[i64; 2]; 3],
    values: [f64; 3],
    doubled_area: i64,
}

/// Fills `triangles` (indices into `corners` and `values`) with `colour(value)`, the value
/// interpolated linearly from the corners. Triangles with an index out of range, a non-finite
/// or far-out corner, or no area are skipped.
pub fn fill_interpolated(
    pixmap: &mut Pixmap,
    corners: &[DVec2],
    triangles: &[[u32; 3]],
    values: &[f64],
    colour: impl Fn(f64) -> PremultipliedColorU8,
) {
    let (width, height) = (pixmap.width() as i64, pixmap.height() as i64);
    let pixels = pixmap.pixels_mut();
    for triangle in triangles {
        let Some(snapped) = snap(corners, values, *triangle) else {
            continue;
        };
        let [x_start, x_end, y_start, y_end] = pixel_range(&snapped, width, height);
        for y in y_start..y_end {
            let row = (y * width) as usize;
            for x in x_start..x_end {
                if let Some(value) = interpolate(&snapped, x, y) {
                    pixels[row + x as usize] = colour(value);
                }
            }
        }
    }
}

/// The triangle's corners on the sub-pixel grid, counter-clockwise in the (x, y-down) frame
/// sense that gives a positive doubled area.
fn snap(corners: &[DVec2], values: &[f64], triangle: [u32; 3]) -> Option<SnappedTriangle> {
    let mut snapped = [[0i64; 2]; 3];
    let mut corner_values = [0.0; 3];
    for k in 0..3 {
        let vertex = triangle[k] as usize;
        let point = *corners.get(vertex)?;
        if !(point.x.abs() < COORDINATE_LIMIT && point.y.abs() < COORDINATE_LIMIT) {
            return None;
        }
        snapped[k] = [
            (point.x * SUBPIXELS).round() as i64,
            (point.y * SUBPIXELS).round() as i64,
        ];
        corner_values[k] = *values.get(vertex)?;
    }
    let mut doubled_area = edge_function(snapped[0], snapped[1], snapped[2]);
    if doubled_area < 0 {
        snapped.swap(1, 2);
        corner_values.swap(1, 2);
        doubled_area = -doubled_area;
    }
    (doubled_area > 0).then_some(SnappedTriangle {
        corners: snapped,
        values: corner_values,
        doubled_area,
    })
}

/// `[x_start, x_end, y_start, y_end]`: the pixels whose centres may lie in the triangle, clipped
/// to the image (empty ranges when it lies outside).
fn pixel_range(triangle: &SnappedTriangle, width: i64, height: i64) -> [i64; 4] {
    let step = SUBPIXELS as i64;
    let half = step / 2;
    let axis_range = |axis: usize, size: i64| {
        let low = triangle.corners.iter().map(|c| c[axis]).min().unwrap_or(0);
        let high = triangle.corners.iter().map(|c| c[axis]).max().unwrap_or(0);
        // Pixel i has its centre at i * step + half.
        let first = (low - half).div_euclid(step);
        let last = (high - half).div_euclid(step) + 1;
        (first.clamp(0, size), last.clamp(0, size))
    };
    let (x_start, x_end) = axis_range(0, width);
    let (y_start, y_end) = axis_range(1, height);
    [x_start, x_end, y_start, y_end]
}

/// The interpolated value at the centre of pixel `(x, y)`, or `None` when the centre is outside.
fn interpolate(triangle: &SnappedTriangle, x: i64, y: i64) -> Option<f64> {
    let step = SUBPIXELS as i64;
    let centre = [x * step + step / 2, y * step + step / 2];
    let [a, b, c] = triangle.corners;
    let weights = [
        edge_function(b, c, centre),
        edge_function(c, a, centre),
        edge_function(a, b, centre),
    ];
    let edges = [(b, c), (c, a), (a, b)];
    let inside = weights
        .iter()
        .zip(edges)
        .all(|(&weight, (start, end))| weight > 0 || (weight == 0 && owns_edge(start, end)));
    inside.then(|| {
        let sum: f64 = weights
            .iter()
            .zip(triangle.values)
            .map(|(&weight, value)| weight as f64 * value)
            .sum();
        sum / triangle.doubled_area as f64
    })
}

/// Twice the signed area of `(start, end, point)`: positive when `point` is on the interior side
/// of the edge `start → end` of a positively oriented triangle.
fn edge_function(start: [i64; 2], end: [i64; 2], point: [i64; 2]) -> i64 {
    (end[0] - start[0]) * (point[1] - start[1]) - (end[1] - start[1]) * (point[0] - start[0])
}

/// The tie rule for pixel centres exactly on an edge: a shared edge runs in opposite directions
/// in its two triangles, and exactly one direction owns it.
fn owns_edge(start: [i64; 2], end: [i64; 2]) -> bool {
    let (dx, dy) = (end[0] - start[0], end[1] - start[1]);
    dy > 0 || (dy == 0 && dx < 0)
}

#[cfg(test)]
mod tests {
    use crate::export::raster::*;

    fn marker(value: f64) -> PremultipliedColorU8 {
        let level = (value.clamp(0.0, 1.0) * 200.0).round() as u8 + 1;
        PremultipliedColorU8::from_rgba(level, 0, 0, 255).expect("opaque colour")
    }

    fn blank(width: u32, height: u32) -> Pixmap {
        Pixmap::new(width, height).expect("pixmap size")
    }

    /// A fan of triangles around a centre, sharing every inner edge.
    fn fan(centre: DVec2, radius: f64, count: usize) -> (Vec<DVec2>, Vec<[u32; 3]>) {
        let mut corners = vec![centre];
        for k in 0..count {
            let angle = std::f64::consts::TAU * k as f64 / count as f64 + 0.3;
            corners.push(centre + radius * DVec2::new(angle.cos(), angle.sin()));
        }
        let triangles = (0..count as u32)
            .map(|k| [0, 1 + k, 1 + (k + 1) % count as u32])
            .collect();
        (corners, triangles)
    }

    #[test]
    fn shared_edges_leave_no_gap_and_no_double_cover() {
        let (corners, triangles) = fan(DVec2::new(32.0, 32.0), 25.0, 13);
        let mut union = blank(64, 64);
        fill_interpolated(&mut union, &corners, &triangles, &[0.0; 14], marker);
        let mut counts = vec![0u32; 64 * 64];
        for triangle in &triangles {
            let mut single = blank(64, 64);
            fill_interpolated(&mut single, &corners, &[*triangle], &[0.0; 14], marker);
            for (count, pixel) in counts.iter_mut().zip(single.pixels()) {
                *count += u32::from(pixel.alpha() > 0);
            }
        }
        assert!(counts.iter().all(|&count| count <= 1), "double cover");
        let covered = union.pixels().iter().filter(|p| p.alpha() > 0).count();
        assert_eq!(covered, counts.iter().filter(|&&count| count == 1).count());
        // No hole inside: every pixel whose centre is well inside the polygon is covered.
        for y in 0..64 {
            for x in 0..64 {
                let centre = DVec2::new(x as f64 + 0.5, y as f64 + 0.5);
                if centre.distance(DVec2::new(32.0, 32.0)) < 20.0 {
                    assert!(union.pixels()[y * 64 + x].alpha() > 0, "hole at {x},{y}");
                }
            }
        }
    }

    #[test]
    fn values_are_interpolated_linearly() {
        let corners = [
            DVec2::new(0.0, 0.0),
            DVec2::new(100.0, 0.0),
            DVec2::new(0.0, 100.0),
        ];
        let mut pixmap = blank(100, 100);
        fill_interpolated(
            &mut pixmap,
            &corners,
            &[[0, 1, 2]],
            &[0.0, 1.0, 0.0],
            marker,
        );
        let pixel = pixmap.pixel(49, 10).expect("inside the image");
        // x = 49.5 of 100: value 0.495, level 0.495 * 200 + 1 = 100.
        assert_eq!(pixel.red(), 100);
    }

    #[test]
    fn triangles_outside_or_degenerate_draw_nothing() {
        let corners = [
            DVec2::new(-50.0, -50.0),
            DVec2::new(-10.0, -50.0),
            DVec2::new(-10.0, -10.0),
            DVec2::new(5.0, 5.0),
            DVec2::new(6.0, 6.0),
            DVec2::new(f64::NAN, 7.0),
        ];
        let mut pixmap = blank(16, 16);
        let triangles = [[0, 1, 2], [3, 4, 4], [3, 4, 5], [3, 4, 99]];
        fill_interpolated(&mut pixmap, &corners, &triangles, &[0.0; 6], marker);
        assert!(pixmap.pixels().iter().all(|p| p.alpha() == 0));
    }

    #[test]
    fn both_orientations_fill_the_same_pixels() {
        let corners = [
            DVec2::new(1.3, 2.1),
            DVec2::new(14.2, 4.7),
            DVec2::new(5.5, 13.9),
        ];
        let mut forward = blank(16, 16);
        let mut backward = blank(16, 16);
        fill_interpolated(&mut forward, &corners, &[[0, 1, 2]], &[0.0; 3], marker);
        fill_interpolated(&mut backward, &corners, &[[0, 2, 1]], &[0.0; 3], marker);
        assert_eq!(forward.data(), backward.data());
        assert!(forward.pixels().iter().any(|p| p.alpha() > 0));
    }
}
