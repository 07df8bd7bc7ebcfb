//! Compressed rows: per-vertex lists (incident faces, edges or springs) in two flat arrays.

/// The compressed rows of `entries` (row, value) over `row_count` rows: offsets (`row_count + 1`,
/// row `r` is `values[offsets[r]..offsets[r + 1]]`) and values, each row in the entries' order.
pub fn compressed_rows<I>(row_count: usize, entries: I) -> (Vec<u32>, Vec<u32>)
where
    I: Iterator<Item = (u32, u32)> + Clone,
{
    let mut offsets = vec![0u32; row_count + 1];
    for (row, _) in entries.clone() {
        offsets[row as usize + 1] += 1;
    }
    for r in 0..row_count {
        offsets[r + 1] += offsets[r];
    }
    let mut fill = offsets.clone();
    let mut values = vec![0u32; offsets[row_count] as usize];
    for (row, value) in entries {
        values[fill[row as usize] as usize] = value;
        fill[row as usize] += 1;
    }
    (offsets, values)
}

#[cfg(test)]
mod tests {
    use crate::mesh::rows::*;

    #[test]
    fn rows_keep_the_entries_order_and_empty_rows_stay_empty() {
        let entries = [(2, 7), (0, 1), (2, 3), (0, 4)];
        let (offsets, values) = compressed_rows(4, entries.into_iter());
        assert_eq!(offsets, vec![0, 2, 2, 4, 4]);
        assert_eq!(values, vec![1, 4, 7, 3]);
    }
}
