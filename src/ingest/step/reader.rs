//! Reading a STEP file into the CAD model's B-rep: statements parsed, units found, the text
//! rewritten where truck-stepio would misread it, shells (or loose surfaces) converted.

use std::panic::catch_unwind;
use std::path::Path;

use truck_stepio::r#in::Table;

use super::convert::{convert_shells, loose_surfaces};
use super::entities::unsupported_entities;
use super::rewrite::{prefer_3d_curves, rewritten_for_truck};
use super::statements::Statements;
use super::text::exchange_text;
use super::units::file_units;
use crate::cad::Brep;
use crate::ingest::errors::IngestError;

/// Reads a STEP file's shells, or its loose surfaces when it has none (see the module
/// documentation).
pub fn read_step(path: &Path, bytes: &[u8]) -> Result<Brep, IngestError> {
    let error = |message: String| IngestError::Step {
        path: path.to_path_buf(),
        message,
    };
    let text = &exchange_text(bytes);
    let statements = Statements::parse(text);
    let default_units = file_units(&statements).map_err(error)?;
    let mut brep = Brep {
        name: path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("part")
            .to_string(),
        shells: Vec::new(),
        loose: Vec::new(),
        unsupported: unsupported_entities(&statements)
            .iter()
            .map(|(id, name)| format!("{name} (#{id})"))
            .collect(),
    };
    let text = &prefer_3d_curves(text);
    let text = &rewritten_for_truck(text, &statements, default_units).map_err(error)?;
    let table = catch_unwind(|| Table::from_step(text))
        .ok()
        .flatten()
        .ok_or_else(|| error("not a valid STEP exchange structure (ISO 10303-21); export it again from the CAD system".into()))?;
    let mut shell_ids: Vec<u64> = table.shell.keys().copied().collect();
    shell_ids.sort_unstable();
    if shell_ids.is_empty() {
        brep.loose = loose_surfaces(&table, &statements, default_units)
            .map_err(|message| error(format!("{message}{}", brep.unsupported_note())))?;
        if brep.loose.is_empty() {
            return Err(error(format!(
                "the file holds no shell, face or B-spline surface to read{}",
                brep.unsupported_note()
            )));
        }
    } else {
        brep.shells = convert_shells(&table, &shell_ids, &statements, default_units)
            .map_err(|message| error(format!("{message}{}", brep.unsupported_note())))?;
    }
    Ok(brep)
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use crate::ingest::step::reader::read_step;

    /// A face whose loop runs out along a line and back along another, on a B-spline surface
    /// 0.3 µm wide (a sliver, as Open CASCADE 6.3 wrote in FreeCAD's IDF model `SOD_323.stp`),
    /// alone in its shell: truck-stepio drops it.
    const SLIVER: &str = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\n\
        FILE_NAME('sliver.step','',(''),(''),'','','');\n\
        FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n\
        #1=CARTESIAN_POINT('',(0.,0.,0.));\n#2=CARTESIAN_POINT('',(0.,1.,0.));\n\
        #3=VERTEX_POINT('',#1);\n#4=VERTEX_POINT('',#2);\n\
        #5=DIRECTION('',(0.,1.,0.));\n#6=VECTOR('',#5,1.);\n#7=LINE('',#1,#6);\n\
        #8=DIRECTION('',(0.,-1.,0.));\n#9=VECTOR('',#8,1.);\n#10=LINE('',#2,#9);\n\
        #11=EDGE_CURVE('',#3,#4,#7,.T.);\n#12=EDGE_CURVE('',#4,#3,#10,.T.);\n\
        #13=ORIENTED_EDGE('',*,*,#11,.T.);\n#14=ORIENTED_EDGE('',*,*,#12,.T.);\n\
        #15=EDGE_LOOP('',(#13,#14));\n#16=FACE_BOUND('',#15,.T.);\n\
        #17=CARTESIAN_POINT('',(3.E-007,0.,0.));\n#18=CARTESIAN_POINT('',(3.E-007,1.,0.));\n\
        #20=B_SPLINE_SURFACE_WITH_KNOTS('',1,1,((#1,#2),(#17,#18)),.UNSPECIFIED.,.F.,.F.,.F.,\
        (2,2),(2,2),(0.,3.E-007),(0.,1.),.PIECEWISE_BEZIER_KNOTS.);\n\
        #21=ADVANCED_FACE('',(#16),#20,.T.);\n#22=OPEN_SHELL('',(#21));\n\
        #23=SHELL_BASED_SURFACE_MODEL('',(#22));\n\
        #24=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));\n\
        #25=(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.));\n\
        #26=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNIT_ASSIGNED_CONTEXT((#24,#25))\
        REPRESENTATION_CONTEXT('',''));\n\
        #27=MANIFOLD_SURFACE_SHAPE_REPRESENTATION('',(#23),#26);\nENDSEC;\nEND-ISO-10303-21;\n";

    #[test]
    fn a_shell_none_of_whose_faces_can_be_read_names_them() {
        let error = read_step(Path::new("sliver.step"), SLIVER.as_bytes())
            .expect_err("truck-stepio drops the sliver");
        let message = error.to_string();
        assert!(
            message.contains("shell #22: 1 of its 1 faces cannot be read")
                && message.contains("ADVANCED_FACE #21 on B_SPLINE_SURFACE_WITH_KNOTS (#20)"),
            "{message}"
        );
    }
}
