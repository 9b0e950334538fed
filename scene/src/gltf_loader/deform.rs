//! A primitive's skin binding (JOINTS_0, WEIGHTS_0) and morph targets, read and checked
//! against its vertices.
//!
//! JOINTS_0 is VEC4 of UNSIGNED_BYTE or UNSIGNED_SHORT, each joint below the skin's joint
//! count; WEIGHTS_0 is VEC4 of FLOAT or normalized UNSIGNED_BYTE or UNSIGNED_SHORT, each
//! weight finite and non-negative, a vertex's four summing to 1 within
//! [`WEIGHT_SUM_TOLERANCE`] (then renormalised: exporters quantise them). A primitive with
//! JOINTS_1 has more than four influences per vertex: only the first four are kept,
//! renormalised, with a warning. Each morph target's POSITION, NORMAL and TANGENT are VEC3
//! with one finite element per vertex; the weights (the node's, else the mesh's, else 0)
//! are one per target. Every count is compared before the data is read.

use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Semantic;

use super::accessor::{self, component_name, type_name};
use super::site::Site;
use super::Loader;
use crate::{MorphTarget, MorphTargets, SceneError, SkinWeights};

/// How far a vertex's four weights may sum from 1 before the file is refused: a few
/// quantisation steps of 8-bit weights, where exporters round each weight apart.
pub(super) const WEIGHT_SUM_TOLERANCE: f32 = 0.05;

/// The component types of morph target offsets: FLOAT, or with KHR_mesh_quantization
/// BYTE and SHORT, normalized or not.
const OFFSET_TYPES: [(DataType, bool); 5] = [
    (DataType::F32, false),
    (DataType::I8, true),
    (DataType::I16, true),
    (DataType::I8, false),
    (DataType::I16, false),
];

/// A primitive's skin binding and morph targets, at least one of them.
pub(super) type Parts = (Option<SkinWeights>, Option<MorphTargets>);

/// What the placing node says about deforming its mesh.
pub(super) struct NodeDeform<'a> {
    /// The node's skin: its index in the file (and the scene) and its joint count.
    pub skin: Option<(usize, usize)>,
    /// The node's own morph weights, which replace the mesh's.
    pub weights: Option<&'a [f32]>,
}

impl Loader<'_> {
    /// The skin binding (when `node` has a skin) and morph targets of `primitive` of
    /// `mesh`, which has `vertices` vertices; `None` for neither.
    pub(super) fn deformation(
        &mut self,
        site: &Site,
        (mesh, primitive): (&gltf::Mesh, &gltf::Primitive),
        node: &NodeDeform,
        vertices: usize,
    ) -> Result<Option<Parts>, SceneError> {
        let skin = match node.skin {
            Some(skin) => Some(self.skin_weights(site, primitive, skin, vertices)?),
            None => None,
        };
        let weights = node.weights.or(mesh.weights());
        let morph = self.morph_targets(site, primitive, weights, vertices)?;
        Ok((skin.is_some() || morph.is_some()).then_some((skin, morph)))
    }

    fn skin_weights(
        &mut self,
        site: &Site,
        primitive: &gltf::Primitive,
        (skin, joint_count): (usize, usize),
        vertices: usize,
    ) -> Result<SkinWeights, SceneError> {
        let (Some(joints), Some(weights)) = (
            primitive.get(&Semantic::Joints(0)),
            primitive.get(&Semantic::Weights(0)),
        ) else {
            return Err(site.invalid(format!(
                "is placed by a node with skin {skin}, but has no JOINTS_0 and WEIGHTS_0 \
                 to bind its vertices to the joints"
            )));
        };
        let unsigned: &[(DataType, bool)] = &[(DataType::U8, false), (DataType::U16, false)];
        let weight_types: &[(DataType, bool)] = &[
            (DataType::F32, false),
            (DataType::U8, true),
            (DataType::U16, true),
        ];
        for (name, accessor, allowed) in [
            ("JOINTS_0", &joints, unsigned),
            ("WEIGHTS_0", &weights, weight_types),
        ] {
            check(accessor, (Dimensions::Vec4, allowed), vertices)
                .map_err(|reason| site.accessor_error(name, accessor, reason))?;
        }
        let joint_values = accessor::read_vectors::<4>(&self.buffers, &joints)
            .map_err(|reason| site.accessor_error("JOINTS_0", &joints, reason))?;
        let mut weight_values = accessor::read_vectors::<4>(&self.buffers, &weights)
            .map_err(|reason| site.accessor_error("WEIGHTS_0", &weights, reason))?;
        let beyond = joint_values.iter().enumerate().find_map(|(vertex, ids)| {
            let joint = ids.iter().find(|&&j| j as usize >= joint_count)?;
            Some((vertex, *joint))
        });
        if let Some((vertex, joint)) = beyond {
            return Err(site.accessor_error(
                "JOINTS_0",
                &joints,
                format!(
                    "vertex {vertex} names joint {joint}, but skin {skin} has {joint_count} joints"
                ),
            ));
        }
        // Influences past the first four are dropped: the first four no longer sum to 1.
        let more = primitive.get(&Semantic::Joints(1)).is_some();
        if more {
            self.builder.warnings.push(format!(
                "{} primitive {}: JOINTS_1 and WEIGHTS_1 are ignored: each vertex keeps its \
                 first four joints, their weights renormalised",
                site.mesh, site.primitive
            ));
        }
        for (vertex, w) in weight_values.iter_mut().enumerate() {
            let sum: f32 = w.iter().sum();
            let valid = w.iter().all(|c| c.is_finite() && *c >= 0.0) && sum > 0.0;
            if !valid || (!more && (sum - 1.0).abs() > WEIGHT_SUM_TOLERANCE) {
                return Err(site.accessor_error(
                    "WEIGHTS_0",
                    &weights,
                    format!(
                        "vertex {vertex} has weights {w:?}, summing to {sum}: a vertex's \
                         weights are non-negative and sum to 1 (within {WEIGHT_SUM_TOLERANCE})"
                    ),
                ));
            }
            *w = w.map(|c| c / sum);
        }
        Ok(SkinWeights {
            skin,
            joints: joint_values
                .iter()
                .map(|ids| ids.map(|j| j as u16))
                .collect(),
            weights: weight_values,
        })
    }

    fn morph_targets(
        &self,
        site: &Site,
        primitive: &gltf::Primitive,
        weights: Option<&[f32]>,
        vertices: usize,
    ) -> Result<Option<MorphTargets>, SceneError> {
        let count = primitive.morph_targets().len();
        if count == 0 {
            return Ok(None);
        }
        let weights = weights.map_or_else(|| vec![0.0; count], <[f32]>::to_vec);
        if weights.len() != count || weights.iter().any(|w| !w.is_finite()) {
            return Err(site.invalid(format!(
                "has {count} morph targets, but its default weights (the node's, else the \
                 mesh's) are {weights:?}: one finite weight per target"
            )));
        }
        let targets = (primitive.morph_targets().enumerate())
            .map(|(target, accessors)| {
                let read = |attribute, accessor: Option<gltf::Accessor>| {
                    let Some(accessor) = accessor else {
                        return Ok(Vec::new());
                    };
                    let values = check(&accessor, (Dimensions::Vec3, &OFFSET_TYPES), vertices)
                        .and_then(|()| accessor::read_vectors::<3>(&self.buffers, &accessor))
                        .and_then(|values| {
                            match values.iter().position(|v| v.iter().any(|c| !c.is_finite())) {
                                Some(i) => Err(format!("offset {i} is not finite")),
                                None => Ok(values),
                            }
                        });
                    values.map_err(|reason| site.morph_error(target, attribute, &accessor, reason))
                };
                Ok(MorphTarget {
                    positions: read("POSITION", accessors.positions())?,
                    normals: read("NORMAL", accessors.normals())?,
                    tangents: read("TANGENT", accessors.tangents())?,
                })
            })
            .collect::<Result<_, SceneError>>()?;
        Ok(Some(MorphTargets { targets, weights }))
    }
}

/// Fails unless `accessor` has the `expected` type and one of its component types, and one
/// element per vertex.
fn check(
    accessor: &gltf::Accessor,
    (expected, allowed): (Dimensions, &[(DataType, bool)]),
    vertices: usize,
) -> Result<(), String> {
    let component = (accessor.data_type(), accessor.normalized());
    let dimensions = accessor.dimensions();
    if dimensions != expected || !allowed.contains(&component) {
        let allowed: Vec<String> = allowed.iter().map(|&(t, n)| component_name(t, n)).collect();
        return Err(format!(
            "is {} of {}, but this attribute is {} of {}",
            type_name(dimensions),
            component_name(component.0, component.1),
            type_name(expected),
            allowed.join(" or ")
        ));
    }
    if accessor.count() != vertices {
        return Err(format!(
            "has {} elements, but the primitive has {vertices} vertices (POSITION's count)",
            accessor.count()
        ));
    }
    Ok(())
}

/// `parts` for a mesh whose vertices were written out per corner (flat shading for
/// MikkTSpace): its vertex `k` is the file's vertex `sources[k]`.
pub(super) fn per_corner((skin, morph): Parts, sources: &[u32]) -> Parts {
    let skin = skin.map(|s| SkinWeights {
        skin: s.skin,
        joints: gather(&s.joints, sources),
        weights: gather(&s.weights, sources),
    });
    let morph = morph.map(|m| MorphTargets {
        targets: (m.targets.iter())
            .map(|t| MorphTarget {
                positions: gather(&t.positions, sources),
                normals: gather(&t.normals, sources),
                tangents: gather(&t.tangents, sources),
            })
            .collect(),
        weights: m.weights,
    });
    (skin, morph)
}

/// `values` as the vertices `sources` name; empty stays empty.
fn gather<T: Copy>(values: &[T], sources: &[u32]) -> Vec<T> {
    match values.is_empty() {
        true => Vec::new(),
        false => sources.iter().map(|&s| values[s as usize]).collect(),
    }
}
