//! What the host application hands the deferred plugins: the scene to draw, the
//! per-render overrides a command line or an engine UI sets, and the per-frame inputs an
//! engine changes between frames.
//!
//! Graph files name plugins and their parameters; the scene is not a graph resource
//! (its geometry and lights are uploaded by the plugins that use them, on their first
//! frame, from the device they record with). A registry made with `host: None` declares
//! the same passes and validates the same graphs, for build scripts and CI; executing
//! such a graph draws no geometry.
//!
//! # Per-frame inputs: who owns what, what a call invalidates
//!
//! The [`Host`] owns the current [`FrameInputs`] behind a lock. The engine replaces them
//! with [`Host::set_frame`] between executions; the next execution's passes upload what
//! changed ([`crate::gpu_scene::SceneCache::for_frame`]) before recording. A call
//! invalidates nothing on the device: geometry, materials, textures and environment maps
//! stay uploaded, plans stay compiled and pipelines stay built. The scene is drawn
//! camera-relative, so a moved camera rewrites the per-mesh model matrices, the lights
//! and the camera uniform, a few hundred bytes per mesh and light; a moved object (an
//! animation's, say) rewrites only its own per-mesh data (the 512-byte pieces of the
//! buffer that changed); moved points and lines the `points_lines` pass's matrices, 64
//! bytes per primitive; a moved light the light data; new particle emitters
//! (a new `Arc`), or a moved camera, make the particle passes sort and write their
//! particles again, in a larger buffer when there are more than it holds. (The fragment light
//! passes build a pipeline per light-volume geometry when a frame first needs it: the
//! first frame whose camera is inside a volume builds the back-face one, once.)
//!
//! What frame inputs cannot change is what plans and shader variants were made for: the
//! scene's feature set ([`rgraph_scene::analysis::Features`]) is the loaded scene's, so lights
//! keep their kind, color and intensity (only their pose moves) and the depth format
//! chosen from the loaded camera's depth range stays. A new output size, sample count or
//! feature set is a recompile of the graph (`CompiledGraph::recompile`), not a frame
//! input.

use std::sync::{Arc, Mutex};

use glam::{DMat4, DVec3, Vec3};

use rgraph_scene::analysis::Features as SceneFeatures;
use rgraph_scene::{check_emitters, Camera, ParticleEmitter, Pose, Scene};

/// The scene and overrides every deferred plugin of one registry shares, and the current
/// [`FrameInputs`] (see the module documentation for the contract).
pub struct Host {
    /// The scene every plugin of the registry draws, loaded once and shared; its geometry
    /// is uploaded on each device's first frame. Read-only: what moves between frames is
    /// set with `set_frame`.
    pub scene: Arc<Scene>,
    /// Per-render choices (tone mapping, exposure, background), copied by
    /// [`register`](crate::register) into the plugins, which bake them into their passes
    /// at setup: to change them, register the plugins with a new host and load the graph
    /// again.
    pub overrides: Overrides,
    frame: Mutex<CurrentFrame>,
}

/// The frame inputs set last and how many times they were set: the scene's uploads
/// compare the count with the one they were written for.
struct CurrentFrame {
    inputs: Arc<FrameInputs>,
    generation: u64,
}

/// Values that, when set, replace what the graph file's parameters say.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overrides {
    /// Tone-mapping operator name: "none", "reinhard" or "aces".
    pub tonemap: Option<String>,
    /// Exposure applied before tone mapping.
    pub exposure: Option<Exposure>,
    /// What shows where nothing is drawn: `None` leaves it to the pipeline (black). A
    /// pipeline draws one with a `background` pass, which it runs under the condition
    /// `background` (set by the host's choice, see
    /// [`rgraph_scene::analysis::Features::background`]).
    pub background: Option<Background>,
    /// Which lights cast shadows and how they are filtered (the default: PCF, the four
    /// most important lights). Turned off, the host unsets the scene's `shadows` feature
    /// so that the pipelines drop their shadow passes.
    pub shadows: crate::shadows::Shadows,
}

impl Overrides {
    /// `features` (a scene's, or the general set) with what these overrides ask of a
    /// frame: the `auto_exposure` passes for a metered exposure; the `background` passes
    /// for the background asked for or, unasked, for the environment of a scene lit by one
    /// (`environment`: what a viewer expects behind a model its surroundings light); the
    /// shadow passes only while shadows are on. `rgraph render`, `view` and `bench` compile
    /// their plans with it, and `explain` plans what they run with it.
    pub fn applied_to(&self, mut features: SceneFeatures, environment: bool) -> SceneFeatures {
        features.auto_exposure = self.exposure == Some(Exposure::Auto);
        features.background = self.background.is_some() || environment;
        features.shadows &= self.shadows.enabled();
        features
    }
}

/// What a frame shows where its opaque passes drew nothing: behind every surface, seen
/// through blended ones and particles, and at silhouettes in proportion to the samples
/// that show nothing.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Background {
    /// The scene's environment as a mirror would reflect it (its image-based lighting's
    /// radiance, level 0 of its cube map), lit and tone mapped with the scene.
    Environment,
    /// A colour, as the output's sRGB bytes show it: tone mapping composites the frame
    /// over it, in linear light.
    Color([u8; 3]),
    /// Nothing: the output's alpha is the frame's coverage (0 where nothing is drawn,
    /// partial at silhouettes and behind blended surfaces), its colour unpremultiplied, as
    /// an RGBA image for compositing is.
    Transparent,
}

/// How bright the image is made before tone mapping.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum Exposure {
    /// A multiplier, finite and positive.
    Fixed(f32),
    /// Metered from each frame's resolved HDR image by the `auto_exposure` pass, which a
    /// pipeline runs under the condition `auto_exposure` (set by the host's choice, see
    /// [`rgraph_scene::analysis::Features::auto_exposure`]); its `tonemap` pass reads the result.
    Auto,
}

impl Exposure {
    /// The largest fixed exposure. ACES squares the exposed color, and the brightest value
    /// a frame stores (half float's 65504) times a larger exposure can overflow f32: an
    /// infinity, then NaN, a black pixel. Twelve orders of magnitude above 1 leave room for
    /// any scene (a 68,000 lux sun wants about 1e-5).
    pub const MAX: f32 = 1e12;
}

/// What an engine may change from one frame to the next without reloading: the camera,
/// the pose of every light, the transform of every mesh and of every points-and-lines
/// primitive, in the scene's order, the skins' joints and the morph weights, and the
/// particles.
/// [`FrameInputs::of`] gives the scene's own; an engine keeps one, changes its fields and
/// hands it to [`Host::set_frame`].
#[derive(Clone, Debug, PartialEq)]
pub struct FrameInputs {
    /// The camera, pose and projection.
    pub camera: Camera,
    /// One pose per light of `Scene::lights`, in its order.
    pub lights: Vec<LightPose>,
    /// One object-to-world transform per mesh of `Scene::meshes` (glTF: per mesh node
    /// primitive), in its order: the scene's own, or an engine's, or a glTF animation's
    /// pose at a time (`Scene::animated_pose`, see [`FrameInputs::set_pose`]).
    pub transforms: Vec<DMat4>,
    /// One object-to-world transform per primitive of `Scene::points_lines`, in its
    /// order: the scene's own, an engine's or an animation's (`Pose::points_lines`). The
    /// `points_lines` pass rewrites its per-primitive matrices (64 bytes each) in a frame
    /// where they differ from the last it drew; its vertices stay uploaded.
    pub points_lines: Vec<DMat4>,
    /// One list per skin of `Scene::skins`, each with one skin matrix per joint: the
    /// joint's world transform times its inverse bind matrix (`Pose::skins`). The host
    /// owns them once set; the scene upload takes each skinned mesh's joints into its
    /// object space (`joints_in_object_space`, with the mesh's transform above) and the
    /// deformation pass moves its vertices by them before any pass of the frame draws.
    /// Empty for a scene without skins.
    pub skins: Vec<Vec<DMat4>>,
    /// One list per deformation of `Scene::deformations`, each with one weight per morph
    /// target (empty for a deformation without targets): the scene's defaults, or an
    /// animation's (`Pose::morph_weights`). Read as the skins are.
    pub morph_weights: Vec<Vec<f32>>,
    /// A factor on the exposure the pipeline tone maps with (the file's, the override's
    /// or the metered one); 1 leaves it as it is. The `tonemap` pass reads it from the
    /// scene's light data each frame, so changing it builds no pipeline.
    pub exposure: f32,
    /// Seconds since the sequence started, for the engine's own passes that animate by
    /// it; the deferred plugins draw a pose, not a time, so they do not read it.
    pub time: f64,
    /// The particles the `particles` passes draw, emitter by emitter: the scene's
    /// (`Scene::emitters`), or wherever an engine's simulation has taken them, in any
    /// number up to `MAX_PARTICLES` (checked like the scene's). Shared, so that frame
    /// inputs clone cheaply; a new `Arc` (or a moved camera) is what makes the passes
    /// upload and sort them again.
    pub emitters: Arc<Vec<ParticleEmitter>>,
}

impl FrameInputs {
    /// Takes `pose`'s mesh and points-and-lines transforms, skin matrices and morph
    /// weights (an animation's at a time, say), leaving the camera, lights, exposure, time
    /// and particles.
    pub fn set_pose(&mut self, pose: Pose) {
        self.transforms = pose.transforms;
        self.points_lines = pose.points_lines;
        self.skins = pose.skins;
        self.morph_weights = pose.morph_weights;
    }
}

/// Where a light is and where it points, in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightPose {
    /// Unused by directional lights.
    pub position: DVec3,
    /// Unit direction the light travels; unused by point lights.
    pub direction: Vec3,
}

impl FrameInputs {
    /// The scene as loaded: its camera, lights, transforms, joints and morph weights
    /// (`Scene::rest_pose`), exposure 1, at time 0.
    pub fn of(scene: &Scene) -> FrameInputs {
        let Pose {
            transforms,
            points_lines,
            skins,
            morph_weights,
        } = scene.rest_pose();
        FrameInputs {
            camera: scene.camera.clone(),
            lights: scene
                .lights
                .iter()
                .map(|l| LightPose {
                    position: l.position,
                    direction: l.direction,
                })
                .collect(),
            transforms,
            points_lines,
            skins,
            morph_weights,
            exposure: 1.0,
            time: 0.0,
            emitters: Arc::new(scene.emitters.clone()),
        }
    }
}

/// Frame inputs that do not fit the host's scene: they are refused whole, and the last
/// accepted ones stay.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FrameInputsError {
    /// The frame inputs' light poses are not one per scene light.
    #[error("frame inputs give {given} light poses, but scene \"{scene}\" has {expected} lights")]
    LightCount {
        /// The scene, by name.
        scene: String,
        /// Poses given.
        given: usize,
        /// The scene's lights.
        expected: usize,
    },
    /// The frame inputs' transforms are not one per scene mesh.
    #[error(
        "frame inputs give {given} mesh transforms, but scene \"{scene}\" has {expected} meshes"
    )]
    MeshCount {
        /// The scene, by name.
        scene: String,
        /// Transforms given.
        given: usize,
        /// The scene's meshes.
        expected: usize,
    },
    /// The points-and-lines transforms are not one per primitive of the scene's points
    /// and lines, the skin matrices or morph weights are not one list per skin or
    /// deformation of the scene, or a list's length is not the skin's joints' or the
    /// deformation's targets'.
    #[error("frame inputs give {given} {what}, but scene \"{scene}\" has {expected}")]
    PoseCount {
        /// The scene, by name.
        scene: String,
        /// What was counted: "points-and-lines transforms", "skins", "joint matrices for
        /// skin 0 \"arm\"", ...
        what: String,
        /// How many were given.
        given: usize,
        /// How many the scene has.
        expected: usize,
    },
    /// A camera, light pose, mesh or points-and-lines transform, skin matrix or morph
    /// weight holds NaN or infinity.
    #[error("frame inputs: {what} of scene \"{scene}\" is not finite")]
    NotFinite {
        /// The scene, by name.
        scene: String,
        /// What: the camera, light N, mesh N.
        what: String,
    },
    /// The exposure factor is not finite and positive.
    #[error("frame inputs: the exposure factor {0} is not finite and positive")]
    Exposure(f32),
    /// The particles do not fit: too many, or one that cannot be drawn (the reason
    /// names the emitter and the particle).
    #[error("frame inputs: {0}")]
    Particles(String),
}

impl Host {
    /// A host drawing `scene` with `overrides`, whose frame inputs are the scene's own
    /// ([`FrameInputs::of`]).
    pub fn new(scene: Arc<Scene>, overrides: Overrides) -> Host {
        let inputs = Arc::new(FrameInputs::of(&scene));
        Host {
            scene,
            overrides,
            frame: Mutex::new(CurrentFrame {
                inputs,
                generation: 0,
            }),
        }
    }

    /// Makes `inputs` what the next execution draws. Call it between executions: passes
    /// recorded after the call see the new inputs, so a call during an execution could
    /// draw one frame with two. Checked against the scene (one pose per light, one
    /// transform per mesh and per points-and-lines primitive, finite values); on error the
    /// previous inputs stay.
    pub fn set_frame(&self, inputs: FrameInputs) -> Result<(), FrameInputsError> {
        self.check(&inputs)?;
        let mut frame = self.frame.lock().unwrap_or_else(|e| e.into_inner());
        frame.inputs = Arc::new(inputs);
        frame.generation += 1;
        Ok(())
    }

    /// The current frame inputs.
    pub fn frame(&self) -> Arc<FrameInputs> {
        self.current().0
    }

    /// The current frame inputs and how many times [`set_frame`](Self::set_frame) has
    /// been called: a count the scene's uploads were written for is up to date.
    pub(crate) fn current(&self) -> (Arc<FrameInputs>, u64) {
        let frame = self.frame.lock().unwrap_or_else(|e| e.into_inner());
        (frame.inputs.clone(), frame.generation)
    }

    fn check(&self, inputs: &FrameInputs) -> Result<(), FrameInputsError> {
        let scene = || self.scene.name.clone();
        if inputs.lights.len() != self.scene.lights.len() {
            return Err(FrameInputsError::LightCount {
                scene: scene(),
                given: inputs.lights.len(),
                expected: self.scene.lights.len(),
            });
        }
        if inputs.transforms.len() != self.scene.meshes.len() {
            return Err(FrameInputsError::MeshCount {
                scene: scene(),
                given: inputs.transforms.len(),
                expected: self.scene.meshes.len(),
            });
        }
        self.check_pose(inputs)?;
        if !(inputs.exposure.is_finite() && inputs.exposure > 0.0) {
            return Err(FrameInputsError::Exposure(inputs.exposure));
        }
        check_emitters(&self.scene.name, &inputs.emitters)
            .map_err(|e| FrameInputsError::Particles(e.to_string()))?;
        let camera = &inputs.camera;
        let not_finite = std::iter::once((
            format!("the camera \"{}\"", camera.name),
            camera.position.is_finite() && camera.orientation.is_finite(),
        ))
        .chain(inputs.lights.iter().zip(&self.scene.lights).map(|(p, l)| {
            (
                format!("the pose of light \"{}\"", l.name),
                p.position.is_finite() && p.direction.is_finite(),
            )
        }))
        .chain(
            inputs
                .transforms
                .iter()
                .zip(&self.scene.meshes)
                .map(|(t, m)| {
                    (
                        format!("the transform of mesh \"{}\"", m.name),
                        t.is_finite(),
                    )
                }),
        )
        .chain(
            (inputs.points_lines.iter().zip(&self.scene.points_lines)).map(|(t, p)| {
                (
                    format!("the transform of points and lines \"{}\"", p.name),
                    t.is_finite(),
                )
            }),
        )
        .chain(
            inputs
                .skins
                .iter()
                .zip(&self.scene.skins)
                .map(|(joints, skin)| {
                    (
                        format!("a joint matrix of {}", skin.name),
                        joints.iter().all(DMat4::is_finite),
                    )
                }),
        )
        .chain(
            (inputs.morph_weights.iter().zip(&self.scene.deformations)).map(|(weights, d)| {
                (
                    format!("a morph weight of {}", self.scene.meshes[d.mesh].name),
                    weights.iter().all(|w| w.is_finite()),
                )
            }),
        )
        .find(|(_, finite)| !finite);
        match not_finite {
            Some((what, _)) => Err(FrameInputsError::NotFinite {
                scene: scene(),
                what,
            }),
            None => Ok(()),
        }
    }

    /// Fails unless the points-and-lines transforms, skin matrices and morph weights are
    /// shaped as the scene's points and lines, skins and deformations.
    fn check_pose(&self, inputs: &FrameInputs) -> Result<(), FrameInputsError> {
        let scene = &self.scene;
        let count = |what: String, given: usize, expected: usize| match given == expected {
            true => Ok(()),
            false => Err(FrameInputsError::PoseCount {
                scene: scene.name.clone(),
                what,
                given,
                expected,
            }),
        };
        count(
            "points-and-lines transforms".to_owned(),
            inputs.points_lines.len(),
            scene.points_lines.len(),
        )?;
        count("skins".to_owned(), inputs.skins.len(), scene.skins.len())?;
        for (joints, skin) in inputs.skins.iter().zip(&scene.skins) {
            let what = format!("joint matrices for {}", skin.name);
            count(what, joints.len(), skin.joints.len())?;
        }
        let (given, expected) = (inputs.morph_weights.len(), scene.deformations.len());
        count(
            "morph weight lists (one per deformed mesh)".to_owned(),
            given,
            expected,
        )?;
        for (weights, d) in inputs.morph_weights.iter().zip(&scene.deformations) {
            let targets = d.morph.as_ref().map_or(0, |m| m.targets.len());
            // Deformed meshes are glTF's, named `mesh N "NAME" primitive P`.
            let what = format!("morph weights for {}", scene.meshes[d.mesh].name);
            count(what, weights.len(), targets)?;
        }
        Ok(())
    }
}
