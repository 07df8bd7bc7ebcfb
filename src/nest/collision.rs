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
use jagua_rs::collision_detection::hazards::filter::NoFilter;
use jagua_rs::collision_detection::hazards::{Hazard, HazardEntity};
use jagua_rs::collision_detection::{CDEConfig, CDEngine};
use jagua_rs::geometry::Transformation;
use jagua_rs::geometry::fail_fast::SPSurrogateConfig;
use jagua_rs::geometry::geo_enums::GeoPosition;
use jagua_rs::geometry::geo_traits::TransformableFrom;
use jagua_rs::geometry::primitives::{Point, Rect, SPolygon};
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

/// A broad-phase + narrow-phase collision engine over one rectangular container.
///
/// Implementations must be deterministic: the same calls give the same answers.
pub trait CollisionEngine: Clone + Send + Sync {
    /// Whether `shape` translated by `translation` lies inside the container and clear of every
    /// inserted part (with the gap). Counts one query.
    fn fits(&mut self, shape: ShapeId, translation: DVec2) -> bool;
    /// Registers a part under the caller's `key` (unique among inserted parts).
    fn insert(&mut self, key: u32, shape: ShapeId, translation: DVec2);
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
        let engine = CDEngine::new(
            bounds,
            vec![Hazard::new(Entity::Exterior, Arc::new(outline))],
            config,
        );
        let scratch = library.shapes.clone();
        Ok(Self {
            library,
            engine,
            scratch,
            queries: 0,
        })
    }

    fn translated(&mut self, shape: ShapeId, translation: DVec2) -> &SPolygon {
        let transform =
            Transformation::from_translation((translation.x as f32, translation.y as f32));
        self.scratch[shape].transform_from(&self.library.shapes[shape], &transform)
    }
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

    fn insert(&mut self, key: u32, shape: ShapeId, translation: DVec2) {
        let placed = self.translated(shape, translation).clone();
        self.engine
            .register_hazard(Hazard::new(Entity::Part(key), Arc::new(placed)));
    }

    fn remove(&mut self, key: u32) {
        if let Some(hazard_key) = self.engine.haz_key(&Entity::Part(key)) {
            self.engine.deregister_hazard_by_key(hazard_key);
        }
    }

    fn queries(&self) -> u64 {
        self.queries
    }
}
