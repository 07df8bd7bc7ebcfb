//! The energy report picture written by `flatten`: a PNG of the default width whose colours span
//! the scale from blue to red on a non-developable part, and all blue on a developable one.

use flatcut::export::colormap::palette_colour;
use flatcut::export::energy_png::DEFAULT_WIDTH_PIXELS;

use crate::util::{flatten_into, sample, stderr};

/// Largest per-channel difference for a pixel to count as a palette colour.
const COLOUR_TOLERANCE: i32 = 8;

/// Pixels left of this x belong to the pattern panel; the legend column lies to the right.
const PANEL_RIGHT: u32 = 1300;

fn energy_png(name: &str, arguments: &[&str]) -> tiny_skia::Pixmap {
    let directory = tempfile::tempdir().expect("temporary directory");
    let output = flatten_into(&sample(&format!("{name}.obj")), directory.path(), arguments);
    assert!(
        matches!(output.status.code(), Some(0 | 3)),
        "{}",
        stderr(&output)
    );
    let bytes =
        std::fs::read(directory.path().join(format!("{name}.energy.png"))).expect("PNG written");
    tiny_skia::Pixmap::decode_png(&bytes).expect("a valid PNG")
}

/// Pixels of the pattern panels within [`COLOUR_TOLERANCE`] of the palette colour at `position`.
fn pixels_near(pixmap: &tiny_skia::Pixmap, position: f64) -> usize {
    pixels_near_between(pixmap, position, 0..PANEL_RIGHT)
}

/// Pixels with x in `columns` within [`COLOUR_TOLERANCE`] of the palette colour at `position`.
fn pixels_near_between(
    pixmap: &tiny_skia::Pixmap,
    position: f64,
    columns: std::ops::Range<u32>,
) -> usize {
    let target = palette_colour(position);
    pixmap
        .pixels()
        .iter()
        .enumerate()
        .filter(|(index, _)| columns.contains(&((*index as u32) % pixmap.width())))
        .filter(|(_, pixel)| {
            let colour = pixel.demultiply();
            let channels = [colour.red(), colour.green(), colour.blue()];
            (0..3)
                .all(|k| (i32::from(channels[k]) - i32::from(target[k])).abs() <= COLOUR_TOLERANCE)
        })
        .count()
}

#[test]
fn saddle_map_spans_the_colour_scale() {
    // Uncut and whole: the cuts (or pieces) that bring the saddle within tolerance release most
    // of its energy.
    let pixmap = energy_png("saddle", &["--max-cuts", "0", "--seams", "whole"]);
    assert_eq!(pixmap.width(), DEFAULT_WIDTH_PIXELS);
    assert!(pixmap.height() > 800, "{}", pixmap.height());
    // Near both ends of the scale and in the middle (the converged saddle has little energy
    // below 10 % of the square-root scale).
    for position in [0.15, 0.5, 0.95] {
        let count = pixels_near(&pixmap, position);
        assert!(count > 500, "{count} pixels at scale position {position}");
    }
}

#[test]
fn developable_part_is_all_low_energy() {
    let pixmap = energy_png("cylinder_segment", &[]);
    assert!(pixels_near(&pixmap, 0.0) > 100_000);
    for position in [0.5, 1.0] {
        assert_eq!(
            pixels_near(&pixmap, position),
            0,
            "scale position {position}"
        );
    }
}

#[test]
fn a_cut_part_shows_its_map_before_cutting_beside_the_map_after() {
    // The hemisphere is cut from about 17 % to under 1 %: on the shared colour scale the panel
    // before cutting (left) reaches orange-red at its rim, the panel after cutting (right)
    // stays blue.
    let pixmap = energy_png("hemisphere", &[]);
    let middle = DEFAULT_WIDTH_PIXELS / 2;
    let red_before = pixels_near_between(&pixmap, 0.85, 0..middle);
    assert!(red_before > 300, "{red_before} red pixels before cutting");
    let blue_after = pixels_near_between(&pixmap, 0.05, middle..PANEL_RIGHT);
    assert!(
        blue_after > 20_000,
        "{blue_after} blue pixels after cutting"
    );
    for position in [0.5, 0.85] {
        let count = pixels_near_between(&pixmap, position, middle..PANEL_RIGHT);
        assert_eq!(count, 0, "after cutting, scale position {position}");
    }
}
