//! A primitive's skin binding (JOINTS_0 and WEIGHTS_0, and JOINTS_1 and WEIGHTS_1 where it
//! has them) and morph targets, read and checked against its vertices.
//!
//! JOINTS_n is VEC4 of UNSIGNED_BYTE or UNSIGNED_SHORT, each joint below the skin's joint
//! count; WEIGHTS_n is VEC4 of FLOAT or normalized UNSIGNED_BYTE or UNSIGNED_SHORT, each
//! weight finite and non-negative, a vertex's four (eight with a second set) summing to 1
//! within [`WEIGHT_SUM_TOLERANCE`] (then renormalised: exporters quantise them); a set
//! needs both. A primitive with JOINTS_2 has more than eight influences per vertex: only
//! the first eight are kept, renormalised, with a warning. Each morph target's POSITION, NORMAL and TANGENT are VEC3
//! with one finite element per vertex; the weights (the node's, else the mesh's, else 0)
//! are one per target. Every count is compared before the data is read.

use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Semantic;

use super::accessor::{self, component_name, type_name};
use super::site::Site;
use super::Loader;
use crate::{Influences, MorphTarget, MorphTargets, SceneError, SkinWeights};

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

/// The attribute names of the influence sets read: JOINTS_n and WEIGHTS_n for n = 0, 1.
const SET_NAMES: [(&str, &str); 2] = [("JOINTS_0", "WEIGHTS_0"), ("JOINTS_1", "WEIGHTS_1")];

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
        let set = |n| self.influences(site, primitive, (skin, joint_count), vertices, n);
        let Some((mut first, weights_0)) = set(0)? else {
            return Err(site.invalid(format!(
                "is placed by a node with skin {skin}, but has no JOINTS_0 and WEIGHTS_0 \
                 to bind its vertices to the joints"
            )));
        };
        let mut second = set(1)?;
        // Influences past the eighth are dropped: the first eight no longer sum to 1.
        let beyond = (2..)
            .take_while(|&n| primitive.get(&Semantic::Joints(n)).is_some())
            .count();
        if beyond > 0 {
            let sets = match beyond {
                1 => "JOINTS_2 and WEIGHTS_2 are".to_owned(),
                n => format!("JOINTS_2 to JOINTS_{} and their weights are", n + 1),
            };
            self.builder.warnings.push(format!(
                "{} primitive {}: {sets} ignored: each vertex keeps its first eight joints, \
                 their weights renormalised",
                site.mesh, site.primitive
            ));
        }
        for vertex in 0..vertices {
            let w0 = &mut first.weights[vertex];
            let w1 = second.as_mut().map(|(s, _)| &mut s.weights[vertex]);
            let all = || w0.iter().chain(w1.iter().flat_map(|w| w.iter()));
            let sum: f32 = all().sum();
            let valid = all().all(|c| c.is_finite() && *c >= 0.0) && sum > 0.0;
            if !valid || (beyond == 0 && (sum - 1.0).abs() > WEIGHT_SUM_TOLERANCE) {
                let second_set = match &second {
                    Some((s, accessor)) => format!(
                        " and {:?} (WEIGHTS_1 accessor {})",
                        s.weights[vertex],
                        accessor.index()
                    ),
                    None => String::new(),
                };
                return Err(site.accessor_error(
                    "WEIGHTS_0",
                    &weights_0,
                    format!(
                        "vertex {vertex} has weights {w0:?}{second_set}, summing to {sum}: a \
                         vertex's weights are non-negative and sum to 1 (within \
                         {WEIGHT_SUM_TOLERANCE})"
                    ),
                ));
            }
            *w0 = w0.map(|c| c / sum);
            if let Some(w1) = w1 {
                *w1 = w1.map(|c| c / sum);
            }
        }
        Ok(SkinWeights {
            skin,
            first,
            second: second.map(|(s, _)| s),
        })
    }

    /// Set `n` of `primitive`'s influences (JOINTS_n and WEIGHTS_n, checked: types, counts,
    /// joints below the skin's `joint_count`), with its weights' accessor; `None` when the
    /// primitive has neither. Fails when it has one without the other.
    fn influences<'d>(
        &self,
        site: &Site,
        primitive: &gltf::Primitive<'d>,
        (skin, joint_count): (usize, usize),
        vertices: usize,
        n: usize,
    ) -> Result<Option<(Influences, gltf::Accessor<'d>)>, SceneError> {
        let (joints_name, weights_name) = SET_NAMES[n];
        let (joints, weights) = match (
            primitive.get(&Semantic::Joints(n as u32)),
            primitive.get(&Semantic::Weights(n as u32)),
        ) {
            (None, None) => return Ok(None),
            (Some(joints), Some(weights)) => (joints, weights),
            (Some(_), None) | (None, Some(_)) => {
                return Err(site.invalid(format!(
                    "has only one of {joints_name} and {weights_name}: a set of joints \
                     needs its weights"
                )))
            }
        };
        let unsigned: &[(DataType, bool)] = &[(DataType::U8, false), (DataType::U16, false)];
        let weight_types: &[(DataType, bool)] = &[
            (DataType::F32, false),
            (DataType::U8, true),
            (DataType::U16, true),
        ];
        for (name, accessor, allowed) in [
            (joints_name, &joints, unsigned),
            (weights_name, &weights, weight_types),
        ] {
            check(accessor, (Dimensions::Vec4, allowed), vertices)
                .map_err(|reason| site.accessor_error(name, accessor, reason))?;
        }
        let joint_values = accessor::read_vectors::<4>(&self.buffers, &joints)
            .map_err(|reason| site.accessor_error(joints_name, &joints, reason))?;
        let weight_values = accessor::read_vectors::<4>(&self.buffers, &weights)
            .map_err(|reason| site.accessor_error(weights_name, &weights, reason))?;
        let beyond = joint_values.iter().enumerate().find_map(|(vertex, ids)| {
            let joint = ids.iter().find(|&&j| j as usize >= joint_count)?;
            Some((vertex, *joint))
        });
        if let Some((vertex, joint)) = beyond {
            return Err(site.accessor_error(
                joints_name,
                &joints,
                format!(
                    "vertex {vertex} names joint {joint}, but skin {skin} has {joint_count} joints"
                ),
            ));
        }
        let influences = Influences {
            joints: joint_values
                .iter()
                .map(|ids| ids.map(|j| j as u16))
                .collect(),
            weights: weight_values,
        };
        Ok(Some((influences, weights)))
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
    let set = |s: &Influences| Influences {
        joints: gather(&s.joints, sources),
        weights: gather(&s.weights, sources),
    };
    let skin = skin.map(|s| SkinWeights {
        skin: s.skin,
        first: set(&s.first),
        second: s.second.as_ref().map(set),
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
