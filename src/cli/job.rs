//! Running a configured job through the library and printing what it did: the nesting figures,
//! one line per part and, with `--json`, the report.

use std::path::Path;

use flatcut::mesh::SeamSource;
use flatcut::pipeline::{RunConfig, run_into};
use flatcut::progress::Progress;

use super::console::{say, stdout_text};
use super::outcome::Outcome;

/// Runs `config` into the output folder `output` (warnings go through `progress`; SIGINT and
/// SIGTERM leave the folder with the previous run), prints
/// the figures on stderr and, when `json`, the report on stdout.
pub fn execute(
    config: &RunConfig,
    output: &Path,
    json: bool,
    progress: &dyn Progress,
) -> anyhow::Result<Outcome> {
    let (result, report) = run_into(config, output, progress, &super::interrupt::watch)?;
    if let Some(nested) = &result.nesting {
        let layout = &nested.layout;
        say!(
            "flatcut: nested on {} sheet(s), utilisation {:.2} %, length used {:.1} mm",
            layout.sheets.len(),
            layout.utilisation * 100.0,
            layout.used_length
        );
    }
    for part in &report.parts {
        say!(
            "flatcut: {}: E_S {:.4} %, E_C {:.4} %, {} flipped, {} seam(s), {} cut(s) of total length {:.4}, {}",
            part.name,
            part.area_error * 100.0,
            part.shape_error * 100.0,
            part.flipped,
            part.seams.len(),
            part.cuts.len(),
            part.total_cut_length,
            if let Some(sheet) = part
                .sheet_metal
                .as_ref()
                .filter(|_| part.rejected.is_empty())
            {
                format!(
                    "sheet metal t {} mm unfolded exactly, {} bend(s) by {}, flat {:.3} x {:.3}",
                    sheet.thickness,
                    sheet.bends.len(),
                    sheet.bend_rule,
                    sheet.flat_width,
                    sheet.flat_height
                )
            } else if part.rejected.is_empty() {
                "within tolerance".to_string()
            } else if output.join(format!("{}.REJECTED.dxf", part.name)).exists() {
                format!(
                    "REJECTED: {}; cut file {}.REJECTED.dxf",
                    part.rejected.join(", "),
                    part.name
                )
            } else {
                format!(
                    "REJECTED: {}; no cut file (its outline cannot be drawn)",
                    part.rejected.join(", ")
                )
            }
        );
    }
    let surface_rejected =
        (report.parts.iter()).any(|part| !part.rejected.is_empty() && part.sheet_metal.is_none());
    if surface_rejected && config.options.seams == SeamSource::Whole {
        say!(
            "flatcut: hint: --seams auto cuts a part that stays over tolerance whole into pieces, \
             each within it (docs/cutting.md)"
        );
    }
    if json {
        stdout_text(&report.to_json());
    }
    Ok(
        if report.parts.iter().all(|part| part.rejected.is_empty()) {
            Outcome::Success
        } else {
            Outcome::OverTolerance
        },
    )
}
