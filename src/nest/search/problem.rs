//! The problem the search works on: the validated input, every allowed orientation of every item
//! as an oriented shape in the collision library, and the copies to place, in order of
//! decreasing area.

use std::sync::Arc;

use glam::DVec2;

use super::validation::{rotation_error, too_large, validate_outline, validate_stock};
use crate::geometry::{bounding_box, signed_area};
use crate::nest::collision::{Pose, ShapeId, ShapeLibrary};
use crate::nest::errors::NestError;
use crate::nest::item::NestItem;
use crate::nest::layout::Placement;
use crate::nest::options::NestOptions;
use crate::nest::rotations::FREE_ROTATION_SAMPLES;

/// Clearance (relative to the stock scale) kept from the stock edge and from the front, above the
/// shapes' inflation, so that a candidate is not rejected for touching after f32 rounding.
pub(super) const CLEARANCE_RELATIVE: f64 = 1e-6;
/// Two lengths closer than this (relative to the stock scale) are equal when the search compares
/// right edges, bottom edges and used lengths; squared, two areas left out.
pub(super) const LENGTH_TOLERANCE_RELATIVE: f64 = 1e-9;
/// How far the search through overlap turns a part free to rotate from its nearest sampled
/// orientation, either way, radians: half the step between the [`FREE_ROTATION_SAMPLES`]
/// orientations, so that a sampled orientation and a turn reach every angle.
pub(super) const TURN_RANGE: f64 = std::f64::consts::PI / FREE_ROTATION_SAMPLES as f64;

/// One copy of an item in one orientation, in the item's rotated frame.
#[derive(Debug, Clone)]
pub(super) struct Orientation {
    pub(super) item: usize,
    pub(super) rotation_degrees: f64,
    pub(super) mirrored: bool,
    /// Inflated bounding box in the rotated frame.
    pub(super) min: DVec2,
    pub(super) max: DVec2,
}

/// One copy to place.
#[derive(Debug, Clone, Copy)]
pub(super) struct PartCopy {
    pub(super) item: usize,
    pub(super) copy: u32,
}

/// Validated input, oriented shapes and the collision library: everything the search needs.
pub(crate) struct Problem<'a> {
    pub(super) items: &'a [NestItem],
    pub(super) options: &'a NestOptions,
    pub(super) orientations: Vec<Orientation>,
    pub(super) item_shapes: Vec<Vec<ShapeId>>,
    /// Per item, whether it is free to rotate ([`NestItem::turns_freely`]): the search
    /// through overlap then turns it to any angle, not only to its sampled orientations.
    pub(super) turns: Vec<bool>,
    /// Per item, its oriented shapes square to the stock (rotations that are multiples of 90°),
    /// which the search through overlap favours for parts free to rotate.
    pub(super) square_shapes: Vec<Vec<ShapeId>>,
    pub(super) copies: Vec<PartCopy>,
    pub(super) library: Arc<ShapeLibrary>,
    /// Stock extent along y (sheet height or roll width) and, for sheets, along x.
    pub(super) height: f64,
    pub(super) sheet_width: Option<f64>,
    pub(super) scale: f64,
}

impl<'a> Problem<'a> {
    /// Validates the input and prepares the oriented shapes.
    pub(crate) fn new(items: &'a [NestItem], options: &'a NestOptions) -> Result<Self, NestError> {
        let (height, sheet_width) = validate_stock(options)?;
        if !options.gap.is_finite() || options.gap < 0.0 {
            return Err(NestError::InvalidGap(options.gap));
        }
        if items.iter().all(|item| item.quantity == 0) {
            return Err(NestError::EmptyInput);
        }
        let mut orientations = Vec::new();
        let mut rings = Vec::new();
        let mut item_shapes = Vec::with_capacity(items.len());
        for (index, item) in items.iter().enumerate() {
            validate_outline(item)?;
            let poses = item.poses().ok_or_else(|| rotation_error(item))?;
            let mut shapes = Vec::new();
            for &(rotation_degrees, mirrored) in &poses {
                let pose = Placement {
                    item: index,
                    copy: 0,
                    rotation_degrees,
                    mirrored,
                    translation: DVec2::ZERO,
                };
                let ring = pose.transform_ring(&item.outer);
                let (min, max) = bounding_box(&ring);
                let size = max - min + DVec2::splat(2.0 * options.gap);
                if size.y <= height && sheet_width.is_none_or(|width| size.x <= width) {
                    shapes.push(orientations.len());
                    orientations.push(Orientation {
                        item: index,
                        rotation_degrees,
                        mirrored,
                        min,
                        max,
                    });
                    rings.push(ring);
                }
            }
            if shapes.is_empty() && item.quantity > 0 {
                return Err(too_large(item, &poses, options));
            }
            item_shapes.push(shapes);
        }
        let net_area: f64 = items
            .iter()
            .map(|item| item.area().max(0.0) * f64::from(item.quantity))
            .sum();
        let scale = sheet_width.unwrap_or(net_area / height).max(height);
        let library = ShapeLibrary::new(&rings, options.gap, scale).map_err(|rejected| {
            NestError::CollisionShape {
                item: items[orientations[rejected.index].item].name.clone(),
                reason: rejected.reason,
            }
        })?;
        for (shape, orientation) in orientations.iter_mut().enumerate() {
            (orientation.min, orientation.max) = library.inflated_bounds(shape);
        }
        let margin = 2.0 * (library.inflation() + CLEARANCE_RELATIVE * scale);
        for (item, shapes) in items.iter().zip(&mut item_shapes) {
            shapes.retain(|&shape| {
                let size = orientations[shape].max - orientations[shape].min + DVec2::splat(margin);
                size.y <= height && sheet_width.is_none_or(|width| size.x <= width)
            });
            if shapes.is_empty() && item.quantity > 0 {
                let poses = item.poses().unwrap_or_default();
                return Err(too_large(item, &poses, options));
            }
        }
        let mut copies: Vec<PartCopy> = items
            .iter()
            .enumerate()
            .flat_map(|(item, entry)| (0..entry.quantity).map(move |copy| PartCopy { item, copy }))
            .collect();
        let areas: Vec<f64> = items
            .iter()
            .map(|item| signed_area(&item.outer).abs())
            .collect();
        copies.sort_by(|a, b| {
            areas[b.item]
                .total_cmp(&areas[a.item])
                .then(a.item.cmp(&b.item))
                .then(a.copy.cmp(&b.copy))
        });
        let turns = (items.iter()).map(NestItem::turns_freely).collect();
        let square_shapes = (item_shapes.iter())
            .map(|shapes| {
                (shapes.iter().copied())
                    .filter(|&shape| {
                        let quarter_turns = orientations[shape].rotation_degrees / 90.0;
                        (quarter_turns - quarter_turns.round()).abs() < 1e-9
                    })
                    .collect()
            })
            .collect();
        Ok(Self {
            items,
            options,
            orientations,
            item_shapes,
            turns,
            square_shapes,
            copies,
            library: Arc::new(library),
            height,
            sheet_width,
            scale,
        })
    }
}

impl Problem<'_> {
    /// Bounding box (min, max) of the inflated shape of `pose`, in its own coordinates (the
    /// orientation's, for an upright pose).
    pub(super) fn bounds(&self, pose: Pose) -> (DVec2, DVec2) {
        if pose.is_upright() {
            let orientation = &self.orientations[pose.shape];
            (orientation.min, orientation.max)
        } else {
            self.library.turned_bounds(pose.shape, pose.turn)
        }
    }

    /// The placement of `copy` in `pose` translated by `translation`.
    pub(super) fn placement(&self, copy: PartCopy, pose: Pose, translation: DVec2) -> Placement {
        let orientation = &self.orientations[pose.shape];
        let rotation_degrees = if pose.is_upright() {
            orientation.rotation_degrees
        } else {
            (orientation.rotation_degrees + pose.turn.to_degrees()).rem_euclid(360.0)
        };
        Placement {
            item: copy.item,
            copy: copy.copy,
            rotation_degrees,
            mirrored: orientation.mirrored,
            translation,
        }
    }
}
