//! Repairs of the dxf crate's (0.6.2) ASCII output that strict readers need, applied to the code
//! pairs after the crate has written them.
//!
//! - R2000: the crate writes no handle on TABLE heads (ezdxf's audit then has to fix seven of
//!   them). Each TABLE head gets a fresh handle after the drawing's last one, and `$HANDSEED`
//!   moves past them.
//! - R12: the crate writes subclass markers (group code 100), which only exist from R13 and make
//!   an R12 reader reject the tables; they are removed. VERTEX and SEQEND entities are put on their
//!   POLYLINE's layer (the crate leaves vertices on layer 0 and SEQEND on none).
//!
//! Input and output: the whole file as bytes, lines ending in CR LF, each pair a right-aligned
//! group code line and a value line. Values are copied byte for byte.

use super::dxf_options::DxfVersion;

/// One group code and its value, as written.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Pair {
    code: i32,
    value: Vec<u8>,
}

impl Pair {
    fn new(code: i32, value: &[u8]) -> Self {
        Self {
            code,
            value: value.to_vec(),
        }
    }

    fn is(&self, code: i32, value: &[u8]) -> bool {
        self.code == code && self.value == value
    }
}

/// The file with the repairs for its version applied. Bytes that are not a sequence of code
/// pairs are returned unchanged.
pub(crate) fn repair(bytes: Vec<u8>, version: DxfVersion) -> Vec<u8> {
    let Some(pairs) = parse(&bytes) else {
        return bytes;
    };
    let repaired = match version {
        DxfVersion::R2000 => add_table_handles(pairs),
        DxfVersion::R12 => polyline_layers(remove_subclass_markers(pairs)),
    };
    serialise(&repaired)
}

/// The code pairs of an ASCII DXF, or `None` if a code line is not a number.
fn parse(bytes: &[u8]) -> Option<Vec<Pair>> {
    let body = bytes.strip_suffix(b"\r\n").unwrap_or(bytes);
    let lines: Vec<&[u8]> = body
        .split(|&byte| byte == b'\n')
        .map(|line| line.strip_suffix(b"\r").unwrap_or(line))
        .collect();
    if !lines.len().is_multiple_of(2) {
        return None;
    }
    lines
        .chunks(2)
        .map(|pair| {
            let code = std::str::from_utf8(pair[0]).ok()?.trim().parse().ok()?;
            Some(Pair::new(code, pair[1]))
        })
        .collect()
}

/// The pairs as file bytes, codes right-aligned on three columns as the dxf crate writes them.
fn serialise(pairs: &[Pair]) -> Vec<u8> {
    let mut bytes = Vec::with_capacity(pairs.len() * 16);
    for pair in pairs {
        bytes.extend_from_slice(format!("{:>3}\r\n", pair.code).as_bytes());
        bytes.extend_from_slice(&pair.value);
        bytes.extend_from_slice(b"\r\n");
    }
    bytes
}

/// A handle on every TABLE head, numbered from `$HANDSEED`, which moves past them.
fn add_table_handles(pairs: Vec<Pair>) -> Vec<Pair> {
    let seed_position = pairs
        .windows(2)
        .position(|window| window[0].is(9, b"$HANDSEED") && window[1].code == 5);
    let Some(seed_index) = seed_position.map(|position| position + 1) else {
        return pairs;
    };
    let Some(mut next_handle) = std::str::from_utf8(&pairs[seed_index].value)
        .ok()
        .and_then(|text| u64::from_str_radix(text.trim(), 16).ok())
    else {
        return pairs;
    };
    let mut repaired = Vec::with_capacity(pairs.len() + 16);
    let mut after_table_head = false;
    for pair in pairs {
        let is_table_name = after_table_head && pair.code == 2;
        after_table_head = pair.is(0, b"TABLE");
        repaired.push(pair);
        if is_table_name {
            repaired.push(Pair::new(5, format!("{next_handle:X}").as_bytes()));
            next_handle += 1;
        }
    }
    repaired[seed_index].value = format!("{next_handle:X}").into_bytes();
    repaired
}

/// The pairs without subclass markers (group code 100).
fn remove_subclass_markers(pairs: Vec<Pair>) -> Vec<Pair> {
    pairs.into_iter().filter(|pair| pair.code != 100).collect()
}

/// VERTEX and SEQEND entities on the layer of the POLYLINE they belong to.
fn polyline_layers(pairs: Vec<Pair>) -> Vec<Pair> {
    let mut repaired = Vec::with_capacity(pairs.len() + 64);
    let mut polyline_layer: Option<Vec<u8>> = None;
    let mut current_entity: Vec<u8> = Vec::new();
    for pair in pairs {
        if pair.code == 0 {
            if current_entity == b"SEQEND"
                && let Some(layer) = polyline_layer.take()
            {
                repaired.push(Pair {
                    code: 8,
                    value: layer,
                });
            }
            current_entity = pair.value.clone();
            if !matches!(current_entity.as_slice(), b"VERTEX" | b"SEQEND") {
                polyline_layer = None;
            }
            repaired.push(pair);
            continue;
        }
        match (current_entity.as_slice(), pair.code) {
            (b"POLYLINE", 8) => polyline_layer = Some(pair.value.clone()),
            (b"VERTEX", 8) => {
                if let Some(layer) = &polyline_layer {
                    repaired.push(Pair {
                        code: 8,
                        value: layer.clone(),
                    });
                    continue;
                }
            }
            _ => {}
        }
        repaired.push(pair);
    }
    repaired
}

#[cfg(test)]
mod tests {
    use crate::export::dxf_repair::*;

    fn file(pairs: &[(i32, &str)]) -> Vec<u8> {
        serialise(
            &pairs
                .iter()
                .map(|(code, value)| Pair::new(*code, value.as_bytes()))
                .collect::<Vec<_>>(),
        )
    }

    #[test]
    fn table_heads_get_handles_after_the_seed() {
        let input = file(&[
            (9, "$HANDSEED"),
            (5, "1C"),
            (0, "TABLE"),
            (2, "LAYER"),
            (0, "ENDTAB"),
            (0, "TABLE"),
            (2, "LTYPE"),
            (0, "EOF"),
        ]);
        let expected = file(&[
            (9, "$HANDSEED"),
            (5, "1E"),
            (0, "TABLE"),
            (2, "LAYER"),
            (5, "1C"),
            (0, "ENDTAB"),
            (0, "TABLE"),
            (2, "LTYPE"),
            (5, "1D"),
            (0, "EOF"),
        ]);
        assert_eq!(repair(input, DxfVersion::R2000), expected);
    }

    #[test]
    fn r12_loses_subclass_markers_and_vertices_follow_their_polyline() {
        let input = file(&[
            (0, "POLYLINE"),
            (8, "CUT_OUTER"),
            (0, "VERTEX"),
            (8, "0"),
            (100, "AcDbVertex"),
            (10, "1.0"),
            (0, "SEQEND"),
            (5, "1A"),
            (0, "LINE"),
            (8, "MARKS"),
            (0, "EOF"),
        ]);
        let expected = file(&[
            (0, "POLYLINE"),
            (8, "CUT_OUTER"),
            (0, "VERTEX"),
            (8, "CUT_OUTER"),
            (10, "1.0"),
            (0, "SEQEND"),
            (5, "1A"),
            (8, "CUT_OUTER"),
            (0, "LINE"),
            (8, "MARKS"),
            (0, "EOF"),
        ]);
        assert_eq!(repair(input, DxfVersion::R12), expected);
    }

    #[test]
    fn bytes_that_are_not_code_pairs_pass_unchanged() {
        let bytes = b"not\r\na dxf\r\n".to_vec();
        assert_eq!(repair(bytes.clone(), DxfVersion::R12), bytes);
    }
}
