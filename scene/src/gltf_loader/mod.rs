//! glTF 2.0 (`.gltf` with external or embedded buffers, `.glb`) to [`Scene`].
//!
//! What is read: the default scene (else the first) with its node hierarchy; triangle
//! primitives (TRIANGLES, and strips and fans converted to lists) with POSITION, NORMAL (flat
//! normals generated when missing), TEXCOORD_0 and _1, COLOR_0 and TANGENT (MikkTSpace
//! tangents generated when a normal texture needs them; application attributes,
//! `_`-prefixed, are ignored as the spec allows); metallic-roughness materials with their
//! base-color, metallicRoughness, normal, occlusion and emissive textures (specular-glossiness
//! ones converted to them, see [`spec_gloss`]), emission, alpha OPAQUE/MASK, double-sided
//! and the extensions in [`extensions::IMPLEMENTED`] (KHR_texture_transform per texture,
//! EXT_mesh_gpu_instancing's instances as placements, see [`instancing`]); cameras;
//! KHR_lights_punctual lights; animations of node translation, rotation, scale and morph
//! weights, with the node tree they move (see [`animation`]); skins (see [`skin`]) and
//! their JOINTS_0/WEIGHTS_0 and JOINTS_1/WEIGHTS_1, and morph targets' POSITION, NORMAL
//! and TANGENT offsets (see [`deform`]); points and lines (POINTS, LINES, and loops and
//! strips converted to lists) with POSITION and COLOR_0 and their material's base colour
//! and emission (see [`points_lines`]), placed by the node tree as meshes are. Meshes
//! placing one primitive share its geometry (see [`Mesh`](crate::Mesh)). What is
//! not: a skinned vertex's influences past eight (JOINTS_2 on), and the skins and morph
//! targets of points and lines, each with a warning in [`Scene::warnings`].

mod accessor;
mod animation;
mod camera;
mod deform;
mod document;
mod drawn;
mod extensions;
mod factors;
mod glb;
mod image;
mod instancing;
mod light;
mod material;
mod material_layers;
mod nodes;
mod points_lines;
mod primitive;
mod reserve;
mod sandbox;
mod site;
mod skin;
mod spec_gloss;
mod texture_transform;
mod transforms;
mod uri;
mod uri_error;
mod validate;
mod world;

use std::collections::{HashMap, HashSet};
use std::path::Path;
use std::sync::Arc;

use glam::DMat4;
use rgraph_core::bounded_read;

use super::builder::SceneBuilder;
use super::error;
use super::node_tree::{LocalTransform, MeshPlacement, NodeId};
use super::{AssetPolicy, Scene, SceneError, Vertex, MAX_LIGHTS};

/// Loads `file`, reading it and the files its URIs name as `policy` allows; see the module
/// documentation for what is kept.
pub(crate) fn load(file: &Path, policy: &AssetPolicy) -> Result<Scene, SceneError> {
    let bytes = bounded_read::read(file, policy.max_bytes).map_err(|source| SceneError::Io {
        file: file.to_owned(),
        source,
    })?;
    glb::check_header(file, &bytes)?;
    let document::Parsed {
        document,
        json,
        blob,
    } = document::parse(file, &bytes)?;
    let warnings = extensions::check(file, &document)?;
    let document = validate::validate(document).map_err(|source| SceneError::Gltf {
        file: file.to_owned(),
        source,
    })?;
    let sandbox = sandbox::Sandbox::new(file, policy)?;
    let mut loader = Loader {
        file,
        buffers: uri::load_buffers(file, &sandbox, &document, blob)?,
        sandbox,
        budget: Budget::new(policy.max_scene_bytes),
        document: &document,
        builder: SceneBuilder::new(file.display().to_string()),
        materials: HashMap::new(),
        images: HashMap::new(),
        encoded: HashMap::new(),
        reserved: HashSet::new(),
        shared: HashMap::new(),
    };
    loader.builder.warnings = warnings;
    if let Some(scene) = document
        .default_scene()
        .or_else(|| document.scenes().next())
    {
        if scene.nodes().len() == 0 {
            let name = error::label("scene", scene.index(), scene.name());
            loader.builder.warnings.push(format!(
                "{name} lists no nodes: nothing to draw, the frame is empty"
            ));
            loader.builder.allow_empty = true;
        }
        let local = transforms::read(file, &json, &document)?;
        let matrices: Vec<DMat4> = local.iter().map(LocalTransform::matrix).collect();
        let placed = nodes::flatten(file, &document, &scene, &matrices)?;
        loader.reserve(&placed)?;
        (loader.builder.nodes, loader.builder.animations) =
            animation::read(file, &document, &loader.buffers, &placed, &local)?;
        let ids = nodes::ids(&document, &placed);
        loader.builder.skins = skin::read(file, &document, &loader.buffers, &ids)?;
        for (index, placed) in placed.iter().enumerate() {
            // `placed` is the node tree's order: its index is the node's id.
            loader.place(NodeId(index as u32), placed)?;
        }
    }
    loader.builder.finish()
}

/// State shared by the per-object conversions in this module's files.
struct Loader<'a> {
    file: &'a Path,
    /// Where URIs may point, and how large a file they name may be.
    sandbox: sandbox::Sandbox,
    document: &'a gltf::Document,
    buffers: Vec<Vec<u8>>,
    builder: SceneBuilder,
    /// glTF material index (`None` = the default material) to scene material index, so each is
    /// converted once and only if some primitive uses it.
    materials: HashMap<Option<usize>, usize>,
    /// glTF image index and whether it is sRGB to scene texture index: each image is decoded
    /// once per role (an image used both as color and as data is uploaded in both formats).
    images: HashMap<(usize, bool), usize>,
    /// glTF image index to its encoded bytes, read once for its header and its decoding.
    encoded: HashMap<usize, Vec<u8>>,
    /// The images, by glTF index and role, whose memory the budget holds.
    reserved: HashSet<(usize, bool)>,
    /// The geometry of each undeformed primitive placed so far, by glTF mesh index,
    /// primitive index and whether the placement mirrors: what its next placements share.
    shared: HashMap<(usize, usize, bool), SharedGeometry>,
    /// What is left of [`AssetPolicy::max_scene_bytes`], taken before anything is built.
    budget: Budget,
}

/// A [`Mesh`](crate::Mesh)'s vertices and indices, as meshes share them.
type SharedGeometry = (Arc<Vec<Vertex>>, Arc<Vec<u32>>);

/// The bytes of vertices, indices and textures a scene may still build.
struct Budget {
    left: u64,
    max: u64,
}

impl Budget {
    fn new(max: u64) -> Budget {
        Budget { left: max, max }
    }

    /// Takes `bytes`, or says (as the end of a sentence about `what`) why it cannot.
    fn take(&mut self, bytes: u64, why: &str) -> Result<(), String> {
        if bytes > self.left {
            return Err(format!(
                "{why} would take the scene past {} bytes of vertices, indices and textures \
                 (the scene memory limit)",
                self.max
            ));
        }
        self.left -= bytes;
        Ok(())
    }
}

impl Loader<'_> {
    /// Adds what one placed node carries: mesh primitives (once, or once per instance of
    /// EXT_mesh_gpu_instancing), its camera if no camera was found yet, its light.
    fn place(&mut self, id: NodeId, placed: &nodes::Placed) -> Result<(), SceneError> {
        if let Some(mesh) = placed.node.mesh() {
            // Instances are read only where they place something: what `reserve` counted.
            let offsets = match &placed.instances {
                Some(_) if mesh.primitives().next().is_none() => Vec::new(),
                Some(instances) => {
                    instances.offsets(self.file, &self.buffers, &placed.node, placed.world)?
                }
                None => vec![DMat4::IDENTITY],
            };
            for primitive in mesh.primitives() {
                let triangles = drawn::is_triangles(&primitive);
                if !triangles {
                    self.undeformed_points_lines(&mesh, &primitive, &placed.node);
                }
                for &offset in &offsets {
                    let world = placed.world * offset;
                    let added = (self.builder.meshes.len(), self.builder.points_lines.len());
                    match triangles {
                        true => self.primitive(&mesh, &primitive, world, &placed.node)?,
                        false => self.points_lines(&mesh, &primitive, world)?,
                    }
                    self.track(id, offset, added);
                }
            }
        }
        if let (None, Some(camera)) = (&self.builder.camera, placed.node.camera()) {
            self.builder.camera = Some(camera::convert(
                self.file,
                self.document,
                &camera,
                &placed.world,
            )?);
        }
        if let Some(light) = placed.node.light() {
            // Checked as each is placed: a light placed by many nodes counts each time.
            if self.builder.lights.len() >= MAX_LIGHTS as usize {
                return Err(SceneError::TooManyLights {
                    scene: self.file.display().to_string(),
                    max: MAX_LIGHTS,
                });
            }
            let light = light::convert(self.file, &light, &placed.world)?;
            self.builder.lights.push(light);
        }
        Ok(())
    }
}

impl Loader<'_> {
    /// Records where the meshes and the points and lines built since there were `added`
    /// of each hang in the node tree, when the file has animations or skins to move them
    /// (the tree is empty otherwise).
    fn track(&mut self, node: NodeId, offset: DMat4, (meshes, points_lines): (usize, usize)) {
        let builder = &mut self.builder;
        if builder.nodes.nodes.is_empty() {
            return;
        }
        let placement = MeshPlacement { node, offset };
        let built = |now: usize, before| std::iter::repeat_n(placement, now - before);
        (builder.nodes.meshes).extend(built(builder.meshes.len(), meshes));
        (builder.nodes.points_lines).extend(built(builder.points_lines.len(), points_lines));
    }
}
