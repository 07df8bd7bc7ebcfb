//! Option values shared by `run`, `flatten` and `nest`: their parsers and conversions.

use std::time::Duration;

use anyhow::bail;
use flatcut::export::DxfVersion;
use flatcut::nest::Rotations;

/// DXF versions on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum DxfVersionArg {
    /// AutoCAD 2000.
    R2000,
    /// AutoCAD R12.
    R12,
}

impl From<DxfVersionArg> for DxfVersion {
    fn from(version: DxfVersionArg) -> Self {
        match version {
            DxfVersionArg::R2000 => DxfVersion::R2000,
            DxfVersionArg::R12 => DxfVersion::R12,
        }
    }
}

/// The nesting search budget `--time S`, refusing a negative or non-finite number of seconds.
pub fn time_limit(seconds: f64) -> anyhow::Result<Duration> {
    if !seconds.is_finite() || seconds < 0.0 {
        bail!("--time {seconds}: give a number of seconds, 0 or more");
    }
    Ok(Duration::from_secs_f64(seconds))
}

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
