//! Cone fans: rulings that all meet at one apex (the corner of a square-to-round), meshed so that
//! triangles keep their shape up to the apex while the mesh stays developable.
//!
//! Input: the apex and the far ends of the fan's rulings (vertices of a [`FaceMesh`], in order,
//! at least two wedges), and the target edge length. Output: triangles added to the mesh and,
//! per ruling, the vertices placed on it from the apex outwards.
//!
//! Why: consecutive rulings of a fan meet at the apex at the small angle between two samples of
//! the far section (about 2° for a 120 mm circle at the default chord), so a mesh that keeps
//! every triangle between two consecutive rulings has that angle at the apex. Triangles that
//! span several rulings are well shaped but leave the cone: the chord between two rulings is
//! shorter than its development by `t · excess(a, b)` at the fraction `t` of the way from the apex
//! (`Development::excess`), which is what makes a mesh not exactly developable.
//!
//! Method: rows across the rulings at fractions `t` from 1 (the far section) towards the apex.
//! A row uses a subset of the rulings (all of them at first). The radial step between rows is
//! [`RADIAL_ASPECT`] times the row's spacing (at most the mesh size), so the cells keep their
//! shape: rows become geometric towards the apex. The subset is halved (every other ruling
//! dropped) as soon as every chord it creates is within [`FAN_TOLERANCE_RATIO`] of the mesh size
//! of its development and the spacing stays below the mesh size; once no merge can keep an
//! interval's apex angle below [`MAXIMUM_APEX_DEGREES`], the apex is closed with one triangle
//! per interval. Every triangle between two rows lies between two consecutive rulings of the
//! subset, so the mesh is exact but for chords below the tolerance, which it leaves in a small
//! neighbourhood of the apex.

use std::collections::HashMap;

use glam::{DVec2, DVec3};

use super::face_mesh::FaceMesh;
use super::strip::stitch_rows;
use crate::geometry::tolerance::FAN_TOLERANCE_RATIO;
use crate::geometry::tolerance::FOLD_ROW_TOLERANCE;

/// Radial step between rows over the row's spacing (cells 1.5 times as long as wide).
pub const RADIAL_ASPECT: f64 = 1.5;
/// A bound on the rows of one fan (they shrink geometrically towards the apex).
const MAXIMUM_ROWS: usize = 10_000;
/// Intervals are merged while their angle at the apex (in the development) stays below this.
pub const MAXIMUM_APEX_DEGREES: f64 = 60.0;

/// The development of a fan: each ruling's far end unfolded into the plane about the apex.
struct Development {
    apex: DVec3,
    far: Vec<DVec3>,
    flat: Vec<DVec2>,
    angles: Vec<f64>,
}

impl Development {
    fn new(apex: DVec3, far: Vec<DVec3>) -> Self {
        let mut angles = vec![0.0];
        for pair in far.windows(2) {
            let turn = (pair[0] - apex).angle_between(pair[1] - apex);
            angles.push(angles[angles.len() - 1] + turn);
        }
        let flat = far
            .iter()
            .zip(&angles)
            .map(|(p, &angle)| DVec2::from_angle(angle) * p.distance(apex))
            .collect();
        Self {
            apex,
            far,
            flat,
            angles,
        }
    }

    /// How much longer the development of the chord between the far ends of rulings `a` and `b`
    /// is than the chord itself (zero for consecutive rulings: their wedge is plane).
    fn excess(&self, a: usize, b: usize) -> f64 {
        (self.flat[a].distance(self.flat[b]) - self.far[a].distance(self.far[b])).max(0.0)
    }

    /// The point at fraction `t` of ruling `ruling` from the apex.
    fn point(&self, ruling: usize, t: f64) -> DVec3 {
        self.apex.lerp(self.far[ruling], t)
    }

    /// The largest chord between consecutive rulings of `subset` at fraction `t`.
    fn spacing(&self, subset: &[usize], t: f64) -> f64 {
        subset
            .windows(2)
            .map(|w| t * self.far[w[0]].distance(self.far[w[1]]))
            .fold(0.0, f64::max)
    }
}

/// Every other ruling of `subset`, keeping the first and the last (an odd number of intervals
/// merges its last three into one).
fn halved(subset: &[usize]) -> Vec<usize> {
    let mut kept: Vec<usize> = subset.iter().step_by(2).copied().collect();
    if kept.last() != subset.last() {
        if kept.len() >= 2 {
            kept.pop();
        }
        kept.extend(subset.last());
    }
    kept
}

/// The vertices a fan put on each of its rulings, from the apex outwards.
pub type RulingVertices = Vec<Vec<u32>>;

/// Meshes the fan with apex vertex `apex` and far vertices `far` (see the module
/// documentation). `apex_at_bottom` tells which end of the rulings the apex is (for the
/// orientation of the triangles, which follows [`super::ruled::mesh_rulings`]). `fold_rows`
/// are fractions from the apex (in `(0, 1)`) at which a row must lie, with every ruling (a fold
/// polyline crossing the fan at the same fraction of each ruling, such as a section at one
/// height): the radial steps are shortened to land on them (no step below half its usual
/// length) and no ruling is dropped before the last of them is passed.
pub fn mesh_cone_fan(
    mesh: &mut FaceMesh,
    apex: u32,
    far: &[u32],
    apex_at_bottom: bool,
    fold_rows: &[f64],
    mesh_size: f64,
) -> RulingVertices {
    let position = |v: u32, mesh: &FaceMesh| mesh.positions[v as usize];
    let development = Development::new(
        position(apex, mesh),
        far.iter().map(|&v| position(v, mesh)).collect(),
    );
    let longest = development
        .far
        .iter()
        .map(|p| p.distance(development.apex))
        .fold(0.0, f64::max);
    let tolerance = FAN_TOLERANCE_RATIO * mesh_size;
    let maximum_apex_angle = MAXIMUM_APEX_DEGREES.to_radians();
    let mut on_ruling: RulingVertices = far.iter().map(|&v| vec![v]).collect();
    let mut subset: Vec<usize> = (0..far.len()).collect();
    let mut row: Vec<u32> = far.to_vec();
    let mut t = 1.0;
    let mut triangles = Vec::new();
    let mut chart = Chart::default();
    for (ruling, &v) in far.iter().enumerate() {
        chart.record(v, ruling, 0);
    }
    let mut rows = 0;
    let fold_row_below = |t: f64| {
        fold_rows
            .iter()
            .copied()
            .filter(|&f| f < t - FOLD_ROW_TOLERANCE)
            .fold(None, |best: Option<f64>, f| {
                Some(best.map_or(f, |b| b.max(f)))
            })
    };
    while rows < MAXIMUM_ROWS {
        let coarser = halved(&subset);
        let can_merge = coarser.len() < subset.len()
            && coarser
                .windows(2)
                .all(|w| development.angles[w[1]] - development.angles[w[0]] <= maximum_apex_angle);
        let fold_row = fold_row_below(t);
        if !can_merge && fold_row.is_none() {
            break;
        }
        let step = (RADIAL_ASPECT * development.spacing(&subset, t)).min(mesh_size);
        let next_t = match fold_row {
            Some(f) if (t - f) * longest <= step => f,
            Some(f) if (t - f) * longest < 2.0 * step => 0.5 * (t + f),
            _ => t - step / longest,
        };
        let merge = can_merge
            && next_t > 0.0
            && fold_rows.iter().all(|&f| f > next_t + FOLD_ROW_TOLERANCE)
            && 2.0 * development.spacing(&subset, next_t) <= mesh_size
            && coarser
                .windows(2)
                .all(|w| next_t * development.excess(w[0], w[1]) <= tolerance);
        if next_t <= 0.0 {
            break;
        }
        let next_subset = if merge { coarser } else { subset.clone() };
        let next_row: Vec<u32> = next_subset
            .iter()
            .map(|&r| {
                let v = mesh.add_vertex(development.point(r, next_t));
                on_ruling[r].push(v);
                chart.record(v, r, rows + 1);
                v
            })
            .collect();
        // Each interval of the inner row is stitched to the part of the outer row it spans, so
        // no triangle crosses a ruling of the inner row.
        for (k, w) in next_subset.windows(2).enumerate() {
            let outer: Vec<u32> = subset
                .iter()
                .zip(&row)
                .filter(|&(&r, _)| (w[0]..=w[1]).contains(&r))
                .map(|(_, &v)| v)
                .collect();
            stitch_rows(&next_row[k..k + 2], &outer, &mesh.positions, &mut triangles);
        }
        subset = next_subset;
        row = next_row;
        t = next_t;
        rows += 1;
    }
    for pair in row.windows(2) {
        triangles.push([apex, pair[0], pair[1]]);
    }
    for triangle in triangles {
        mesh.triangles
            .push(chart.oriented(triangle, rows + 1, apex_at_bottom));
    }
    for vertices in &mut on_ruling {
        vertices.push(apex);
        vertices.reverse();
    }
    on_ruling
}

/// Where each fan vertex is in the chart (ruling index, row counted from the far section), for
/// orienting triangles like the other ruled meshes.
#[derive(Default)]
struct Chart {
    place: HashMap<u32, (usize, usize)>,
}

impl Chart {
    fn record(&mut self, vertex: u32, ruling: usize, row: usize) {
        self.place.insert(vertex, (ruling, row));
    }

    /// The triangle counter-clockwise in the chart (ruling index, distance from the bottom end):
    /// the orientation of [`super::ruled::mesh_rulings`]. The apex sits one row past the last,
    /// at the mean ruling of the triangle's other corners.
    fn oriented(&self, triangle: [u32; 3], apex_row: usize, apex_at_bottom: bool) -> [u32; 3] {
        let known: Vec<(usize, usize)> = triangle
            .iter()
            .filter_map(|v| self.place.get(v).copied())
            .collect();
        let mean_ruling = known.iter().map(|k| k.0 as f64).sum::<f64>() / known.len().max(1) as f64;
        let point = |v: u32| {
            let (ruling, row) = self
                .place
                .get(&v)
                .map_or((mean_ruling, apex_row), |&(r, row)| (r as f64, row));
            let from_far = row as f64;
            DVec2::new(ruling, if apex_at_bottom { -from_far } else { from_far })
        };
        let [a, b, c] = triangle.map(point);
        if (b - a).perp_dot(c - a) >= 0.0 {
            triangle
        } else {
            [triangle[0], triangle[2], triangle[1]]
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::tessellate::fan::*;

    fn angle_at(a: DVec3, b: DVec3, c: DVec3) -> f64 {
        (b - a).angle_between(c - a).to_degrees()
    }

    #[test]
    fn a_square_to_round_corner_fan_is_well_shaped_and_covers_its_wedges() {
        // The corner (100, -100, 0) of a square-to-round and a quarter of its 120 mm top circle.
        let mut mesh = FaceMesh::default();
        let apex = mesh.add_vertex(DVec3::new(100.0, -100.0, 0.0));
        let pieces = 48;
        let far: Vec<u32> = (0..=pieces)
            .map(|k| {
                let angle = -std::f64::consts::FRAC_PI_2
                    + std::f64::consts::FRAC_PI_2 * k as f64 / pieces as f64;
                mesh.add_vertex(DVec3::new(60.0 * angle.cos(), 60.0 * angle.sin(), 150.0))
            })
            .collect();
        let wedges: f64 = far
            .windows(2)
            .map(|w| {
                let [a, b, c] = [apex, w[0], w[1]].map(|v| mesh.positions[v as usize]);
                0.5 * (b - a).cross(c - a).length()
            })
            .sum();
        let on_ruling = mesh_cone_fan(&mut mesh, apex, &far, true, &[], 6.4);
        assert_eq!(on_ruling.len(), far.len());
        assert!(on_ruling.iter().all(|r| r[0] == apex));
        let mut area = 0.0;
        let mut worst: f64 = 180.0;
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
            area += 0.5 * (b - a).cross(c - a).length();
            worst = worst.min(
                angle_at(a, b, c)
                    .min(angle_at(b, c, a))
                    .min(angle_at(c, a, b)),
            );
        }
        assert!(worst >= 20.0, "worst angle {worst}");
        // Chords that span two or more wedges lie slightly inside the fan (1.3e-4 of its area
        // here, against the 1e-3 the issue allows a tessellation).
        assert!((area - wedges).abs() / wedges < 3e-4, "{area} vs {wedges}");
    }
}
