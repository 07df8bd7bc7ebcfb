//! The file's text rewritten where truck-stepio would misread it.

use super::entities::basis_curve;
use super::statements::Statements;
use super::units::{ContextUnits, units_of};

/// The file with every surface curve's 3D curve preferred to its parameter-space curves
/// (`.PCURVE_S1.` and `.PCURVE_S2.` become `.CURVE_3D.`). The representations are equivalent by
/// the standard; truck-stepio trims a closed parameter-space curve (Open CASCADE writes circles
/// as closed 2D B-splines) the long way round, but trims 3D circles and lines correctly.
pub fn prefer_3d_curves(text: &str) -> String {
    text.replace(".PCURVE_S1.", ".CURVE_3D.")
        .replace(".PCURVE_S2.", ".CURVE_3D.")
}

/// The file rewritten where truck-stepio would misread it: every `CONICAL_SURFACE`'s
/// semi-angle in radians (truck-stepio reads it as radians, but it is in the plane angle unit of
/// its representation's context: degrees in files CATIA V4 writes), and every `TRIMMED_CURVE`
/// replaced by its basis curve (truck-stepio cannot read trimmed curves; an edge's vertices
/// bound its curve anyway).
pub fn rewritten_for_truck(
    text: &str,
    statements: &Statements,
    default_units: ContextUnits,
) -> Result<String, String> {
    let mut replacements = Vec::new();
    for (&id, statement) in statements.iter() {
        if statement.is("CONICAL_SURFACE") {
            let radians = units_of(statements, id)?.unwrap_or(default_units).radians;
            if radians != 1.0 {
                let rewritten = with_last_argument_scaled(&statement.body, radians)
                    .ok_or_else(|| format!("CONICAL_SURFACE #{id} could not be read"))?;
                replacements.push((id, rewritten));
            }
        } else if statement.is("TRIMMED_CURVE")
            && let Some(basis) = basis_curve(statements, id)
        {
            replacements.push((id, basis.body.clone()));
        }
    }
    let mut spans = Vec::with_capacity(replacements.len());
    for (id, body) in replacements {
        let (start, end) =
            statement_span(text, id).ok_or_else(|| format!("#{id} could not be read"))?;
        spans.push((start, end, format!("#{id}={body}")));
    }
    spans.sort_unstable_by_key(|&(start, _, _)| start);
    let mut rewritten = String::with_capacity(text.len());
    let mut copied = 0;
    for (start, end, statement) in spans {
        rewritten.push_str(&text[copied..start]);
        rewritten.push_str(&statement);
        copied = end;
    }
    rewritten.push_str(&text[copied..]);
    Ok(rewritten)
}

/// `NAME(..., x)` with its last argument (a number) multiplied by `factor`.
fn with_last_argument_scaled(body: &str, factor: f64) -> Option<String> {
    let close = body.rfind(')')?;
    let comma = body[..close].rfind(',')?;
    let value: f64 = body[comma + 1..close].trim().parse().ok()?;
    Some(format!(
        "{},{:?}{}",
        &body[..comma],
        value * factor,
        &body[close..]
    ))
}

/// The byte range of instance `#id`'s statement in `text`, from its `#` to before its `;`.
fn statement_span(text: &str, id: u64) -> Option<(usize, usize)> {
    let label = format!("#{id}");
    let mut from = 0;
    while let Some(found) = text[from..].find(&label) {
        let start = from + found;
        let after = &text[start + label.len()..];
        let before = text[..start].trim_end();
        let at_statement = before.is_empty() || before.ends_with(';') || before.ends_with("*/");
        if after.trim_start().starts_with('=') && at_statement {
            let end = start + after.find(';')? + label.len();
            return Some((start, end));
        }
        from = start + label.len();
    }
    None
}
