//! The tessellation's options and errors, and the mesh size and chord tolerance they give for a
//! part of a given size.

use serde::{Deserialize, Serialize};

use crate::cad::CadPart;

/// Default mesh size: the part's bounding diagonal divided by this.
pub const DEFAULT_DIVISIONS: f64 = 50.0;
/// Default chord tolerance, as a fraction of the part's bounding diagonal. A cone frustum's rim
/// is an inscribed polygon whose development subtends a little less than the analytic sector:
/// at 2e-4 the seam end of a 100/50/80 mm frustum is 0.065 mm off the analytic development when
/// the other end is pinned, at 1e-4 0.037 mm.
pub const DEFAULT_CHORD_RATIO: f64 = 1e-4;
/// The smallest mesh size accepted, as a fraction of the bounding diagonal (bounds the
/// triangle count near four million).
pub const MINIMUM_MESH_SIZE_RATIO: f64 = 1.0 / 2000.0;
/// The smallest chord tolerance accepted, as a fraction of the bounding diagonal: on a curve of
/// radius half the diagonal it asks for edges near the smallest mesh size (a chord of 1e-12 mm
/// refined without end).
pub const MINIMUM_CHORD_RATIO: f64 = 1e-7;
/// Options of the tessellation of part files and STEP files. `Default` is the only source of
/// defaults.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct TessellateOptions {
    /// Target edge length (part units); default the bounding diagonal / [`DEFAULT_DIVISIONS`].
    pub mesh_size: Option<f64>,
    /// Largest distance between the surface and a triangle (part units); default the bounding
    /// diagonal × [`DEFAULT_CHORD_RATIO`].
    pub chord: Option<f64>,
}

/// `value` rounded to 4 significant digits for a message (`0.02939`, not `0.02939387691339814`).
fn significant(value: &f64) -> f64 {
    format!("{value:.3e}").parse().unwrap_or(*value)
}

/// Errors of tessellation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TessellateError {
    /// The mesh size or chord tolerance is not a positive length, or too small for the part.
    #[error(
        "the mesh size {} and chord {} must be positive, the mesh size at least {} and the chord \
         at least {} for a part of this size; give a larger --mesh-size or --chord",
        significant(.mesh_size),
        significant(.chord),
        significant(.minimum),
        significant(.minimum_chord)
    )]
    BadSize {
        /// The mesh size used.
        mesh_size: f64,
        /// The chord tolerance used.
        chord: f64,
        /// The smallest mesh size accepted.
        minimum: f64,
        /// The smallest chord tolerance accepted.
        minimum_chord: f64,
    },
    /// A patch's derivatives vanish: it has no area.
    #[error("a patch is degenerate (its derivatives vanish); check its control points")]
    DegenerateSurface,
    /// A parameter point could not be triangulated (NaN or huge).
    #[error("the parameter point ({u}, {v}) cannot be triangulated")]
    BadParameterPoint {
        /// u.
        u: f64,
        /// v.
        v: f64,
    },
    /// A fold line crosses a trim loop or another fold line.
    #[error(
        "a fold line or trim loop crosses another near parameters ({u}, {v}); fold lines must \
         stay inside the trimmed domain"
    )]
    CrossingConstraints {
        /// u.
        u: f64,
        /// v.
        v: f64,
    },
    /// A fold polyline point is not on its surface.
    #[error("the fold polyline point ({u}, {v}) is not on its surface")]
    FoldOffSurface {
        /// u.
        u: f64,
        /// v.
        v: f64,
    },
    /// A surface produced no triangles.
    #[error("surface {surface} produced no triangles; check its dimensions")]
    EmptySurface {
        /// Surface index.
        surface: usize,
    },
}

/// The mesh size and chord tolerance for a part, defaults filled in and checked.
pub fn resolve_sizes(
    part: &CadPart,
    options: &TessellateOptions,
) -> Result<(f64, f64), TessellateError> {
    sizes_for_diagonal(part.size(), options)
}

/// The mesh size and chord tolerance for a part whose bounding diagonal is `size`, defaults
/// filled in and checked.
pub fn sizes_for_diagonal(
    size: f64,
    options: &TessellateOptions,
) -> Result<(f64, f64), TessellateError> {
    let mesh_size = options.mesh_size.unwrap_or(size / DEFAULT_DIVISIONS);
    let chord = options.chord.unwrap_or(size * DEFAULT_CHORD_RATIO);
    let minimum = size * MINIMUM_MESH_SIZE_RATIO;
    let minimum_chord = size * MINIMUM_CHORD_RATIO;
    if !(mesh_size.is_finite()
        && mesh_size >= minimum
        && chord.is_finite()
        && chord > 0.0
        && chord >= minimum_chord)
    {
        return Err(TessellateError::BadSize {
            mesh_size,
            chord,
            minimum,
            minimum_chord,
        });
    }
    Ok((mesh_size, chord))
}

/// A STEP file's B-rep that could not be tessellated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{message}")]
pub struct BrepError {
    /// What went wrong, naming the shell and face (`shell #12, ADVANCED_FACE #17 on
    /// CONICAL_SURFACE (#31): ...`) or the loose surface.
    pub message: String,
}
