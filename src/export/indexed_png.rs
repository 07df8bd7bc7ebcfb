//! Compact PNG encoding of an opaque picture: an 8-bit indexed (palette) PNG.
//!
//! Input: an opaque [`Pixmap`]. Output: PNG bytes with a palette of at most 256 colours. A
//! picture with 256 colours or fewer is encoded exactly. A richer one (the energy report's
//! smooth colour ramp under anti-aliased lines and text holds a few thousand colours) gets the
//! palette that greedy variance splitting of its colour histogram finds (Wu, *Efficient
//! statistical computations for optimal color quantization*, Graphics Gems II, 1991, with
//! axis-aligned cuts): starting from one box holding every colour, the box with the largest
//! squared error is cut across its widest channel where the two halves' squared errors sum
//! least, until there are 256 boxes; each box's count-weighted mean is a palette colour, and each
//! pixel takes its nearest palette colour. No dithering, so flat areas stay flat and the output
//! is a pure function of the pixels (byte-identical for the same picture).
//!
//! One byte per pixel instead of three, and runs of equal indices that deflate well, make the
//! file several times smaller than 24-bit RGB.

use rustc_hash::FxHashMap;
use tiny_skia::Pixmap;

/// Most colours a PNG palette holds (8-bit indices).
pub const PALETTE_SIZE: usize = 256;

/// When boxes are chosen and cut, a colour weighs as many pixels as it covers, up to this many:
/// the colours of a smooth ramp drawn small (the legend's colour bar, a thin band of the map)
/// then get palette entries as well as the large areas do, and no step shows. A box's palette
/// colour is its mean weighted by the full counts, so large flat areas (the white background)
/// keep their exact colour.
const WEIGHT_CAP: u64 = 16;

/// One colour of the histogram and how many pixels have it.
#[derive(Debug, Clone, Copy)]
struct Entry {
    rgb: [u8; 3],
    count: u64,
}

/// Encodes an opaque pixmap as an indexed PNG (see the module documentation). Alpha is dropped,
/// which is exact for an opaque image.
pub fn encode_indexed_png(pixmap: &Pixmap) -> Result<Vec<u8>, png::EncodingError> {
    let packed = pixmap.pixels().iter().map(|pixel| {
        let colour = pixel.demultiply();
        pack([colour.red(), colour.green(), colour.blue()])
    });
    let runs = runs(packed);
    let (histogram, entry_of_run) = histogram(&runs);
    let palette = palette(&histogram);
    let nearest: Vec<u8> = histogram
        .iter()
        .map(|entry| nearest_index(entry.rgb, &palette))
        .collect();
    let mut indices = Vec::with_capacity(pixmap.pixels().len());
    for (&(_, length), &entry) in runs.iter().zip(&entry_of_run) {
        indices.extend(std::iter::repeat_n(
            nearest[entry as usize],
            length as usize,
        ));
    }
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, pixmap.width(), pixmap.height());
    encoder.set_color(png::ColorType::Indexed);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_palette(palette.concat());
    encoder.set_compression(png::Compression::Balanced);
    encoder.set_filter(png::Filter::NoFilter);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(&indices)?;
    writer.finish()?;
    Ok(bytes)
}

fn pack([red, green, blue]: [u8; 3]) -> u32 {
    (u32::from(red) << 16) | (u32::from(green) << 8) | u32::from(blue)
}

/// Runs of equal colours in pixel order: `(packed colour, length)`. A picture of large flat and
/// smooth areas has far fewer runs than pixels, so the histogram and the indices are made from
/// runs.
fn runs(packed: impl IntoIterator<Item = u32>) -> Vec<(u32, u32)> {
    let mut runs: Vec<(u32, u32)> = Vec::new();
    for colour in packed {
        match runs.last_mut() {
            Some((last, length)) if *last == colour => *length += 1,
            _ => runs.push((colour, 1)),
        }
    }
    runs
}

/// The distinct colours of the picture with their pixel counts, sorted by packed colour, and
/// for each run the index of its colour's entry.
fn histogram(runs: &[(u32, u32)]) -> (Vec<Entry>, Vec<u32>) {
    // Each colour gets a slot when first seen (a hash lookup per run); only the distinct colours,
    // a few thousand against up to a million runs, are sorted.
    let mut slot_of: FxHashMap<u32, u32> = FxHashMap::default();
    let mut slots: Vec<(u32, u64)> = Vec::new();
    let mut slot_of_run = Vec::with_capacity(runs.len());
    for &(colour, length) in runs {
        let slot = *slot_of.entry(colour).or_insert_with(|| {
            slots.push((colour, 0));
            (slots.len() - 1) as u32
        });
        slots[slot as usize].1 += u64::from(length);
        slot_of_run.push(slot);
    }
    let mut order: Vec<u32> = (0..slots.len() as u32).collect();
    order.sort_unstable_by_key(|&slot| slots[slot as usize].0);
    let mut entry_of_slot = vec![0; slots.len()];
    for (entry, &slot) in order.iter().enumerate() {
        entry_of_slot[slot as usize] = entry as u32;
    }
    let entries = (order.iter())
        .map(|&slot| {
            let (colour, count) = slots[slot as usize];
            Entry {
                rgb: [(colour >> 16) as u8, (colour >> 8) as u8, colour as u8],
                count,
            }
        })
        .collect();
    let entry_of_run = (slot_of_run.iter())
        .map(|&slot| entry_of_slot[slot as usize])
        .collect();
    (entries, entry_of_run)
}

/// At most [`PALETTE_SIZE`] colours for `histogram`: its own colours when they fit, else the
/// means of the boxes of greedy variance splitting.
fn palette(histogram: &[Entry]) -> Vec<[u8; 3]> {
    if histogram.len() <= PALETTE_SIZE {
        return histogram.iter().map(|entry| entry.rgb).collect();
    }
    let mut entries = histogram.to_vec();
    let error_of = |entries: &[Entry]| Moments::of(entries, WEIGHT_CAP).squared_error();
    let mut boxes = Vec::with_capacity(PALETTE_SIZE);
    let mut errors = Vec::with_capacity(PALETTE_SIZE);
    boxes.push(0..entries.len());
    errors.push(error_of(&entries));
    while boxes.len() < PALETTE_SIZE {
        let (worst, error) =
            (errors.iter().copied().enumerate()).fold((0, f64::NEG_INFINITY), |best, candidate| {
                if candidate.1 > best.1 {
                    candidate
                } else {
                    best
                }
            });
        if error <= 0.0 {
            break;
        }
        let range = boxes[worst].clone();
        let cut = range.start + best_cut(&mut entries[range.clone()]);
        boxes[worst] = range.start..cut;
        errors[worst] = error_of(&entries[range.start..cut]);
        boxes.push(cut..range.end);
        errors.push(error_of(&entries[cut..range.end]));
    }
    boxes
        .iter()
        .map(|range| Moments::of(&entries[range.clone()], u64::MAX).mean())
        .collect()
}

/// Sorts a box's colours along its widest channel (by variance) and returns where to cut it so
/// that the two halves' squared errors sum least (at least one colour each side).
fn best_cut(entries: &mut [Entry]) -> usize {
    let moments = Moments::of(entries, WEIGHT_CAP);
    let channel = (0..3)
        .max_by(|&a, &b| {
            moments
                .variance(a)
                .total_cmp(&moments.variance(b))
                .then(b.cmp(&a))
        })
        .unwrap_or(0);
    entries.sort_unstable_by_key(|entry| (entry.rgb[channel], pack(entry.rgb)));
    let mut left = Moments::default();
    let mut best = (1, f64::INFINITY);
    for cut in 1..entries.len() {
        left.add(entries[cut - 1], WEIGHT_CAP);
        let error = left.squared_error() + moments.minus(&left).squared_error();
        if error < best.1 {
            best = (cut, error);
        }
    }
    best.0
}

/// Count, sums and sums of squares of a set of colours, weighted by pixel count.
#[derive(Debug, Clone, Copy, Default)]
struct Moments {
    count: f64,
    sum: [f64; 3],
    squares: [f64; 3],
}

impl Moments {
    /// The moments of `entries`, each weighing its pixel count up to `cap`.
    fn of(entries: &[Entry], cap: u64) -> Self {
        let mut moments = Self::default();
        for &entry in entries {
            moments.add(entry, cap);
        }
        moments
    }

    fn add(&mut self, entry: Entry, cap: u64) {
        let count = entry.count.min(cap) as f64;
        self.count += count;
        for channel in 0..3 {
            let value = f64::from(entry.rgb[channel]);
            self.sum[channel] += count * value;
            self.squares[channel] += count * value * value;
        }
    }

    fn minus(&self, other: &Self) -> Self {
        Self {
            count: self.count - other.count,
            sum: [0, 1, 2].map(|c| self.sum[c] - other.sum[c]),
            squares: [0, 1, 2].map(|c| self.squares[c] - other.squares[c]),
        }
    }

    /// Count times the variance of one channel.
    fn variance(&self, channel: usize) -> f64 {
        if self.count <= 0.0 {
            return 0.0;
        }
        self.squares[channel] - self.sum[channel] * self.sum[channel] / self.count
    }

    /// Sum over the colours of count times squared distance to the mean.
    fn squared_error(&self) -> f64 {
        (0..3).map(|channel| self.variance(channel)).sum()
    }

    fn mean(&self) -> [u8; 3] {
        self.sum
            .map(|sum| (sum / self.count.max(1.0)).round().clamp(0.0, 255.0) as u8)
    }
}

/// The index of the palette colour nearest to `rgb` (squared distance; the first on a tie).
fn nearest_index(rgb: [u8; 3], palette: &[[u8; 3]]) -> u8 {
    let distance = |colour: &[u8; 3]| -> i32 {
        (0..3)
            .map(|c| (i32::from(colour[c]) - i32::from(rgb[c])).pow(2))
            .sum()
    };
    palette
        .iter()
        .enumerate()
        .min_by_key(|&(index, colour)| (distance(colour), index))
        .map_or(0, |(index, _)| index as u8)
}

#[cfg(test)]
mod tests {
    use crate::export::indexed_png::*;
    use tiny_skia::Color;

    /// The RGB bytes of a PNG, through tiny-skia's decoder (palette expanded).
    fn decode(bytes: &[u8]) -> Pixmap {
        Pixmap::decode_png(bytes).expect("a PNG")
    }

    /// A picture with `columns` distinct grey-blue columns, 4 pixels wide.
    fn ramp(columns: u32) -> Pixmap {
        let mut pixmap = Pixmap::new(columns * 4, 8).expect("size");
        for (k, pixel) in pixmap.pixels_mut().iter_mut().enumerate() {
            let column = (k as u32 % (columns * 4)) / 4;
            let value = (column * 255 / columns.max(2)) as u8;
            *pixel = Color::from_rgba8(value, value / 2, 255 - value, 255)
                .premultiply()
                .to_color_u8();
        }
        pixmap
    }

    fn rgb(pixmap: &Pixmap) -> Vec<u8> {
        pixmap
            .pixels()
            .iter()
            .flat_map(|p| [p.red(), p.green(), p.blue()])
            .collect()
    }

    #[test]
    fn a_picture_of_few_colours_is_encoded_exactly() {
        let pixmap = ramp(200);
        let decoded = decode(&encode_indexed_png(&pixmap).expect("encodes"));
        assert_eq!((decoded.width(), decoded.height()), (800, 8));
        assert_eq!(rgb(&decoded), rgb(&pixmap));
    }

    #[test]
    fn a_picture_of_many_colours_is_close_and_deterministic() {
        let mut pixmap = Pixmap::new(1000, 20).expect("size");
        for (k, pixel) in pixmap.pixels_mut().iter_mut().enumerate() {
            let (x, y) = (k % 1000, k / 1000);
            let red = (x * 255 / 999) as u8;
            let green = (y * 12) as u8;
            *pixel = Color::from_rgba8(red, green, 255 - red / 2, 255)
                .premultiply()
                .to_color_u8();
        }
        let bytes = encode_indexed_png(&pixmap).expect("encodes");
        assert_eq!(bytes, encode_indexed_png(&pixmap).expect("encodes"));
        let largest = rgb(&decode(&bytes))
            .iter()
            .zip(rgb(&pixmap))
            .map(|(&a, b)| (i32::from(a) - i32::from(b)).abs())
            .max()
            .unwrap_or(0);
        // 256 × 21 colours spread evenly over a 256-colour palette: boxes of about 5 × 5 levels
        // of red and green (measured: 9 levels at most).
        assert!(largest <= 12, "largest channel error {largest}");
    }
}
