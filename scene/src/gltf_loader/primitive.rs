//! Mesh primitives to [`Mesh`]es.

use std::sync::Arc;

use glam::DMat4;
use gltf::mesh::{Mode, Semantic};

use super::deform::{per_corner, NodeDeform, Parts};
use super::site::Site;
use super::{accessor, Loader};
use crate::error::label;
use crate::{flat_shaded, generate_tangents, Deformation, Mesh, SceneError, Vertex};

impl Loader<'_> {
    /// Converts one primitive of a mesh placed at `world` by `node` and adds it to the
    /// scene, with its deformation (the node's skin, the primitive's morph targets) if it
    /// has one. Strips and fans become triangle lists; points and lines are
    /// [`points_lines`](Self::points_lines)'.
    ///
    /// Undeformed placements of one primitive share its geometry (see [`Mesh`]): it is
    /// read and built at its first placement of each handedness, mirrored or not, and later
    /// placements of that handedness take the same arrays. Deformed ones build their own.
    pub(super) fn primitive(
        &mut self,
        mesh: &gltf::Mesh,
        primitive: &gltf::Primitive,
        world: DMat4,
        node: &gltf::Node,
    ) -> Result<(), SceneError> {
        let site = Site {
            file: self.file,
            mesh: label("mesh", mesh.index(), mesh.name()),
            primitive: primitive.index(),
        };
        let mirrored = world.determinant() < 0.0;
        let key = (mesh.index(), primitive.index(), mirrored);
        let shared = (self.shared.get(&key)).filter(|_| !deformed(node, primitive));
        let (vertices, indices, deformation) = match shared {
            Some((vertices, indices)) => (vertices.clone(), indices.clone(), None),
            None => {
                let (vertices, indices, deformation) =
                    self.geometry(&site, (mesh, primitive), mirrored, node)?;
                let (vertices, indices) = (Arc::new(vertices), Arc::new(indices));
                if deformation.is_none() {
                    self.shared.insert(key, (vertices.clone(), indices.clone()));
                }
                (vertices, indices, deformation)
            }
        };
        let material = self.material(&primitive.material())?;
        if let Some((skin, morph)) = deformation {
            self.builder.deformations.push(Deformation {
                mesh: self.builder.meshes.len(),
                skin,
                morph,
            });
        }
        self.builder.meshes.push(Mesh {
            name: format!("{} primitive {}", site.mesh, site.primitive),
            vertices,
            indices,
            material,
            transform: world,
        });
        Ok(())
    }

    /// One placement's vertices, indices (counter-clockwise after a transform that is
    /// `mirrored` or not) and deformation, read from the file.
    fn geometry(
        &mut self,
        site: &Site,
        (mesh, primitive): (&gltf::Mesh, &gltf::Primitive),
        mirrored: bool,
        node: &gltf::Node,
    ) -> Result<Built, SceneError> {
        let mode = primitive.mode();
        let positions = self
            .attribute::<3>(site, primitive, Semantic::Positions, "POSITION")?
            .ok_or_else(|| site.invalid("has no POSITION attribute".to_owned()))?;
        let normals = self.attribute::<3>(site, primitive, Semantic::Normals, "NORMAL")?;
        let uvs = self.attribute::<2>(site, primitive, Semantic::TexCoords(0), "TEXCOORD_0")?;
        let uvs1 = self.attribute::<2>(site, primitive, Semantic::TexCoords(1), "TEXCOORD_1")?;
        let colors = self.colors(site, primitive)?;
        let tangents = self.attribute::<4>(site, primitive, Semantic::Tangents, "TANGENT")?;
        site.check_finite(
            &positions,
            normals.as_deref(),
            uvs.as_deref(),
            uvs1.as_deref(),
            colors.as_deref(),
            tangents.as_deref(),
        )?;
        let indices = match primitive.indices() {
            Some(accessor) => accessor::read_indices(&self.buffers, &accessor)
                .map_err(|reason| site.accessor_error("indices", &accessor, reason))?,
            None => (0..positions.len() as u32).collect(),
        };
        // What this placement keeps was taken from the budget before anything was built
        // (see `reserve`).
        site.check_indices(&indices, positions.len())?;
        let indices = triangle_list(mode, indices).map_err(|reason| site.invalid(reason))?;
        let vertices = interleave(
            &positions,
            normals.as_deref(),
            [uvs.as_deref(), uvs1.as_deref()],
            colors.as_deref(),
            tangents.as_deref(),
        );
        // Tangents are generated only for a normal texture the material keeps (it drops
        // those on UV sets past 1), along the UV set it is sampled with.
        let normal_set = primitive.material().normal_texture().map(|n| n.tex_coord());
        let tangent_set = match (&tangents, normal_set) {
            (None, Some(set @ 0..=1)) => Some(set),
            _ => None,
        };
        let tangent_uvs = tangent_set.filter(|&set| [uvs.is_some(), uvs1.is_some()][set as usize]);
        // Without NORMAL, glTF asks for flat normals. The renderers take a zero normal for
        // the triangle's face normal, so the mesh keeps its shared vertices; only MikkTSpace,
        // which needs a normal at every corner, gets them written out, three vertices a
        // triangle.
        let node = NodeDeform {
            skin: (node.skin()).map(|skin| (skin.index(), skin.joints().len())),
            weights: node.weights(),
        };
        let deformation = self.deformation(site, (mesh, primitive), &node, positions.len())?;
        let (mut vertices, mut indices, deformation) = match (&normals, tangent_uvs) {
            (None, Some(_)) => {
                // Flat shading writes each corner out: vertex k is the file's `indices[k]`.
                let (flat, flat_indices) = flat_shaded(&vertices, &indices);
                let deformation = deformation.map(|parts| per_corner(parts, &indices));
                (flat, flat_indices, deformation)
            }
            _ => (vertices, indices, deformation),
        };
        match (tangent_set, tangent_uvs) {
            (_, Some(set)) => generate_tangents(&mut vertices, &indices, set).map_err(|e| {
                site.invalid(format!("MikkTSpace cannot generate its tangents: {e:?}"))
            })?,
            (Some(set), None) => self.builder.warnings.push(format!(
                "{} primitive {}: its material's normal texture needs TEXCOORD_{set}, which it \
                 lacks; drawn without the normal texture",
                site.mesh, site.primitive
            )),
            (None, None) => {}
        }
        // A mirroring transform turns counter-clockwise triangles clockwise on screen; reversing
        // them here keeps the Mesh contract (front faces CCW in world space) for renderers. It
        // also turns the bitangent `normal x tangent` around: the sign keeps it on the side
        // the normal texture was baked for.
        if mirrored {
            indices.chunks_exact_mut(3).for_each(|tri| tri.swap(1, 2));
            vertices
                .iter_mut()
                .for_each(|v| v.tangent[3] = -v.tangent[3]);
        }
        Ok((vertices, indices, deformation))
    }

    /// Reads an optional vertex attribute (`None` when the primitive has none). Its length is
    /// compared with POSITION's in `Site::check_finite`.
    pub(super) fn attribute<const N: usize>(
        &self,
        site: &Site,
        primitive: &gltf::Primitive,
        semantic: Semantic,
        name: &'static str,
    ) -> Result<Option<Vec<[f32; N]>>, SceneError> {
        primitive
            .get(&semantic)
            .map(|accessor| {
                accessor::read_vectors::<N>(&self.buffers, &accessor)
                    .map_err(|reason| site.accessor_error(name, &accessor, reason))
            })
            .transpose()
    }

    /// COLOR_0 as RGBA (`None` when the primitive has none): VEC3 gets alpha 1; float,
    /// normalized UNSIGNED_BYTE and UNSIGNED_SHORT as the spec allows.
    pub(super) fn colors(
        &self,
        site: &Site,
        primitive: &gltf::Primitive,
    ) -> Result<Option<Vec<[f32; 4]>>, SceneError> {
        let Some(accessor) = primitive.get(&Semantic::Colors(0)) else {
            return Ok(None);
        };
        let colors = match accessor.dimensions() {
            gltf::accessor::Dimensions::Vec3 => {
                accessor::read_vectors::<3>(&self.buffers, &accessor)
                    .map(|rgb| rgb.into_iter().map(|[r, g, b]| [r, g, b, 1.0]).collect())
            }
            _ => accessor::read_vectors::<4>(&self.buffers, &accessor),
        };
        colors
            .map(Some)
            .map_err(|reason| site.accessor_error("COLOR_0", &accessor, reason))
    }
}

impl Site<'_> {
    /// Fails on attribute arrays of different lengths, and on the lowest-numbered vertex with a
    /// NaN or infinite component (NaN would silently poison bounds, normals and depth tests).
    pub(super) fn check_finite(
        &self,
        positions: &[[f32; 3]],
        normals: Option<&[[f32; 3]]>,
        uvs: Option<&[[f32; 2]]>,
        uvs1: Option<&[[f32; 2]]>,
        colors: Option<&[[f32; 4]]>,
        tangents: Option<&[[f32; 4]]>,
    ) -> Result<(), SceneError> {
        let attributes: [(&'static str, Option<Vec<&[f32]>>); 6] = [
            ("position", Some(positions.iter().map(|p| &p[..]).collect())),
            (
                "normal",
                normals.map(|n| n.iter().map(|v| &v[..]).collect()),
            ),
            ("uv", uvs.map(|u| u.iter().map(|v| &v[..]).collect())),
            ("uv1", uvs1.map(|u| u.iter().map(|v| &v[..]).collect())),
            ("color", colors.map(|c| c.iter().map(|v| &v[..]).collect())),
            (
                "tangent",
                tangents.map(|t| t.iter().map(|v| &v[..]).collect()),
            ),
        ];
        let mut first_bad: Option<(usize, &'static str, Vec<f32>)> = None;
        for (attribute, values) in attributes {
            let Some(values) = values else { continue };
            if values.len() != positions.len() {
                return Err(self.invalid(format!(
                    "{attribute} has {} elements but POSITION has {}",
                    values.len(),
                    positions.len()
                )));
            }
            let limit = first_bad
                .as_ref()
                .map_or(values.len(), |(vertex, ..)| *vertex);
            if let Some(vertex) = values[..limit]
                .iter()
                .position(|v| v.iter().any(|c| !c.is_finite()))
            {
                first_bad = Some((vertex, attribute, values[vertex].to_vec()));
            }
        }
        match first_bad {
            None => Ok(()),
            Some((vertex, attribute, value)) => Err(SceneError::NonFiniteVertex {
                file: self.file.to_owned(),
                mesh: self.mesh.clone(),
                primitive: self.primitive,
                vertex,
                attribute,
                value,
            }),
        }
    }

    pub(super) fn check_indices(
        &self,
        indices: &[u32],
        vertex_count: usize,
    ) -> Result<(), SceneError> {
        match indices.iter().position(|&i| i as usize >= vertex_count) {
            None => Ok(()),
            Some(position) => Err(SceneError::IndexOutOfRange {
                file: self.file.to_owned(),
                mesh: self.mesh.clone(),
                primitive: self.primitive,
                position,
                index: indices[position],
                vertex_count,
            }),
        }
    }
}

/// Turns the index sequence of a triangle mode into a triangle list, keeping every triangle
/// counter-clockwise as the glTF spec orders strip and fan vertices.
fn triangle_list(mode: Mode, indices: Vec<u32>) -> Result<Vec<u32>, String> {
    let n = indices.len();
    match mode {
        Mode::Triangles if n.is_multiple_of(3) => Ok(indices),
        Mode::Triangles => Err(format!("TRIANGLES needs a multiple of 3 indices, has {n}")),
        // Odd triangles of a strip swap their first two vertices to keep the winding.
        Mode::TriangleStrip => Ok((2..n)
            .flat_map(|i| match i % 2 {
                0 => [indices[i - 2], indices[i - 1], indices[i]],
                _ => [indices[i - 1], indices[i - 2], indices[i]],
            })
            .collect()),
        Mode::TriangleFan => Ok((2..n)
            .flat_map(|i| [indices[0], indices[i - 1], indices[i]])
            .collect()),
        other => Err(format!("mode {other:?} is not a triangle mode")),
    }
}

/// Builds vertices from per-vertex attributes as long as `positions` (`None`: zero normals,
/// for [`flat_shaded`] to replace; uvs 0; white; no tangent). `uvs` are TEXCOORD_0 and _1.
fn interleave(
    positions: &[[f32; 3]],
    normals: Option<&[[f32; 3]]>,
    [uvs, uvs1]: [Option<&[[f32; 2]]>; 2],
    colors: Option<&[[f32; 4]]>,
    tangents: Option<&[[f32; 4]]>,
) -> Vec<Vertex> {
    (0..positions.len())
        .map(|i| Vertex {
            position: positions[i],
            normal: normals.map_or([0.0; 3], |n| n[i]),
            uv: uvs.map_or([0.0; 2], |u| u[i]),
            uv1: uvs1.map_or([0.0; 2], |u| u[i]),
            color: colors.map_or(Vertex::WHITE, |c| Vertex::color_from(c[i])),
            tangent: tangents.map_or(Vertex::NO_TANGENT, |t| Vertex::tangent_from(t[i])),
        })
        .collect()
}

/// A placement's vertices, indices and deformation as read.
type Built = (Vec<Vertex>, Vec<u32>, Option<Parts>);

/// Whether `node`'s placement of `primitive` deforms: a skin on the node, or morph targets
/// on the primitive (see `deform.rs`). Such a placement gets geometry of its own.
pub(super) fn deformed(node: &gltf::Node, primitive: &gltf::Primitive) -> bool {
    node.skin().is_some() || primitive.morph_targets().len() > 0
}
