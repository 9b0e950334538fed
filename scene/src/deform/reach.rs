//! Where a deformed mesh's vertices may be in a pose, without deforming each one: what
//! culling, shadow cascades and the scene's bounds take for a deformed mesh.

use glam::{DMat4, DVec3, Vec3};

use super::Deformation;
use crate::{Aabb, Vertex};

/// What bounds one deformed mesh in any pose: the box of its rest vertices, each morph
/// target's least and greatest offsets, and per joint the box of the vertices it moves.
/// Made once per mesh (it reads every vertex); [`Reach::object_box`] then costs a few
/// operations per joint and target.
#[derive(Clone, Debug, PartialEq)]
pub struct Reach {
    rest: Aabb,
    /// Per morph target, the least and greatest position offset per axis.
    targets: Vec<(DVec3, DVec3)>,
    /// Per joint of the skin, the box of the rest vertices it moves with a weight above
    /// 0; `None` for a joint that moves none. Empty without a skin.
    joints: Vec<Option<Aabb>>,
}

impl Reach {
    /// The reach of `deformation` over its mesh's rest `vertices`; `None` without
    /// vertices.
    pub fn new(deformation: &Deformation, vertices: &[Vertex]) -> Option<Reach> {
        let point = |v: &Vertex| Vec3::from_array(v.position).as_dvec3();
        let rest = Aabb::from_points(vertices.iter().map(point))?;
        let targets = (deformation.morph.iter().flat_map(|m| &m.targets))
            .map(|target| {
                let offsets = target
                    .positions
                    .iter()
                    .map(|d| Vec3::from_array(*d).as_dvec3());
                let b = Aabb::from_points(offsets).unwrap_or(Aabb {
                    min: DVec3::ZERO,
                    max: DVec3::ZERO,
                });
                (b.min, b.max)
            })
            .collect();
        let mut joints: Vec<Option<Aabb>> = Vec::new();
        if let Some(skin) = &deformation.skin {
            for (i, vertex) in vertices.iter().enumerate() {
                for (joint, weight) in skin.influences(i) {
                    if weight <= 0.0 {
                        continue;
                    }
                    let joint = joint as usize;
                    if joints.len() <= joint {
                        joints.resize(joint + 1, None);
                    }
                    let p = Aabb {
                        min: point(vertex),
                        max: point(vertex),
                    };
                    joints[joint] = Some(joints[joint].map_or(p, |b| b.union(&p)));
                }
            }
        }
        Some(Reach {
            rest,
            targets,
            joints,
        })
    }

    /// A box in the mesh's object space holding every vertex deformed by `joints` (object
    /// space, as [`Deformation::deform`] takes them) and morph `weights`. Conservative:
    /// the morph offsets widen every vertex's box by their extremes, and a skinned vertex,
    /// a blend of its joints' transforms with weights summing to 1, lies in the union of
    /// each joint's transformed box.
    pub fn object_box(&self, joints: &[DMat4], weights: &[f32]) -> Aabb {
        let (mut low, mut high) = (DVec3::ZERO, DVec3::ZERO);
        for ((min, max), &weight) in self.targets.iter().zip(weights) {
            let (a, b) = (*min * f64::from(weight), *max * f64::from(weight));
            low += a.min(b);
            high += a.max(b);
        }
        let widen = |b: &Aabb| Aabb {
            min: b.min + low,
            max: b.max + high,
        };
        if self.joints.is_empty() {
            return widen(&self.rest);
        }
        let moved = (self.joints.iter().zip(joints))
            .filter_map(|(b, joint)| Some(widen(b.as_ref()?).transformed(joint)));
        moved
            .reduce(|a, b| a.union(&b))
            .unwrap_or_else(|| widen(&self.rest))
    }
}
