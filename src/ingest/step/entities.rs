//! What a STEP file's statements say about its geometry, read before truck-stepio is called:
//! the entities truck-stepio cannot convert, a shell's faces, a face's surface, descriptions of
//! faces for messages.

use std::collections::BTreeSet;

use super::statements::{Statement, Statements};

/// Geometric entities truck-stepio converts (and `TRIMMED_CURVE`, which flatcut replaces by its
/// basis curve); other `*_SURFACE` and `*_CURVE` entities are not.
const SUPPORTED_GEOMETRY: &[&str] = &[
    "LINE",
    "POLYLINE",
    "B_SPLINE_CURVE_WITH_KNOTS",
    "BEZIER_CURVE",
    "QUASI_UNIFORM_CURVE",
    "UNIFORM_CURVE",
    "RATIONAL_B_SPLINE_CURVE",
    "B_SPLINE_CURVE",
    "BOUNDED_CURVE",
    "CIRCLE",
    "ELLIPSE",
    "HYPERBOLA",
    "PARABOLA",
    "PCURVE",
    "SURFACE_CURVE",
    "SEAM_CURVE",
    "TRIMMED_CURVE",
    "EDGE_CURVE",
    "PLANE",
    "SPHERICAL_SURFACE",
    "CYLINDRICAL_SURFACE",
    "TOROIDAL_SURFACE",
    "CONICAL_SURFACE",
    "B_SPLINE_SURFACE_WITH_KNOTS",
    "B_SPLINE_SURFACE",
    "BOUNDED_SURFACE",
    "UNIFORM_SURFACE",
    "QUASI_UNIFORM_SURFACE",
    "BEZIER_SURFACE",
    "RATIONAL_B_SPLINE_SURFACE",
    "SURFACE_OF_LINEAR_EXTRUSION",
    "SURFACE_OF_REVOLUTION",
];

/// Face entities a shell lists.
const FACE_ENTITIES: &[&str] = &["ADVANCED_FACE", "FACE_SURFACE", "ORIENTED_FACE"];

/// Trimmed curves are nested at most this deep.
const MAX_TRIM_DEPTH: usize = 8;

/// The curve a `TRIMMED_CURVE` (possibly of another trimmed curve) trims.
pub fn basis_curve(statements: &Statements, id: u64) -> Option<&Statement> {
    let mut current = statements.get(&id)?;
    for _ in 0..MAX_TRIM_DEPTH {
        if !current.is("TRIMMED_CURVE") {
            return Some(current);
        }
        current = statements.get(current.references.first()?)?;
    }
    None
}

/// The faces among `faces` whose surface or one of whose edges' curves is missing or of a kind
/// truck-stepio cannot read, described for an error message.
pub fn unreadable_faces(statements: &Statements, faces: &[u64]) -> Vec<String> {
    faces
        .iter()
        .filter_map(|&face| {
            let surface_unreadable = face_surface(statements, face)
                .is_none_or(|(_, names)| names.iter().any(|name| is_unsupported_geometry(name)));
            if surface_unreadable {
                return Some(describe_face(statements, face));
            }
            unreadable_edge(statements, face)
                .map(|edge| format!("{}: {edge}", describe_face(statements, face)))
        })
        .collect()
}

/// The first edge of a face whose curve truck-stepio cannot read, described (`edge
/// EDGE_CURVE #33 on OFFSET_CURVE_3D (#32)`).
fn unreadable_edge(statements: &Statements, face: u64) -> Option<String> {
    let mut statement = statements.get(&face)?;
    if statement.is("ORIENTED_FACE") {
        statement = statements.get(statement.references.last()?)?;
    }
    let bounds = statement
        .references
        .iter()
        .filter_map(|r| statements.get(r));
    let loops = bounds.filter_map(|bound| statements.get(bound.references.first()?));
    for edge_loop in loops.filter(|l| l.is("EDGE_LOOP")) {
        for oriented in edge_loop
            .references
            .iter()
            .filter_map(|r| statements.get(r))
        {
            let Some(&edge) = oriented.references.last() else {
                continue;
            };
            let Some(curve) = statements
                .get(&edge)
                .and_then(|e| e.references.get(2).copied())
            else {
                return Some(format!("edge #{edge} is missing"));
            };
            if let Some(unreadable) = unreadable_curve(statements, curve) {
                return Some(format!("edge EDGE_CURVE #{edge} on {unreadable}"));
            }
        }
    }
    None
}

/// The curve (or the 3D curve of a surface curve, or the basis of a trimmed curve) truck-stepio
/// cannot read, described (`OFFSET_CURVE_3D (#32)`).
fn unreadable_curve(statements: &Statements, curve: u64) -> Option<String> {
    let Some(statement) = statements.get(&curve) else {
        return Some(format!("#{curve}, which is missing"));
    };
    let describe =
        |statement: &Statement, id: u64| format!("{} (#{id})", statement.names.join(" "));
    if statement.is("SURFACE_CURVE") || statement.is("SEAM_CURVE") {
        return unreadable_curve(statements, *statement.references.first()?);
    }
    if statement.is("TRIMMED_CURVE") {
        return match basis_curve(statements, curve) {
            Some(_) => unreadable_curve(statements, *statement.references.first()?),
            None => Some(describe(statement, curve)),
        };
    }
    statement
        .names
        .iter()
        .any(|name| is_unsupported_geometry(name))
        .then(|| describe(statement, curve))
}

/// The face entities a shell statement lists, in order.
pub fn shell_faces(statements: &Statements, shell: u64) -> Vec<u64> {
    statements.get(&shell).map_or(Vec::new(), |statement| {
        statement
            .references
            .iter()
            .copied()
            .filter(|r| {
                statements.get(r).is_some_and(|face| {
                    face.names
                        .iter()
                        .any(|name| FACE_ENTITIES.contains(&name.as_str()))
                })
            })
            .collect()
    })
}

/// A face's surface entity `(id, names)` (through an oriented face).
fn face_surface(statements: &Statements, face: u64) -> Option<(u64, Vec<String>)> {
    let statement = statements.get(&face)?;
    if statement.is("ORIENTED_FACE") {
        return face_surface(statements, *statement.references.last()?);
    }
    let surface = *statement.references.last()?;
    statements
        .get(&surface)
        .map(|found| (surface, found.names.clone()))
}

/// `ADVANCED_FACE #17 on CONICAL_SURFACE #31`.
pub fn describe_face(statements: &Statements, face: u64) -> String {
    let name = statements
        .get(&face)
        .and_then(|statement| statement.names.first())
        .map_or("face", String::as_str);
    match face_surface(statements, face) {
        Some((id, surface)) => format!("{name} #{face} on {} (#{id})", surface.join(" ")),
        None => format!("{name} #{face}"),
    }
}

/// Whether a name is a geometric entity (`*_SURFACE`, `*_CURVE`) truck-stepio does not convert.
fn is_unsupported_geometry(name: &str) -> bool {
    (name.ends_with("_SURFACE") || name.ends_with("_CURVE") || name.ends_with("_CURVE_3D"))
        && !name.contains("STYLE")
        && !SUPPORTED_GEOMETRY.contains(&name)
}

/// Geometric entities truck-stepio does not convert, `(id, name)`.
pub fn unsupported_entities(statements: &Statements) -> BTreeSet<(u64, String)> {
    statements
        .iter()
        .flat_map(|(id, statement)| {
            statement
                .names
                .iter()
                .filter(|name| is_unsupported_geometry(name))
                .map(|name| (*id, name.clone()))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::ingest::step::entities::*;

    #[test]
    fn unsupported_geometry_is_named() {
        let text = "#10=OFFSET_SURFACE('',#11,2.,.F.);\n#11=PLANE('',#12);\n#12=SURFACE_STYLE_USAGE(.BOTH.,#13);";
        let found = unsupported_entities(&Statements::parse(text));
        assert_eq!(
            found.into_iter().collect::<Vec<_>>(),
            vec![(10, "OFFSET_SURFACE".to_string())]
        );
    }
}
