//! The bundled mesh samples as facet models, for the stage's unit tests: read and validated
//! directly (ingest and mesh, both left of flatten), without the pipeline.

use crate::mesh::FacetModel;

/// The first component of the bundled sample mesh `name` (an OBJ or STL in `samples/`).
pub(crate) fn sample(name: &str) -> FacetModel {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("samples")
        .join(name);
    let soup = crate::ingest::read_mesh(&path, Default::default())
        .expect("sample reads")
        .soup;
    crate::mesh::validate(&soup)
        .expect("sample is valid")
        .components
        .remove(0)
}
