//! `flatcut tessellate INPUT -o MESH.obj`: the facet model of a part file or STEP file (or a
//! mesh file, validated), written as OBJ, one file holding every component.

use std::path::PathBuf;

use clap::Args;

use flatcut::pipeline::{FacetSource, facet_model, write_facet_model};
use flatcut::tessellate::TessellateOptions;
use flatcut::units::Units;

use super::console::say;
use super::outcome::Outcome;

/// Arguments of `tessellate`.
#[derive(Debug, Args)]
pub struct TessellateArgs {
    /// Input: a part file (.toml), a STEP file (.step, .stp) or a mesh (.obj, .stl).
    input: PathBuf,
    /// Output OBJ file.
    #[arg(short, long, value_name = "MESH.obj")]
    output: PathBuf,
    #[command(flatten)]
    sizes: MeshSizeArgs,
    /// Units of mesh coordinates.
    #[arg(long, value_enum, default_value_t = Units::default())]
    units: Units,
}

/// `--mesh-size` and `--chord`, shared by `tessellate`, `flatten` and `run`.
#[derive(Debug, Args)]
pub struct MeshSizeArgs {
    /// Target edge length of the facet model, in the part's units (default: the part's bounding
    /// diagonal / 50).
    #[arg(long, value_name = "LENGTH")]
    mesh_size: Option<f64>,
    /// Largest distance between a surface and its triangles, in the part's units (default: the
    /// part's bounding diagonal × 0.0001).
    #[arg(long, value_name = "LENGTH")]
    chord: Option<f64>,
}

impl MeshSizeArgs {
    /// The library options.
    pub fn options(&self) -> anyhow::Result<TessellateOptions> {
        for (value, flag) in [(self.mesh_size, "--mesh-size"), (self.chord, "--chord")] {
            if let Some(value) = value {
                anyhow::ensure!(
                    value.is_finite() && value > 0.0,
                    "{flag} must be a positive length, got {value}"
                );
            }
        }
        Ok(TessellateOptions {
            mesh_size: self.mesh_size,
            chord: self.chord,
        })
    }
}

/// Runs `tessellate`.
pub fn run(args: TessellateArgs) -> anyhow::Result<Outcome> {
    let options = args.sizes.options()?;
    let model = facet_model(&args.input, args.units, &options)?;
    for warning in &model.warnings {
        say!("flatcut: warning: {}: {warning}", args.input.display());
    }
    let summary = summary(&model.source);
    let header = format!(
        "flatcut {} facet model of {}\n{summary}",
        env!("CARGO_PKG_VERSION"),
        args.input.display()
    );
    write_facet_model(&model, &header, &args.output)?;
    let soup = &model.soup;
    say!(
        "flatcut: {}: {} triangles, {} vertices, {} fold edges; {summary}",
        args.input.display(),
        soup.triangles.len(),
        soup.positions.len(),
        soup.fold_edges.len()
    );
    Ok(Outcome::Success)
}

/// The line that says where the facet model came from and how it was meshed.
fn summary(source: &FacetSource) -> String {
    match source {
        FacetSource::Part { units, figures } => format!(
            "mesh size {:.4} {}, chord {:.4} {}, smallest angle {:.2}°",
            figures.mesh_size,
            units.symbol(),
            figures.chord,
            units.symbol(),
            figures.minimum_angle
        ),
        FacetSource::Step { figures } => format!(
            "STEP faces in mm, mesh size {:.4} mm, chord {:.4} mm, smallest angle {:.2}°",
            figures.mesh_size, figures.chord, figures.minimum_angle
        ),
        FacetSource::Mesh => "mesh file".to_string(),
    }
}
