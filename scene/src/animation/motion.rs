//! Bounds that hold the meshes and the points and lines wherever the animations take
//! them, so that a camera framed on them (and its near plane) sees every frame.

use glam::Vec3;

use super::clip::Animation;
use crate::{joints_in_object_space, Aabb, Mesh, PointsLines, Pose, Reach, Scene};

/// Poses sampled between two consecutive key times (the keys themselves included once):
/// LINEAR motion is bounded by its keys, but rotations sweep arcs and cubic splines
/// overshoot between them.
const STEPS_PER_INTERVAL: usize = 4;

/// The most poses sampled per animation: a long animation is sampled evenly rather than
/// at every key.
const MAX_POSES: usize = 4096;

/// The most node and mesh transforms computed per animation: a scene of many meshes gets
/// fewer poses (at least its first and last), so that loading stays fast.
const MAX_TRANSFORMS: usize = 1 << 24;

/// The world box of every mesh's object-space box (a deformed mesh's [`Reach`] in the
/// pose) and every points-and-lines primitive's, over the rest pose of a scene with
/// deformed meshes and poses of every animation sampled at and between its key times;
/// `None` without either. Approximate between samples (a fast spin can leave a box corner
/// a little outside), conservative at them.
pub(crate) fn swept_bounds(scene: &Scene) -> Option<Aabb> {
    let boxes: Vec<Option<Aabb>> = scene.meshes.iter().map(object_bounds).collect();
    let strokes: Vec<Option<Aabb>> = (scene.points_lines.iter())
        .map(PointsLines::object_bounds)
        .collect();
    let reaches: Vec<Option<Reach>> = (scene.deformations.iter())
        .map(|d| Reach::new(d, &scene.meshes[d.mesh].vertices))
        .collect();
    let per_pose = scene.nodes.nodes.len() + scene.meshes.len() + scene.points_lines.len();
    let max_poses = (MAX_TRANSFORMS / per_pose.max(1)).clamp(2, MAX_POSES);
    let rest = (!scene.deformations.is_empty()).then(|| scene.rest_pose());
    let animated = scene.animation_ids().flat_map(|id| {
        let times = sample_times(scene.animation(id), max_poses);
        times
            .into_iter()
            .map(move |time| scene.animated_pose(id, time))
    });
    rest.into_iter()
        .chain(animated)
        .filter_map(|pose| posed_bounds(scene, &pose, (&boxes, &strokes), &reaches))
        .reduce(|a, b| a.union(&b))
}

/// The world box of the meshes and the points and lines in `pose`: each mesh's
/// object-space box in `boxes`, or its deformation's reach in `reaches` (one per
/// deformation of the scene), and each points-and-lines primitive's in `strokes`,
/// transformed.
fn posed_bounds(
    scene: &Scene,
    pose: &Pose,
    (boxes, strokes): (&[Option<Aabb>], &[Option<Aabb>]),
    reaches: &[Option<Reach>],
) -> Option<Aabb> {
    let mut boxes = boxes.to_vec();
    for ((deformation, reach), weights) in
        (scene.deformations.iter().zip(reaches)).zip(&pose.morph_weights)
    {
        let transform = pose.transforms[deformation.mesh];
        let joints = match &deformation.skin {
            Some(skin) => joints_in_object_space(transform, &pose.skins[skin.skin]),
            None => Vec::new(),
        };
        boxes[deformation.mesh] = reach.as_ref().map(|r| r.object_box(&joints, weights));
    }
    let placed = (pose.transforms.iter().zip(&boxes)).chain(pose.points_lines.iter().zip(strokes));
    Aabb::from_points(placed.flat_map(|(transform, b)| {
        let corners = b.iter().flat_map(Aabb::corners);
        corners.map(|c| transform.transform_point3(c))
    }))
}

/// The mesh's object-space box.
fn object_bounds(mesh: &Mesh) -> Option<Aabb> {
    Aabb::from_points((mesh.vertices.iter()).map(|v| Vec3::from_array(v.position).as_dvec3()))
}

/// The times an animation's poses are sampled at: its channels' key times and
/// [`STEPS_PER_INTERVAL`] - 1 between each two, or `max_poses` (2 or more) evenly over its
/// span when that is more.
fn sample_times(animation: &Animation, max_poses: usize) -> Vec<f64> {
    let mut keys: Vec<f64> = (animation.channels.iter())
        .flat_map(|c| c.times.iter().copied())
        .collect();
    keys.sort_by(f64::total_cmp);
    keys.dedup();
    let poses = keys.len().saturating_sub(1) * STEPS_PER_INTERVAL + 1;
    if poses > max_poses {
        let span = animation.end - animation.start;
        let last = (max_poses - 1) as f64;
        return (0..max_poses)
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
