//! The units of STEP geometry: each shape representation's context assigns a length unit (an SI
//! metre with a prefix, or a conversion-based unit such as the inch, defined by a measure of
//! another unit) and a plane angle unit (radian or degree). A file may hold several contexts in
//! different units (Autodesk Inventor writes an inch context beside the millimetre one its
//! solids use), so the units of a piece of geometry are those of the representation that holds
//! it, found by walking up through the instances that refer to it.

use std::collections::{BTreeSet, VecDeque};

use super::statements::{Statement, Statements, measure_value};

/// The length and plane angle units of a geometric representation context.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContextUnits {
    /// Millimetres per length unit.
    pub millimetres: f64,
    /// Radians per plane angle unit.
    pub radians: f64,
}

impl Default for ContextUnits {
    /// Millimetres and radians: what a file that declares no unit is read in.
    fn default() -> Self {
        Self {
            millimetres: 1.0,
            radians: 1.0,
        }
    }
}

/// Conversion-based units are defined through at most this many other units.
const MAX_UNIT_DEPTH: usize = 8;

/// The units of the representation that holds `item` (walking up through the instances that
/// refer to it, nearest first, to a `*SHAPE_REPRESENTATION`); `None` when no such
/// representation or no length unit in its context is found.
pub fn units_of(statements: &Statements, item: u64) -> Result<Option<ContextUnits>, String> {
    let Some(representation) = holding_representation(statements, item) else {
        return Ok(None);
    };
    let context = statements
        .get(&representation)
        .and_then(|r| r.references.last())
        .copied();
    context.map_or(Ok(None), |context| context_units(statements, context))
}

/// The units of the file's geometry where an item's own representation is not found: those of
/// the context of the first shape representation whose context declares a length unit, else of
/// the first context that does; millimetres and radians if none does.
pub fn file_units(statements: &Statements) -> Result<ContextUnits, String> {
    for (_, statement) in statements.iter() {
        if is_shape_representation(statement)
            && let Some(&context) = statement.references.last()
            && let Some(units) = context_units(statements, context)?
        {
            return Ok(units);
        }
    }
    for (&id, statement) in statements.iter() {
        if statement.is("GLOBAL_UNIT_ASSIGNED_CONTEXT")
            && let Some(units) = context_units(statements, id)?
        {
            return Ok(units);
        }
    }
    Ok(ContextUnits::default())
}

fn is_shape_representation(statement: &Statement) -> bool {
    statement
        .names
        .iter()
        .any(|name| name.ends_with("SHAPE_REPRESENTATION"))
}

/// The nearest shape representation above `item` (breadth first, referrers in id order).
fn holding_representation(statements: &Statements, item: u64) -> Option<u64> {
    let mut queue = VecDeque::from([item]);
    let mut seen = BTreeSet::from([item]);
    while let Some(id) = queue.pop_front() {
        for &referrer in statements.referrers(id) {
            if !seen.insert(referrer) {
                continue;
            }
            if statements
                .get(&referrer)
                .is_some_and(is_shape_representation)
            {
                return Some(referrer);
            }
            queue.push_back(referrer);
        }
    }
    None
}

/// The units a context assigns (its `GLOBAL_UNIT_ASSIGNED_CONTEXT`); `None` without a length
/// unit.
fn context_units(statements: &Statements, context: u64) -> Result<Option<ContextUnits>, String> {
    let Some(statement) = statements.get(&context) else {
        return Ok(None);
    };
    let unit_with = |kind: &str| {
        statement
            .references
            .iter()
            .copied()
            .find(|id| statements.get(id).is_some_and(|s| s.is(kind)))
    };
    let Some(length) = unit_with("LENGTH_UNIT") else {
        return Ok(None);
    };
    let millimetres = length_millimetres(statements, length, 0)?;
    let radians = match unit_with("PLANE_ANGLE_UNIT") {
        Some(angle) => angle_radians(statements, angle, 0)?,
        None => 1.0,
    };
    Ok(Some(ContextUnits {
        millimetres,
        radians,
    }))
}

/// Millimetres per length unit `#id`.
fn length_millimetres(statements: &Statements, id: u64, depth: usize) -> Result<f64, String> {
    let statement = unit_statement(statements, id, depth)?;
    if let Some((prefix, name)) = si_unit(&statement.body) {
        if name != "METRE" {
            return Err(format!(
                "the length unit #{id} is not a metre (.{name}.); export in millimetres, metres, \
                 inches or feet"
            ));
        }
        return Ok(1000.0 * prefix);
    }
    let (name, measure) = conversion_based(statements, statement, id)?;
    match name.as_str() {
        "INCH" | "IN" => return Ok(25.4),
        "FOOT" | "FT" => return Ok(304.8),
        "MILLIMETRE" | "MM" => return Ok(1.0),
        "CENTIMETRE" | "CM" => return Ok(10.0),
        "METRE" | "M" => return Ok(1000.0),
        _ => {}
    }
    let value = ["LENGTH_MEASURE", "POSITIVE_LENGTH_MEASURE"]
        .iter()
        .find_map(|keyword| measure_value(&measure.body, keyword));
    match (value, measure.references.last()) {
        (Some(value), Some(&unit)) if value > 0.0 && value.is_finite() => {
            Ok(value * length_millimetres(statements, unit, depth + 1)?)
        }
        _ => Err(format!(
            "the length unit '{name}' (#{id}) is not supported; export in millimetres, metres, \
             inches or feet"
        )),
    }
}

/// Radians per plane angle unit `#id`.
fn angle_radians(statements: &Statements, id: u64, depth: usize) -> Result<f64, String> {
    let statement = unit_statement(statements, id, depth)?;
    if let Some((prefix, _)) = si_unit(&statement.body) {
        return Ok(prefix);
    }
    let (name, measure) = conversion_based(statements, statement, id)?;
    match name.as_str() {
        "DEGREE" | "DEGREES" | "DEG" => return Ok(std::f64::consts::PI / 180.0),
        "RADIAN" | "RAD" => return Ok(1.0),
        _ => {}
    }
    let value = measure_value(&measure.body, "PLANE_ANGLE_MEASURE");
    match (value, measure.references.last()) {
        (Some(value), Some(&unit)) if value > 0.0 && value.is_finite() => {
            Ok(value * angle_radians(statements, unit, depth + 1)?)
        }
        _ => Err(format!(
            "the plane angle unit '{name}' (#{id}) is not supported; export in degrees or radians"
        )),
    }
}

fn unit_statement(statements: &Statements, id: u64, depth: usize) -> Result<&Statement, String> {
    if depth > MAX_UNIT_DEPTH {
        return Err(format!("the unit #{id} is defined in a loop"));
    }
    statements
        .get(&id)
        .ok_or_else(|| format!("the unit #{id} is missing from the file"))
}

/// The name of a conversion-based unit and the measure instance that defines it.
fn conversion_based<'a>(
    statements: &'a Statements,
    statement: &Statement,
    id: u64,
) -> Result<(String, &'a Statement), String> {
    let marker = "CONVERSION_BASED_UNIT(";
    let unreadable = || format!("the unit #{id} could not be read");
    let compact: String = statement
        .body
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect();
    let start = compact.find(marker).ok_or_else(unreadable)? + marker.len();
    let arguments = &compact[start..];
    let name = arguments
        .strip_prefix('\'')
        .and_then(|rest| rest.split('\'').next())
        .ok_or_else(unreadable)?
        .to_ascii_uppercase();
    let measure = arguments
        .split_once('#')
        .and_then(|(_, rest)| {
            let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
            digits.parse::<u64>().ok()
        })
        .and_then(|measure| statements.get(&measure))
        .ok_or_else(unreadable)?;
    Ok((name, measure))
}

/// The factor of an `SI_UNIT(prefix, name)`'s prefix (1 for `$`) and its name.
fn si_unit(body: &str) -> Option<(f64, String)> {
    let compact: String = body.chars().filter(|c| !c.is_whitespace()).collect();
    let start = compact.find("SI_UNIT(")? + "SI_UNIT(".len();
    let end = compact[start..].find(')')? + start;
    let (prefix, name) = compact[start..end].split_once(',')?;
    let factor = match prefix.trim_matches('.') {
        "$" => 1.0,
        "EXA" => 1e18,
        "PETA" => 1e15,
        "TERA" => 1e12,
        "GIGA" => 1e9,
        "MEGA" => 1e6,
        "KILO" => 1e3,
        "HECTO" => 1e2,
        "DECA" => 1e1,
        "DECI" => 1e-1,
        "CENTI" => 1e-2,
        "MILLI" => 1e-3,
        "MICRO" => 1e-6,
        "NANO" => 1e-9,
        "PICO" => 1e-12,
        "FEMTO" => 1e-15,
        "ATTO" => 1e-18,
        _ => return None,
    };
    Some((factor, name.trim_matches('.').to_string()))
}

#[cfg(test)]
mod tests {
    use crate::ingest::step::units::*;

    fn units(text: &str, item: u64) -> Option<ContextUnits> {
        units_of(&Statements::parse(text), item).expect("readable units")
    }

    #[test]
    fn units_come_from_the_context_of_the_representation_holding_the_item() {
        // An inch context beside the millimetre one the solid uses (as Autodesk Inventor
        // writes), the inch defined through centimetres.
        let text = "#1=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.CENTI.,.METRE.));\n\
            #2=LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(2.54),#1);\n\
            #3=(CONVERSION_BASED_UNIT('INCH',#2)LENGTH_UNIT()NAMED_UNIT(#9));\n\
            #4=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNIT_ASSIGNED_CONTEXT((#3))REPRESENTATION_CONTEXT('',''));\n\
            #5=SHAPE_REPRESENTATION('',(#20),#4);\n\
            #6=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));\n\
            #7=(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.));\n\
            #8=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNIT_ASSIGNED_CONTEXT((#6,#7))REPRESENTATION_CONTEXT('',''));\n\
            #10=CLOSED_SHELL('',(#11));\n#12=MANIFOLD_SOLID_BREP('',#10);\n\
            #13=ADVANCED_BREP_SHAPE_REPRESENTATION('',(#12),#8);\n#20=AXIS2_PLACEMENT_3D('',#21,$,$);";
        assert_eq!(units(text, 10), Some(ContextUnits::default()));
        let inch = units(text, 20).expect("the inch context");
        assert!((inch.millimetres - 25.4).abs() < 1e-12);
        assert_eq!(units(text, 99), None);
    }

    #[test]
    fn conversion_based_units_are_read_from_their_measures() {
        let text = "#1=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT($,.METRE.));\n\
            #2=(LENGTH_MEASURE_WITH_UNIT()MEASURE_WITH_UNIT(LENGTH_MEASURE(0.3048),#1));\n\
            #3=(CONVERSION_BASED_UNIT('SURVEY FOOT',#2)LENGTH_UNIT()NAMED_UNIT(#9));\n\
            #4=(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.));\n\
            #5=PLANE_ANGLE_MEASURE_WITH_UNIT(PLANE_ANGLE_MEASURE(0.0174532925),#4);\n\
            #6=(CONVERSION_BASED_UNIT('DEGREE',#5)NAMED_UNIT(#9)PLANE_ANGLE_UNIT());\n\
            #7=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNIT_ASSIGNED_CONTEXT((#3,#6))REPRESENTATION_CONTEXT('',''));\n\
            #8=SHAPE_REPRESENTATION('',(#10),#7);";
        let found = units(text, 10).expect("units");
        assert!((found.millimetres - 304.8).abs() < 1e-9, "{found:?}");
        assert!((found.radians - std::f64::consts::PI / 180.0).abs() < 1e-15);
        assert_eq!(file_units(&Statements::parse(text)), Ok(found));
    }

    #[test]
    fn units_that_are_not_lengths_are_refused_naming_them() {
        let text = "#1=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT($,.GRAM.));\n\
            #2=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNIT_ASSIGNED_CONTEXT((#1))REPRESENTATION_CONTEXT('',''));\n\
            #3=SHAPE_REPRESENTATION('',(#10),#2);";
        let error = units_of(&Statements::parse(text), 10).expect_err("not a length");
        assert!(error.contains("#1 is not a metre"), "{error}");
    }
}
