//! World-space bounding volumes.

use glam::{DMat4, DVec3};

/// The largest world coordinate a scene may have, in magnitude: vertex positions, node
/// transform entries, light and camera positions. f64 still resolves 1/8000 unit at 1e12, and
/// differences of such coordinates stay far inside f32's range on the way to the GPU.
pub const MAX_COORDINATE: f64 = 1e12;

/// An axis-aligned box in world space. Always non-empty: `min <= max` per axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// The smallest coordinate on each axis.
    pub min: DVec3,
    /// The largest coordinate on each axis.
    pub max: DVec3,
}

/// A sphere in world space, `radius >= 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundingSphere {
    /// Its center, world space.
    pub center: DVec3,
    /// Its radius, world units.
    pub radius: f64,
}

impl Aabb {
    /// The smallest box holding every point, or `None` when there are none.
    pub fn from_points(points: impl IntoIterator<Item = DVec3>) -> Option<Aabb> {
        points.into_iter().fold(None, |acc, p| {
            Some(match acc {
                None => Aabb { min: p, max: p },
                Some(b) => Aabb {
                    min: b.min.min(p),
                    max: b.max.max(p),
                },
            })
        })
    }

    /// The smallest box holding both.
    pub fn union(&self, other: &Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// The largest coordinate magnitude of its corners (NaN when a corner is NaN).
    pub fn largest_coordinate(&self) -> f64 {
        self.min.abs().max(self.max.abs()).max_element()
    }

    /// The box's center.
    pub fn center(&self) -> DVec3 {
        (self.min + self.max) * 0.5
    }

    /// The smallest box holding this one's corners moved by `transform` (an affine
    /// transform: the box of a placed object-space box).
    pub fn transformed(&self, transform: &DMat4) -> Aabb {
        let corners = self.corners().map(|c| transform.transform_point3(c));
        Aabb::from_points(corners).expect("a box has corners")
    }

    /// Its eight corners.
    pub fn corners(&self) -> [DVec3; 8] {
        let pick = |bit: bool, min: f64, max: f64| if bit { max } else { min };
        std::array::from_fn(|i| {
            DVec3::new(
                pick(i & 1 != 0, self.min.x, self.max.x),
                pick(i & 2 != 0, self.min.y, self.max.y),
                pick(i & 4 != 0, self.min.z, self.max.z),
            )
        })
    }

    /// Edge lengths per axis.
    pub fn size(&self) -> DVec3 {
        self.max - self.min
    }
}

impl BoundingSphere {
    /// The smallest sphere centred at `center` that holds every point: the box center and
    /// the farthest vertex frame a model as a viewer does, where the sphere through the
    /// box's corners is up to √3 times as large as the model (radius 0 without points).
    pub fn around(center: DVec3, points: impl IntoIterator<Item = DVec3>) -> BoundingSphere {
        let radius = points
            .into_iter()
            .map(|p| p.distance_squared(center))
            .fold(0.0, f64::max)
            .sqrt();
        BoundingSphere { center, radius }
    }
}
