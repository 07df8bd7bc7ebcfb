//! Options of the cut loop and the user's cut constraints, with the constants that tune the loop.
//! `Default` is the only source of defaults.

use std::f64::consts::PI;

use serde::{Deserialize, Serialize};

use super::crest::{DEFAULT_CANDIDATES, DEFAULT_DART_FLOOR};

/// Smallest default number of crest-line cuts per part (seams not counted); see
/// [`super::cut_loop::default_cut_budget`].
pub const DEFAULT_MAX_CUTS: usize = 8;
/// Total absolute Gaussian curvature `∫|K| dA` of the spherical cap of half-angle 60°,
/// `2π (1 − cos 60°) = π`, the unit of [`super::cut_loop::default_cut_budget`].
pub const CAP_CURVATURE: f64 = PI;
/// Crest-line cuts allowed per [`CAP_CURVATURE`] of total absolute curvature: the 60° cap reaches
/// 1 % with 5 of its 8, a closed UV sphere halved along its bisector (`3.5π` left) with 27.
pub const CUTS_PER_CAP: f64 = DEFAULT_MAX_CUTS as f64;
/// With the default cut budget, `--seams auto` cuts a part whose total absolute Gaussian
/// curvature is over this into pieces without trying crest-line cuts first: it would get over
/// 128 of them, no pattern a cutter follows. The real meshes of the README over it (the beetle,
/// the draped dress, the spot head: 20-23 π; scans and closed bodies: 40-420 π) all ended
/// rejected after their cuts, in up to 140 s; the parts the cuts bring within tolerance hold a
/// few π (the hemisphere 1.87 π, a UV sphere halved 3.5 π).
pub const PIECES_CURVATURE: f64 = 16.0 * CAP_CURVATURE;
/// The cut loop keeps the candidate of largest `ΔE / L^LENGTH_EXPONENT` (measured energy drop
/// `ΔE`, cut length `L`). With 1 (drop per unit length) the loop prefers ever shorter steps, since
/// returns diminish along a cut, and spends its budget on millimetre extensions; with 1/2 a cut
/// three times as long wins if it releases more than `√3 ≈ 1.7` times the energy.
pub const LENGTH_EXPONENT: f64 = 0.5;
/// Candidate cuts are flattened with the fast solver's convergence threshold raised to this (a
/// fraction of the mean rest length; see [`crate::flatten::FastOptions::step_tolerance`]): enough to rank them,
/// at a fraction of the cost. The chosen cut is then flattened to the full threshold.
pub const TRIAL_STEP_TOLERANCE: f64 = 1e-4;
/// Solver iterations of the screening round, in which every candidate cut is flattened briefly
/// to rank it (see `super::trials`).
pub const SCREEN_ITERATIONS: usize = 20;
/// Screened candidates that must still lower the error after being flattened on to
/// [`TRIAL_STEP_TOLERANCE`] before the choice is made among them.
pub const FULL_TRIALS: usize = 3;
/// Screened candidates flattened on per cut step (non-overlapping ones first, then by gain) before
/// the choice is made among those accepted; while none is, the trials go on down the list.
pub const TRIAL_BUDGET: usize = 6;
/// Extensions of a cut from its inner end allowed per cut, on average: the loop makes at most
/// `max_cuts × (1 + EXTENSIONS_PER_CUT)` cut steps. An extension lengthens a cut and does not
/// count as a new one.
pub const EXTENSIONS_PER_CUT: usize = 3;
/// Cut steps pay when, together, they lower the pattern's spring energy by at least this
/// fraction: a step may open the way for the next (a short dart from the boundary releases
/// little until it is extended), but steps that release less than this together are length for
/// nothing (a 0.53 m cut on a real garment panel changed `E_S` by under 0.001 %). See
/// [`STALLED_STEPS`].
pub const MIN_RELEASE: f64 = 0.01;
/// The cut loop stops after this many steps in a row that did not pay together
/// ([`MIN_RELEASE`]), and unless the steps brought the pattern within tolerance or ended an
/// overlap, the steps since the last that paid are taken back (the cut model, its pattern and the
/// cuts).
pub const STALLED_STEPS: usize = 4;
/// When no line from the [`CutOptions::candidates`] highest maxima lowers the error without
/// overlap, the lines from this many times as many maxima are measured before the loop gives up.
pub const WIDER_SEARCH: usize = 4;

/// Options of [`super::cut_loop::cut_and_flatten`]. `Default` is the only source of defaults. The tolerance is the
/// flattening's ([`crate::flatten::FlattenOptions::tolerance`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CutOptions {
    /// Largest number of crest-line cuts; `None` (the default) for [`super::cut_loop::default_cut_budget`] of the
    /// opened part. `Some(0)` disables cutting (seams are still made).
    pub max_cuts: Option<usize>,
    /// Crest lines traced before each cut, from the highest energy maxima; default
    /// [`crate::cut::DEFAULT_CANDIDATES`].
    pub candidates: usize,
    /// A dart stops where the energy falls below this multiple of the mean energy density (see `density`);
    /// default [`crate::cut::DEFAULT_DART_FLOOR`].
    pub dart_floor: f64,
}

/// What the user says about where a part is cut: read from the part's sidecar file (see
/// [`crate::ingest::read_cut_sidecar`]), empty by default.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CutConstraints {
    /// User seams: 3D polylines in model units, cut before anything else.
    #[serde(default)]
    pub seams: Vec<Vec<[f64; 3]>>,
    /// Regions no cut or automatic seam may pass through.
    #[serde(default)]
    pub no_cut_regions: Vec<NoCutRegion>,
}

impl Default for CutOptions {
    fn default() -> Self {
        Self {
            max_cuts: None,
            candidates: DEFAULT_CANDIDATES,
            dart_floor: DEFAULT_DART_FLOOR,
        }
    }
}

/// A ball of the part where nothing may be cut.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NoCutRegion {
    /// Centre, model units.
    pub center: [f64; 3],
    /// Radius, model units.
    pub radius: f64,
}

/// The fast solver's energy criterion inside the cut loop. The loop ranks candidate cuts by the
/// patterns they give, so each pattern is converged further than a single flattening needs: with
/// the solver's default (1e-4 over its window) the hemisphere sample ended its 8 cuts at
/// 1.46 % / 1.00 %, with 1e-6 at 0.99 % / 0.62 %.
pub const CUT_LOOP_ENERGY_TOLERANCE: f64 = 1e-6;
