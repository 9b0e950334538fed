//! glTF animations to [`Animation`]s over the loaded scene's [`NodeTree`].
//!
//! Every channel is checked before its data is read: the sampler's input is a SCALAR
//! FLOAT accessor of at least one key time, its output of the type the property takes
//! (VEC3 FLOAT for translation and scale; VEC4 FLOAT or normalized BYTE, UNSIGNED_BYTE,
//! SHORT or UNSIGNED_SHORT for rotation) with one element per key (three for
//! CUBICSPLINE). Counts are compared as declared, and the accessor reader checks them
//! against the buffer views before allocating, so a bad file costs no more memory than
//! its bytes. Then key times must be finite and strictly increasing, and values finite.
//! A morph target weights channel's output is SCALAR (FLOAT or a normalized integer type)
//! with one element per morph target of the node's mesh per key (three for CUBICSPLINE).

use std::path::Path;

use glam::{DQuat, DVec3, DVec4};
use gltf::accessor::{DataType, Dimensions};
use gltf::animation::{Interpolation as GltfInterpolation, Property};

use super::accessor::{self, component_name, type_name};
use super::nodes::{self, Placed};
use crate::animation::{Animation, Channel, Interpolation, Keyframes};
use crate::error::label;
use crate::node_tree::{LocalTransform, Node, NodeId, NodeTree};
use crate::SceneError;

/// How many morph targets the mesh of `node` has (its primitives have as many each, as
/// the primitives' loading checks), which a weights channel drives; an error when it has
/// none.
fn morph_targets(node: &gltf::Node) -> Result<usize, String> {
    let targets = (node.mesh().iter().flat_map(|m| m.primitives()))
        .map(|p| p.morph_targets().len())
        .max()
        .unwrap_or(0);
    match targets {
        0 => Err(format!(
            "animates the morph weights of {}, whose mesh has no morph targets",
            label("node", node.index(), node.name())
        )),
        targets => Ok(targets),
    }
}

/// The component types a rotation's or a morph weight's output may have, as (type,
/// normalized).
const FLOAT_OR_NORMALIZED: [(DataType, bool); 5] = [
    (DataType::F32, false),
    (DataType::I8, true),
    (DataType::U8, true),
    (DataType::I16, true),
    (DataType::U16, true),
];

/// The file's animations, and the tree of `placed` nodes they move and skins hang on (with
/// no mesh placements yet: the loader adds one per mesh it builds). Both empty when the
/// file has neither animations nor skins. `locals` is every glTF node's transform, by
/// index.
pub(super) fn read(
    file: &Path,
    document: &gltf::Document,
    buffers: &[Vec<u8>],
    placed: &[Placed],
    locals: &[LocalTransform],
) -> Result<(NodeTree, Vec<Animation>), SceneError> {
    if document.animations().len() == 0 && document.skins().len() == 0 {
        return Ok((NodeTree::default(), Vec::new()));
    }
    let ids = nodes::ids(document, placed);
    let nodes = placed
        .iter()
        .map(|p| Node {
            name: label("node", p.node.index(), p.node.name()),
            parent: p.parent.map(|parent| NodeId(parent as u32)),
            rest: locals[p.node.index()],
        })
        .collect();
    let animations = document
        .animations()
        .map(|animation| {
            let reader = Reader {
                file,
                buffers,
                animation: label("animation", animation.index(), animation.name()),
            };
            let mut channels = Vec::new();
            for channel in animation.channels() {
                let target = channel.target().node();
                let property = channel.target().property();
                let error = |reason| reader.error(channel.index(), reason);
                let targets = match property {
                    Property::MorphTargetWeights => morph_targets(&target).map_err(error)?,
                    _ => 0,
                };
                let moves_node = property != Property::MorphTargetWeights;
                if let (true, LocalTransform::Matrix(_)) = (moves_node, locals[target.index()]) {
                    return Err(error(format!(
                        "targets {}, whose transform is a matrix: glTF animates only nodes \
                         with translation, rotation and scale",
                        label("node", target.index(), target.name())
                    )));
                }
                let (interpolation, times, values) = reader
                    .sampler(&channel.sampler(), property, targets)
                    .map_err(error)?;
                // Channels of nodes the loaded scene does not place move nothing drawn.
                if let Some(node) = ids[target.index()] {
                    channels.push(Channel {
                        node,
                        interpolation,
                        times,
                        values,
                    });
                }
            }
            let start = channels.iter().map(|c| c.times[0]).reduce(f64::min);
            let end = channels
                .iter()
                .filter_map(|c| c.times.last().copied())
                .reduce(f64::max);
            Ok(Animation {
                name: animation
                    .name()
                    .map_or_else(|| format!("animation {}", animation.index()), str::to_owned),
                channels,
                start: start.unwrap_or(0.0),
                end: end.unwrap_or(0.0),
            })
        })
        .collect::<Result<_, _>>()?;
    Ok((
        NodeTree {
            nodes,
            meshes: Vec::new(),
            points_lines: Vec::new(),
        },
        animations,
    ))
}

/// Reads the channels of one animation.
struct Reader<'a> {
    file: &'a Path,
    buffers: &'a [Vec<u8>],
    /// The animation, as errors name it.
    animation: String,
}

impl Reader<'_> {
    fn error(&self, channel: usize, reason: String) -> SceneError {
        SceneError::InvalidAnimation {
            file: self.file.to_owned(),
            animation: self.animation.clone(),
            channel,
            reason,
        }
    }

    /// A channel's sampler driving `property` (of a node whose mesh has `targets` morph
    /// targets, for weights), checked, read and converted. Errors are the reason, naming
    /// the accessor.
    fn sampler(
        &self,
        sampler: &gltf::animation::Sampler,
        property: Property,
        targets: usize,
    ) -> Result<(Interpolation, Vec<f64>, Keyframes), String> {
        let (input, output) = (sampler.input(), sampler.output());
        let interpolation = match sampler.interpolation() {
            GltfInterpolation::Step => Interpolation::Step,
            GltfInterpolation::Linear => Interpolation::Linear,
            GltfInterpolation::CubicSpline => Interpolation::CubicSpline,
        };
        let (dimensions, allowed, what): (_, &[_], _) = match property {
            Property::Translation => (Dimensions::Vec3, &[(DataType::F32, false)], "a translation"),
            Property::Scale => (Dimensions::Vec3, &[(DataType::F32, false)], "a scale"),
            Property::Rotation => (Dimensions::Vec4, &FLOAT_OR_NORMALIZED, "a rotation"),
            Property::MorphTargetWeights => {
                (Dimensions::Scalar, &FLOAT_OR_NORMALIZED, "a morph weight")
            }
        };
        check_type(
            &input,
            "input",
            Dimensions::Scalar,
            &[(DataType::F32, false)],
            "key times",
        )?;
        check_type(&output, "output", dimensions, allowed, what)?;
        let keys = input.count();
        if keys == 0 {
            return Err(format!(
                "input accessor {} has no elements: a sampler needs at least one key time",
                input.index()
            ));
        }
        let (per_key, why) = match interpolation {
            Interpolation::CubicSpline => (
                3,
                "three per key time (in-tangent, value, out-tangent) for CUBICSPLINE",
            ),
            _ => (1, "one per key time"),
        };
        let (per_key, why) = match property {
            Property::MorphTargetWeights => (
                per_key * targets,
                format!("{why}, times the mesh's {targets} morph targets"),
            ),
            _ => (per_key, why.to_owned()),
        };
        // Declared counts, not yet checked against the buffers: the product may overflow.
        if keys.checked_mul(per_key) != Some(output.count()) {
            return Err(format!(
                "output accessor {} has {} elements, but its input accessor {} has {keys} key \
                 times and it needs {why}",
                output.index(),
                output.count(),
                input.index(),
            ));
        }
        let times = self.times(&input)?;
        let values = match property {
            Property::Translation => Keyframes::Translation(self.vectors(&output)?),
            Property::Scale => Keyframes::Scale(self.vectors(&output)?),
            Property::Rotation => Keyframes::Rotation(self.rotations(&output, interpolation)?),
            Property::MorphTargetWeights => {
                let values = self.finite::<1>(&output)?;
                // Stored per target: the keys' values of one weight together.
                let per_target = (0..targets).map(|target| {
                    let values = values.iter().skip(target).step_by(targets);
                    values.map(|[w]| f64::from(*w)).collect()
                });
                Keyframes::Weights(per_target.collect())
            }
        };
        Ok((interpolation, times, values))
    }

    /// Key times: finite and strictly increasing.
    fn times(&self, input: &gltf::Accessor) -> Result<Vec<f64>, String> {
        let index = input.index();
        let times: Vec<f64> = accessor::read_vectors::<1>(self.buffers, input)
            .map_err(|reason| format!("input accessor {index}: {reason}"))?
            .into_iter()
            .map(|[t]| f64::from(t))
            .collect();
        if let Some(k) = times.iter().position(|t| !t.is_finite()) {
            return Err(format!(
                "input accessor {index}: key time {k} is not finite"
            ));
        }
        if let Some(k) = times.windows(2).position(|pair| pair[1] <= pair[0]) {
            return Err(format!(
                "input accessor {index}: key time {} ({}) is not after key time {k} ({}): key \
                 times must be strictly increasing",
                k + 1,
                times[k + 1],
                times[k]
            ));
        }
        Ok(times)
    }

    /// VEC3 values, each finite.
    fn vectors(&self, output: &gltf::Accessor) -> Result<Vec<DVec3>, String> {
        let values = self.finite::<3>(output)?;
        Ok(values
            .into_iter()
            .map(|v| DVec3::from_array(v.map(f64::from)))
            .collect())
    }

    /// Quaternions (x, y, z, w), each finite; key values (not a cubic spline's tangents)
    /// normalised, as exporters write them slightly off unit length and slerp needs unit
    /// length. A zero key value is an error: it is no rotation at all.
    fn rotations(
        &self,
        output: &gltf::Accessor,
        interpolation: Interpolation,
    ) -> Result<Vec<DQuat>, String> {
        let values = self.finite::<4>(output)?;
        values
            .into_iter()
            .enumerate()
            .map(|(i, v)| {
                let v = DVec4::from_array(v.map(f64::from));
                let is_key = interpolation != Interpolation::CubicSpline || i % 3 == 1;
                match is_key {
                    false => Ok(DQuat::from_vec4(v)),
                    true => v.try_normalize().map(DQuat::from_vec4).ok_or_else(|| {
                        format!(
                            "output accessor {}: rotation {i} is zero, not a unit quaternion",
                            output.index()
                        )
                    }),
                }
            })
            .collect()
    }

    /// The output's elements, each component finite.
    fn finite<const N: usize>(&self, output: &gltf::Accessor) -> Result<Vec<[f32; N]>, String> {
        let index = output.index();
        let values = accessor::read_vectors::<N>(self.buffers, output)
            .map_err(|reason| format!("output accessor {index}: {reason}"))?;
        match values.iter().position(|v| v.iter().any(|c| !c.is_finite())) {
            Some(i) => Err(format!("output accessor {index}: value {i} is not finite")),
            None => Ok(values),
        }
    }
}

/// Fails unless `accessor` has `dimensions` and one of the `allowed` component types,
/// naming the accessor by its `role` in the sampler and what it holds (`what`).
fn check_type(
    accessor: &gltf::Accessor,
    role: &str,
    dimensions: Dimensions,
    allowed: &[(DataType, bool)],
    what: &str,
) -> Result<(), String> {
    let component = (accessor.data_type(), accessor.normalized());
    if accessor.dimensions() == dimensions && allowed.contains(&component) {
        return Ok(());
    }
    let allowed: Vec<String> = (allowed.iter())
        .map(|&(t, n)| component_name(t, n))
        .collect();
    Err(format!(
        "{role} accessor {} is {} of {}, but {what} must be {} of {}",
        accessor.index(),
        type_name(accessor.dimensions()),
        component_name(component.0, component.1),
        type_name(dimensions),
        allowed.join(" or ")
    ))
}
