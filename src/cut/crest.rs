//! Crest lines of the energy map (paper §6.3): candidate cutting lines along mesh edges.
//!
//! Inputs: a [`FacetModel`], a planning map ([`super::density`]: the energy of Eq. 1 of the
//! current flat pattern per unit area, smoothed over a length tied to the part's size, so the
//! lines do not depend on the mesh), the inner ends of earlier cuts, and the vertices a cut may
//! not pass through (on or next to a fold line, in a no-cut region). "Energy" below is that map.
//! Output: candidate [`CrestLine`]s, best first.
//!
//! The paper's crest line passes through the maximum-energy point along the slowest descent of
//! the energy. On the mesh, from a start vertex (a local maximum of the energy), each step goes to
//! the unvisited neighbour of highest energy among those that do not climb (slowest descent).
//! A crest line has two branches from its maximum:
//! - the *opening branch* descends to the boundary (or an earlier cut, which is boundary now),
//!   which is what opens the surface; when no neighbour descends any more, it finishes along the
//!   shortest edge path to the boundary;
//! - the *dart branch* continues from the maximum the other way and stops inside the part where
//!   extending no longer pays: at the first vertex whose energy is below `dart_floor` times the
//!   mean energy (the cut would run through less strained material than the average), or
//!   before it would touch the boundary (which would cut a piece off).
//!
//! A start on the boundary has only the dart branch: a dart inward from the boundary. A start
//! near the inner end of an earlier cut (within [`TIP_SNAP`] smoothing lengths) is that end's
//! stress peak: its line runs from the cut's end to the start by the shortest path and on along
//! the dart branch, extending the cut. Once no new cut is allowed, the lines start from the
//! highest vertex near each cut's end instead of from the highest maxima.
//!
//! Candidates: from each of the `candidates` highest local maxima, one line per [`Descent`] (the
//! paper's slowest descent, and the steepest descent, which on a dome is the radial dart the
//! slowest descent misses by running along the rim), each with its dart branch stopped on the
//! energy alone and also where the tension energy ([`CrestSettings::tension`]) falls low; from an
//! interior maximum also a slit (the dart branch both ways, both ends inside); and the first third
//! and two thirds of each line of four or more vertices.
//!
//! Estimated score (beyond the paper): the energy released per unit of cut length,
//! `Σ_{v on the line} E(v) / L`: a cut frees the springs of every vertex it passes to move apart,
//! so the energy of those vertices is what it can release at most. The cut loop measures the real
//! release of each candidate by flattening; the estimate only orders them.

use super::density::{DensityMap, smoothing_length};
use super::paths::{Adjacency, dijkstra, path_length};
use crate::mesh::FacetModel;

/// Default number of crest lines traced per cut (from the highest local maxima).
pub const DEFAULT_CANDIDATES: usize = 3;
/// Default multiple of the map's mean (area-weighted) below which the dart branch stops.
pub const DEFAULT_DART_FLOOR: f64 = 0.25;
/// Smallest distance between the starts of candidate lines, as a fraction of the part's bounding
/// diagonal: candidates from one energy peak would all be near copies of one another.
pub const START_SPACING: f64 = 0.1;
/// A maximum within this many smoothing lengths ([`smoothing_length`]) of
/// the inner end of an earlier cut is that end's stress peak, spread by the smoothing: its line
/// starts at the cut's end and extends the cut (and it gives no slit, which would leave a
/// sliver of material between the two).
pub const TIP_SNAP: f64 = 1.0;
/// Lines of at least this many vertices also yield their shorter prefixes as candidates.
const PREFIX_MIN_VERTICES: usize = 4;
/// A long line also yields its first `k / PREFIX_PARTS` for `k = 1 .. PREFIX_PARTS − 1`.
const PREFIX_PARTS: usize = 3;

/// A candidate cutting line: a simple edge path.
#[derive(Debug, Clone, PartialEq)]
pub struct CrestLine {
    /// The path's vertices; consecutive ones share an edge.
    pub vertices: Vec<u32>,
    /// 3D length, model units.
    pub length: f64,
    /// Estimated energy the cut can release: the sum of the energies of its vertices.
    pub estimated_release: f64,
}

impl CrestLine {
    /// The line along `vertices`, with its length and estimated release.
    fn along(model: &FacetModel, energies: &[f64], vertices: Vec<u32>) -> Self {
        let estimated_release = vertices.iter().map(|&v| energies[v as usize]).sum();
        Self {
            length: path_length(model, &vertices),
            vertices,
            estimated_release,
        }
    }

    /// The line's first `count` vertices (it starts on the boundary, so any prefix is a dart).
    fn prefix(&self, model: &FacetModel, energies: &[f64], count: usize) -> Self {
        Self::along(model, energies, self.vertices[..count].to_vec())
    }

    /// Estimated energy released per unit of cut length.
    pub fn score(&self) -> f64 {
        self.estimated_release / self.length
    }
}

/// How a line descends the energy map.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Descent {
    /// The paper's crest line: the slowest descent, along a ridge of the energy.
    Slowest,
    /// The gradient line: the steepest descent, across the isolines.
    Steepest,
}

/// Where cuts may go and how crest lines are traced.
#[derive(Debug, Clone, Copy)]
pub struct CrestSettings<'a> {
    /// Per-vertex flags: true where a cut may not pass.
    pub blocked: &'a [bool],
    /// Number of local maxima to start from.
    pub candidates: usize,
    /// Multiple of the area-weighted mean of the map below which the dart branch stops.
    pub dart_floor: f64,
    /// The tension map: the planning map ([`super::density`]) of the energy of the stretched
    /// springs ([`crate::flatten::SpringSystem::tension_energies`]).
    /// Each start also gives darts that stop where it falls below `dart_floor` times its mean,
    /// since a cut through compressed material would make its sides overlap.
    pub tension: &'a DensityMap,
    /// The inner ends of earlier cuts: a line from a maximum near one starts there (see
    /// [`TIP_SNAP`]).
    pub tips: &'a [u32],
    /// True when no new cut may be made: the lines then start from the highest vertex at or near
    /// each of `tips` (within [`TIP_SNAP`] smoothing lengths), instead of the highest maxima.
    pub extensions_only: bool,
}

/// Traces a line of each [`Descent`] from each of the highest local energy maxima and returns
/// them best estimated score first (ties keep the order of tracing). Lines of a single vertex and
/// repeated lines are dropped.
pub fn crest_lines(
    model: &FacetModel,
    adjacency: &Adjacency,
    map: &DensityMap,
    settings: &CrestSettings<'_>,
) -> Vec<CrestLine> {
    let energies = &map.values;
    let on_boundary = model.boundary_flags();
    let snap_distance = TIP_SNAP * smoothing_length(model);
    let (starts, start_count) = if settings.extensions_only {
        let peaks = tip_peaks(model, adjacency, energies, settings, snap_distance);
        let count = peaks.len();
        (peaks, count)
    } else {
        let maxima = local_maxima(adjacency, energies, settings.blocked);
        (maxima, settings.candidates)
    };
    let energy_floor = settings.dart_floor * map.mean;
    // Darts that stop on the energy alone, and darts that also stop where the material turns
    // compressed: on a dome the first reach further towards the compressed centre, which can pay.
    let floors = [
        Floor {
            energy: energy_floor,
            tension: 0.0,
        },
        Floor {
            energy: energy_floor,
            tension: settings.dart_floor * settings.tension.mean,
        },
    ];
    let mut lines: Vec<CrestLine> = Vec::new();
    for start in spread_out(model, &starts, start_count) {
        let tip = nearby_tip(model, adjacency, settings.tips, start, snap_distance);
        for descent in [Descent::Slowest, Descent::Steepest] {
            let tracer = Tracer {
                descent,
                model,
                adjacency,
                energies,
                tension: &settings.tension.values,
                blocked: settings.blocked,
                on_boundary: &on_boundary,
            };
            for floor in floors {
                let slit = match tip {
                    Some(_) => None,
                    None => tracer.slit(start, floor),
                };
                for line in [tracer.crest_line(start, tip, floor), slit]
                    .into_iter()
                    .flatten()
                {
                    push_with_prefixes(model, energies, line, &mut lines);
                }
            }
        }
    }
    lines.sort_by(|a, b| b.score().total_cmp(&a.score()));
    lines
}

/// Adds `line` to `lines`, and for a line of [`PREFIX_MIN_VERTICES`] or more its first
/// `k / PREFIX_PARTS`, skipping lines already there.
fn push_with_prefixes(
    model: &FacetModel,
    energies: &[f64],
    line: CrestLine,
    lines: &mut Vec<CrestLine>,
) {
    let count = line.vertices.len();
    let prefixes: Vec<CrestLine> = if count >= PREFIX_MIN_VERTICES {
        (1..PREFIX_PARTS)
            .map(|part| (count * part).div_ceil(PREFIX_PARTS).max(2))
            .map(|length| line.prefix(model, energies, length))
            .collect()
    } else {
        Vec::new()
    };
    for candidate in std::iter::once(line).chain(prefixes) {
        if !lines
            .iter()
            .any(|known| known.vertices == candidate.vertices)
        {
            lines.push(candidate);
        }
    }
}

/// Where a dart branch stops: below either energy.
#[derive(Debug, Clone, Copy)]
struct Floor {
    /// On the map being traced.
    energy: f64,
    /// On the tension map.
    tension: f64,
}

/// Unblocked vertices whose energy is at least that of every neighbour (ties go to the lower
/// index), highest energy first.
fn local_maxima(adjacency: &Adjacency, energies: &[f64], blocked: &[bool]) -> Vec<u32> {
    let mut maxima: Vec<u32> = (0..energies.len() as u32)
        .filter(|&v| !blocked[v as usize])
        .filter(|&v| {
            adjacency.neighbours(v).iter().all(|&(w, _)| {
                let (ev, ew) = (energies[v as usize], energies[w as usize]);
                ev > ew || (ev >= ew && v < w)
            })
        })
        .collect();
    maxima.sort_by(|&a, &b| energies[b as usize].total_cmp(&energies[a as usize]));
    maxima
}

/// The first `count` of `starts` (in their order) that lie at least [`START_SPACING`] times the
/// part's size away from every start taken before, so candidates come from different regions.
fn spread_out(model: &FacetModel, starts: &[u32], count: usize) -> Vec<u32> {
    let spacing = START_SPACING * model.bounding_diagonal();
    let positions = model.positions();
    let mut taken: Vec<u32> = Vec::with_capacity(count);
    for &start in starts {
        if taken.len() == count {
            break;
        }
        let position = positions[start as usize];
        if taken
            .iter()
            .all(|&known| positions[known as usize].distance(position) >= spacing)
        {
            taken.push(start);
        }
    }
    taken
}

/// The inner end of an earlier cut (one of `tips`) next to `start` (a neighbour) or within
/// `snap_distance` of it: the closest, if any. On the smoothed map the stress peak at a cut's
/// end lies a little inside the material; a line from it continues that cut.
fn nearby_tip(
    model: &FacetModel,
    adjacency: &Adjacency,
    tips: &[u32],
    start: u32,
    snap_distance: f64,
) -> Option<u32> {
    let positions = model.positions();
    let here = positions[start as usize];
    tips.iter()
        .copied()
        .filter(|&tip| tip != start)
        .map(|tip| (tip, positions[tip as usize].distance(here)))
        .filter(|&(tip, distance)| {
            distance <= snap_distance || adjacency.neighbours(start).iter().any(|&(w, _)| w == tip)
        })
        .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)))
        .map(|(tip, _)| tip)
}

/// For each of the settings' tips, the unblocked vertex of highest energy among the tip, its
/// neighbours and the vertices within `snap_distance` of it; highest energy first, without
/// repeats.
fn tip_peaks(
    model: &FacetModel,
    adjacency: &Adjacency,
    energies: &[f64],
    settings: &CrestSettings<'_>,
    snap_distance: f64,
) -> Vec<u32> {
    let positions = model.positions();
    let mut peaks: Vec<u32> = Vec::new();
    for &tip in settings.tips {
        let near = (0..model.vertex_count() as u32).filter(|&v| {
            v == tip
                || positions[v as usize].distance(positions[tip as usize]) <= snap_distance
                || adjacency.neighbours(tip).iter().any(|&(w, _)| w == v)
        });
        let peak = near
            .filter(|&v| !settings.blocked[v as usize])
            .max_by(|&a, &b| {
                energies[a as usize]
                    .total_cmp(&energies[b as usize])
                    .then(b.cmp(&a))
            });
        if let Some(peak) = peak.filter(|peak| !peaks.contains(peak)) {
            peaks.push(peak);
        }
    }
    peaks.sort_by(|&a, &b| {
        energies[b as usize]
            .total_cmp(&energies[a as usize])
            .then(a.cmp(&b))
    });
    peaks
}

/// The data one trace needs.
struct Tracer<'a> {
    descent: Descent,
    model: &'a FacetModel,
    adjacency: &'a Adjacency,
    energies: &'a [f64],
    tension: &'a [f64],
    blocked: &'a [bool],
    on_boundary: &'a [bool],
}

impl Tracer<'_> {
    /// The crest line through `start`: opening branch reversed (so the line starts on the
    /// boundary), then the dart branch down to `floor`. With a `tip` (the inner end of an earlier
    /// cut next to `start`), the line starts there instead and extends that cut: the shortest way
    /// from the tip to `start` (or, for a `start` on the boundary, to the first vertex of its
    /// dart), then the dart branch on from there.
    fn crest_line(&self, start: u32, tip: Option<u32>, floor: Floor) -> Option<CrestLine> {
        let mut visited = vec![false; self.model.vertex_count()];
        let (mut vertices, dart_start) = match tip {
            Some(tip) => {
                let first = self.first_inner_vertex(start, &visited)?;
                let mut way = self.way_to_tip(first, tip, &mut visited)?;
                way.reverse();
                (way, first)
            }
            None => {
                visited[start as usize] = true;
                if self.on_boundary[start as usize] {
                    (vec![start], start)
                } else {
                    let mut opening = self.opening_branch(start, &mut visited)?;
                    opening.reverse();
                    (opening, start)
                }
            }
        };
        vertices.extend(self.dart_branch(dart_start, floor, &mut visited));
        if vertices.len() < 2 {
            return None;
        }
        Some(CrestLine::along(self.model, self.energies, vertices))
    }

    /// The slit through an interior `start`: the dart branch, reversed, then the dart branch
    /// the other way, both ends inside the part. Cutting it opens a slot (a new boundary loop)
    /// where the material is stretched across it; `None` for a start on the boundary or a slit
    /// of fewer than three vertices (which duplicates no vertex).
    fn slit(&self, start: u32, floor: Floor) -> Option<CrestLine> {
        if self.on_boundary[start as usize] {
            return None;
        }
        let mut visited = vec![false; self.model.vertex_count()];
        visited[start as usize] = true;
        let mut vertices = self.dart_branch(start, floor, &mut visited);
        vertices.reverse();
        vertices.push(start);
        vertices.extend(self.dart_branch(start, floor, &mut visited));
        (vertices.len() >= 3).then(|| CrestLine::along(self.model, self.energies, vertices))
    }

    /// From `start` (interior) down to the boundary: `start` first, a boundary vertex last.
    fn opening_branch(&self, start: u32, visited: &mut [bool]) -> Option<Vec<u32>> {
        let mut branch = vec![start];
        let mut current = start;
        while !self.on_boundary[current as usize] {
            match self.descend(current, visited, true) {
                Some(next) => {
                    visited[next as usize] = true;
                    branch.push(next);
                    current = next;
                }
                None => {
                    let rest = self.shortest_way_out(current, visited)?;
                    for &v in &rest[1..] {
                        visited[v as usize] = true;
                    }
                    branch.extend_from_slice(&rest[1..]);
                    break;
                }
            }
        }
        Some(branch)
    }

    /// From `start` inward while the energy and the tension energy stay at or above `floor`,
    /// never onto the boundary;
    /// `start` itself is not included.
    fn dart_branch(&self, start: u32, floor: Floor, visited: &mut [bool]) -> Vec<u32> {
        let mut branch = Vec::new();
        let mut current = start;
        while let Some(next) = self.descend(current, visited, false) {
            if self.energies[next as usize] < floor.energy
                || self.tension[next as usize] < floor.tension
            {
                break;
            }
            visited[next as usize] = true;
            branch.push(next);
            current = next;
        }
        branch
    }

    /// The next vertex of a descent from `current`: among the unvisited, unblocked neighbours
    /// whose energy is not above that of `current`, the one of highest energy ([`Descent::Slowest`])
    /// or of steepest energy drop per unit length ([`Descent::Steepest`]). A neighbour of a visited
    /// vertex other than `current` is skipped, so the line never touches itself; boundary
    /// neighbours qualify only when `boundary_allowed`.
    fn descend(&self, current: u32, visited: &[bool], boundary_allowed: bool) -> Option<u32> {
        let here = self.energies[current as usize];
        let positions = self.model.positions();
        let key = |w: u32| match self.descent {
            Descent::Slowest => self.energies[w as usize],
            Descent::Steepest => {
                let run = positions[current as usize].distance(positions[w as usize]);
                (here - self.energies[w as usize]) / run
            }
        };
        self.adjacency
            .neighbours(current)
            .iter()
            .map(|&(w, _)| w)
            .filter(|&w| {
                !visited[w as usize]
                    && !self.blocked[w as usize]
                    && (boundary_allowed || !self.on_boundary[w as usize])
                    && self.energies[w as usize] <= here
                    && !self.touches_line(w, current, visited)
            })
            .max_by(|&a, &b| key(a).total_cmp(&key(b)).then_with(|| b.cmp(&a)))
    }

    /// True if `w` neighbours a visited vertex other than `current`.
    fn touches_line(&self, w: u32, current: u32, visited: &[bool]) -> bool {
        self.adjacency
            .neighbours(w)
            .iter()
            .any(|&(x, _)| x != current && visited[x as usize])
    }

    /// `start` if it is interior, else the first vertex of a dart from it.
    fn first_inner_vertex(&self, start: u32, visited: &[bool]) -> Option<u32> {
        if !self.on_boundary[start as usize] {
            return Some(start);
        }
        let mut visited = visited.to_vec();
        visited[start as usize] = true;
        self.descend(start, &visited, false)
    }

    /// The shortest edge path from `start` (interior) to `tip` through unvisited, unblocked
    /// interior vertices (`start` first), marked visited.
    fn way_to_tip(&self, start: u32, tip: u32, visited: &mut [bool]) -> Option<Vec<u32>> {
        let passable = |v: u32| {
            v == tip
                || (!visited[v as usize]
                    && !self.blocked[v as usize]
                    && !self.on_boundary[v as usize])
        };
        let (paths, reached) =
            dijkstra(self.model, self.adjacency, &[start], passable, |v| v == tip);
        let path = paths.path_to(reached?)?;
        for &v in &path {
            visited[v as usize] = true;
        }
        Some(path)
    }

    /// The shortest edge path from `current` to the boundary through unvisited, unblocked
    /// vertices (`current` first).
    fn shortest_way_out(&self, current: u32, visited: &[bool]) -> Option<Vec<u32>> {
        let passable = |v: u32| !visited[v as usize] && !self.blocked[v as usize];
        let is_exit = |v: u32| self.on_boundary[v as usize];
        let (paths, reached) = dijkstra(self.model, self.adjacency, &[current], passable, is_exit);
        paths.path_to(reached?)
    }
}

#[cfg(test)]
mod tests {
    use crate::cut::crest::*;
    use crate::cut::paths::tests::grid;

    /// The first crest line of the 4 x 4 test grid with these vertex energies (also the tension
    /// map) and blocked vertices.
    fn first_crest_line(energies: &[f64], blocked: &[bool]) -> CrestLine {
        let model = grid();
        let adjacency = Adjacency::new(&model);
        let map = DensityMap {
            values: energies.to_vec(),
            mean: energies.iter().sum::<f64>() / energies.len() as f64,
        };
        let settings = CrestSettings {
            blocked,
            candidates: 1,
            dart_floor: DEFAULT_DART_FLOOR,
            tension: &map,
            tips: &[],
            extensions_only: false,
        };
        crest_lines(&model, &adjacency, &map, &settings).remove(0)
    }

    #[test]
    fn the_crest_runs_along_the_energy_ridge_to_the_boundary() {
        // Energy peaks at vertex 5 (interior) and falls along the column x = 1 towards y = 0.
        let mut energies = vec![0.0; 16];
        energies[5] = 10.0;
        energies[1] = 8.0;
        energies[9] = 2.0;
        let line = first_crest_line(&energies, &[false; 16]);
        // The dart branch goes on to 9, whose energy is above the mean (1.25).
        assert_eq!(line.vertices, vec![1, 5, 9]);
        assert!((line.score() - 10.0).abs() < 1e-12);
    }

    #[test]
    fn a_dart_extends_while_the_energy_stays_high() {
        let mut energies = vec![0.0; 16];
        energies[1] = 10.0;
        energies[5] = 9.0;
        energies[9] = 6.0;
        energies[13] = 5.0;
        let line = first_crest_line(&energies, &[false; 16]);
        // From boundary vertex 1 inward; 13 is on the far boundary and is never reached.
        assert_eq!(line.vertices, vec![1, 5, 9]);
    }

    #[test]
    fn blocked_vertices_are_never_on_a_line() {
        let mut energies = vec![0.0; 16];
        energies[5] = 10.0;
        energies[1] = 8.0;
        let mut blocked = vec![false; 16];
        blocked[1] = true;
        let line = first_crest_line(&energies, &blocked);
        assert!(!line.vertices.contains(&1));
        assert!(line.vertices.contains(&5));
    }
}
