//! Fairing of a plane section's curve (issue 13): its crossing points slid along the edges they
//! lie on until the curve turns as evenly as it can on the surface.
//!
//! A plane crosses a coarse, curved surface along a curve that turns on the surface (its
//! geodesic curvature) wherever the plane meets a face at a slant, and a flat pattern keeps
//! those turns: the section curves of the pieces zig-zag. Sliding a crossing point along its
//! edge changes neither the surface nor its area (the split faces still tile the face), nor the
//! edges the curve crosses, and both sides of the section share the point; so each point is
//! placed, within a margin of its edge's ends, where the turns of the curve at it and at its two
//! neighbours, squared and summed, are least (Gauss-Seidel sweeps of a golden-section search).
//!
//! The turn at a crossing is measured on the surface itself, as the flat pattern sees it: the
//! two faces of the edge unfolded about it, the curve's segments before and after make angles
//! with the edge whose difference is the turn.

use glam::DVec3;

use super::facet::{FacetModel, NONE};
use crate::geometry::golden_section_minimum;

/// Sweeps over the crossing points.
const SWEEPS: usize = 64;

/// Golden-section steps per point and sweep (the interval shrinks to 0.618¹² ≈ 3·10⁻³ of it).
const GOLDEN_STEPS: usize = 12;

/// A point that moves by less than this fraction of its edge is settled: its neighbours are not
/// tried again for it, and a sweep that moves no point more ends the fairing.
const SETTLED: f64 = 1e-4;

/// A point moves only where that lowers its squared turns by more than this (radians squared, a
/// turn of a microradian): a curve that is already straight stays where the plane put it.
const NEGLIGIBLE_COST: f64 = 1e-12;

/// A point of the section curve: a crossing point (by its index) or a model vertex on it.
#[derive(Debug, Clone, Copy, PartialEq)]
enum CurvePoint {
    Crossing(usize),
    Vertex(u32),
}

/// A model vertex inside the surface that the curve passes through, between two points of the
/// curve at least one of which is a crossing: the curve turns there by how far the angle on one
/// side of it, round the vertex, is from half the angle sum (as the straightest geodesics of
/// Polthier and Schmies measure it).
struct VertexTurn {
    /// The vertex.
    vertex: u32,
    /// The curve's points before and after it, each with the corners `[v, a, b]` of the face
    /// it lies in from the vertex, in the faces' orientation: a crossing on `a b`, or the
    /// vertex `a`.
    ends: [(CurvePoint, [u32; 3]); 2],
    /// The angles of the faces strictly between the two, round the vertex from the first.
    between: f64,
    /// Half the vertex's angle sum.
    half_sum: f64,
}

/// The section curve: its crossing points and, per crossing, its neighbours on the curve.
struct SectionCurve<'a> {
    model: &'a FacetModel,
    /// The model's vertex positions (those moved onto the section where they moved).
    vertices: &'a [DVec3],
    /// Per crossing, the model edge it lies on.
    edges: &'a [u32],
    /// Per crossing, the curve's point in each face of its edge (none at a boundary edge).
    neighbours: Vec<Option<[CurvePoint; 2]>>,
    /// The vertices the curve passes through between two crossings, with their turns' terms.
    vertex_turns: Vec<VertexTurn>,
    /// Per model vertex, its index in `vertex_turns`, or [`NONE`].
    vertex_turn_of: Vec<u32>,
}

/// Slides each crossing point `t[i]` (a fraction along model edge `edges[i]`, from its first
/// vertex to its second) along its edge so that the section curve turns evenly. A point stays
/// within `[min(t, margin), max(t, 1 − margin)]` of its own edge, and a point on a boundary edge
/// (an end of the curve) does not move. `on_curve` tells which model vertices the curve passes
/// through, `vertices` where they are.
pub(super) fn fair_crossings(
    model: &FacetModel,
    vertices: &[DVec3],
    on_curve: &[bool],
    edges: &[u32],
    t: &mut [f64],
    margin: f64,
) {
    let curve = SectionCurve::new(model, vertices, on_curve, edges);
    let bounds: Vec<(f64, f64)> = t
        .iter()
        .map(|&t0| (t0.min(margin), t0.max(1.0 - margin)))
        .collect();
    // Only the points near one that moved in a sweep are tried again in the next.
    let adjacent = curve.adjacent_crossings();
    let mut pending: Vec<bool> = (0..t.len())
        .map(|i| curve.neighbours[i].is_some())
        .collect();
    for _ in 0..SWEEPS {
        let mut next = vec![false; t.len()];
        for i in 0..t.len() {
            if !pending[i] || curve.neighbours[i].is_none() {
                continue;
            }
            let before = t[i];
            let cost_before = curve.local_cost(i, t);
            t[i] = curve.least_turning(i, t, bounds[i]);
            if curve.local_cost(i, t) >= cost_before - NEGLIGIBLE_COST {
                t[i] = before;
            }
            if (t[i] - before).abs() >= SETTLED {
                for &k in &adjacent[i] {
                    next[k] = true;
                    for &m in &adjacent[k] {
                        next[m] = true;
                    }
                }
            }
        }
        if !next.contains(&true) {
            break;
        }
        pending = next;
    }
}

impl<'a> SectionCurve<'a> {
    /// The curve through the crossings on `edges` and the vertices `on_curve` of the model
    /// (its vertices at `vertices`).
    fn new(
        model: &'a FacetModel,
        vertices: &'a [DVec3],
        on_curve: &[bool],
        edges: &'a [u32],
    ) -> Self {
        let mut crossing_of_edge = vec![NONE; model.edges().len()];
        for (i, &e) in edges.iter().enumerate() {
            crossing_of_edge[e as usize] = i as u32;
        }
        let vertex_turns: Vec<VertexTurn> = (0..model.vertex_count() as u32)
            .filter(|&v| on_curve[v as usize])
            .filter_map(|v| vertex_turn(model, vertices, on_curve, &crossing_of_edge, v))
            .collect();
        let mut vertex_turn_of = vec![NONE; model.vertex_count()];
        for (k, turn) in vertex_turns.iter().enumerate() {
            vertex_turn_of[turn.vertex as usize] = k as u32;
        }
        Self {
            model,
            vertices,
            edges,
            neighbours: (edges.iter())
                .map(|&e| neighbours(model, on_curve, &crossing_of_edge, e))
                .collect(),
            vertex_turns,
            vertex_turn_of,
        }
    }
}

/// The curve's points in the faces of crossed edge `e`: in each face, the crossing on another
/// of its edges or, where the plane passes through the face's third corner, that corner.
fn neighbours(
    model: &FacetModel,
    on_curve: &[bool],
    crossing_of_edge: &[u32],
    e: u32,
) -> Option<[CurvePoint; 2]> {
    let faces = model.edge_faces()[e as usize];
    if faces.contains(&NONE) {
        return None;
    }
    let [a, b] = model.edges()[e as usize];
    let in_face = |f: u32| {
        let other_crossing = (model.face_edges()[f as usize].iter())
            .find(|&&g| g != e && crossing_of_edge[g as usize] != NONE)
            .map(|&g| CurvePoint::Crossing(crossing_of_edge[g as usize] as usize));
        other_crossing.or_else(|| {
            let corner = (model.triangles()[f as usize].iter())
                .find(|&&v| v != a && v != b)
                .copied()?;
            on_curve[corner as usize].then_some(CurvePoint::Vertex(corner))
        })
    };
    Some([in_face(faces[0])?, in_face(faces[1])?])
}

/// The turn terms of vertex `v` on the curve, where it is inside the surface and the curve passes
/// it between exactly two points, at least one a crossing; `None` otherwise (the vertex is then a
/// fixed point of the curve whose turn is not counted).
fn vertex_turn(
    model: &FacetModel,
    vertices: &[DVec3],
    on_curve: &[bool],
    crossing_of_edge: &[u32],
    v: u32,
) -> Option<VertexTurn> {
    let from_vertex = |face: u32| model.corners_from(face, v);
    let corner_angle = |[v, a, b]: [u32; 3]| {
        let at = |w: u32| vertices[w as usize];
        (at(a) - at(v)).angle_between(at(b) - at(v))
    };
    let mut ends = Vec::new();
    let mut angle_sum = 0.0;
    for &face in model.vertex_faces(v) {
        let corners = from_vertex(face)?;
        let [_, a, b] = corners;
        if model
            .find_edge(v, a)
            .is_none_or(|e| model.is_boundary_edge(e))
        {
            return None;
        }
        if on_curve[a as usize] {
            ends.push((CurvePoint::Vertex(a), corners));
        }
        let far = model.find_edge(a, b)?;
        if crossing_of_edge[far] != NONE {
            let crossing = CurvePoint::Crossing(crossing_of_edge[far] as usize);
            ends.push((crossing, corners));
        }
        angle_sum += corner_angle(corners);
    }
    let [first, last] = <[(CurvePoint, [u32; 3]); 2]>::try_from(ends).ok()?;
    if [first, last]
        .iter()
        .all(|end| matches!(end.0, CurvePoint::Vertex(_)))
    {
        return None;
    }
    // Round the vertex from the first face to the last, each time across the edge (v, b).
    let mut between = 0.0;
    let mut face = first.1;
    for _ in 0..model.vertex_faces(v).len() {
        let edge = model.find_edge(v, face[2])?;
        let next = (model.edge_faces()[edge].into_iter())
            .find(|&f| f != NONE && from_vertex(f) != Some(face))?;
        face = from_vertex(next)?;
        if face == last.1 {
            return Some(VertexTurn {
                vertex: v,
                ends: [first, last],
                between,
                half_sum: 0.5 * angle_sum,
            });
        }
        between += corner_angle(face);
    }
    None
}

impl SectionCurve<'_> {
    /// Per crossing, the crossings whose turns its place changes: its neighbours on the curve,
    /// itself, and the other crossing round each vertex next to it whose turn is counted.
    fn adjacent_crossings(&self) -> Vec<Vec<usize>> {
        (0..self.edges.len())
            .map(|i| {
                let mut adjacent = vec![i];
                for point in self.neighbours[i].into_iter().flatten() {
                    match point {
                        CurvePoint::Crossing(k) => adjacent.push(k),
                        CurvePoint::Vertex(v) => {
                            let ends = self.turn_at(v).into_iter().flat_map(|turn| turn.ends);
                            adjacent.extend(ends.filter_map(|(end, _)| match end {
                                CurvePoint::Crossing(k) => Some(k),
                                CurvePoint::Vertex(_) => None,
                            }));
                        }
                    }
                }
                adjacent.sort_unstable();
                adjacent.dedup();
                adjacent
            })
            .collect()
    }

    /// The turn terms of model vertex `v`, when the curve passes it and its turn is counted.
    fn turn_at(&self, v: u32) -> Option<&VertexTurn> {
        self.vertex_turns
            .get(self.vertex_turn_of[v as usize] as usize)
    }

    /// Where crossing `i` is best placed within `bounds`, the other crossings at `t`: the least
    /// sum of the squared turns at it and at its neighbours, by golden-section search.
    fn least_turning(&self, i: usize, t: &mut [f64], (low, high): (f64, f64)) -> f64 {
        let cost_at = |x: f64| {
            t[i] = x;
            self.local_cost(i, t)
        };
        golden_section_minimum(cost_at, low, high, GOLDEN_STEPS)
    }

    /// The squared turns at crossing `i` and at the crossings next to it.
    fn local_cost(&self, i: usize, t: &[f64]) -> f64 {
        let mut cost = self.turn(i, t).powi(2);
        if let Some(points) = self.neighbours[i] {
            for point in points {
                cost += match point {
                    CurvePoint::Crossing(k) => self.turn(k, t).powi(2),
                    CurvePoint::Vertex(v) => self
                        .turn_at(v)
                        .map_or(0.0, |turn| self.vertex_turn(turn, t).powi(2)),
                };
            }
        }
        cost
    }

    /// The curve's turn (radians) at crossing `i`, on the two faces of its edge unfolded about
    /// it; 0 at an end of the curve.
    fn turn(&self, i: usize, t: &[f64]) -> f64 {
        let Some([before, after]) = self.neighbours[i] else {
            return 0.0;
        };
        let [a, b] = self.ends(i);
        let along = (b - a).normalize_or_zero();
        let here = a.lerp(b, t[i]);
        let angle_to_edge = |d: DVec3| d.cross(along).length().atan2(d.dot(along));
        angle_to_edge(self.position(after, t) - here)
            - angle_to_edge(here - self.position(before, t))
    }

    /// The curve's turn (radians) at a vertex it passes through: the angle round the vertex
    /// from the point before to the point after, less half the angle sum.
    fn vertex_turn(&self, turn: &VertexTurn, t: &[f64]) -> f64 {
        let at = |w: u32| self.vertices[w as usize];
        // The angle in a face [v, a, b] from its edge (v, a) to the point.
        let from_first_edge = |(point, [v, a, _]): (CurvePoint, [u32; 3])| {
            (at(a) - at(v)).angle_between(self.position(point, t) - at(v))
        };
        let [first, last] = turn.ends;
        if first.1 == last.1 {
            return from_first_edge(last) - from_first_edge(first) - turn.half_sum;
        }
        let [v, a, b] = first.1;
        let in_first = (at(a) - at(v)).angle_between(at(b) - at(v)) - from_first_edge(first);
        in_first + turn.between + from_first_edge(last) - turn.half_sum
    }

    /// The positions of the ends of crossing `i`'s edge.
    fn ends(&self, i: usize) -> [DVec3; 2] {
        self.model.edges()[self.edges[i] as usize].map(|v| self.vertices[v as usize])
    }

    /// Where a curve point is, the crossings at `t`.
    fn position(&self, point: CurvePoint, t: &[f64]) -> DVec3 {
        match point {
            CurvePoint::Crossing(k) => {
                let [a, b] = self.ends(k);
                a.lerp(b, t[k])
            }
            CurvePoint::Vertex(v) => self.vertices[v as usize],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::validate::validate;
    use super::*;
    use crate::cad::TriangleSoup;

    /// A flat grid of `n` × `n` unit squares, two triangles each.
    fn grid(n: u32) -> FacetModel {
        let at = |i: u32, j: u32| j * (n + 1) + i;
        let positions = (0..=n)
            .flat_map(|j| (0..=n).map(move |i| DVec3::new(f64::from(i), f64::from(j), 0.0)))
            .collect();
        let triangles = (0..n)
            .flat_map(|j| (0..n).map(move |i| (i, j)))
            .flat_map(|(i, j)| {
                [
                    [at(i, j), at(i + 1, j), at(i + 1, j + 1)],
                    [at(i, j), at(i + 1, j + 1), at(i, j + 1)],
                ]
            })
            .collect();
        validate(&TriangleSoup::new(positions, triangles))
            .unwrap()
            .components
            .remove(0)
    }

    /// The curve where the plane `normal · p = offset` crosses the grid, its vertices on the
    /// plane held on it, with the crossings' fractions.
    fn plane_curve(
        model: &FacetModel,
        normal: DVec3,
        offset: f64,
    ) -> (Vec<bool>, Vec<u32>, Vec<f64>) {
        let distance = |v: u32| normal.dot(model.positions()[v as usize]) - offset;
        let on_curve: Vec<bool> = (0..model.vertex_count() as u32)
            .map(|v| distance(v).abs() < 1e-12)
            .collect();
        let (edges, t) = (0..model.edges().len() as u32)
            .filter_map(|e| {
                let [a, b] = model.edges()[e as usize].map(distance);
                (a * b < 0.0).then(|| (e, a / (a - b)))
            })
            .unzip();
        (on_curve, edges, t)
    }

    #[test]
    fn a_straight_line_across_a_flat_grid_turns_nowhere() {
        let model = grid(4);
        let normal = DVec3::new(1.0, 0.3, 0.0).normalize();
        let offset = normal.dot(DVec3::new(2.0, 2.0, 0.0));
        let (on_curve, edges, t) = plane_curve(&model, normal, offset);
        let curve = SectionCurve::new(&model, model.positions(), &on_curve, &edges);
        assert_eq!(
            curve.vertex_turns.len(),
            1,
            "the line passes the vertex (2, 2)"
        );
        assert!(curve.vertex_turn(&curve.vertex_turns[0], &t).abs() < 1e-12);
        for i in 0..t.len() {
            assert!(curve.turn(i, &t).abs() < 1e-12);
        }
    }
}
