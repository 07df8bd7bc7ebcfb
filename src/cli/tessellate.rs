//! `flatcut tessellate INPUT -o MESH.obj`: the facet model of a part file or STEP file (or a
//! mesh file, validated), written as OBJ, one file holding every component.

use std::path::PathBuf;

use anyhow::Context;
use clap::Args;

use flatcut::export::obj::mesh_obj;
use flatcut::export::write_atomically;
use flatcut::ingest::{Input, read_input};
use flatcut::mesh::TriangleSoup;
use flatcut::pipeline::tessellate_part;
use flatcut::tessellate::{TessellateOptions, tessellate_brep};
use flatcut::units::Units;

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
    let input = read_input(&args.input, args.units)?;
    let (soup, summary): (TriangleSoup, String) = match &input {
        Input::Part(part) => {
            let tessellation = tessellate_part(&args.input, part, &options)?;
            let figures = tessellation.figures;
            let summary = format!(
                "mesh size {:.4} {}, chord {:.4} {}, smallest angle {:.2}°",
                figures.mesh_size,
                part.units.symbol(),
                figures.chord,
                part.units.symbol(),
                figures.minimum_angle
            );
            (tessellation.soup().clone(), summary)
        }
        Input::Step(brep) => {
            let tessellation = tessellate_brep(brep, &options)
                .map_err(|defect| anyhow::anyhow!("{}: {defect}", args.input.display()))?;
            let figures = tessellation.figures;
            let summary = format!(
                "STEP faces in mm, mesh size {:.4} mm, chord {:.4} mm, smallest angle {:.2}°",
                figures.mesh_size, figures.chord, figures.minimum_angle
            );
            (tessellation.soup().clone(), summary)
        }
        Input::Mesh(mesh) => (mesh.soup.clone(), "mesh file".to_string()),
    };
    let validated = flatcut::mesh::validate(&soup).map_err(|defects| {
        anyhow::anyhow!(
            "{}: the facet model cannot be used: {defects}",
            args.input.display()
        )
    })?;
    for warning in &validated.warnings {
        eprintln!("flatcut: warning: {}: {warning}", args.input.display());
    }
    let header = format!(
        "flatcut {} facet model of {}\n{summary}",
        env!("CARGO_PKG_VERSION"),
        args.input.display()
    );
    let text = mesh_obj(&header, &soup.positions, &soup.triangles);
    write_atomically(&args.output, text.as_bytes())
        .with_context(|| format!("{}: cannot write", args.output.display()))?;
    eprintln!(
        "flatcut: {}: {} triangles, {} vertices, {} fold edges; {summary}",
        args.input.display(),
        soup.triangles.len(),
        soup.positions.len(),
        soup.fold_edges.len()
    );
    Ok(Outcome::Success)
}
