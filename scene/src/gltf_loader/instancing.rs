//! EXT_mesh_gpu_instancing: a node's TRANSLATION, ROTATION and SCALE instance attributes
//! place copies of its mesh, instance `i` at `node world * T[i] * R[i] * S[i]` (the
//! extension's order; a missing attribute is the identity).
//!
//! The scene model has no instancing of its own: every instance becomes a placement like a
//! node's, counted against [`MAX_MESHES`](crate::MAX_MESHES) and the memory budget before
//! anything is built (`reserve` takes each node's count from the accessors' declared `count`,
//! and nothing is read until the node is placed). Custom attributes (`_ID`, ...) are
//! ignored, as the extension allows.

use std::path::Path;

use glam::{DMat4, DQuat, DVec3, DVec4};
use gltf::accessor::{DataType, Dimensions};
use serde_json::Value;

use super::accessor::{self, component_name, type_name};
use super::world;
use crate::error::label;
use crate::SceneError;

/// The extension's name, as nodes and `extensionsUsed` spell it.
pub(super) const EXTENSION: &str = "EXT_mesh_gpu_instancing";

/// An instance attribute this loader reads, with the accessor type and the (component
/// type, normalized) pairs the extension allows it.
struct Attribute {
    name: &'static str,
    dimensions: Dimensions,
    components: &'static [(DataType, bool)],
}

/// The attributes, in `Instances::attributes` order.
const ATTRIBUTES: [Attribute; 3] = [
    Attribute {
        name: "TRANSLATION",
        dimensions: Dimensions::Vec3,
        components: &[(DataType::F32, false)],
    },
    Attribute {
        name: "ROTATION",
        dimensions: Dimensions::Vec4,
        components: &[
            (DataType::F32, false),
            (DataType::I8, true),
            (DataType::I16, true),
        ],
    },
    Attribute {
        name: "SCALE",
        dimensions: Dimensions::Vec3,
        components: &[(DataType::F32, false)],
    },
];

/// One node's instance attributes, checked against the extension without reading them.
pub(super) struct Instances<'a> {
    /// How many instances: every attribute's `count`.
    pub count: usize,
    /// TRANSLATION, ROTATION and SCALE, where present.
    attributes: [Option<gltf::Accessor<'a>>; 3],
}

/// The instances `node` declares: `None` without the extension, or on a node without a mesh
/// (for which the extension defines nothing; such a node places nothing either way). Fails,
/// naming the node and the attribute, on an attribute that names no accessor, one of
/// another type or component type than the extension allows, attributes of different
/// counts, and an extension object naming none of TRANSLATION, ROTATION and SCALE (which
/// leaves the count undefined).
pub(super) fn declared<'a>(
    file: &Path,
    document: &'a gltf::Document,
    node: &gltf::Node<'a>,
) -> Result<Option<Instances<'a>>, SceneError> {
    let Some(extension) = node.extension_value(EXTENSION) else {
        return Ok(None);
    };
    if node.mesh().is_none() {
        return Ok(None);
    }
    let error = |attribute, reason| invalid(file, node, attribute, reason);
    let names = extension
        .get("attributes")
        .and_then(Value::as_object)
        .ok_or_else(|| {
            error(
                "attributes",
                "is not an object of accessor indices".to_owned(),
            )
        })?;
    let mut attributes = [None, None, None];
    let mut first: Option<(&str, usize)> = None;
    for (slot, attribute) in ATTRIBUTES.iter().enumerate() {
        let Attribute {
            name,
            dimensions,
            components: allowed,
        } = attribute;
        let Some(index) = names.get(*name) else {
            continue;
        };
        let accessor = index
            .as_u64()
            .and_then(|i| document.accessors().nth(usize::try_from(i).ok()?))
            .ok_or_else(|| {
                let count = document.accessors().len();
                error(
                    name,
                    format!("{index} is not an accessor index (the file has {count} accessors)"),
                )
            })?;
        let component = (accessor.data_type(), accessor.normalized());
        if accessor.dimensions() != *dimensions || !allowed.contains(&component) {
            let allowed: Vec<String> = allowed
                .iter()
                .map(|&(data_type, normalized)| component_name(data_type, normalized))
                .collect();
            return Err(error(
                name,
                format!(
                    "accessor {} is {} of {}; the extension allows {} of {}",
                    accessor.index(),
                    type_name(accessor.dimensions()),
                    component_name(component.0, component.1),
                    type_name(*dimensions),
                    allowed.join(" or ")
                ),
            ));
        }
        match first {
            None => first = Some((name, accessor.count())),
            Some((first, count)) if count != accessor.count() => {
                return Err(error(
                    name,
                    format!(
                        "accessor {} has {} elements, but {first} has {count}: every instance \
                         attribute of a node must have the same count",
                        accessor.index(),
                        accessor.count()
                    ),
                ))
            }
            Some(_) => {}
        }
        attributes[slot] = Some(accessor);
    }
    let (_, count) = first.ok_or_else(|| {
        error(
            "attributes",
            "names none of TRANSLATION, ROTATION and SCALE, so the number of instances is \
             undefined"
                .to_owned(),
        )
    })?;
    Ok(Some(Instances { count, attributes }))
}

impl Instances<'_> {
    /// Each instance's transform, `T * R * S`, in instance order: its world transform is
    /// `world * T * R * S`. Fails,
    /// naming `node` and the attribute, on data that cannot be read and on a value that is
    /// not finite; and, as for nodes, on a world transform beyond
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE). A zero rotation (invalid) is taken as no
    /// rotation, as node rotations are.
    pub(super) fn offsets(
        &self,
        file: &Path,
        buffers: &[Vec<u8>],
        node: &gltf::Node,
        world: DMat4,
    ) -> Result<Vec<DMat4>, SceneError> {
        let [translations, rotations, scales] = &self.attributes;
        let translations = read::<3>(file, buffers, node, 0, translations.as_ref())?;
        let rotations = read::<4>(file, buffers, node, 1, rotations.as_ref())?;
        let scales = read::<3>(file, buffers, node, 2, scales.as_ref())?;
        let vec3 = |values: &Option<Vec<[f32; 3]>>, i: usize, default| {
            values
                .as_ref()
                .map_or(default, |v| DVec3::from_array(v[i].map(f64::from)))
        };
        (0..self.count)
            .map(|i| {
                let rotation = rotations
                    .as_ref()
                    .and_then(|r| DVec4::from_array(r[i].map(f64::from)).try_normalize())
                    .map_or(DQuat::IDENTITY, DQuat::from_vec4);
                let instance = DMat4::from_scale_rotation_translation(
                    vec3(&scales, i, DVec3::ONE),
                    rotation,
                    vec3(&translations, i, DVec3::ZERO),
                );
                let placed = world * instance;
                world::check(file, node, &placed, &format!("instance {i}'s"))?;
                Ok(instance)
            })
            .collect()
    }
}

/// The values of the attribute `ATTRIBUTES[slot]`, if present; every one finite.
fn read<const N: usize>(
    file: &Path,
    buffers: &[Vec<u8>],
    node: &gltf::Node,
    slot: usize,
    accessor: Option<&gltf::Accessor>,
) -> Result<Option<Vec<[f32; N]>>, SceneError> {
    let name = ATTRIBUTES[slot].name;
    let Some(accessor) = accessor else {
        return Ok(None);
    };
    let values = accessor::read_vectors::<N>(buffers, accessor).map_err(|reason| {
        invalid(
            file,
            node,
            name,
            format!("accessor {}: {reason}", accessor.index()),
        )
    })?;
    if let Some(i) = values.iter().position(|v| v.iter().any(|c| !c.is_finite())) {
        return Err(invalid(
            file,
            node,
            name,
            format!("instance {i} is {:?}, not finite", values[i]),
        ));
    }
    Ok(Some(values))
}

fn invalid(file: &Path, node: &gltf::Node, attribute: &'static str, reason: String) -> SceneError {
    SceneError::InvalidInstances {
        file: file.to_owned(),
        node: label("node", node.index(), node.name()),
        attribute,
        reason,
    }
}
