//! Shadow maps' views: which lights cast shadows this frame (the most important by
//! screen coverage, as many as [`Shadows::lights`] and the atlas allow), and for each its
//! views into the shadow atlas, as shadow.wgsl's `ShadowView` holds them (group 0,
//! binding 8). The light data name each shadowed light's first view
//! (`LightData::shadow`); the `shadow_maps` pass writes the views each frame
//! ([`GpuScene::write_shadow_views`](super::GpuScene::write_shadow_views)), since the
//! cascades depend on the output's aspect ratio and the atlas's size.
//!
//! - A directional light takes [`CASCADES`] orthographic maps, splitting the view depths
//!   the camera sees of the meshes' bounding boxes, blended ones too, which receive
//!   shadows though they cast none (seen_depths.rs; the practical
//!   split scheme, λ = 0.75: Zhang et al. 2006, as in Dimitrov's cascaded shadow maps).
//!   Each cascade is the sphere
//!   around its slice of the view frustum, whose size depends only on the slice, not on
//!   the camera's rotation, and its centre is snapped to whole texels in the light's
//!   world-anchored view: moving or turning the camera neither resizes nor shifts the
//!   texel grid, so shadow edges do not shimmer. Depth spans the scene's bounds along the
//!   light, so casters outside the cascade still cast into it.
//! - A spot light takes one perspective map over its cone, to its range.
//! - A point light takes [`POINT_FACES`] perspective maps, a cube's faces (+x, -x, +y,
//!   -y, +z, -z, shadow.wgsl picks one by the direction's largest axis), each a little
//!   wider than 90 degrees so that the filter's taps, kept two texels inside a tile, still
//!   cover the whole face.

use glam::{DMat4, DVec3};

use super::seen_depths::seen_depths;
use crate::shadows::{Shadows, ATLAS_UNITS, CASCADES, POINT_FACES, SHADOW_VIEWS};
use rgraph_scene::{Aabb, Camera, Light, LightKind, Projection, DEFAULT_CUTOFF_ILLUMINANCE};

/// `LightData::shadow` of a light without a shadow map (shadow.wgsl's `NO_SHADOW`).
pub(super) const NO_SHADOW: u32 = u32::MAX;

/// Texels around each point-light face's own quarter of directions in its tile: the
/// filter's taps stay two texels inside a tile (shadow.wgsl), and reach two more.
const POINT_MARGIN: u32 = 4;

/// The practical split scheme's weight of the logarithmic split against the uniform one.
const SPLIT_LAMBDA: f64 = 0.75;

/// `ShadowView` in shadow.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(super) struct ShadowView {
    clip_from_world: [[f32; 4]; 4],
    rect: [f32; 4],
    params: [f32; 4],
}

impl ShadowView {
    /// Its clip space from camera-relative world positions, as the shaders have it.
    pub fn clip_from_world(&self) -> DMat4 {
        glam::Mat4::from_cols_array_2d(&self.clip_from_world).as_dmat4()
    }
}

/// What group 0's binding 8 holds.
pub(super) type ShadowViews = [ShadowView; SHADOW_VIEWS as usize];

/// A light given shadow maps this frame.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Shadowed {
    /// The light as the frame places it.
    pub light: Light,
    /// Its first view; a directional light's cascades, a point light's faces follow it.
    pub first_view: u32,
    /// Its maps' side, in [`ATLAS_UNITS`] of the atlas's (each view's the same).
    pub side: u32,
}

impl Shadowed {
    /// Maps the light takes.
    fn views(&self) -> u32 {
        views_of(&self.light)
    }
}

/// The largest map's side in atlas units: a quarter of the atlas's.
const LARGEST_SIDE: u32 = ATLAS_UNITS / 4;
/// The smallest map's side: 1 unit, 1/8 of the largest (128 of 4096 texels).
const SMALLEST_SIDE: u32 = LARGEST_SIDE / 8;

/// The side a light's maps get when the atlas has room: the largest for a light that may
/// light the whole screen (coverage 1, every directional light), and in proportion to the
/// height of the screen it may light for others (the square root of the share of its
/// area), a power of two no smaller than [`SMALLEST_SIDE`]: a map's texels spread over
/// about as many pixels whatever the light's size on screen.
fn wanted_side(coverage: f64) -> u32 {
    let side = f64::from(LARGEST_SIDE) * coverage.clamp(0.0, 1.0).sqrt();
    (side.max(1.0).ceil() as u32)
        .next_power_of_two()
        .clamp(SMALLEST_SIDE, LARGEST_SIDE)
}

fn views_of(light: &Light) -> u32 {
    match light.kind {
        LightKind::Directional => CASCADES,
        LightKind::Point => POINT_FACES,
        LightKind::Spot { .. } => 1,
    }
}

/// The lights of `lights` (in the light buffer's order) given shadow maps, with the
/// index of each in `lights`: lights that emit, by the share of the screen they may light
/// seen from `camera` (every pixel for a directional light; the outline of a point or
/// spot light's bounding sphere, for the vertical field of view), largest
/// first and in buffer order among equals, at most `settings.lights`. Each wants maps of
/// the side [`wanted_side`] gives it; where they do not all fit the atlas, the largest
/// maps halve, the least important light's first, down to [`SMALLEST_SIDE`], and only
/// when every map is that small does the least important light go without. Where room
/// is left, maps double, the most important light's first, up to [`LARGEST_SIDE`].
pub(super) fn select(
    lights: &[&Light],
    camera: &Camera,
    settings: Shadows,
) -> Vec<(usize, Shadowed)> {
    if !settings.enabled() {
        return Vec::new();
    }
    let mut ranked: Vec<(usize, f64)> = lights
        .iter()
        .enumerate()
        .filter(|(_, l)| l.emits())
        .map(|(i, l)| (i, coverage(l, camera)))
        .filter(|&(_, c)| c > 0.0)
        .collect();
    ranked.sort_by(|a, b| b.1.total_cmp(&a.1));
    ranked.truncate(settings.lights as usize);
    let mut sides: Vec<u32> = ranked.iter().map(|&(_, c)| wanted_side(c)).collect();
    loop {
        let views = |k: usize| views_of(lights[ranked[k].0]);
        let units: u32 = (0..sides.len())
            .map(|k| views(k) * sides[k] * sides[k])
            .sum();
        let count: u32 = (0..sides.len()).map(views).sum();
        if units <= ATLAS_UNITS * ATLAS_UNITS && count <= SHADOW_VIEWS {
            break;
        }
        // Too many maps: the largest shrink first, the least important of them first;
        // with every map at the smallest, the least important light goes.
        let shrinkable = (0..sides.len()).filter(|&k| sides[k] > SMALLEST_SIDE);
        match shrinkable.max_by_key(|&k| sides[k]) {
            Some(k) if count <= SHADOW_VIEWS => sides[k] /= 2,
            _ => {
                sides.pop();
                ranked.pop();
            }
        }
    }
    // Room left: the most important light's maps double first, while they fit, so that
    // a few lights use the atlas whole (a sun and two point lights at 1024 texels).
    let views = |k: usize| views_of(lights[ranked[k].0]);
    let mut free = ATLAS_UNITS * ATLAS_UNITS
        - (0..sides.len())
            .map(|k| views(k) * sides[k] * sides[k])
            .sum::<u32>();
    while let Some(k) = (0..sides.len())
        .find(|&k| sides[k] < LARGEST_SIDE && 3 * views(k) * sides[k] * sides[k] <= free)
    {
        free -= 3 * views(k) * sides[k] * sides[k];
        sides[k] *= 2;
    }
    let mut first_view = 0;
    ranked
        .iter()
        .zip(sides)
        .map(|(&(index, _), side)| {
            let light = lights[index];
            let shadowed = Shadowed {
                light: light.clone(),
                first_view,
                side,
            };
            first_view += views_of(light);
            (index, shadowed)
        })
        .collect()
}

/// The share of the screen (0 to 1) `light` may light, roughly: what ranks lights for
/// shadow maps.
fn coverage(light: &Light, camera: &Camera) -> f64 {
    match light.kind {
        LightKind::Directional => 1.0,
        LightKind::Point | LightKind::Spot { .. } => {
            let Some(sphere) = light.bounding_sphere(DEFAULT_CUTOFF_ILLUMINANCE) else {
                return 0.0;
            };
            let to = sphere.center - camera.position;
            let distance = to.length();
            if distance <= sphere.radius {
                return 1.0;
            }
            if to.dot(camera.forward()) < -sphere.radius {
                return 0.0;
            }
            let half_height = match camera.projection {
                Projection::Perspective { yfov, .. } => f64::from(yfov * 0.5).tan(),
                Projection::Orthographic { ymag, .. } => f64::from(ymag) / distance,
            };
            ((sphere.radius / distance) / half_height).powi(2).min(1.0)
        }
    }
}

/// Every view of the `shadowed` lights for `camera` at `aspect` (width over height), in
/// an atlas `atlas` texels wide, around the receiving meshes' bounding boxes `boxes`
/// (camera-relative). Views past the last stay zero.
pub(super) fn views(
    shadowed: &[Shadowed],
    camera: &Camera,
    aspect: f64,
    atlas: u32,
    boxes: &[Aabb],
) -> ShadowViews {
    let mut views = [bytemuck::Zeroable::zeroed(); SHADOW_VIEWS as usize];
    let Some(bounds) = boxes.iter().copied().reduce(|a, b| a.union(&b)) else {
        return views;
    };
    let scene = Sphere {
        center: bounds.center() + camera.position,
        radius: 0.5 * bounds.size().length(),
    };
    let seen = seen_depths(camera, aspect, boxes);
    let placed = placements(shadowed);
    let unit = f64::from(atlas.max(ATLAS_UNITS) / ATLAS_UNITS);
    for shadowed in shadowed {
        let light = &shadowed.light;
        let tile = f64::from(shadowed.side) * unit;
        let made: Vec<ShadowView> = match (light.kind, seen) {
            (LightKind::Directional, Some(seen)) => {
                cascades(light, camera, aspect, tile, &scene, seen)
            }
            (LightKind::Directional, None) => Vec::new(),
            (LightKind::Spot { outer_cone, .. }, _) => {
                vec![spot(light, outer_cone, camera, tile)]
            }
            (LightKind::Point, _) => point_faces(light, camera, tile),
        };
        for (i, mut view) in made.into_iter().enumerate() {
            let at = shadowed.first_view + i as u32;
            let (x, y, side) = placed[at as usize];
            let units = f64::from(ATLAS_UNITS);
            view.rect = [x, y, side, side].map(|u| (f64::from(u) / units) as f32);
            // A light's first view says how many it has.
            if i == 0 {
                view.params[3] = shadowed.views() as f32;
            }
            views[at as usize] = view;
        }
    }
    views
}

/// The atlas tiles the views of `shadowed` take in an atlas `atlas` texels wide, in
/// texels: x, y and side, for the `shadow_maps` pass's viewports, by view index.
pub(super) fn tiles(shadowed: &[Shadowed], atlas: u32) -> Vec<(u32, u32, u32)> {
    let unit = atlas / ATLAS_UNITS;
    placements(shadowed)
        .into_iter()
        .map(|(x, y, side)| (x * unit, y * unit, side * unit))
        .collect()
}

/// Where each view of `shadowed` lies in the atlas, in [`ATLAS_UNITS`]: x, y and side,
/// by view index. The maps go largest first (in view order among equals) along the
/// Z-order curve over the units: each starts at a multiple of its own area, which is a
/// whole square of the curve, so squares of power-of-two sides placed in descending size
/// never overlap and leave no gap (the selection checked that their areas fit).
fn placements(shadowed: &[Shadowed]) -> Vec<(u32, u32, u32)> {
    let mut views: Vec<(u32, u32)> = shadowed
        .iter()
        .flat_map(|s| (s.first_view..s.first_view + s.views()).map(|v| (v, s.side)))
        .collect();
    views.sort_by_key(|&(view, side)| (std::cmp::Reverse(side), view));
    let mut placed = vec![(0, 0, 0); views.len()];
    let mut next = 0;
    for (view, side) in views {
        let (x, y) = z_order(next);
        placed[view as usize] = (x, y, side);
        next += side * side;
    }
    placed
}

/// The point at position `i` of the Z-order (Morton) curve: x from the even bits, y
/// from the odd.
fn z_order(i: u32) -> (u32, u32) {
    let every_other = |mut v: u32| {
        v &= 0x5555_5555;
        v = (v | (v >> 1)) & 0x3333_3333;
        v = (v | (v >> 2)) & 0x0f0f_0f0f;
        v = (v | (v >> 4)) & 0x00ff_00ff;
        (v | (v >> 8)) & 0x0000_ffff
    };
    (every_other(i), every_other(i >> 1))
}

/// What group 0 holds for shadows: the views (binding 8), which the first shadow pass of
/// a frame writes.
pub(super) struct ShadowBuffers {
    pub views: wgpu::Buffer,
}

impl ShadowBuffers {
    pub fn new(device: &wgpu::Device) -> ShadowBuffers {
        ShadowBuffers {
            views: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("shadow views"),
                size: std::mem::size_of::<ShadowViews>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
        }
    }
}

/// A sphere in world space.
struct Sphere {
    center: DVec3,
    radius: f64,
}

/// A directional light's cascades over the view depths `(near, far)` the camera sees of
/// the geometry within `scene`.
fn cascades(
    light: &Light,
    camera: &Camera,
    aspect: f64,
    tile: f64,
    scene: &Sphere,
    (near, far): (f64, f64),
) -> Vec<ShadowView> {
    let n = f64::from(CASCADES);
    let split = |i: f64| {
        let log = near * (far / near).powf(i / n);
        let uniform = near + (far - near) * i / n;
        SPLIT_LAMBDA * log + (1.0 - SPLIT_LAMBDA) * uniform
    };
    let direction = light.direction.as_dvec3().normalize();
    let up = match direction.y.abs() < 0.99 {
        true => DVec3::Y,
        false => DVec3::X,
    };
    // Anchored at the world origin, so that snapping to its texels is the same from
    // every camera position.
    let light_view = DMat4::look_to_rh(DVec3::ZERO, direction, up);
    let scene_center = light_view.transform_point3(scene.center);
    (0..CASCADES)
        .map(|c| {
            let (a, b) = (split(f64::from(c)), split(f64::from(c + 1)));
            let (along, radius) = slice_sphere(camera, aspect, a, b);
            let center = light_view.transform_point3(camera.position + camera.forward() * along);
            let texel = 2.0 * radius / tile;
            let snapped = DVec3::new(
                (center.x / texel).round() * texel,
                (center.y / texel).round() * texel,
                0.0,
            );
            // Light view space looks down -Z: depths are -z, the scene's within its radius.
            let (z_near, z_far) = (
                -scene_center.z - scene.radius,
                -scene_center.z + scene.radius,
            );
            let projection = DMat4::orthographic_rh(
                snapped.x - radius,
                snapped.x + radius,
                snapped.y - radius,
                snapped.y + radius,
                z_near,
                z_far,
            );
            ShadowView {
                clip_from_world: clip_from_camera_relative(projection * light_view, camera),
                rect: [0.0; 4],
                params: [texel as f32, b as f32, 0.0, 0.0],
            }
        })
        .collect()
}

/// The sphere around the camera frustum's slice between view depths `a` and `b`: its
/// centre's view depth and its radius. It depends on the slice alone (the projection, the
/// aspect ratio and the two depths), so a turning camera keeps each cascade's size.
fn slice_sphere(camera: &Camera, aspect: f64, a: f64, b: f64) -> (f64, f64) {
    match camera.projection {
        Projection::Perspective { yfov, .. } => {
            let tan_y = f64::from(yfov * 0.5).tan();
            let tan_x = tan_y * aspect;
            // A corner at depth d lies sqrt(k) d off the axis; the centre z equidistant
            // from the near and far corners, no farther than the far plane.
            let k = tan_x * tan_x + tan_y * tan_y;
            let z = (0.5 * (a + b) * (1.0 + k)).min(b);
            (z, (b * b * k + (b - z) * (b - z)).sqrt())
        }
        Projection::Orthographic { ymag, .. } => {
            let (y, x) = (f64::from(ymag), f64::from(ymag) * aspect);
            let half = 0.5 * (b - a);
            (0.5 * (a + b), (x * x + y * y + half * half).sqrt())
        }
    }
}

/// A spot light's perspective map over its cone (a little wider, for the filter's
/// taps at its rim), from a near plane at a thousandth of its range to the range.
fn spot(light: &Light, outer_cone: f32, camera: &Camera, tile: f64) -> ShadowView {
    let range = light_range(light);
    let fov = (2.0 * f64::from(outer_cone) * 1.05).min(170f64.to_radians());
    let direction = light.direction.as_dvec3().normalize();
    let up = match direction.y.abs() < 0.99 {
        true => DVec3::Y,
        false => DVec3::X,
    };
    let view = DMat4::look_to_rh(light.position, direction, up);
    let projection = DMat4::perspective_rh(fov, 1.0, range * 1e-3, range);
    ShadowView {
        clip_from_world: clip_from_camera_relative(projection * view, camera),
        rect: [0.0; 4],
        params: [(2.0 * (0.5 * fov).tan() / tile) as f32, 0.0, 1.0, 0.0],
    }
}

/// A point light's cube of perspective maps, in shadow.wgsl's face order: +x, -x, +y,
/// -y, +z, -z. Each face's map is `tile` texels over a little more than 90 degrees: the
/// face's own quarter of the directions takes the `tile - 2 * POINT_MARGIN` texels in the
/// middle, so the filter's taps, which stay two texels inside the tile, never leave it.
fn point_faces(light: &Light, camera: &Camera, tile: f64) -> Vec<ShadowView> {
    let range = light_range(light);
    let margin = f64::from(POINT_MARGIN);
    // tan of the half angle: 1 at the face's edge, `tile / 2` texels from the centre of
    // the `tile / 2 - margin` the face itself takes.
    let tan_half = 0.5 * tile / (0.5 * tile - margin).max(1.0);
    let fov = 2.0 * tan_half.atan();
    let projection = DMat4::perspective_rh(fov, 1.0, range * 1e-3, range);
    let faces = [
        (DVec3::X, DVec3::NEG_Y),
        (DVec3::NEG_X, DVec3::NEG_Y),
        (DVec3::Y, DVec3::Z),
        (DVec3::NEG_Y, DVec3::NEG_Z),
        (DVec3::Z, DVec3::NEG_Y),
        (DVec3::NEG_Z, DVec3::NEG_Y),
    ];
    faces
        .iter()
        .map(|&(direction, up)| {
            let view = DMat4::look_to_rh(light.position, direction, up);
            ShadowView {
                clip_from_world: clip_from_camera_relative(projection * view, camera),
                rect: [0.0; 4],
                params: [(2.0 * tan_half / tile) as f32, 0.0, 1.0, 0.0],
            }
        })
        .collect()
}

/// How far a point or spot light's maps reach: its effective range.
fn light_range(light: &Light) -> f64 {
    f64::from(
        light
            .effective_range(DEFAULT_CUTOFF_ILLUMINANCE)
            .unwrap_or(1.0),
    )
    .max(1e-3)
}

/// `clip_from_world` taking camera-relative positions, as the shaders have them.
fn clip_from_camera_relative(clip_from_world: DMat4, camera: &Camera) -> [[f32; 4]; 4] {
    (clip_from_world * DMat4::from_translation(camera.position))
        .as_mat4()
        .to_cols_array_2d()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shadows::ShadowFilter;
    use glam::Vec3;

    /// Point lights rank with the others by the screen they may light and take a cube's
    /// six maps, sized by that share: the sun's cascades the largest, the nearest point
    /// light's faces next; every face of a point light looks out of its position.
    #[test]
    fn point_lights_take_six_maps_ranked_and_sized_by_coverage() {
        let light = |name: &str, kind, position: DVec3| Light {
            name: name.into(),
            kind,
            color: [1.0; 3],
            intensity: 5.0,
            position,
            direction: Vec3::NEG_Y,
            range: Some(2.0),
        };
        let lights = [
            light("far", LightKind::Point, DVec3::new(0.0, 1.0, -30.0)),
            light("sun", LightKind::Directional, DVec3::ZERO),
            light("near", LightKind::Point, DVec3::new(0.0, 1.0, -4.0)),
            light("mid", LightKind::Point, DVec3::new(0.0, 1.0, -10.0)),
        ];
        let projection = Projection::Perspective {
            yfov: 0.8,
            znear: 0.1,
            zfar: None,
        };
        let camera = Camera::look_at("c", DVec3::ZERO, DVec3::NEG_Z, DVec3::Y, projection);
        let settings = Shadows {
            filter: ShadowFilter::Pcf,
            lights: 4,
        };
        let refs: Vec<&Light> = lights.iter().collect();
        let chosen = select(&refs, &camera, settings);
        let picked: Vec<(&str, u32)> = chosen
            .iter()
            .map(|(_, s)| (s.light.name.as_str(), s.first_view))
            .collect();
        assert_eq!(picked, [("sun", 0), ("near", 4), ("mid", 10), ("far", 16)]);
        let sides: Vec<u32> = chosen.iter().map(|(_, s)| s.side).collect();
        assert!(
            sides[0] == LARGEST_SIDE && sides.windows(2).all(|p| p[0] >= p[1]),
            "{sides:?}"
        );
        let shadowed: Vec<Shadowed> = chosen.into_iter().map(|(_, s)| s).collect();
        let views = views(&shadowed, &camera, 1.5, 4096, &[]);
        assert_eq!(views[4].params, [0.0; 4], "no views without scene bounds");
        let faces = point_faces(&lights[2], &camera, 1024.0);
        assert_eq!(faces.len() as u32, POINT_FACES);
        for (face, axis) in faces.iter().zip([
            DVec3::X,
            DVec3::NEG_X,
            DVec3::Y,
            DVec3::NEG_Y,
            DVec3::Z,
            DVec3::NEG_Z,
        ]) {
            // A point one unit out along the face's axis (camera-relative) lands at the
            // middle of its map.
            let clip = glam::Mat4::from_cols_array_2d(&face.clip_from_world)
                * (lights[2].position + axis).as_vec3().extend(1.0);
            let ndc = clip.truncate() / clip.w;
            assert!(ndc.x.abs() < 1e-4 && ndc.y.abs() < 1e-4, "{axis}: {ndc}");
            assert!((0.0..1.0).contains(&ndc.z), "{axis}: depth {}", ndc.z);
        }
        // The face's own 90 degrees end POINT_MARGIN texels inside its 1024.
        let edge = glam::Mat4::from_cols_array_2d(&faces[0].clip_from_world)
            * (lights[2].position + DVec3::new(1.0, 1.0, 0.0))
                .as_vec3()
                .extend(1.0);
        let texels_in = (1.0 - (edge.y / edge.w).abs()) * 512.0;
        assert!(
            (texels_in - POINT_MARGIN as f32).abs() < 0.01,
            "{texels_in}"
        );
    }

    /// The cascades split the depths the camera sees of the meshes' boxes: over a ground
    /// plane seen from 2 units up, the first starts past the near plane, where the
    /// ground does, and the last ends where the view leaves the ground; a camera moved
    /// a little keeps every cascade's size (the range is rounded to steps).
    #[test]
    fn cascades_split_the_seen_depths_and_keep_their_size() {
        let sun = Light {
            name: "sun".into(),
            kind: LightKind::Directional,
            color: [1.0; 3],
            intensity: 3.0,
            position: DVec3::ZERO,
            direction: Vec3::new(0.3, -1.0, -0.2),
            range: None,
        };
        let shadowed = [Shadowed {
            light: sun,
            first_view: 0,
            side: LARGEST_SIDE,
        }];
        let projection = Projection::Perspective {
            yfov: 0.8,
            znear: 0.1,
            zfar: None,
        };
        let cascades_at = |eye: DVec3| {
            let camera = Camera::look_at(
                "c",
                eye,
                eye + DVec3::new(0.0, -0.5, -1.0),
                DVec3::Y,
                projection,
            );
            let ground = Aabb {
                min: DVec3::new(-50.0, 0.0, -50.0) - eye,
                max: DVec3::new(50.0, 0.0, 50.0) - eye,
            };
            let views = views(&shadowed, &camera, 1.5, 4096, &[ground]);
            let seen = seen_depths(&camera, 1.5, &[ground]).expect("the ground is seen");
            (std::array::from_fn::<_, 4, _>(|i| views[i].params), seen)
        };
        let (params, (near, far)) = cascades_at(DVec3::new(0.0, 2.0, 0.0));
        assert!(near > 2.0, "the ground starts {near} out");
        assert!(far < 60.0, "the ground's end within the view: {far}");
        assert_eq!(
            params[3][1], far as f32,
            "the last cascade ends at the far depth"
        );
        for pair in params.windows(2) {
            assert!(
                pair[0][1] < pair[1][1] && pair[0][0] < pair[1][0],
                "{params:?}"
            );
        }
        let (moved, _) = cascades_at(DVec3::new(0.003, 2.002, -0.004));
        let sizes = |p: [[f32; 4]; 4]| p.map(|v| v[0]);
        assert_eq!(
            sizes(moved),
            sizes(params),
            "texel sizes after a small move"
        );
    }

    /// A cascade's sphere keeps its size whichever way the camera looks.
    #[test]
    fn slice_spheres_depend_on_the_slice_alone() {
        let projection = Projection::Perspective {
            yfov: 0.8,
            znear: 0.1,
            zfar: None,
        };
        let camera = |target| Camera::look_at("c", DVec3::ZERO, target, DVec3::Y, projection);
        let a = slice_sphere(&camera(DVec3::new(0.0, 0.0, -1.0)), 1.5, 2.0, 9.0);
        let b = slice_sphere(&camera(DVec3::new(3.0, 1.0, 2.0)), 1.5, 2.0, 9.0);
        assert_eq!(a, b);
        // Every corner of the slice is inside.
        let tan_y = 0.4f64.tan();
        for d in [2.0, 9.0] {
            let corner = DVec3::new(d * tan_y * 1.5, d * tan_y, d);
            let off = (corner - DVec3::new(0.0, 0.0, a.0)).length();
            assert!(
                off <= a.1 + 1e-9,
                "corner at depth {d} is {off} from the centre, radius {}",
                a.1
            );
        }
    }

    fn light_of(kind: LightKind) -> Light {
        Light {
            name: "l".into(),
            kind,
            color: [1.0; 3],
            intensity: 1.0,
            position: DVec3::ZERO,
            direction: Vec3::NEG_Y,
            range: Some(1.0),
        }
    }

    /// Maps of mixed sizes tile the atlas without overlapping, each inside it: a sun's
    /// four largest, point lights' faces and spot lights' maps of every size.
    #[test]
    fn maps_of_every_size_fill_the_atlas_without_overlap() {
        let mut shadowed = Vec::new();
        let mut first_view = 0;
        let kinds = [
            (LightKind::Point, SMALLEST_SIDE),
            (LightKind::Directional, LARGEST_SIDE),
            (
                LightKind::Spot {
                    inner_cone: 0.1,
                    outer_cone: 0.2,
                },
                2 * SMALLEST_SIDE,
            ),
            (LightKind::Point, LARGEST_SIDE / 2),
            (
                LightKind::Spot {
                    inner_cone: 0.1,
                    outer_cone: 0.2,
                },
                SMALLEST_SIDE,
            ),
        ];
        for (kind, side) in kinds {
            let light = light_of(kind);
            let views = views_of(&light);
            shadowed.push(Shadowed {
                light,
                first_view,
                side,
            });
            first_view += views;
        }
        let placed = placements(&shadowed);
        assert_eq!(placed.len() as u32, first_view);
        let mut owner = vec![None; (ATLAS_UNITS * ATLAS_UNITS) as usize];
        for (view, &(x, y, side)) in placed.iter().enumerate() {
            assert!(
                side > 0 && x % side == 0 && y % side == 0,
                "view {view}: {x}, {y}, {side}"
            );
            for v in y..y + side {
                for u in x..x + side {
                    assert!(
                        u < ATLAS_UNITS && v < ATLAS_UNITS,
                        "view {view} leaves the atlas"
                    );
                    let cell = &mut owner[(v * ATLAS_UNITS + u) as usize];
                    assert_eq!(*cell, None, "views {cell:?} and {view} overlap at {u}, {v}");
                    *cell = Some(view);
                }
            }
        }
        // The texels' tiles are the units' at 128 texels a unit.
        assert_eq!(
            tiles(&shadowed, 4096)[6],
            (0, 0, 1024),
            "the sun's first cascade"
        );
    }

    /// With 64 point lights allowed, each ranks, gets the size its coverage wants or a
    /// smaller one, and every one taken fits: the units used never exceed the atlas's.
    #[test]
    fn many_lights_shrink_to_fit_the_atlas() {
        let lights: Vec<Light> = (0..64)
            .map(|i| Light {
                position: DVec3::new(f64::from(i % 8) - 4.0, 0.0, -3.0 - f64::from(i / 8)),
                ..light_of(LightKind::Point)
            })
            .collect();
        let projection = Projection::Perspective {
            yfov: 0.8,
            znear: 0.1,
            zfar: None,
        };
        let camera = Camera::look_at("c", DVec3::ZERO, DVec3::NEG_Z, DVec3::Y, projection);
        let refs: Vec<&Light> = lights.iter().collect();
        let settings = Shadows {
            filter: ShadowFilter::Pcf,
            lights: 64,
        };
        let chosen = select(&refs, &camera, settings);
        let used: u32 = chosen
            .iter()
            .map(|(_, s)| s.views() * s.side * s.side)
            .sum();
        assert!(used <= ATLAS_UNITS * ATLAS_UNITS, "{used} units");
        // 64 lights of 6 smallest maps take 384 of the 1024 units: every light is
        // shadowed, the nearest with larger maps than the farthest.
        assert_eq!(chosen.len(), 64);
        assert!(chosen
            .iter()
            .all(|(_, s)| (SMALLEST_SIDE..=LARGEST_SIDE).contains(&s.side)));
        let (first, last) = (chosen[0].1.side, chosen[63].1.side);
        assert!(first > last, "nearest {first}, farthest {last}");
        // Twice the views the atlas may hold: the least important go.
        let doubled: Vec<&Light> = refs.iter().chain(&refs).copied().collect();
        let settings = Shadows {
            lights: 128,
            ..settings
        };
        let chosen = select(&doubled, &camera, settings);
        let views: u32 = chosen.iter().map(|(_, s)| s.views()).sum();
        assert!(
            views <= SHADOW_VIEWS && views + POINT_FACES > SHADOW_VIEWS,
            "{views} views"
        );
    }
}
