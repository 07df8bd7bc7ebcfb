//! InitFlatten (paper §6.1): the initial 2D pattern, built triangle by triangle.
//!
//! Triangles are taken in breadth-first order across shared edges from a seed near the middle of
//! the surface (the midpoint of a longest breadth-first path in the face graph, so the pattern
//! grows outwards evenly; if that pattern has flipped triangles, the face farthest from the
//! boundary is tried as the seed too, see [`init_flatten()`]). The seed is laid with its first edge on the x axis. Each later triangle
//! shares a placed edge with the triangle it was reached from; its third vertex is placed at the
//! intersection of the circles around the edge's ends with the 3D edge lengths as radii, on the
//! side that keeps the triangle counter-clockwise (unconstrained flattening, Fig. 4). When the
//! third vertex was placed before, through another triangle, the positions conflict and their mean
//! is used (constrained flattening, Fig. 5).
//!
//! After each triangle the strain that averaging creates is released (§6.1.2), in one of two ways:
//! - [`InitRelease::WholeSystem`]: the paper's procedure, EnergyRelease over every triangle placed
//!   so far for `N` steps (N = 50). Quadratic in the triangle count: for reproduction and small
//!   meshes.
//! - [`InitRelease::Neighbourhood`]: only the new triangle's vertices and their placed neighbours
//!   move, each to the position that minimises the energy of its springs with their directions
//!   held (a local step of the fast mass-spring method); near linear.
//!
//! A developable surface has no conflicts: its pattern is exact, up to round-off.

use glam::DVec2;

use super::accuracy::flipped_triangles;
use super::energy_release::{EnergyRelease, ReleaseParameters};
use super::springs::SpringSystem;
use crate::mesh::{FacetModel, NONE, compressed_rows};
use crate::progress::Progress;

/// The paper's step count for the release after each triangle ("N = 50").
pub const PAPER_INIT_RELEASE_STEPS: usize = 50;
/// Sweeps of the neighbourhood release after each triangle. One: the fast solver's phase two
/// removes what a second sweep would (measured on the 100k-triangle fender: 2 sweeps give an
/// initial E_C of 0.69 % in 0.27 s, 1 sweep 0.75 % in 0.22 s, and phase two ends at the same
/// energy within 0.01 % with 44 and 45 iterations).
pub const NEIGHBOURHOOD_SWEEPS: usize = 1;

/// How the strain is released while the pattern grows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum InitRelease {
    /// The paper's: EnergyRelease over the whole growing system for this many steps.
    WholeSystem {
        /// Steps after each triangle (the paper's N).
        steps: usize,
        /// Time step of the explicit integration.
        time_step: f64,
    },
    /// Local: the new triangle's neighbourhood only, for this many sweeps.
    Neighbourhood {
        /// Gauss-Seidel sweeps over the neighbourhood after each triangle.
        sweeps: usize,
    },
}

/// Builds the initial pattern. `springs` must be the model's spring system. The model must have
/// a boundary (a closed surface is cut open first).
///
/// The pattern grows from the middle of a longest breadth-first path. When that pattern has
/// flipped triangles (the path can run along the boundary, as on a hemisphere, whose opposite
/// rim points are joined by equally long paths over the pole and along the rim; growing from
/// the rim folds the pattern), it is grown again from the face farthest from the boundary and
/// the one with fewer flipped triangles is kept (the first on a tie).
pub fn init_flatten(
    model: &FacetModel,
    springs: &SpringSystem,
    release: InitRelease,
    progress: &dyn Progress,
) -> Vec<DVec2> {
    let first = grow_pattern(model, springs, path_middle_face(model), release, progress);
    let first_flipped = flipped_triangles(model, &first);
    if first_flipped == 0 {
        return first;
    }
    let second = grow_pattern(model, springs, innermost_face(model), release, progress);
    if flipped_triangles(model, &second) < first_flipped {
        second
    } else {
        first
    }
}

/// The pattern grown triangle by triangle in breadth-first order from `seed`.
fn grow_pattern(
    model: &FacetModel,
    springs: &SpringSystem,
    seed: u32,
    release: InitRelease,
    progress: &dyn Progress,
) -> Vec<DVec2> {
    let order: Vec<(u32, u32)> = breadth_first(model, seed)
        .into_iter()
        .map(|visit| (visit.face, visit.via_edge))
        .collect();
    let mut placer = Placer::new(model, springs);
    let energy = EnergyRelease::new(model, springs);
    let mut system = energy.empty_system();
    progress.start("unfolding", order.len() as u64);
    for (done, &(f, via_edge)) in order.iter().enumerate() {
        placer.place_triangle(f, via_edge);
        match release {
            InitRelease::WholeSystem { steps, time_step } => {
                energy.add_triangle(&mut system, f);
                let parameters = ReleaseParameters {
                    time_step,
                    max_steps: steps,
                    ..ReleaseParameters::default()
                };
                energy.release(&system, &mut placer.positions, &parameters, false);
            }
            InitRelease::Neighbourhood { sweeps } => placer.relax_neighbourhood(f, sweeps),
        }
        if done % 256 == 0 {
            progress.advance(done as u64);
        }
    }
    progress.finish();
    placer.positions
}

/// The face in the middle of a longest breadth-first path in the face graph.
fn path_middle_face(model: &FacetModel) -> u32 {
    let far = breadth_first(model, 0).last().map_or(0, |visit| visit.face);
    let visits = breadth_first(model, far);
    let mut parent = vec![NONE; model.triangle_count()];
    for visit in &visits {
        parent[visit.face as usize] = visit.parent;
    }
    let mut path = vec![visits.last().map_or(far, |visit| visit.face)];
    while let Some(&last) = path.last() {
        match parent[last as usize] {
            NONE => break,
            up => path.push(up),
        }
    }
    path[path.len() / 2]
}

/// The face farthest from the boundary in the face graph (the last one a breadth-first search
/// from every boundary face reaches).
fn innermost_face(model: &FacetModel) -> u32 {
    let boundary_faces: Vec<u32> = (0..model.triangle_count() as u32)
        .filter(|&f| {
            model.face_edges()[f as usize]
                .iter()
                .any(|&e| model.is_boundary_edge(e as usize))
        })
        .collect();
    breadth_first_from(model, &boundary_faces)
        .last()
        .map_or(0, |visit| visit.face)
}

/// One face reached by a breadth-first search in the face graph.
struct Visit {
    face: u32,
    parent: u32,
    via_edge: u32,
}

/// Breadth-first search in the face graph from `start`, in visiting order.
fn breadth_first(model: &FacetModel, start: u32) -> Vec<Visit> {
    breadth_first_from(model, &[start])
}

/// Breadth-first search in the face graph from all of `starts` at once, in visiting order.
fn breadth_first_from(model: &FacetModel, starts: &[u32]) -> Vec<Visit> {
    let mut visited = vec![false; model.triangle_count()];
    let mut visits: Vec<Visit> = starts
        .iter()
        .map(|&face| Visit {
            face,
            parent: NONE,
            via_edge: NONE,
        })
        .collect();
    for &start in starts {
        visited[start as usize] = true;
    }
    let mut next = 0;
    while next < visits.len() {
        let f = visits[next].face;
        next += 1;
        for (e, g) in face_neighbours_with_edges(model, f) {
            if !visited[g as usize] {
                visited[g as usize] = true;
                visits.push(Visit {
                    face: g,
                    parent: f,
                    via_edge: e,
                });
            }
        }
    }
    visits
}

fn face_neighbours_with_edges(model: &FacetModel, f: u32) -> impl Iterator<Item = (u32, u32)> + '_ {
    model.face_edges()[f as usize]
        .into_iter()
        .filter_map(move |e| {
            let [a, b] = model.edge_faces()[e as usize];
            let other = if a == f { b } else { a };
            (other != NONE).then_some((e, other))
        })
}

/// The growing pattern: positions, how many proposals each vertex has had, and each vertex's
/// springs (for the neighbourhood release).
struct Placer<'a> {
    model: &'a FacetModel,
    springs: &'a SpringSystem,
    positions: Vec<DVec2>,
    proposals: Vec<u32>,
    placed_triangle: Vec<bool>,
    vertex_edge_offsets: Vec<u32>,
    vertex_edges: Vec<u32>,
    /// Scratch list of the vertices the neighbourhood release moves, kept between triangles.
    neighbourhood: Vec<u32>,
}

impl<'a> Placer<'a> {
    fn new(model: &'a FacetModel, springs: &'a SpringSystem) -> Self {
        let n = model.vertex_count();
        let edge_ends = model
            .edges()
            .iter()
            .enumerate()
            .flat_map(|(e, &[a, b])| [(a, e as u32), (b, e as u32)]);
        let (offsets, vertex_edges) = compressed_rows(n, edge_ends);
        Self {
            model,
            springs,
            positions: vec![DVec2::ZERO; n],
            proposals: vec![0; n],
            placed_triangle: vec![false; model.triangle_count()],
            vertex_edge_offsets: offsets,
            vertex_edges,
            neighbourhood: Vec::new(),
        }
    }

    /// Places triangle `f`, reached through edge `via_edge` (or the seed when [`NONE`]).
    fn place_triangle(&mut self, f: u32, via_edge: u32) {
        let t = self.model.triangles()[f as usize];
        let edges = self.model.face_edges()[f as usize];
        let k = if via_edge == NONE {
            self.place_seed_edge(t, edges[0]);
            0
        } else {
            (edges.iter())
                .position(|&e| e == via_edge)
                .expect("face owns the edge")
        };
        let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
        // Edge k joins corners k and k + 1: the edges to c are k + 1 (from b) and k + 2 (to a).
        let rest = |e: u32| self.springs.rest_lengths[e as usize];
        let radii = (rest(edges[(k + 2) % 3]), rest(edges[(k + 1) % 3]));
        let proposal = self.third_vertex(a, b, c, radii);
        let count = self.proposals[c as usize] as f64;
        self.positions[c as usize] =
            (self.positions[c as usize] * count + proposal) / (count + 1.0);
        self.proposals[c as usize] += 1;
        self.placed_triangle[f as usize] = true;
    }

    /// Lays the seed triangle's first edge, `edge` (from corner 0 to corner 1), on the x axis.
    fn place_seed_edge(&mut self, t: [u32; 3], edge: u32) {
        let length = self.springs.rest_lengths[edge as usize];
        self.positions[t[0] as usize] = DVec2::ZERO;
        self.positions[t[1] as usize] = DVec2::new(length, 0.0);
        self.proposals[t[0] as usize] = 1;
        self.proposals[t[1] as usize] = 1;
    }

    /// The intersection of the circles around `a` and `b` with the rest lengths to `c`, `(ra,
    /// rb)`, as radii, to the left of `a → b`. Where the circles miss (the flat edge `ab` is
    /// longer or shorter than the triangle allows), the triangle's 3D shape scaled to the flat
    /// edge is used.
    fn third_vertex(&self, a: u32, b: u32, c: u32, (ra, rb): (f64, f64)) -> DVec2 {
        let (pa, pb) = (self.positions[a as usize], self.positions[b as usize]);
        let distance = pa.distance(pb);
        let direction = (pb - pa) / distance;
        let along = (distance * distance + ra * ra - rb * rb) / (2.0 * distance);
        let height_squared = ra * ra - along * along;
        if height_squared > 0.0 {
            return pa + direction * along + direction.perp() * height_squared.sqrt();
        }
        let positions = self.model.positions();
        let (qa, qb, qc) = (
            positions[a as usize],
            positions[b as usize],
            positions[c as usize],
        );
        let edge = qb - qa;
        let along_3d = (qc - qa).dot(edge) / edge.length();
        let height_3d = (qc - qa).cross(edge).length() / edge.length();
        let scale = distance / edge.length();
        pa + direction * along_3d * scale + direction.perp() * height_3d * scale
    }

    /// Moves the vertices of `f` and their placed neighbours, one after the other, to the
    /// minimiser of their springs' energy with directions held: `p_i = Σ C (p_j + d u_ij) / Σ C`.
    fn relax_neighbourhood(&mut self, f: u32, sweeps: usize) {
        let mut vertices = std::mem::take(&mut self.neighbourhood);
        vertices.clear();
        for &v in &self.model.triangles()[f as usize] {
            vertices.push(v);
            vertices.extend(self.active_springs(v).map(|(_, other)| other));
        }
        vertices.sort_unstable();
        vertices.dedup();
        for _ in 0..sweeps {
            for &v in &vertices {
                self.relax_vertex(v);
            }
        }
        self.neighbourhood = vertices;
    }

    /// Springs of `v` that belong to a placed triangle, with the vertex at their other end.
    fn active_springs(&self, v: u32) -> impl Iterator<Item = (usize, u32)> + '_ {
        let range = self.vertex_edge_offsets[v as usize] as usize
            ..self.vertex_edge_offsets[v as usize + 1] as usize;
        self.vertex_edges[range].iter().filter_map(move |&e| {
            let faces = self.model.edge_faces()[e as usize];
            let placed = faces
                .iter()
                .any(|&g| g != NONE && self.placed_triangle[g as usize]);
            let [a, b] = self.model.edges()[e as usize];
            placed.then_some((e as usize, if a == v { b } else { a }))
        })
    }

    fn relax_vertex(&mut self, v: u32) {
        let here = self.positions[v as usize];
        let (mut weighted, mut total) = (DVec2::ZERO, 0.0);
        for (e, other) in self.active_springs(v) {
            let there = self.positions[other as usize];
            let offset = here - there;
            let length = offset.length();
            if length <= 0.0 {
                return;
            }
            let constant = self.springs.constants[e];
            weighted += constant * (there + offset * (self.springs.rest_lengths[e] / length));
            total += constant;
        }
        if total > 0.0 {
            self.positions[v as usize] = weighted / total;
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::flatten::energy_release::{EnergyRelease, ReleaseParameters};
    use crate::flatten::init_flatten::{InitRelease, init_flatten};
    use crate::flatten::samples::sample;
    use crate::flatten::springs::SpringSystem;
    use crate::flatten::stiffness::Stiffness;
    use crate::progress::NoProgress;

    #[test]
    fn kinetic_damping_releases_energy_cycle_after_cycle() {
        for name in ["hemisphere.obj", "saddle.obj"] {
            let model = sample(name);
            let springs = SpringSystem::new(&model, Stiffness::uniform(&model).factors(), 0.5);
            let start = init_flatten(
                &model,
                &springs,
                InitRelease::Neighbourhood { sweeps: 2 },
                &NoProgress,
            );
            let release = EnergyRelease::new(&model, &springs);
            let mut energies = vec![springs.energy(&start)];
            for steps in (500..=4000).step_by(500) {
                let parameters = ReleaseParameters {
                    max_steps: steps,
                    tolerance: 0.0,
                    energy_variation: 0.0,
                    ..ReleaseParameters::default()
                };
                let mut positions = start.clone();
                release.release(&release.whole_system(), &mut positions, &parameters, true);
                energies.push(springs.energy(&positions));
            }
            for pair in energies.windows(2) {
                assert!(
                    pair[1] < pair[0],
                    "{name}: energy rose from {} to {}: {energies:?}",
                    pair[0],
                    pair[1]
                );
            }
            assert!(
                energies[energies.len() - 1] < 0.8 * energies[0],
                "{name}: {energies:?}"
            );
        }
    }
}
