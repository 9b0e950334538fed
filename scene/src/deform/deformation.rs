//! What deforms one mesh, and the deformation done on the CPU.

use glam::{DMat3, DMat4, DVec3, Vec3};

use super::{MorphTargets, SkinWeights};
use crate::Vertex;

/// The skin and morph targets of one mesh of [`Scene::meshes`](crate::Scene::meshes): at
/// least one of the two.
///
/// Deformation happens in the mesh's object space, before its transform: morph targets
/// first, then the skin (as glTF orders them). A skinned mesh's transform is its node's
/// as for any mesh, and its joints reach object space through the inverse of it
/// ([`joints_in_object_space`]), so that the world position is the joints' alone, as glTF
/// says (the skinned node's own transform is ignored).
#[derive(Clone, Debug, PartialEq)]
pub struct Deformation {
    /// Index into [`Scene::meshes`](crate::Scene::meshes); each mesh has at most one.
    pub mesh: usize,
    /// Its skin binding, if skinned.
    pub skin: Option<SkinWeights>,
    /// Its morph targets, if morphed.
    pub morph: Option<MorphTargets>,
}

/// Each joint's matrix in the object space of a mesh placed at `transform`:
/// `transform⁻¹ · skin matrix`, where a skin matrix is a joint's world transform times its
/// inverse bind matrix ([`Pose::skins`](super::Pose::skins)). What
/// [`Deformation::deform`] and the GPU's skinning take. A singular `transform` (a node
/// scaled to nothing) leaves the skin matrices as they are.
pub fn joints_in_object_space(transform: DMat4, skin_matrices: &[DMat4]) -> Vec<DMat4> {
    let inverse = match transform.determinant() {
        0.0 => DMat4::IDENTITY,
        _ => transform.inverse(),
    };
    skin_matrices.iter().map(|m| inverse * *m).collect()
}

impl Deformation {
    /// `vertices` (the mesh's rest vertices) deformed: each morph target's offsets times
    /// its weight of `weights` added, then each vertex moved by its joints of `joints`
    /// (object space, see [`joints_in_object_space`]) blended by its weights. Normals
    /// move by each matrix's cofactor (the inverse transpose up to scale) and tangents by
    /// the matrix itself, both renormalised; a zero normal or tangent (a face normal
    /// asked for, no tangent) stays zero. `joints` is ignored without a skin and
    /// `weights` without morph targets.
    pub fn deform(&self, vertices: &[Vertex], joints: &[DMat4], weights: &[f32]) -> Vec<Vertex> {
        let vector = |v: [f32; 3]| Vec3::from_array(v).as_dvec3();
        (vertices.iter().enumerate())
            .map(|(i, vertex)| {
                let tangent = vertex.tangent.map(|c| f64::from(c) / f64::from(i16::MAX));
                let (mut position, mut normal) = (vector(vertex.position), vector(vertex.normal));
                let mut tangent_xyz = DVec3::new(tangent[0], tangent[1], tangent[2]);
                let targets = self.morph.iter().flat_map(|m| &m.targets);
                for (target, &weight) in targets.zip(weights) {
                    let weight = f64::from(weight);
                    let offset = |list: &[[f32; 3]]| {
                        list.get(i).map_or(DVec3::ZERO, |d| vector(*d) * weight)
                    };
                    position += offset(&target.positions);
                    normal += offset(&target.normals);
                    tangent_xyz += offset(&target.tangents);
                }
                if let Some(skin) = &self.skin {
                    let blended: DMat4 = (skin.influences(i))
                        .map(|(joint, weight)| joints[joint as usize] * f64::from(weight))
                        .fold(DMat4::ZERO, |sum, m| sum + m);
                    let linear = DMat3::from_mat4(blended);
                    position = blended.transform_point3(position);
                    normal = cofactor(linear) * normal;
                    tangent_xyz = linear * tangent_xyz;
                }
                let unit = |v: DVec3| v.try_normalize().unwrap_or(DVec3::ZERO).as_vec3();
                let t = unit(tangent_xyz);
                Vertex {
                    position: position.as_vec3().to_array(),
                    normal: unit(normal).to_array(),
                    tangent: Vertex::tangent_from([t.x, t.y, t.z, tangent[3] as f32]),
                    ..*vertex
                }
            })
            .collect()
    }
}

/// The cofactor matrix of `m`: its inverse transpose times its determinant, which maps
/// normals as the inverse transpose does (up to length) and exists for singular `m` too.
pub(crate) fn cofactor(m: DMat3) -> DMat3 {
    DMat3::from_cols(
        m.y_axis.cross(m.z_axis),
        m.z_axis.cross(m.x_axis),
        m.x_axis.cross(m.y_axis),
    )
}
