//! Bounds that hold the meshes wherever the animations take them, so that a camera framed
//! on them (and its near plane) sees every frame.

use glam::{DVec3, Vec3};

use super::clip::Animation;
use crate::{Aabb, Mesh, Scene};

/// Poses sampled between two consecutive key times (the keys themselves included once):
/// LINEAR motion is bounded by its keys, but rotations sweep arcs and cubic splines
/// overshoot between them.
const STEPS_PER_INTERVAL: usize = 4;

/// The most poses sampled per animation: a long animation is sampled evenly rather than
/// at every key, so loading stays bounded by meshes x this.
const MAX_POSES: usize = 4096;

/// The world box of every mesh's object-space box, over poses of every animation sampled
/// at and between its key times; `None` without animations. Approximate between samples
/// (a fast spin can leave a box corner a little outside), conservative at them.
pub(crate) fn swept_bounds(scene: &Scene) -> Option<Aabb> {
    let boxes: Vec<Option<Aabb>> = scene.meshes.iter().map(object_bounds).collect();
    scene
        .animation_ids()
        .flat_map(|id| {
            sample_times(scene.animation(id))
                .into_iter()
                .map(move |time| (id, time))
        })
        .flat_map(|(id, time)| {
            let transforms = scene.animated_transforms(id, time);
            let corners: Vec<DVec3> = transforms
                .iter()
                .zip(&boxes)
                .filter_map(|(transform, b)| b.map(|b| (transform, b)))
                .flat_map(|(transform, b)| b.corners().map(|c| transform.transform_point3(c)))
                .collect();
            Aabb::from_points(corners)
        })
        .reduce(|a, b| a.union(&b))
}

/// The mesh's object-space box.
fn object_bounds(mesh: &Mesh) -> Option<Aabb> {
    Aabb::from_points((mesh.vertices.iter()).map(|v| Vec3::from_array(v.position).as_dvec3()))
}

/// The times an animation's poses are sampled at: its channels' key times and
/// [`STEPS_PER_INTERVAL`] - 1 between each two, or [`MAX_POSES`] evenly over its span
/// when that is more.
fn sample_times(animation: &Animation) -> Vec<f64> {
    let mut keys: Vec<f64> = (animation.channels.iter())
        .flat_map(|c| c.times.iter().copied())
        .collect();
    keys.sort_by(f64::total_cmp);
    keys.dedup();
    let poses = keys.len().saturating_sub(1) * STEPS_PER_INTERVAL + 1;
    if poses > MAX_POSES {
        let span = animation.end - animation.start;
        let last = (MAX_POSES - 1) as f64;
        return (0..MAX_POSES)
            .map(|i| animation.start + span * i as f64 / last)
            .collect();
    }
    let between = keys.windows(2).flat_map(|pair| {
        (0..STEPS_PER_INTERVAL).map(move |step| {
            pair[0] + (pair[1] - pair[0]) * step as f64 / STEPS_PER_INTERVAL as f64
        })
    });
    between.chain(keys.last().copied()).collect()
}
