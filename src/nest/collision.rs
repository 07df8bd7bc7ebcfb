//! Collision detection for the search, behind our own trait so that no other file names a jagua-rs
//! type (its API changes between releases; the version is pinned to exactly 1.1.0 in Cargo.toml).
//!
//! The search works with *oriented shapes*: an item's outer ring already rotated (and mirrored)
//! about its origin, registered once in a [`ShapeLibrary`]. Queries then only translate them.
//!
//! Gap and round-off: jagua-rs works in f32 and counts touching as colliding. Each shape is
//! inflated by `gap / 2` (divided by the cosine of half the round-join step, so the chords of the
//! rounded corners stay outside the exact offset) plus [`INFLATION_RELATIVE`] × the stock's scale,
//! and the container is shrunk by the same amount. Two shapes that do not collide are therefore at
//! least `gap` apart in exact geometry, with a margin that covers the f32 rounding.

use std::sync::Arc;

use glam::DVec2;
use jagua_rs::collision_detection::hazards::collector::{BasicHazardCollector, HazardCollector};
use jagua_rs::collision_detection::hazards::filter::{HazardFilter, NoFilter};
use jagua_rs::collision_detection::hazards::{HazKey, Hazard, HazardEntity};
use jagua_rs::collision_detection::{CDEConfig, CDEngine};
use jagua_rs::geometry::Transformation;
use jagua_rs::geometry::fail_fast::SPSurrogateConfig;
use jagua_rs::geometry::geo_enums::GeoPosition;
use jagua_rs::geometry::geo_traits::{CollidesWith, TransformableFrom};
use jagua_rs::geometry::primitives::{Circle, Point, Rect, SPolygon};
use jagua_rs::geometry::shape_modification::{ShapeModifyMode, offset_shape, simplify_shape};

/// Extra inflation of every shape, relative to the stock's largest dimension: covers the f32
/// rounding of coordinates (relative error about 6e-8) with a wide margin.
pub const INFLATION_RELATIVE: f64 = 1e-5;
/// Half the angle step (radians) of the round joins jagua-rs uses when offsetting (0.1 rad steps).
const ROUND_JOIN_HALF_STEP: f64 = 0.05;
/// Largest relative area the inflated shape may gain when its round corners are simplified.
const SIMPLIFY_AREA_RATIO: f32 = 0.002;

/// Index of an oriented shape in the [`ShapeLibrary`].
pub type ShapeId = usize;

/// An oriented shape of the [`ShapeLibrary`] turned further by `turn` radians, counter-clockwise
/// about its own origin: 0 (upright) for every part the construction places, any angle for a
/// part free to rotate that the search through overlap turns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// The oriented shape.
    pub shape: ShapeId,
    /// The further turn, radians.
    pub turn: f64,
}

impl Pose {
    /// The oriented shape `shape` as registered, not turned.
    pub fn upright(shape: ShapeId) -> Self {
        Self { shape, turn: 0.0 }
    }

    /// Whether the pose is the oriented shape as registered.
    pub fn is_upright(&self) -> bool {
        self.turn == 0.0
    }

    /// jagua-rs's transformation of the pose translated by `translation`: the turn (when there is
    /// one), then the translation.
    fn transformation(&self, translation: DVec2) -> Transformation {
        let moved = (translation.x as f32, translation.y as f32);
        if self.is_upright() {
            Transformation::from_translation(moved)
        } else {
            Transformation::from_rotation(self.turn as f32).translate(moved)
        }
    }
}

/// A broad-phase + narrow-phase collision engine over one rectangular container.
///
/// Implementations must be deterministic: the same calls give the same answers.
pub trait CollisionEngine: Clone + Send + Sync {
    /// Whether `shape` translated by `translation` lies inside the container and clear of every
    /// inserted part (with the gap). Counts one query.
    fn fits(&mut self, shape: ShapeId, translation: DVec2) -> bool;
    /// Registers a part in `pose` under the caller's `key` (unique among inserted parts).
    fn insert(&mut self, key: u32, pose: Pose, translation: DVec2);
    /// Removes the part registered under `key`; does nothing if there is none.
    fn remove(&mut self, key: u32);
    /// Number of [`CollisionEngine::fits`] queries answered so far.
    fn queries(&self) -> u64;
}

/// Oriented shapes prepared for jagua-rs: inflated, simplified, with fail-fast surrogates.
#[derive(Debug)]
pub struct ShapeLibrary {
    shapes: Vec<SPolygon>,
    inflation: f64,
}

/// A shape the engine could not accept: which one and why.
#[derive(Debug, Clone)]
pub struct ShapeRejected {
    /// Index of the polygon in the list given to [`ShapeLibrary::new`].
    pub index: usize,
    /// The engine's message.
    pub reason: String,
}

impl ShapeLibrary {
    /// Prepares `polygons` (exact rings, either orientation) for a stock whose largest dimension is
    /// `scale` mm, with `gap` mm between parts.
    pub fn new(polygons: &[Vec<DVec2>], gap: f64, scale: f64) -> Result<Self, ShapeRejected> {
        let inflation = gap / 2.0 / ROUND_JOIN_HALF_STEP.cos() + INFLATION_RELATIVE * scale;
        let surrogate = SPSurrogateConfig {
            n_pole_limits: [(64, 0.0), (16, 0.8), (8, 0.9)],
            ff_pole_area_ratio: 0.01,
            n_ff_piers: 0,
        };
        let shapes = polygons
            .iter()
            .enumerate()
            .map(|(index, polygon)| {
                let rejected = |error: anyhow::Error| ShapeRejected {
                    index,
                    reason: format!("{error:#}"),
                };
                let exact = to_spolygon(polygon).map_err(rejected)?;
                let inflated = offset_shape(&exact, ShapeModifyMode::Inflate, inflation as f32)
                    .map_err(rejected)?;
                let mut simplified =
                    simplify_shape(&inflated, ShapeModifyMode::Inflate, SIMPLIFY_AREA_RATIO);
                simplified.generate_surrogate(surrogate).map_err(rejected)?;
                Ok(simplified)
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self { shapes, inflation })
    }

    /// How far every shape was inflated, mm.
    pub fn inflation(&self) -> f64 {
        self.inflation
    }

    /// Bounding box (min, max) of an inflated shape, in its own coordinates.
    pub fn inflated_bounds(&self, shape: ShapeId) -> (DVec2, DVec2) {
        let bbox = self.shapes[shape].bbox();
        (
            DVec2::new(f64::from(bbox.x_min), f64::from(bbox.y_min)),
            DVec2::new(f64::from(bbox.x_max), f64::from(bbox.y_max)),
        )
    }

    /// The centre of an inflated shape's pole of inaccessibility (the centre of its largest
    /// inscribed circle: a point well inside it) for `pose` translated by `translation`.
    pub fn inner_point(&self, pose: Pose, translation: DVec2) -> DVec2 {
        let centre = self.shapes[pose.shape].poi().center;
        let local = DVec2::new(f64::from(centre.0), f64::from(centre.1));
        DVec2::from_angle(pose.turn).rotate(local) + translation
    }

    /// Whether `point` lies inside the inflated shape of `pose` translated by `translation`.
    pub fn contains(&self, pose: Pose, translation: DVec2, point: DVec2) -> bool {
        let local = DVec2::from_angle(-pose.turn).rotate(point - translation);
        self.shapes[pose.shape].collides_with(&Point(local.x as f32, local.y as f32))
    }

    /// Bounding box (min, max) of an inflated shape turned by `turn` radians about its origin
    /// (a [`Pose`]'s), in the shape's own coordinates.
    pub fn turned_bounds(&self, shape: ShapeId, turn: f64) -> (DVec2, DVec2) {
        let rotation = DVec2::from_angle(turn);
        (self.shapes[shape].vertices().iter()).fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(min, max), vertex| {
                let point = rotation.rotate(DVec2::new(f64::from(vertex.0), f64::from(vertex.1)));
                (min.min(point), max.max(point))
            },
        )
    }
}

fn to_spolygon(polygon: &[DVec2]) -> anyhow::Result<SPolygon> {
    SPolygon::new(
        polygon
            .iter()
            .map(|point| Point(point.x as f32, point.y as f32))
            .collect(),
    )
}

/// Who causes a hazard in our engine: the outside of the container, or a part by key.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Entity {
    Exterior,
    Part(u32),
}

impl HazardEntity for Entity {
    fn scope(&self) -> GeoPosition {
        match self {
            Entity::Exterior => GeoPosition::Exterior,
            Entity::Part(_) => GeoPosition::Interior,
        }
    }

    fn is_dynamic(&self) -> bool {
        matches!(self, Entity::Part(_))
    }
}

/// [`CollisionEngine`] on jagua-rs 1.1.0's quadtree engine.
#[derive(Clone)]
pub struct JaguaEngine {
    library: Arc<ShapeLibrary>,
    engine: CDEngine<Entity>,
    /// One scratch copy per shape, reused for every translated query (no allocation per query).
    scratch: Vec<SPolygon>,
    queries: u64,
    /// Bounding box of the container's inside (after the inset), for the edge overlap.
    inside: (DVec2, DVec2),
    /// Reused by every overlap query (cleared first): no allocation per query.
    collector: BasicHazardCollector<Entity>,
    /// The hazard key and placed shape of each inserted part, indexed by our key (jagua-rs only
    /// finds a hazard by its entity through a linear search).
    parts: Vec<Option<(HazKey, Arc<SPolygon>)>>,
}

/// Depth of the quadtree (jagua-rs recommends 3–10).
const QUADTREE_DEPTH: u8 = 5;
/// Below this many edges in a node, the quadtree stops descending and tests edges directly.
const COLLISION_THRESHOLD: u8 = 16;

impl JaguaEngine {
    /// An empty container spanning `min`..`max` (exact coordinates, mm); it is shrunk by the
    /// library's inflation so that parts keep the gap to its edge.
    pub fn new(library: Arc<ShapeLibrary>, min: DVec2, max: DVec2) -> anyhow::Result<Self> {
        let inset = library.inflation();
        let (low, high) = (min + DVec2::splat(inset), max - DVec2::splat(inset));
        anyhow::ensure!(
            high.x > low.x && high.y > low.y,
            "the container is smaller than twice the gap"
        );
        let corners = vec![
            Point(low.x as f32, low.y as f32),
            Point(high.x as f32, low.y as f32),
            Point(high.x as f32, high.y as f32),
            Point(low.x as f32, high.y as f32),
        ];
        Self::with_outline(library, SPolygon::new(corners)?, min, max)
    }

    /// An empty container bounded by the closed `ring` (exact coordinates, mm, either
    /// orientation; a part's hole), shrunk by the library's inflation (an inward offset with
    /// round joins, whose chords lie at most `1 − cos 0.05` of it closer to the ring, covered by
    /// the parts' own inflation) so that parts keep the gap to the ring.
    pub fn in_polygon(library: Arc<ShapeLibrary>, ring: &[DVec2]) -> anyhow::Result<Self> {
        let exact = to_spolygon(ring)?;
        let outline = offset_shape(&exact, ShapeModifyMode::Deflate, library.inflation() as f32)?;
        let (min, max) = ring.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(min, max), point| (min.min(*point), max.max(*point)),
        );
        Self::with_outline(library, outline, min, max)
    }

    /// An empty engine whose container is the inside of `outline`, within `min`..`max`.
    fn with_outline(
        library: Arc<ShapeLibrary>,
        outline: SPolygon,
        min: DVec2,
        max: DVec2,
    ) -> anyhow::Result<Self> {
        let bounds = Rect::try_new(min.x as f32, min.y as f32, max.x as f32, max.y as f32)?
            .inflate_to_square();
        let config = CDEConfig {
            quadtree_depth: QUADTREE_DEPTH,
            cd_threshold: COLLISION_THRESHOLD,
            item_surrogate_config: SPSurrogateConfig::none(),
        };
        let scratch = library.shapes.clone();
        let inside_box = outline.bbox();
        let inside = (
            DVec2::new(f64::from(inside_box.x_min), f64::from(inside_box.y_min)),
            DVec2::new(f64::from(inside_box.x_max), f64::from(inside_box.y_max)),
        );
        let engine = CDEngine::new(
            bounds,
            vec![Hazard::new(Entity::Exterior, Arc::new(outline))],
            config,
        );
        Ok(Self {
            library,
            engine,
            scratch,
            queries: 0,
            inside,
            collector: BasicHazardCollector::new(),
            parts: Vec::new(),
        })
    }
}

/// The library's shape of `pose` translated by `translation`, made in its `scratch` copy (one
/// per shape: no allocation per query).
fn place<'s>(
    scratch: &'s mut [SPolygon],
    library: &ShapeLibrary,
    pose: Pose,
    translation: DVec2,
) -> &'s SPolygon {
    let transform = pose.transformation(translation);
    scratch[pose.shape].transform_from(&library.shapes[pose.shape], &transform)
}

impl CollisionEngine for JaguaEngine {
    fn fits(&mut self, shape: ShapeId, translation: DVec2) -> bool {
        self.queries += 1;
        let transform =
            Transformation::from_translation((translation.x as f32, translation.y as f32));
        let surrogate = self.library.shapes[shape].surrogate();
        if self
            .engine
            .detect_surrogate_collision(surrogate, &transform, &NoFilter)
        {
            return false;
        }
        let placed = self.scratch[shape].transform_from(&self.library.shapes[shape], &transform);
        !self.engine.detect_poly_collision(placed, &NoFilter)
    }

    fn insert(&mut self, key: u32, pose: Pose, translation: DVec2) {
        let placed = Arc::new(place(&mut self.scratch, &self.library, pose, translation).clone());
        self.engine
            .register_hazard(Hazard::new(Entity::Part(key), Arc::clone(&placed)));
        let hazard_key = (self.engine)
            .haz_key(&Entity::Part(key))
            .expect("the hazard was just registered");
        let index = key as usize;
        if self.parts.len() <= index {
            self.parts.resize(index + 1, None);
        }
        self.parts[index] = Some((hazard_key, placed));
    }

    fn remove(&mut self, key: u32) {
        if let Some((hazard_key, _)) = self.parts.get_mut(key as usize).and_then(Option::take) {
            self.engine.deregister_hazard_by_key(hazard_key);
        }
    }

    fn queries(&self) -> u64 {
        self.queries
    }
}

/// Poles (inscribed circles, largest first) of each shape that the overlap measure uses.
pub const OVERLAP_POLES: usize = 16;
/// Overlap charged for a collision that the poles do not see (jagua-rs finds the outlines
/// intersecting, but no two poles overlap, or a part crosses a curved container edge), as a
/// fraction of the square of the smaller largest pole's radius: small, but never zero, so that a
/// layout whose total overlap is zero is one without any collision.
pub const UNSEEN_OVERLAP_FRACTION: f64 = 1e-3;

/// Weight of the bounding boxes' common area in the overlap of two parts (see `part_overlap`).
pub const BOX_OVERLAP_FRACTION: f64 = 0.1;

/// What a part overlaps: the container's edge or another part (by key).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Obstacle {
    /// The container's edge (the outside of the stock).
    Edge,
    /// The part inserted under this key.
    Part(u32),
}

/// Penetration depth of two sets of poles: the largest `r_a + r_b − |c_a − c_b|` over pairs, or
/// 0 if no two poles overlap. Each pole lies inside its shape, so separating the shapes needs a
/// translation at least this long: a lower bound of the shapes' penetration depth, exact when the
/// deepest contact is between two inscribed circles (two squares offset along a side). The search
/// uses the smoother [`pole_overlap`]; the depth is its analytic check.
#[cfg(test)]
fn pole_depth(a: &[Circle], b: &[Circle]) -> f64 {
    let mut depth: f64 = 0.0;
    for pole_a in a {
        for pole_b in b {
            let distance = f64::from(pole_a.center.0 - pole_b.center.0)
                .hypot(f64::from(pole_a.center.1 - pole_b.center.1));
            depth = depth.max(f64::from(pole_a.radius) + f64::from(pole_b.radius) - distance);
        }
    }
    depth
}

/// Overlap quantity of two sets of poles: over every overlapping pair, its penetration times the
/// smaller radius (mm², an area-like quantity that grows smoothly as the shapes move deeper into
/// each other and weighs contacts between large poles more than between small ones).
fn pole_overlap(a: &[Circle], b: &[Circle], b_box: Rect) -> f64 {
    let near_b = |pole: &Circle| {
        let (x, y, radius) = (pole.center.0, pole.center.1, pole.radius);
        x + radius > b_box.x_min
            && x - radius < b_box.x_max
            && y + radius > b_box.y_min
            && y - radius < b_box.y_max
    };
    // A pole clear of the other shape's bounding box overlaps none of its poles; the poles of
    // `b` are tested only against the box of the poles of `a` that are near it.
    let mut near: [Option<&Circle>; OVERLAP_POLES] = [None; OVERLAP_POLES];
    let mut count = 0;
    let (mut x_min, mut y_min, mut x_max, mut y_max) = (f32::MAX, f32::MAX, f32::MIN, f32::MIN);
    for pole in a.iter().filter(|pole| near_b(pole)).take(OVERLAP_POLES) {
        x_min = x_min.min(pole.center.0 - pole.radius);
        x_max = x_max.max(pole.center.0 + pole.radius);
        y_min = y_min.min(pole.center.1 - pole.radius);
        y_max = y_max.max(pole.center.1 + pole.radius);
        near[count] = Some(pole);
        count += 1;
    }
    if count == 0 {
        return 0.0;
    }
    let mut total = 0.0;
    for pole_b in b {
        let (x, y, radius) = (pole_b.center.0, pole_b.center.1, pole_b.radius);
        if x + radius <= x_min || x - radius >= x_max || y + radius <= y_min || y - radius >= y_max
        {
            continue;
        }
        for pole_a in near[..count].iter().flatten() {
            let reach = f64::from(pole_a.radius + radius);
            let dx = f64::from(pole_a.center.0 - x);
            let dy = f64::from(pole_a.center.1 - y);
            let squared = dx * dx + dy * dy;
            if squared >= reach * reach {
                continue;
            }
            total += (reach - squared.sqrt()) * f64::from(pole_a.radius.min(radius));
        }
    }
    total
}

/// The poles the measure uses (the largest [`OVERLAP_POLES`]).
fn measured_poles(shape: &SPolygon) -> &[Circle] {
    let poles = &shape.surrogate().poles;
    &poles[..poles.len().min(OVERLAP_POLES)]
}

/// The measure of a collision from its raw area-like quantity `raw` (mm², [`raw_part_overlap`]
/// or [`raw_edge_overlap`]) and the size `size` (mm²) of what collides, the geometric mean of
/// the two parts' convex-hull areas (a part and the edge: the part's own): their geometric
/// mean `√(raw × size)`. Still an area, 0 only when `raw` is; the same penetration costs more
/// between large parts than between small ones (the small part is the one to move), and a
/// shallow collision costs relatively more than under `raw` alone. (`raw^α × size^(1−α)` with
/// α = 0.35 or 0.65 instead of 1/2 did worse on shirts.)
fn sized(raw: f64, size: f64) -> f64 {
    (raw * size).sqrt()
}

/// The convex-hull area of a placed shape, mm² (jagua-rs's surrogate keeps it).
fn hull_area(shape: &SPolygon) -> f64 {
    f64::from(shape.surrogate().convex_hull_area)
}

/// Overlap of two placed shapes that jagua-rs finds colliding: [`raw_part_overlap`], [`sized`]
/// by their convex-hull areas.
fn part_overlap(a: &SPolygon, b: &SPolygon) -> f64 {
    sized(raw_part_overlap(a, b), (hull_area(a) * hull_area(b)).sqrt())
}

/// Raw overlap of two placed shapes that jagua-rs finds colliding: [`pole_overlap`] plus
/// [`BOX_OVERLAP_FRACTION`] × the area common to their bounding boxes (which still shrinks as
/// two shapes that only graze each other, outside their poles, move apart), never below the
/// [`UNSEEN_OVERLAP_FRACTION`] floor.
fn raw_part_overlap(a: &SPolygon, b: &SPolygon) -> f64 {
    let (poles_a, poles_b) = (measured_poles(a), measured_poles(b));
    let floor = unseen_floor(poles_a, poles_b);
    let (box_a, box_b) = (a.bbox(), b.bbox());
    let common_x = f64::from(box_a.x_max.min(box_b.x_max) - box_a.x_min.max(box_b.x_min));
    let common_y = f64::from(box_a.y_max.min(box_b.y_max) - box_a.y_min.max(box_b.y_min));
    let boxes = BOX_OVERLAP_FRACTION * common_x.max(0.0) * common_y.max(0.0);
    (pole_overlap(poles_a, poles_b, box_b) + boxes).max(floor)
}

fn unseen_floor(a: &[Circle], b: &[Circle]) -> f64 {
    let radius = |poles: &[Circle]| poles.first().map_or(0.0, |pole| f64::from(pole.radius));
    UNSEEN_OVERLAP_FRACTION * radius(a).min(radius(b)).powi(2)
}

/// Overlap of a placed shape with the container's edge, which jagua-rs finds crossed:
/// [`raw_edge_overlap`], [`sized`] by the shape's convex-hull area.
fn edge_overlap(shape: &SPolygon, inside: (DVec2, DVec2)) -> f64 {
    sized(raw_edge_overlap(shape, inside), hull_area(shape))
}

/// Raw overlap of a placed shape with the container's edge: how far its bounding box sticks out
/// of the container's inside on each side, times the box's extent along that side (mm²), never
/// below the [`UNSEEN_OVERLAP_FRACTION`] floor.
fn raw_edge_overlap(shape: &SPolygon, inside: (DVec2, DVec2)) -> f64 {
    let bbox = shape.bbox();
    let (min, max) = (
        DVec2::new(f64::from(bbox.x_min), f64::from(bbox.y_min)),
        DVec2::new(f64::from(bbox.x_max), f64::from(bbox.y_max)),
    );
    let size = max - min;
    let out_x = (inside.0.x - min.x).max(0.0) + (max.x - inside.1.x).max(0.0);
    let out_y = (inside.0.y - min.y).max(0.0) + (max.y - inside.1.y).max(0.0);
    let poles = measured_poles(shape);
    (out_x * size.y + out_y * size.x).max(unseen_floor(poles, poles))
}

/// A hazard filter that ignores one part, if any.
struct Ignore(Option<u32>);

impl HazardFilter<Entity> for Ignore {
    fn is_irrelevant(&self, _key: HazKey, entity: &Entity) -> bool {
        matches!((self.0, entity), (Some(ignored), Entity::Part(key)) if ignored == *key)
    }
}

impl JaguaEngine {
    /// Weighted overlap of `pose` translated by `translation` with the container's edge and the
    /// inserted parts: the sum over every obstacle it collides with of `weight(obstacle)` times
    /// the obstacle's overlap (mm²; see [`JaguaEngine::overlaps`]). Stops as soon as the sum
    /// exceeds `bound` and returns the partial sum (then above `bound`). 0 exactly when
    /// [`CollisionEngine::fits`] would say yes (for an upright pose). Counts one query.
    pub fn overlap(
        &mut self,
        pose: Pose,
        translation: DVec2,
        bound: f64,
        weight: impl Fn(Obstacle) -> f64,
    ) -> f64 {
        self.queries += 1;
        let placed = place(&mut self.scratch, &self.library, pose, translation);
        let engine = &self.engine;
        let parts = &self.parts;
        let inside = self.inside;
        let collector = &mut self.collector;
        collector.clear();
        let mut total = 0.0;
        let _ = engine.collect_poly_collisions_until(placed, &NoFilter, collector, |entity| {
            total += match entity {
                Entity::Exterior => weight(Obstacle::Edge) * edge_overlap(placed, inside),
                Entity::Part(key) => {
                    weight(Obstacle::Part(key)) * Self::overlap_with(parts, placed, key)
                }
            };
            total > bound
        });
        total
    }

    /// Every obstacle that `pose` translated by `translation` collides with and its unweighted
    /// overlap (mm²), in the order of the obstacle (edge first, then by key), ignoring the part
    /// inserted under `ignore` (the part itself, measured in place). Counts one query.
    pub fn overlaps(
        &mut self,
        pose: Pose,
        translation: DVec2,
        ignore: Option<u32>,
    ) -> Vec<(Obstacle, f64)> {
        self.queries += 1;
        let placed = place(&mut self.scratch, &self.library, pose, translation);
        self.collector.clear();
        self.engine
            .collect_poly_collisions(placed, &Ignore(ignore), &mut self.collector);
        let mut found: Vec<(Obstacle, f64)> = (self.collector)
            .entities()
            .map(|entity| match *entity {
                Entity::Exterior => (Obstacle::Edge, edge_overlap(placed, self.inside)),
                Entity::Part(key) => (
                    Obstacle::Part(key),
                    Self::overlap_with(&self.parts, placed, key),
                ),
            })
            .collect();
        found.sort_by_key(|&(obstacle, _)| match obstacle {
            Obstacle::Edge => None,
            Obstacle::Part(key) => Some(key),
        });
        found
    }

    /// Penetration depth (mm) of `shape` translated by `translation` into the part inserted under
    /// `key`, estimated from their poles (a lower bound; see [`pole_depth`]); 0 without that part.
    #[cfg(test)]
    pub fn depth_into(&mut self, shape: ShapeId, translation: DVec2, key: u32) -> f64 {
        let placed = place(
            &mut self.scratch,
            &self.library,
            Pose::upright(shape),
            translation,
        );
        let Some(Some((_, other))) = self.parts.get(key as usize) else {
            return 0.0;
        };
        pole_depth(measured_poles(placed), measured_poles(other))
    }

    fn overlap_with(parts: &[Option<(HazKey, Arc<SPolygon>)>], placed: &SPolygon, key: u32) -> f64 {
        match parts.get(key as usize) {
            Some(Some((_, other))) => part_overlap(placed, other),
            _ => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn circle(x: f32, y: f32, radius: f32) -> Circle {
        Circle::try_new(Point(x, y), radius).unwrap()
    }

    fn square(side: f64) -> Vec<DVec2> {
        vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(side, 0.0),
            DVec2::new(side, side),
            DVec2::new(0.0, side),
        ]
    }

    #[test]
    fn two_circles_overlap_by_their_penetration_times_the_smaller_radius() {
        let (a, b) = ([circle(0.0, 0.0, 5.0)], [circle(4.0, 0.0, 3.0)]);
        assert!((pole_depth(&a, &b) - 4.0).abs() < 1e-6);
        let wide = Rect::try_new(-100.0, -100.0, 100.0, 100.0).unwrap();
        assert!((pole_overlap(&a, &b, wide) - 12.0).abs() < 1e-5);
        let apart = [circle(9.0, 0.0, 3.0)];
        assert_eq!(pole_depth(&a, &apart), 0.0);
        assert_eq!(pole_overlap(&a, &apart, wide), 0.0);
        // The other shape's bounding box clear of the poles: nothing is counted.
        let far = Rect::try_new(50.0, 50.0, 60.0, 60.0).unwrap();
        assert_eq!(pole_overlap(&a, &b, far), 0.0);
    }

    #[test]
    fn two_squares_offset_along_a_side_penetrate_by_the_overlap_width() {
        let library = Arc::new(ShapeLibrary::new(&[square(10.0)], 0.0, 100.0).unwrap());
        let inflation = library.inflation();
        let mut engine =
            JaguaEngine::new(Arc::clone(&library), DVec2::ZERO, DVec2::new(100.0, 100.0)).unwrap();
        engine.insert(7, Pose::upright(0), DVec2::new(20.0, 20.0));
        for offset in [1.0, 4.0, 9.0] {
            let at = DVec2::new(20.0 + offset, 20.0);
            // Overlap width of the two squares, each inflated by `inflation` on every side.
            let width = 10.0 - offset + 2.0 * inflation;
            let depth = engine.depth_into(0, at, 7);
            assert!(
                (depth - width).abs() < 1e-3,
                "offset {offset}: {depth} vs {width}"
            );
            let overlaps = engine.overlaps(Pose::upright(0), at, None);
            assert_eq!(overlaps.len(), 1);
            assert_eq!(overlaps[0].0, Obstacle::Part(7));
            // Raw: the poles at least the inscribed circles' penetration times their radius, the
            // boxes their common area (width × height) weighted; then sized by the hull areas,
            // each at least the square's 100 mm².
            let boxes = BOX_OVERLAP_FRACTION * width * (10.0 + 2.0 * inflation);
            let raw = width * (5.0 + inflation) + boxes;
            assert!(overlaps[0].1 >= sized(raw, 100.0) - 1e-6);
            assert!(!engine.fits(0, at));
        }
        // Deeper overlap, larger measure; clear, zero.
        let shallow = engine.overlap(
            Pose::upright(0),
            DVec2::new(28.0, 20.0),
            f64::INFINITY,
            |_| 1.0,
        );
        let deep = engine.overlap(
            Pose::upright(0),
            DVec2::new(24.0, 20.0),
            f64::INFINITY,
            |_| 1.0,
        );
        assert!(deep > shallow && shallow > 0.0);
        assert_eq!(
            engine.overlap(
                Pose::upright(0),
                DVec2::new(50.0, 50.0),
                f64::INFINITY,
                |_| 1.0
            ),
            0.0
        );
        // Weights scale it; the bound stops it early (the partial sum exceeds the bound).
        let doubled = engine.overlap(
            Pose::upright(0),
            DVec2::new(24.0, 20.0),
            f64::INFINITY,
            |_| 2.0,
        );
        assert!((doubled - 2.0 * deep).abs() < 1e-9 * deep.max(1.0));
        assert!(engine.overlap(Pose::upright(0), DVec2::new(24.0, 20.0), 1.0, |_| 1.0) > 1.0);
    }

    /// A pose turned by 45° is the shape rotated about its origin: a 10 mm square so turned
    /// spans ±10/√2 mm along x and 10·√2 mm along y (up to the inflation), and at a translation
    /// where the upright square clears a square beside it, its left corner reaches into it.
    #[test]
    fn a_turned_pose_is_the_shape_rotated_about_its_origin() {
        let library = Arc::new(ShapeLibrary::new(&[square(10.0)], 0.0, 100.0).unwrap());
        let turned = Pose {
            shape: 0,
            turn: std::f64::consts::FRAC_PI_4,
        };
        let (min, max) = library.turned_bounds(0, turned.turn);
        let half_diagonal = 10.0 / 2f64.sqrt();
        let slack = 2.0 * library.inflation();
        assert!((min.x + half_diagonal).abs() < slack, "{min}");
        assert!((max.x - half_diagonal).abs() < slack, "{max}");
        assert!(min.y.abs() < slack && (max.y - 2.0 * half_diagonal).abs() < slack);
        let mut engine =
            JaguaEngine::new(Arc::clone(&library), DVec2::ZERO, DVec2::new(100.0, 100.0)).unwrap();
        engine.insert(7, Pose::upright(0), DVec2::new(20.0, 20.0));
        let beside = DVec2::new(35.0, 20.0);
        assert_eq!(
            engine.overlap(Pose::upright(0), beside, f64::INFINITY, |_| 1.0),
            0.0
        );
        let overlaps = engine.overlaps(turned, beside, None);
        assert_eq!(overlaps.len(), 1);
        assert_eq!(overlaps[0].0, Obstacle::Part(7));
        assert!(overlaps[0].1 > 0.0);
        // Turned on the far side of its own corner, it clears the square again.
        assert_eq!(
            engine.overlap(turned, DVec2::new(45.0, 20.0), f64::INFINITY, |_| 1.0),
            0.0
        );
    }

    #[test]
    fn a_square_past_the_edge_overlaps_by_the_part_outside() {
        let library = Arc::new(ShapeLibrary::new(&[square(10.0)], 0.0, 100.0).unwrap());
        let mut engine =
            JaguaEngine::new(Arc::clone(&library), DVec2::ZERO, DVec2::new(100.0, 100.0)).unwrap();
        let overlaps = engine.overlaps(Pose::upright(0), DVec2::new(93.0, 40.0), None);
        assert_eq!(overlaps.len(), 1);
        assert_eq!(overlaps[0].0, Obstacle::Edge);
        // 3 mm out (plus twice the inflation), over the square's 10 mm height, sized by the
        // square's area (100 mm², plus its inflation).
        let expected = sized(30.0, 100.0);
        assert!((overlaps[0].1 - expected).abs() < 0.2, "{}", overlaps[0].1);
        assert_eq!(
            engine.overlap(
                Pose::upright(0),
                DVec2::new(40.0, 40.0),
                f64::INFINITY,
                |_| 1.0
            ),
            0.0
        );
    }
}
