//! A conical bend (issue 17): `samples/sheet_conical_bend_freecad.step`, two flat flanges
//! (40 wide, 50 and 30 long) joined by a bend whose skins are coaxial cones (half-angle
//! `atan 0.1`, inner radius 2 mm at one end of the bend line and 6 at the other, t 2), the
//! flanges at 90° to each other (`samples/step-sources/freecad_samples.py`,
//! `sheet_conical_bend`). Its flat pattern, computed here from the sample's dimensions alone:
//! the neutral cone (the inner one `K · t` out along the normal) develops onto an annular sector
//! of angle `Δφ · sin α` (`cos Δφ = −tan² α`), radii `20 + K t / tan α` and 40 more, and each
//! flange is its rectangle on the sector's straight edge (`docs/sheet-metal.md`, "Conical
//! bends"). The binary's DXF outline, bend line and zone, report extents, area and bend figures
//! must match it within 0.001 mm.

use glam::DVec2;

use crate::sheet_metal::{Entity, FLAT_TOLERANCE_MM, check_with_ezdxf, dxf_entities, number};
use crate::util::{flatten_into, read_obj, read_report, sample, stderr};

/// The sample's file.
const SAMPLE: &str = "sheet_conical_bend_freecad.step";
/// `tan α` of the bend's cones.
const TAN_HALF_ANGLE: f64 = 0.1;
/// Sheet thickness, mm.
const THICKNESS: f64 = 2.0;
/// The inner skin's distance from its apex at the bend line's small end, and the bend line's
/// length along the generator (the flanges' width), mm.
const SLANT: [f64; 2] = [20.0, 40.0];
/// The two flanges' lengths, mm.
const FLANGES: [f64; 2] = [50.0, 30.0];
/// The DXF's contours follow the flat pattern's outline within its chord tolerance (mm, the
/// default `--dxf-chord`).
const DXF_CHORD_TOLERANCE_MM: f64 = 0.01;

/// One piece of the analytic outline: a segment, or an arc about the developed apex of
/// `radius` from the start generator's ray to the end one's.
enum Piece {
    Segment(DVec2, DVec2),
    Arc(f64),
}

/// The analytic flat pattern at a K-factor, the developed apex at the origin, the first flange's
/// ray along +x and the sector turning counter-clockwise.
struct Flat {
    /// The angle about the cone's axis the bend turns through, radians.
    sweep: f64,
    /// The sector's angle on the flat, radians.
    sector: f64,
    /// The sector's inner and outer radius.
    radii: [f64; 2],
    /// The four far corners of the flanges, in the outline's order.
    corners: [DVec2; 4],
    pieces: Vec<Piece>,
}

impl Flat {
    fn at(k: f64) -> Self {
        let alpha = TAN_HALF_ANGLE.atan();
        let sweep = (-TAN_HALF_ANGLE * TAN_HALF_ANGLE).acos();
        let sector = sweep * alpha.sin();
        let inner = SLANT[0] + k * THICKNESS / TAN_HALF_ANGLE;
        let radii = [inner, inner + SLANT[1]];
        let ray = DVec2::from_angle(sector);
        let onward = ray.perp();
        let corners = [
            DVec2::new(radii[0], -FLANGES[0]),
            DVec2::new(radii[1], -FLANGES[0]),
            ray * radii[1] + onward * FLANGES[1],
            ray * radii[0] + onward * FLANGES[1],
        ];
        let pieces = vec![
            Piece::Segment(corners[0], corners[1]),
            Piece::Segment(corners[1], DVec2::new(radii[1], 0.0)),
            Piece::Arc(radii[1]),
            Piece::Segment(ray * radii[1], corners[2]),
            Piece::Segment(corners[2], corners[3]),
            Piece::Segment(corners[3], ray * radii[0]),
            Piece::Arc(radii[0]),
            Piece::Segment(DVec2::new(radii[0], 0.0), corners[0]),
        ];
        Self {
            sweep,
            sector,
            radii,
            corners,
            pieces,
        }
    }

    /// Two rectangles and the annular sector.
    fn area(&self) -> f64 {
        let [inner, outer] = self.radii;
        SLANT[1] * (FLANGES[0] + FLANGES[1]) + self.sector / 2.0 * (outer * outer - inner * inner)
    }

    /// Distance from a point to the outline.
    fn distance(&self, point: DVec2) -> f64 {
        self.pieces
            .iter()
            .map(|piece| match *piece {
                Piece::Segment(a, b) => {
                    let along = ((point - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
                    point.distance(a + (b - a) * along)
                }
                Piece::Arc(radius) => {
                    let angle = point.y.atan2(point.x);
                    if (0.0..=self.sector).contains(&angle) {
                        (point.length() - radius).abs()
                    } else {
                        point
                            .distance(DVec2::new(radius, 0.0))
                            .min(point.distance(DVec2::from_angle(self.sector) * radius))
                    }
                }
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// The outline's points: the corners and the arcs sampled finely.
    fn points(&self) -> Vec<DVec2> {
        let mut points = self.corners.to_vec();
        for radius in self.radii {
            points.extend(
                (0..=20_000).map(|i| DVec2::from_angle(self.sector * i as f64 / 20_000.0) * radius),
            );
        }
        points
    }

    /// The sides of the smallest-area rectangle around the outline (longer first): over the
    /// directions of its convex hull's edges (rotating calipers).
    fn smallest_rectangle(&self) -> [f64; 2] {
        let hull = convex_hull(self.points());
        let mut best = [f64::INFINITY, 0.0, 0.0];
        for (i, &a) in hull.iter().enumerate() {
            let along = (hull[(i + 1) % hull.len()] - a).normalize();
            let (mut low, mut high) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
            for &p in &hull {
                let q = DVec2::new(p.dot(along), p.perp_dot(along));
                (low, high) = (low.min(q), high.max(q));
            }
            let size = high - low;
            if size.x * size.y < best[0] {
                best = [size.x * size.y, size.x.max(size.y), size.x.min(size.y)];
            }
        }
        [best[1], best[2]]
    }
}

/// The convex hull of points, counter-clockwise (Andrew's monotone chain).
fn convex_hull(mut points: Vec<DVec2>) -> Vec<DVec2> {
    points.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    let mut hull: Vec<DVec2> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        for &p in &points {
            while hull.len() >= start + 2 {
                let [a, b] = [hull[hull.len() - 2], hull[hull.len() - 1]];
                if (b - a).perp_dot(p - b) > 0.0 {
                    break;
                }
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
        if pass == 0 {
            points.reverse();
        }
    }
    hull
}

/// The outer contour's vertices and bulges.
fn outline(entities: &[Entity]) -> (Vec<DVec2>, Vec<f64>) {
    let outer: Vec<&Entity> = entities.iter().filter(|e| e.layer == "CUT_OUTER").collect();
    let [outer] = outer.as_slice() else {
        panic!("{} outer contours", outer.len());
    };
    let points = outer
        .points
        .iter()
        .map(|&[x, y]| DVec2::new(x, y))
        .collect();
    (points, outer.bulges.clone())
}

/// The vertices where the outline turns by more than 45° (its corners), with their indices: the
/// tangent of a bulged segment leaves its chord by twice `atan(bulge)`.
fn corners(points: &[DVec2], bulges: &[f64]) -> Vec<usize> {
    let count = points.len();
    let direction = |from: usize, turn: f64| {
        let chord = points[(from + 1) % count] - points[from];
        DVec2::from_angle(turn).rotate(chord.normalize())
    };
    (0..count)
        .filter(|&i| {
            let previous = (i + count - 1) % count;
            let incoming = direction(previous, -2.0 * bulges[previous].atan());
            let outgoing = direction(i, 2.0 * bulges[i].atan());
            incoming.dot(outgoing) < std::f64::consts::FRAC_1_SQRT_2
        })
        .collect()
}

/// The rigid motion (possibly mirrored) taking `from` onto `to` best, and its largest residual.
fn fit(from: &[DVec2], to: &[DVec2]) -> (impl Fn(DVec2) -> DVec2 + use<>, f64) {
    let centre = |points: &[DVec2]| points.iter().sum::<DVec2>() / points.len() as f64;
    let mut best: Option<(bool, DVec2, f64)> = None;
    for mirrored in [false, true] {
        let flip = |p: DVec2| if mirrored { DVec2::new(p.x, -p.y) } else { p };
        let (from_centre, to_centre) = (centre(from), centre(to));
        let (mut dot, mut cross) = (0.0, 0.0);
        for (&a, &b) in from.iter().zip(to) {
            let (a, b) = (flip(a - from_centre), b - to_centre);
            dot += a.dot(b);
            cross += a.perp_dot(b);
        }
        let rotation = DVec2::new(dot, cross).normalize();
        let residual = from
            .iter()
            .zip(to)
            .map(|(&a, &b)| (rotation.rotate(flip(a - from_centre)) + to_centre).distance(b))
            .fold(0.0, f64::max);
        if best.is_none_or(|(_, _, r)| residual < r) {
            best = Some((mirrored, rotation, residual));
        }
    }
    let (mirrored, rotation, residual) = best.expect("two tries");
    let (from_centre, to_centre) = (centre(from), centre(to));
    let map = move |p: DVec2| {
        let p = p - from_centre;
        let p = if mirrored { DVec2::new(p.x, -p.y) } else { p };
        rotation.rotate(p) + to_centre
    };
    (map, residual)
}

/// The flat pattern's triangles (`pattern.obj`): the vertices on its boundary (on an edge of
/// one triangle only), and how many triangles turn the other way from the majority.
fn boundary_and_flips(path: &std::path::Path) -> (Vec<DVec2>, usize) {
    let (vertices, triangles) = read_obj(path);
    let flat = |v: usize| DVec2::new(vertices[v][0], vertices[v][1]);
    let mut edges = std::collections::HashMap::new();
    let mut positive = 0;
    for &[a, b, c] in &triangles {
        if (flat(b) - flat(a)).perp_dot(flat(c) - flat(a)) > 0.0 {
            positive += 1;
        }
        for (u, v) in [(a, b), (b, c), (c, a)] {
            *edges.entry((u.min(v), u.max(v))).or_insert(0) += 1;
        }
    }
    let mut boundary: Vec<usize> = edges
        .into_iter()
        .filter(|&(_, count)| count == 1)
        .flat_map(|((u, v), _)| [u, v])
        .collect();
    boundary.sort_unstable();
    boundary.dedup();
    let flipped = positive.min(triangles.len() - positive);
    (boundary.into_iter().map(flat).collect(), flipped)
}

/// Flattens the sample with `extra` options, checks the DXF with ezdxf, and returns the report's
/// part, the DXF's entities and the flat pattern's boundary vertices and flipped triangles.
fn unfold(extra: &[&str]) -> (serde_json::Value, Vec<Entity>, (Vec<DVec2>, usize)) {
    let directory = tempfile::tempdir().expect("a temporary directory");
    let output = flatten_into(&sample(SAMPLE), directory.path(), extra);
    assert!(output.status.success(), "{}", stderr(&output));
    let part = read_report(directory.path())["parts"][0].clone();
    let dxf = directory.path().join(SAMPLE.replace(".step", ".dxf"));
    check_with_ezdxf(&dxf);
    let pattern = directory
        .path()
        .join(SAMPLE.replace(".step", ".pattern.obj"));
    (part, dxf_entities(&dxf), boundary_and_flips(&pattern))
}

/// Checks a flattened conical bend against the analytic flat at `k`, the bend `direction`.
fn assert_conical_flat(k: f64, extra: &[&str], direction: &str) {
    let flat = Flat::at(k);
    let k_text = k.to_string();
    let mut arguments = vec!["--k-factor", &k_text, "--bend-zones"];
    arguments.extend_from_slice(extra);
    let (part, entities, (boundary, flipped)) = unfold(&arguments);
    assert_eq!(part["stop_reason"], "exact_unfold", "{part}");
    assert_eq!(flipped, 0, "K {k}: flipped triangles in pattern.obj");
    assert_eq!(number(&part["flipped"]), 0.0);
    let sheet = &part["sheet_metal"];
    // Extents and area.
    let [width, height] = flat.smallest_rectangle();
    let extents = [number(&sheet["flat_width"]), number(&sheet["flat_height"])];
    assert!(
        (extents[0] - width).abs() <= FLAT_TOLERANCE_MM
            && (extents[1] - height).abs() <= FLAT_TOLERANCE_MM,
        "K {k}: flat {extents:?}, expected {width} x {height}"
    );
    let area = number(&sheet["flat_area"]);
    // The mesh's chords cut the arcs by less than 0.001 mm²; a misplaced flange by 0.001 mm
    // would change it by 0.04 mm².
    assert!(
        (area - flat.area()).abs() <= 0.005,
        "K {k}: area {area}, expected {}",
        flat.area()
    );
    // The bend: 90° between the flanges; radius 2 to 6; allowance θ_c (R + K t), θ_c = Δφ cos α.
    let bends = sheet["bends"].as_array().expect("bends");
    let [bend] = bends.as_slice() else {
        panic!("{} bends", bends.len());
    };
    let developed = flat.sweep * TAN_HALF_ANGLE.atan().cos();
    let conical = &bend["conical"];
    assert_eq!(bend["direction"], direction);
    assert!((number(&bend["angle"]) - 90.0).abs() < 1e-6, "{bend}");
    assert!((number(&bend["inner_radius"]) - 4.0).abs() < 1e-6, "{bend}");
    assert!((number(&bend["allowance"]) - developed * (4.0 + k * THICKNESS)).abs() < 1e-6);
    assert!((number(&bend["length"]) - SLANT[1]).abs() <= FLAT_TOLERANCE_MM);
    assert!((number(&conical["developed_angle"]) - developed.to_degrees()).abs() < 1e-6);
    for (end, radius) in [2.0, 6.0].into_iter().enumerate() {
        assert!(
            (number(&conical["inner_radius_ends"][end]) - radius).abs() < 1e-6,
            "{bend}"
        );
        let allowance = number(&conical["allowance_ends"][end]);
        assert!(
            (allowance - developed * (radius + k * THICKNESS)).abs() < 1e-6,
            "{bend}"
        );
        // The same width, as the developed neutral arc at that end.
        assert!((allowance - flat.sector * flat.radii[end]).abs() < 1e-6);
    }
    // The outline: the DXF's four corners are the flanges' far corners; every boundary vertex of
    // the flat pattern lies on the analytic outline, and every vertex and segment middle of the
    // DXF's outer contour within its chord tolerance of it.
    let (points, bulges) = outline(&entities);
    let found: Vec<DVec2> = corners(&points, &bulges)
        .iter()
        .map(|&i| points[i])
        .collect();
    assert_eq!(found.len(), 4, "K {k}: corners {found:?}");
    let (to_flat, residual) = (0..8)
        .map(|order| {
            let mut ordered: Vec<DVec2> = (0..4).map(|i| found[(i + order) % 4]).collect();
            if order >= 4 {
                ordered.reverse();
            }
            fit(&ordered, &flat.corners)
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .expect("eight orders");
    assert!(
        residual <= FLAT_TOLERANCE_MM,
        "K {k}: corners {residual} mm off"
    );
    let farthest = boundary
        .iter()
        .map(|&p| flat.distance(to_flat(p)))
        .fold(0.0, f64::max);
    assert!(
        farthest <= FLAT_TOLERANCE_MM,
        "K {k}: a boundary vertex {farthest} mm off"
    );
    for (i, &point) in points.iter().enumerate() {
        let next = points[(i + 1) % points.len()];
        let chord = next - point;
        // The middle of the segment: the chord's, moved by the sagitta for an arc.
        let middle = (point + next) / 2.0 - chord.perp() * (bulges[i] / 2.0);
        for p in [point, middle] {
            let off = flat.distance(to_flat(p));
            assert!(
                off <= DXF_CHORD_TOLERANCE_MM,
                "K {k}: DXF point {p} is {off} mm off"
            );
        }
    }
    // The bend line: the developed generator halfway through the bend, on its layer; the zone's
    // edges the sector's two straight edges.
    let on = |layer: &str| -> Vec<[DVec2; 2]> {
        entities
            .iter()
            .filter(|e| e.layer == layer && e.kind == "LINE")
            .map(|e| {
                let [x, y] = e.points[0];
                let [u, v] = e.end.expect("a LINE's end");
                [to_flat(DVec2::new(x, y)), to_flat(DVec2::new(u, v))]
            })
            .collect()
    };
    let layer = format!("BEND_{}", direction.to_uppercase());
    let other = if direction == "up" {
        "BEND_DOWN"
    } else {
        "BEND_UP"
    };
    assert!(on(other).is_empty());
    let ray = |angle: f64| flat.radii.map(|r| DVec2::from_angle(angle) * r);
    let same = |found: [DVec2; 2], wanted: [DVec2; 2]| {
        let forward = found[0]
            .distance(wanted[0])
            .max(found[1].distance(wanted[1]));
        let backward = found[0]
            .distance(wanted[1])
            .max(found[1].distance(wanted[0]));
        forward.min(backward) <= FLAT_TOLERANCE_MM
    };
    let lines = on(&layer);
    assert!(
        lines.len() == 1 && same(lines[0], ray(flat.sector / 2.0)),
        "{lines:?}"
    );
    let zone = on("BEND_ZONE");
    assert_eq!(zone.len(), 2);
    assert!(zone.iter().any(|&edge| same(edge, ray(0.0))), "{zone:?}");
    assert!(
        zone.iter().any(|&edge| same(edge, ray(flat.sector))),
        "{zone:?}"
    );
    let note = format!("{} 90%%d R2-6", direction.to_uppercase());
    assert!(
        entities
            .iter()
            .any(|e| e.layer == "MARKS" && e.text == note)
    );
}

#[test]
fn a_conical_bend_unfolds_to_its_developed_neutral_cone_between_rigid_flanges() {
    assert_conical_flat(0.44, &[], "up");
    assert_conical_flat(0.3, &[], "up");
}

#[test]
fn a_conical_bend_drawn_from_its_outer_skin_is_the_same_flat_bent_down() {
    // ADVANCED_FACE #767 is the 50 mm flange's outer face.
    assert_conical_flat(0.44, &["--base-face", "767"], "down");
}

#[test]
fn a_conical_bend_is_refused_by_a_rule_other_than_the_k_factor() {
    let directory = tempfile::tempdir().expect("a temporary directory");
    let output = flatten_into(
        &sample(SAMPLE),
        directory.path(),
        &["--bend-rule", "din6935"],
    );
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(
        message.contains("a conical bend (inner radius 4.0000 mm")
            && message.contains("is unfolded exactly with the K-factor only, not by DIN 6935"),
        "{message}"
    );
}
