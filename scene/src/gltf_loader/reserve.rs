//! What a scene will hold, counted before anything is built: every placement of every mesh
//! (by a node, or by each instance of an instanced node; from its accessors' counts), every
//! image (from its header) and every texture baked from images, taken from the scene's
//! memory budget first, so that a small file asking for more than the limit fails before
//! the memory is spent (a 20 MB GLB placing a skinned 1M-triangle mesh 1,000 times asks for
//! 50 GB). Geometry that placements share (see [`Mesh`]) is counted once, each placement's
//! own [`Mesh`] record every time.

use std::collections::{HashMap, HashSet};

use gltf::mesh::{Mode, Semantic};

use super::nodes::Placed;
use super::{drawn, material, material_layers, primitive, Loader};
use crate::error::label;
use crate::{Mesh, SceneError, Vertex, MAX_MESHES};

impl Loader<'_> {
    /// Takes from the budget what the meshes `placed` places and the images their
    /// materials name will hold, in the order they are built; fails on the first that does
    /// not fit, naming it.
    pub(super) fn reserve(&mut self, placed: &[Placed<'_>]) -> Result<(), SceneError> {
        // Placements per mesh, in the order meshes are first placed: one per placing node,
        // or one per instance of an instanced one; and the copies of its geometry they
        // take, per primitive (see `primitive.rs`): one per handedness its undeformed
        // placements have (both for an instanced node, whose instances' scales are not read
        // yet: a bound), one per deformed placement and per placement of points or lines.
        let mut meshes: Vec<(gltf::Mesh, u64, Vec<Copies>)> = Vec::new();
        let mut slot_of: HashMap<usize, usize> = HashMap::new();
        for placed in placed {
            let Some(mesh) = placed.node.mesh() else {
                continue;
            };
            let count = placed.instances.as_ref().map_or(1, |i| i.count as u64);
            if count == 0 {
                continue;
            }
            let slot = *slot_of.entry(mesh.index()).or_insert_with(|| {
                let copies = vec![Copies::default(); mesh.primitives().len()];
                meshes.push((mesh.clone(), 0, copies));
                meshes.len() - 1
            });
            let (_, placements, copies) = &mut meshes[slot];
            *placements += count;
            let mirrored = placed.world.determinant() < 0.0;
            for (primitive, copies) in mesh.primitives().zip(copies) {
                let own = !drawn::is_triangles(&primitive)
                    || primitive::deformed(&placed.node, &primitive);
                if own {
                    copies.deformed += count;
                } else if placed.instances.is_some() {
                    copies.handedness = [true; 2];
                } else {
                    copies.handedness[usize::from(mirrored)] = true;
                }
            }
        }
        // Every primitive of every placement is a mesh of the scene, or points or lines
        // (counted alike: a bound on both).
        let mesh_count = meshes
            .iter()
            .map(|(mesh, count, _)| mesh.primitives().count() as u64 * count)
            .fold(0, u64::saturating_add);
        if mesh_count > MAX_MESHES as u64 {
            return Err(SceneError::TooManyMeshes {
                scene: self.file.display().to_string(),
                count: mesh_count,
                max: MAX_MESHES,
            });
        }
        for (mesh, count, copies) in &meshes {
            let geometry = (mesh.primitives().zip(copies))
                .map(|(p, copies)| primitive_bytes(&p).saturating_mul(copies.count()))
                .fold(0, u64::saturating_add);
            let record = std::mem::size_of::<Mesh>() as u64;
            let records = record.saturating_mul(mesh.primitives().len() as u64 * count);
            let why = match count {
                1 => "building it".to_owned(),
                n => format!(
                    "placing it {n} times ({geometry} bytes of geometry, which its undeformed \
                     placements share, and {record} bytes a primitive placed)"
                ),
            };
            self.budget
                .take(geometry.saturating_add(records), &why)
                .map_err(|reason| SceneError::InvalidMesh {
                    file: self.file.to_owned(),
                    mesh: label("mesh", mesh.index(), mesh.name()),
                    reason,
                })?;
        }
        let mut materials = HashSet::new();
        for (mesh, _, _) in &meshes {
            for primitive in mesh.primitives() {
                let material = primitive.material();
                if !materials.insert(material.index()) {
                    continue;
                }
                let name = material::name(&material);
                let core = material::images(&material);
                let layers = material_layers::images(self.document, &material);
                for (image, slot, srgb) in core.into_iter().chain(layers) {
                    self.reserve_image(image, srgb, slot, &name)?;
                }
                self.reserve_spec_gloss(&material, &name)?;
            }
        }
        Ok(())
    }

    /// Takes from the budget what glTF image `index` decoded as `srgb` color or linear data
    /// will hold (RGBA8 and its mips), read from its header, unless that was taken already.
    pub(super) fn reserve_image(
        &mut self,
        index: usize,
        srgb: bool,
        slot: &'static str,
        material: &str,
    ) -> Result<(), SceneError> {
        let (width, height) = self.image_size(index, slot, material)?;
        if self.reserved.insert((index, srgb)) {
            let why = format!("decoding it ({width}x{height})");
            if let Err(reason) = self.budget.take(texture_bytes(width, height), &why) {
                return Err(self.image_error(index, slot, material, reason));
            }
        }
        Ok(())
    }

    /// The size glTF image `index` declares in its header (only the header is read: a few
    /// kilobytes of PNG can hold gigabytes of pixels).
    pub(super) fn image_size(
        &mut self,
        index: usize,
        slot: &'static str,
        material: &str,
    ) -> Result<(u32, u32), SceneError> {
        let invalid = |loader: &Self, reason| loader.image_error(index, slot, material, reason);
        let size = match self.encoded(index) {
            Ok(encoded) => ::image::ImageReader::new(std::io::Cursor::new(encoded))
                .with_guessed_format()
                .map_err(|e| e.to_string())
                .and_then(|reader| reader.into_dimensions().map_err(|e| e.to_string())),
            Err(e) => return Err(e.into_named_error(|reason| invalid(self, reason))),
        };
        size.map_err(|e| invalid(self, format!("cannot decode: {e}")))
    }
}

/// The copies of one primitive's geometry a mesh's placements take.
#[derive(Clone, Copy, Default)]
struct Copies {
    /// Whether undeformed placements place it unmirrored, mirrored: one shared copy each.
    handedness: [bool; 2],
    /// Deformed placements, and placements of points or lines: a copy each.
    deformed: u64,
}

impl Copies {
    fn count(&self) -> u64 {
        self.handedness.iter().filter(|&&h| h).count() as u64 + self.deformed
    }
}

/// What an RGBA8 texture of `width` x `height` holds with its mip chain (a third more).
pub(super) fn texture_bytes(width: u32, height: u32) -> u64 {
    u64::from(width) * u64::from(height) * 4 / 3 * 4
}

/// What one copy of `primitive` keeps, from its accessors' counts: its vertices (one per
/// index when flat normals are written out for MikkTSpace, see `primitive.rs`), their
/// skin joints and weights and morph target offsets where it has them, and its indices
/// (up to three per index when a strip or fan becomes a list). Points and lines are
/// bounded by the same count: a [`PointsLines`](crate::PointsLines) keeps 28 bytes a vertex
/// (under a [`Vertex`]'s 56) and at most two indices per index (a loop or strip as a list).
fn primitive_bytes(primitive: &gltf::Primitive) -> u64 {
    let positions = primitive
        .get(&Semantic::Positions)
        .map_or(0, |a| a.count() as u64);
    let per_index = match primitive.mode() {
        Mode::Triangles => 1,
        _ => 3,
    };
    let indices = primitive
        .indices()
        .map_or(positions, |a| a.count() as u64)
        .saturating_mul(per_index);
    let written_out = primitive.get(&Semantic::Normals).is_none()
        && primitive.get(&Semantic::Tangents).is_none()
        && primitive.material().normal_texture().is_some();
    let vertices = if written_out { indices } else { positions };
    // JOINTS_0 and _1 as [u16; 4] and WEIGHTS_0 and _1 as [f32; 4], each set where the
    // primitive has it; each target's three offsets [f32; 3] (counted whether present or
    // not: a bound, not a tally).
    let sets = (0..2)
        .filter(|&n| primitive.get(&Semantic::Joints(n)).is_some())
        .count() as u64;
    let skin_bytes = sets * (8 + 16);
    let morph_bytes = primitive.morph_targets().len() as u64 * 3 * 12;
    let vertex_bytes = std::mem::size_of::<Vertex>() as u64 + skin_bytes + morph_bytes;
    vertices
        .saturating_mul(vertex_bytes)
        .saturating_add(indices.saturating_mul(4))
}
