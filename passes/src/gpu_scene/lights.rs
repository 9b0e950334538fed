//! Lights on the device: every light in one storage buffer (directional lights first), the
//! ambient term and the environment's irradiance, and per point or spot light the volume to rasterize and whether the
//! camera may be inside it.

use glam::{DMat4, DQuat, DVec3};
use wgpu::util::DeviceExt;

use super::mesh::camera_relative;
use super::shadows::{self, Shadowed, NO_SHADOW};
use super::volumes::{VolumeMesh, VolumeShape};
use crate::host::LightPose;
use crate::shadows::Shadows;
use rgraph_scene::{
    BoundingSphere, Camera, Irradiance, Light, LightKind, LightVolume, Projection, Scene,
    CUBE_LEVELS, DEFAULT_CUTOFF_ILLUMINANCE,
};

/// `LIGHT_*` in scene.wgsl.
const DIRECTIONAL: u32 = 0;
const POINT: u32 = 1;
const SPOT: u32 = 2;

/// `LightData` in scene.wgsl.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct LightData {
    volume: [[f32; 4]; 4],
    position: [f32; 3],
    range: f32,
    direction: [f32; 3],
    kind: u32,
    radiance: [f32; 3],
    spot_scale: f32,
    spot_offset: f32,
    bound_offset: f32,
    bound_radius: f32,
    /// The light's first shadow view (gpu_scene/shadows.rs), or `NO_SHADOW`.
    shadow: u32,
}

/// `LightInfo` in scene.wgsl.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct LightInfo {
    ambient: [f32; 3],
    directional_count: u32,
    light_count: u32,
    _pad: [u32; 3],
    environment_intensity: f32,
    environment_max_level: f32,
    /// A factor on the tone mapper's exposure: the frame's (`FrameInputs::exposure`).
    exposure: f32,
    _pad1: f32,
    irradiance: [[f32; 4]; 9],
}

/// A point or spot light to draw as a volume.
#[derive(Clone, Debug, PartialEq)]
pub struct VolumeLight {
    /// Index into the light buffer, drawn as the instance index.
    pub index: u32,
    /// The volume mesh drawn for it: a sphere or a cone.
    pub shape: VolumeShape,
    /// A sphere around the rasterized volume mesh (camera-relative), for deciding whether
    /// the camera's near plane may cut the volume.
    pub bounds: BoundingSphere,
}

pub(super) struct LightBuffers {
    pub data: wgpu::Buffer,
    pub info: wgpu::Buffer,
}

/// The lights of one frame: what the buffers hold, and what the light passes draw.
#[derive(Clone)]
pub(super) struct LightFrame {
    data: Vec<LightData>,
    info: LightInfo,
    /// Some directional light emits, or the ambient term is nonzero: the full-screen
    /// light draw adds something.
    pub fullscreen: bool,
    pub volumes: Vec<VolumeLight>,
    /// The lights given shadow maps, as `shadows` chose them.
    pub shadowed: Vec<Shadowed>,
}

impl LightFrame {
    /// The lights of `scene` placed as `poses` says (one per light), seen from `camera`,
    /// with `exposure` for the tone mapper, the most important of them given shadow maps
    /// as `shadows` says.
    pub fn new(
        scene: &Scene,
        poses: &[LightPose],
        camera: &Camera,
        exposure: f32,
        (sphere, cone): (&VolumeMesh, &VolumeMesh),
        shadows: Shadows,
    ) -> LightFrame {
        let eye = camera.position;
        let placed: Vec<Light> = scene
            .lights
            .iter()
            .zip(poses)
            .map(|(light, pose)| Light {
                position: pose.position,
                direction: pose.direction,
                ..light.clone()
            })
            .collect();
        // Directional lights first: the full-screen draw loops over them.
        let (directional, local): (Vec<&Light>, Vec<&Light>) = placed
            .iter()
            .partition(|l| l.kind == LightKind::Directional);
        let mut data = Vec::new();
        let mut volumes = Vec::new();
        for light in directional.iter().chain(&local) {
            let index = data.len() as u32;
            let kind = match light.kind {
                LightKind::Directional => DIRECTIONAL,
                LightKind::Point => POINT,
                LightKind::Spot { .. } => SPOT,
            };
            let volume = match light.volume(DEFAULT_CUTOFF_ILLUMINANCE) {
                LightVolume::FullScreen => DMat4::IDENTITY,
                LightVolume::Sphere(sphere_volume) => {
                    let m = DMat4::from_scale_rotation_translation(
                        DVec3::splat(sphere_volume.radius),
                        DQuat::IDENTITY,
                        sphere_volume.center,
                    );
                    volumes.push(volume_light(index, VolumeShape::Sphere, m, sphere, eye));
                    m
                }
                LightVolume::Cone {
                    apex,
                    axis,
                    height,
                    base_radius,
                } => {
                    let m = DMat4::from_scale_rotation_translation(
                        DVec3::new(
                            f64::from(base_radius),
                            f64::from(base_radius),
                            f64::from(height),
                        ),
                        DQuat::from_rotation_arc(DVec3::Z, axis.as_dvec3().normalize()),
                        apex,
                    );
                    volumes.push(volume_light(index, VolumeShape::Cone, m, cone, eye));
                    m
                }
            };
            data.push(light_data(light, kind, volume, eye));
        }
        let ordered: Vec<&Light> = directional.iter().chain(&local).copied().collect();
        let chosen = shadows::select(&ordered, camera, shadows);
        for (index, shadowed) in &chosen {
            data[*index].shadow = shadowed.first_view;
        }
        let intensity = scene.environment.map_or(0.0, |e| e.intensity);
        let info = LightInfo {
            ambient: scene.ambient,
            directional_count: directional.len() as u32,
            environment_intensity: intensity,
            environment_max_level: (CUBE_LEVELS - 1) as f32,
            exposure,
            _pad1: 0.0,
            irradiance: match scene.environment {
                Some(_) => Irradiance::neutral().0.map(|c| [c * intensity; 4]),
                None => [[0.0; 4]; 9],
            },
            light_count: data.len() as u32,
            _pad: [0; 3],
        };
        // Storage bindings cannot be empty.
        if data.is_empty() {
            data.push(bytemuck::Zeroable::zeroed());
        }
        // A light whose range is zero reaches nothing.
        volumes.retain(|v| v.bounds.radius > 0.0);
        LightFrame {
            data,
            info,
            fullscreen: directional.iter().any(|l| l.emits())
                || scene.ambient.iter().any(|&c| c > 0.0)
                || intensity > 0.0,
            volumes,
            shadowed: chosen.into_iter().map(|(_, s)| s).collect(),
        }
    }

    /// The contents of the light buffer.
    pub fn data_bytes(&self) -> &[u8] {
        bytemuck::cast_slice(&self.data)
    }

    /// The contents of the light info buffer.
    pub fn info_bytes(&self) -> &[u8] {
        bytemuck::bytes_of(&self.info)
    }
}

impl LightBuffers {
    /// Buffers holding `frame`, rewritable for later frames.
    pub fn new(device: &wgpu::Device, frame: &LightFrame) -> LightBuffers {
        let init = |label, contents: &[u8], usage| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage: usage | wgpu::BufferUsages::COPY_DST,
            })
        };
        LightBuffers {
            data: init(
                "scene lights",
                frame.data_bytes(),
                wgpu::BufferUsages::STORAGE,
            ),
            info: init(
                "scene light info",
                frame.info_bytes(),
                wgpu::BufferUsages::UNIFORM,
            ),
        }
    }
}

fn light_data(light: &Light, kind: u32, volume: DMat4, eye: DVec3) -> LightData {
    // The tiled pass culls with the light's bounding sphere, whose centre lies along
    // the light's direction (on its position for point lights).
    let (bound_offset, bound_radius) = match light.bounding_sphere(DEFAULT_CUTOFF_ILLUMINANCE) {
        Some(sphere) if light.emits() => (
            (sphere.center - light.position).length() as f32,
            sphere.radius as f32,
        ),
        _ => (0.0, -1.0),
    };
    let (spot_scale, spot_offset) = match light.kind {
        LightKind::Spot {
            inner_cone,
            outer_cone,
        } => {
            let (cos_inner, cos_outer) = (inner_cone.cos(), outer_cone.cos());
            let scale = 1.0 / (cos_inner - cos_outer).max(1e-3);
            (scale, -cos_outer * scale)
        }
        // No angular falloff: clamp(0 * cos + 1) = 1.
        LightKind::Point | LightKind::Directional => (0.0, 1.0),
    };
    LightData {
        volume: camera_relative(volume, eye),
        position: (light.position - eye).as_vec3().to_array(),
        range: light
            .effective_range(DEFAULT_CUTOFF_ILLUMINANCE)
            .unwrap_or(0.0),
        direction: light.direction.normalize_or_zero().to_array(),
        kind,
        // A light that emits nothing adds exactly nothing (not, through a negative
        // color, something negative): the shader variants of scenes without its kind
        // compile its code out (variant.rs), and the volumes skip it.
        radiance: match light.emits() {
            true => light.color.map(|c| c * light.intensity),
            false => [0.0; 3],
        },
        spot_scale,
        spot_offset,
        bound_offset,
        bound_radius,
        shadow: NO_SHADOW,
    }
}

fn volume_light(
    index: u32,
    shape: VolumeShape,
    m: DMat4,
    mesh: &VolumeMesh,
    eye: DVec3,
) -> VolumeLight {
    let placed: Vec<DVec3> = mesh
        .positions
        .iter()
        .map(|p| m.transform_point3(p.as_dvec3()) - eye)
        .collect();
    let center = placed.iter().sum::<DVec3>() / placed.len().max(1) as f64;
    let radius = placed
        .iter()
        .map(|p| p.distance(center))
        .fold(0.0, f64::max);
    VolumeLight {
        index,
        shape,
        bounds: BoundingSphere { center, radius },
    }
}

/// Whether the near plane of `camera` (at the origin: bounds are camera-relative) may cut
/// a volume inside `bounds`, for an output of `aspect`. Conservative: true whenever the
/// sphere reaches within the distance of the near plane's farthest corner, so front faces
/// are only used when no part of them can be clipped away.
pub fn camera_may_be_inside(camera: &Camera, aspect: f64, bounds: &BoundingSphere) -> bool {
    let margin = match camera.projection {
        Projection::Perspective { yfov, znear, .. } => {
            let t = (f64::from(yfov) * 0.5).tan();
            f64::from(znear) * (1.0 + t * t * (1.0 + aspect * aspect)).sqrt()
        }
        Projection::Orthographic { ymag, znear, .. } => {
            let (y, z) = (f64::from(ymag), f64::from(znear));
            (z * z + y * y * (1.0 + aspect * aspect)).sqrt()
        }
    };
    bounds.center.length() < bounds.radius + margin
}

/// Whether a volume inside `bounds` (camera-relative) may reach beyond the finite far
/// plane of `camera`: its back faces would then be clipped there and the pixels behind
/// the cut lose the light, so the light passes draw such a volume's light full screen
/// instead when they would draw its back faces. Conservative by a relative 1e-3; never
/// for an infinite far plane.
pub fn far_plane_may_cut(camera: &Camera, bounds: &BoundingSphere) -> bool {
    let zfar = match camera.projection {
        Projection::Perspective { zfar: None, .. } => return false,
        Projection::Perspective {
            zfar: Some(zfar), ..
        }
        | Projection::Orthographic { zfar, .. } => f64::from(zfar),
    };
    bounds.center.dot(camera.forward()) + bounds.radius >= zfar * (1.0 - 1e-3)
}
