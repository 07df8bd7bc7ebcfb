//! Parsers of option values shared by `run` and `nest`.

use flatcut::nest::Rotations;

/// Parses `WxH` (mm).
pub fn parse_sheet(text: &str) -> Result<(f64, f64), String> {
    let (width, height) = text
        .split_once(['x', 'X'])
        .ok_or("expected WIDTHxHEIGHT, for example 3000x1500")?;
    let number = |part: &str| {
        part.trim()
            .parse::<f64>()
            .map_err(|error| format!("'{part}': {error}"))
    };
    Ok((number(width)?, number(height)?))
}

/// Parses `0,90,180`, `step:15` or `free`.
pub fn parse_rotations(text: &str) -> Result<Rotations, String> {
    if text.eq_ignore_ascii_case("free") {
        return Ok(Rotations::Free);
    }
    if let Some(step) = text.strip_prefix("step:") {
        return step
            .trim()
            .parse()
            .map(Rotations::Step)
            .map_err(|error| format!("'{step}': {error}"));
    }
    text.split(',')
        .map(|angle| {
            angle
                .trim()
                .parse::<f64>()
                .map_err(|error| format!("'{angle}': {error}"))
        })
        .collect::<Result<Vec<_>, _>>()
        .map(Rotations::Fixed)
}
