//! Light volumes against full-screen lights, per light type and camera position (issue 4:
//! "each light type, camera inside and outside, equals a full-screen evaluation of the
//! same light within tolerance").
//!
//! The scene is built in code: a 20 x 20 ground plane at y = 0, a unit box on it at
//! x in [0.5, 1.5], z in [-0.5, 0.5], and one light: a point light (sphere volume) or a
//! spot light (cone volume). Each case places a perspective camera (50° vertical field of
//! view, near plane 0.05, infinite far plane) with `Camera::look_at`: well outside the
//! volume, inside it, exactly on its boundary (the sphere of the effective range; the
//! cone's side, on the line where the tessellated cone touches the exact one), at the
//! cone's apex, and beside the cone within its bounding sphere (back faces from outside).
//! Also a camera inside with a finite far plane cutting the volume (its back faces would
//! be clipped: the light is then drawn full screen; before that fix 637 of 2283 lit
//! pixels went dark), an orthographic camera outside and with its near plane cutting the
//! sphere, spot cones of 0.3° (a footprint far below a pixel), 89.5° and exactly 90°
//! (glTF's largest), and a point light whose range is a twentieth of a pixel. Every
//! render is 64x64, 4x MSAA, the resolved linear HDR read back.
//!
//! Two bounds against the same pipeline with `volumes: false` (every light a full-screen
//! triangle: the reference), and one between pipelines:
//! - `deferred_per_sample_4x` (detector `all`: every sample shaded at its own position and
//!   depth): **bit-identical**. The falloff window and the spot cone factor are exactly 0
//!   outside the light's reach, and the tessellated volumes circumscribe that reach, so
//!   the volume only skips samples the light adds exactly 0 to.
//! - `deferred_msaa_4x` (detector `compare`): edge pixels are as above; a non-edge pixel
//!   is shaded once, at its center, and the value written to the samples the volume
//!   covers, where the full-screen draw writes it to all four. So a pixel may differ only
//!   where the light reaches its center but not all its samples (computed on the CPU,
//!   with margins for what f32 cannot decide), and there the volume's value is the
//!   full-screen one times (covered samples) / 4: never more than it.
//! - `deferred_msaa_4x_sample_mask` (edge samples drawn once per sample with the
//!   multisample mask), with volumes: bit-identical to `deferred_msaa_4x` with volumes.
//!
//! The tests also check which path the light passes take ([`Path`]: front faces, back
//! faces with the depth test reversed, or full screen), and that the light reaches enough
//! pixels for the comparison to mean something. Run with `--nocapture` for the numbers.
//! Measured on lavapipe: every case bit-identical per sample; under compare at most 13
//! pixels differ per case, by at most 4.8e-4 (linear HDR), all where allowed.

use crate::deferred_support;

use deferred_support::scenes::{Parts, RayHit};
use deferred_support::unlit::SAMPLES_4X;
use deferred_support::{gpu, Render};
use rgraph_core::gpu::Gpu;
use rgraph_passes::gpu_scene::{view_projection, GpuScene};
use rgraph_scene::glam::{DMat4, DQuat, DVec3, DVec4};
use rgraph_scene::{
    Camera, DepthConvention, Light, LightKind, Projection, Scene, DEFAULT_CUTOFF_ILLUMINANCE,
};

const SIZE: (u32, u32) = (64, 64);

const POINT_AT: DVec3 = DVec3::new(0.0, 2.0, 0.0);
const POINT_RANGE: f32 = 3.0;
const SPOT_AT: DVec3 = DVec3::new(0.0, 4.0, 0.0);
const SPOT_RANGE: f32 = 5.5;
const SPOT_INNER: f32 = 25.0;
const SPOT_OUTER: f32 = 35.0;
/// The camera of the "well outside" cases.
const OUTSIDE_EYE: DVec3 = DVec3::new(6.0, 7.0, 10.0);
const OUTSIDE_TARGET: DVec3 = DVec3::new(0.5, 0.0, 0.0);

fn spot_axis() -> DVec3 {
    DVec3::new(0.3, -1.0, -0.2).normalize()
}

/// Ground, box, no light yet.
fn world() -> Parts {
    let mut parts = Parts::new();
    let ground = parts.material("ground", [0.8, 0.8, 0.8], 0.6);
    let s = 10.0;
    let corners = vec![
        DVec3::new(-s, 0.0, s),
        DVec3::new(s, 0.0, s),
        DVec3::new(s, 0.0, -s),
        DVec3::new(-s, 0.0, -s),
    ];
    parts.mesh("ground", &[corners], ground);
    let orange = parts.material("box", [0.9, 0.4, 0.2], 0.4);
    let (min, max) = (DVec3::new(0.5, 0.0, -0.5), DVec3::new(1.5, 1.0, 0.5));
    parts.cuboid("box", min, max, orange);
    parts
}

/// The perspective camera of most cases.
const PERSPECTIVE: Projection = Projection::Perspective {
    yfov: 50f32.to_radians(),
    znear: 0.05,
    zfar: None,
};
/// An orthographic camera 6 units wide and high, near plane 0.5 ahead of the eye.
const ORTHOGRAPHIC: Projection = Projection::Orthographic {
    xmag: 3.0,
    ymag: 3.0,
    znear: 0.5,
    zfar: 30.0,
};

fn camera(eye: DVec3, target: DVec3, projection: Projection) -> Camera {
    let forward = (target - eye).normalize();
    let up = match forward.dot(DVec3::Y).abs() > 0.99 {
        true => DVec3::Z,
        false => DVec3::Y,
    };
    Camera::look_at("test", eye, target, up, projection)
}

fn point_light(position: DVec3, range: f32, intensity: f32) -> Light {
    Light::point("point", position, [1.0, 0.9, 0.8], intensity, Some(range))
}

/// A spot light; angles in degrees.
fn spot_light(apex: DVec3, axis: DVec3, cones: (f32, f32), range: f32) -> Light {
    Light {
        name: "spot".into(),
        kind: LightKind::Spot {
            inner_cone: cones.0.to_radians(),
            outer_cone: cones.1.to_radians(),
        },
        color: [0.8, 0.9, 1.0],
        intensity: 60.0,
        position: apex,
        direction: axis.normalize().as_vec3(),
        range: Some(range),
    }
}

/// A point on the standard spot's cone surface, `t` of the way from the apex to the rim,
/// on the line where the 16-sided volume mesh touches the exact cone, the one that runs
/// most steeply down. The mesh's rim vertex k lies at angle 2πk/16 about the axis in the
/// frame `from_rotation_arc(Z, axis)` (gpu_scene/volumes.rs and lights.rs), so its side
/// faces touch the exact cone half way between two vertices.
fn on_spot_side(t: f64) -> DVec3 {
    let axis = spot_axis().as_vec3().as_dvec3().normalize();
    let rotation = DQuat::from_rotation_arc(DVec3::Z, axis);
    let height = f64::from(SPOT_RANGE);
    let radius = height * f64::from(SPOT_OUTER.to_radians().tan());
    let line = (0..16)
        .map(|k| {
            let phi = std::f64::consts::PI * (2 * k + 1) as f64 / 16.0;
            rotation * DVec3::new(radius * phi.cos(), radius * phi.sin(), height)
        })
        .min_by(|a, b| a.normalize().y.total_cmp(&b.normalize().y))
        .expect("16 lines");
    SPOT_AT + line * t
}

/// A unit vector perpendicular to the spot's axis, pointing up as far as it can.
fn spot_up() -> DVec3 {
    let axis = spot_axis();
    (DVec3::Y - axis * axis.y).normalize()
}

/// How the light passes draw a point or spot light (passes/light.rs).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Path {
    /// The volume's front faces, depth test "in front of the surface": the camera's near
    /// plane cannot cut the volume.
    FrontFaces,
    /// Its back faces, depth test "behind the surface": the camera may be inside.
    BackFaces,
    /// A full-screen triangle: the camera may be inside and the far plane may cut the
    /// volume's back faces.
    FullScreen,
}

/// One comparison: a light, a camera, and what the test expects of them.
struct Case {
    name: &'static str,
    light: Light,
    eye: DVec3,
    target: DVec3,
    /// How the light passes must draw the light; `None`: not checked.
    path: Option<Path>,
    /// At least this many pixels must receive light.
    min_lit: usize,
    /// A pixel that must receive light, where the light is aimed at one sample.
    lit_pixel: Option<(u32, u32)>,
    projection: Projection,
}

impl Case {
    fn new(name: &'static str, light: Light, eye: DVec3, target: DVec3) -> Case {
        Case {
            name,
            light,
            eye,
            target,
            path: None,
            min_lit: 200,
            lit_pixel: None,
            projection: PERSPECTIVE,
        }
    }

    fn orthographic(mut self) -> Case {
        self.projection = ORTHOGRAPHIC;
        self
    }

    fn projection(mut self, projection: Projection) -> Case {
        self.projection = projection;
        self
    }

    fn path(mut self, path: Path) -> Case {
        self.path = Some(path);
        self
    }

    fn parts(&self) -> Parts {
        let mut parts = world();
        parts.lights.push(self.light.clone());
        parts
    }

    fn scene(&self) -> Scene {
        let camera = camera(self.eye, self.target, self.projection);
        self.parts().scene(self.name, camera)
    }
}

/// Pixel coordinates to world rays, as the GPU projects (camera-relative f32 matrix).
struct Rays {
    eye: DVec3,
    inverse: DMat4,
}

impl Rays {
    fn new(camera: &Camera) -> Rays {
        let view_proj = view_projection(camera, SIZE, DepthConvention::ReversedZ);
        Rays {
            eye: camera.position,
            inverse: view_proj.as_dmat4().inverse(),
        }
    }

    /// The ray through pixel coordinate (x, y) (y down): origin on the near plane, unit
    /// direction.
    fn at(&self, x: f64, y: f64) -> (DVec3, DVec3) {
        let ndc = (
            x / f64::from(SIZE.0) * 2.0 - 1.0,
            1.0 - y / f64::from(SIZE.1) * 2.0,
        );
        let unproject = |depth: f64| {
            let h = self.inverse * DVec4::new(ndc.0, ndc.1, depth, 1.0);
            h.truncate() / h.w
        };
        // Reversed Z: 1 is the near plane.
        let (near, farther) = (unproject(1.0), unproject(0.5));
        (self.eye + near, (farther - near).normalize())
    }
}

/// Whether the light adds something at a surface point.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Reach {
    Lit,
    Dark,
    /// Too close to the boundary of its reach for f32 to decide.
    Unsure,
}

/// The CPU's version of the light shader's zeros (brdf.wgsl `shade_light`): the window is
/// 0 from the effective range on, the cone factor 0 from the outer cone on, and
/// `brdf_times_cosine` 0 where the light is behind the surface.
fn reach(light: &Light, point: DVec3, normal: DVec3) -> Reach {
    let range = f64::from(
        light
            .effective_range(DEFAULT_CUTOFF_ILLUMINANCE)
            .expect("point and spot lights have a range"),
    );
    let to_light = light.position - point;
    let distance = to_light.length();
    let l = to_light / distance.max(1e-30);
    let mut lit = [distance < range * (1.0 - 1e-3), normal.dot(l) > 1e-4];
    let mut dark = [distance > range * (1.0 + 1e-3), normal.dot(l) < -1e-4];
    if let LightKind::Spot { outer_cone, .. } = light.kind {
        let outer = f64::from(outer_cone);
        let angle = light.direction.as_dvec3().dot(-l).clamp(-1.0, 1.0).acos();
        let margin = 2e-4 + 1e-3 * outer;
        lit[0] &= angle < outer - margin;
        dark[0] |= angle > outer + margin;
    }
    match (lit.iter().all(|&b| b), dark.iter().any(|&b| b)) {
        (_, true) => Reach::Dark,
        (true, false) => Reach::Lit,
        (false, false) => Reach::Unsure,
    }
}

/// What the CPU knows of a pixel: what each sample sees, and whether that is certain.
struct PixelView {
    samples: [Option<RayHit>; 4],
    /// Some sample is within 1/64 pixel of a polygon boundary.
    ambiguous: bool,
    /// The ray through the pixel center met with sample 0's polygon's plane: the point
    /// `light_nonedge` shades (from sample 0's depth at the pixel center).
    center: Option<DVec3>,
}

fn view_pixel(parts: &Parts, rays: &Rays, x: u32, y: u32) -> PixelView {
    const NUDGE: f64 = 1.0 / 64.0;
    let (px, py) = (f64::from(x), f64::from(y));
    let mut ambiguous = false;
    let samples = SAMPLES_4X.map(|(dx, dy)| {
        let hit_at = |sx: f64, sy: f64| {
            let (origin, dir) = rays.at(sx, sy);
            parts.cast(origin, dir)
        };
        let hit = hit_at(px + dx, py + dy);
        for (ox, oy) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)] {
            let nudged = hit_at(px + dx + ox * NUDGE, py + dy + oy * NUDGE);
            ambiguous |= nudged.map(|h| h.polygon) != hit.map(|h| h.polygon);
        }
        hit
    });
    let center = samples[0].map(|hit| {
        let polygon = &parts.polygons[hit.polygon];
        let (origin, dir) = rays.at(px + 0.5, py + 0.5);
        let t = (polygon.corners[0] - origin).dot(polygon.normal) / dir.dot(polygon.normal);
        origin + dir * t
    });
    PixelView {
        samples,
        ambiguous,
        center,
    }
}

/// Whether `deferred_msaa_4x` may shade this pixel differently with the light's volume:
/// only a non-edge pixel (all samples on one polygon: the scene's polygons all differ in
/// normal, so compare marks any other pixel) whose center the light reaches while it
/// misses a sample. Undecidable pixels may differ.
fn may_differ(light: &Light, parts: &Parts, view: &PixelView) -> bool {
    if view.ambiguous {
        return true;
    }
    let first = view.samples[0].map(|h| h.polygon);
    if view.samples.iter().any(|s| s.map(|h| h.polygon) != first) {
        return false;
    }
    let (Some(hit), Some(center)) = (view.samples[0], view.center) else {
        return false;
    };
    let normal = parts.polygons[hit.polygon].normal;
    let sample_missed = view.samples.iter().flatten().any(|s| {
        let r = reach(light, s.point, normal);
        r != Reach::Lit
    });
    reach(light, center, normal) != Reach::Dark && sample_missed
}

/// The resolved HDR of `pipeline` on `scene`, with light volumes or every light full
/// screen.
fn resolved(gpu: &Gpu, scene: &Scene, label: &str, pipeline: &str, volumes: bool) -> Vec<[f32; 4]> {
    let mut render = Render::new(pipeline, label, SIZE)
        .with_scene(scene.clone())
        .export_resolved();
    if !volumes {
        render = render.full_screen_lights();
    }
    render.run(gpu).hdr(gpu, "resolved")
}

fn xy(i: usize) -> (u32, u32) {
    (i as u32 % SIZE.0, i as u32 / SIZE.0)
}

/// Runs each case through both pipelines with and without volumes; returns one message
/// per violated bound (empty when all hold) and prints the measured numbers.
fn run_cases(cases: &[Case]) -> Vec<String> {
    let gpu = gpu();
    let mut failures = Vec::new();
    for case in cases {
        let scene = case.scene();
        let parts = case.parts();
        let name = case.name;
        let label = format!("volumes-{}", name.replace([' ', ',', '°', '.'], "_"));

        let uploaded = GpuScene::upload(&gpu.device, &gpu.queue, &scene).expect("the scene fits");
        let [volume] = uploaded.volume_lights() else {
            failures.push(format!(
                "{name}: expected one light volume, got {}",
                uploaded.volume_lights().len()
            ));
            continue;
        };
        let path = match (
            uploaded.camera_may_be_inside(volume, SIZE),
            uploaded.far_plane_may_cut(volume),
        ) {
            (false, _) => Path::FrontFaces,
            (true, false) => Path::BackFaces,
            (true, true) => Path::FullScreen,
        };
        if case.path.is_some_and(|expected| expected != path) {
            failures.push(format!(
                "{name}: the light passes take the path {path:?}, the case expects {:?} (eye \
                 {:?}, volume bounds {:?})",
                case.path, case.eye, volume.bounds
            ));
        }

        // Every sample shaded: bit-identical.
        let all = "deferred_per_sample_4x.ron";
        let (with, without) = (
            resolved(&gpu, &scene, &label, all, true),
            resolved(&gpu, &scene, &label, all, false),
        );
        let lit = without.iter().filter(|p| p[0] + p[1] + p[2] > 0.0).count();
        if lit < case.min_lit {
            failures.push(format!(
                "{name}: only {lit} pixels receive light with the full-screen light, the case \
                 needs {} to mean something",
                case.min_lit
            ));
        }
        if let Some((x, y)) = case.lit_pixel {
            let p = without[(y * SIZE.0 + x) as usize];
            if p[0] + p[1] + p[2] <= 0.0 {
                failures.push(format!(
                    "{name}: pixel ({x}, {y}), where the light is aimed, gets no light: {p:?}"
                ));
            }
        }
        let exact: Vec<String> = with
            .iter()
            .zip(&without)
            .enumerate()
            .filter(|(_, (a, b))| a.map(f32::to_bits) != b.map(f32::to_bits))
            .map(|(i, (a, b))| {
                let (x, y) = xy(i);
                format!("({x}, {y}): volume {a:?}, full screen {b:?}")
            })
            .collect();
        if !exact.is_empty() {
            failures.push(format!(
                "{name}, {all} (every sample shaded): {} of {lit} lit pixels differ between the \
                 light volume and the full-screen light (must be bit-identical), e.g.:\n  {}",
                exact.len(),
                exact[..exact.len().min(8)].join("\n  ")
            ));
        }

        // Edge pixels per sample, the rest per pixel: differences only where allowed.
        let compare = "deferred_msaa_4x.ron";
        let (with, without) = (
            resolved(&gpu, &scene, &label, compare, true),
            resolved(&gpu, &scene, &label, compare, false),
        );
        let rays = Rays::new(&scene.camera);
        let (mut differing, mut allowed, mut worst) = (0, 0, (0.0f32, (0, 0)));
        let mut wrong = Vec::new();
        for (i, (a, b)) in with.iter().zip(&without).enumerate() {
            let (x, y) = xy(i);
            let view = view_pixel(&parts, &rays, x, y);
            let may = may_differ(&case.light, &parts, &view);
            allowed += usize::from(may);
            if a.map(f32::to_bits) == b.map(f32::to_bits) {
                continue;
            }
            differing += 1;
            let diff = (0..3).map(|c| (a[c] - b[c]).abs()).fold(0.0, f32::max);
            if diff > worst.0 {
                worst = (diff, (x, y));
            }
            let brighter = (0..3).any(|c| a[c] > b[c] * (1.0 + 2e-3) + 1e-7);
            if !may || brighter {
                let why = match may {
                    false => "the light reaches all of its samples or none of its center",
                    true => "the volume's pixel is brighter than the full-screen one",
                };
                wrong.push(format!(
                    "({x}, {y}): volume {a:?}, full screen {b:?}: {why}"
                ));
            }
        }
        // DX10.0's way (one draw per sample, multisample mask 1 << i) draws the same
        // volumes: bit-identical to the sample_index pipeline.
        let mask = "deferred_msaa_4x_sample_mask.ron";
        let by_mask = resolved(&gpu, &scene, &label, mask, true);
        let mask_differs: Vec<String> = with
            .iter()
            .zip(&by_mask)
            .enumerate()
            .filter(|(_, (a, b))| a.map(f32::to_bits) != b.map(f32::to_bits))
            .map(|(i, (a, b))| {
                let (x, y) = xy(i);
                format!("({x}, {y}): sample_index {a:?}, sample_mask {b:?}")
            })
            .collect();
        if !mask_differs.is_empty() {
            failures.push(format!(
                "{name}: with light volumes, {mask} differs from {compare} at {} pixels (must \
                 be bit-identical), e.g.:\n  {}",
                mask_differs.len(),
                mask_differs[..mask_differs.len().min(8)].join("\n  ")
            ));
        }
        if !wrong.is_empty() {
            failures.push(format!(
                "{name}, {compare}: {} of {differing} differing pixels break the bound (only \
                 pixels whose center the light reaches while it misses a sample may differ, and \
                 by covering fewer samples only), e.g.:\n  {}",
                wrong.len(),
                wrong[..wrong.len().min(8)].join("\n  ")
            ));
        }
        eprintln!(
            "{name}: {path:?}, {lit} lit pixels; per sample bit-identical: {}; compare: \
             {differing} pixels differ (at most {allowed} may), worst by {:.3e} at {:?}",
            exact.is_empty(),
            worst.0,
            worst.1
        );
    }
    failures
}

fn assert_cases(cases: &[Case]) {
    let failures = run_cases(cases);
    assert!(
        failures.is_empty(),
        "{} failures in {} light-volume cases:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

/// A point light (sphere volume of the effective range, 3 units, around (0, 2, 0)) with
/// the camera well outside, inside, and exactly on the range sphere looking in and
/// looking 15° in from along it; inside with the far plane 4 ahead, short of the back
/// faces; and an orthographic camera (6 x 6 units, near plane 0.5 ahead) well outside and
/// with its near plane cutting the sphere though the eye is outside. Bounds: see the
/// module documentation.
#[test]
fn point_light_volume_matches_full_screen_from_every_camera_position() {
    let light = || point_light(POINT_AT, POINT_RANGE, 20.0);
    let range = f64::from(POINT_RANGE);
    let on_sphere = POINT_AT + DVec3::new(-1.0, -0.2, 2.0).normalize() * range;
    // On the sphere, up and to the left, looking 15° inward from the tangent that runs
    // down: the volume's boundary passes through the eye and across the view.
    let on_sphere_2 = POINT_AT + DVec3::new(-1.0, 0.4, 0.3).normalize() * range;
    let out = (on_sphere_2 - POINT_AT).normalize();
    let down_tangent = (DVec3::NEG_Y - out * out.dot(DVec3::NEG_Y)).normalize();
    let grazing = down_tangent * 15f64.to_radians().cos() - out * 15f64.to_radians().sin();
    let cases = [
        Case::new(
            "point, camera well outside",
            light(),
            DVec3::new(5.0, 6.0, 9.0),
            DVec3::new(0.5, 0.3, 0.0),
        )
        .path(Path::FrontFaces),
        Case::new(
            "point, camera inside",
            light(),
            DVec3::new(-1.0, 1.2, 1.5),
            DVec3::new(1.0, 0.3, -0.5),
        )
        .path(Path::BackFaces),
        Case::new(
            "point, camera on the range sphere looking in",
            light(),
            on_sphere,
            DVec3::new(0.5, 0.0, 0.0),
        )
        .path(Path::BackFaces),
        Case::new(
            "point, camera on the range sphere looking 15° in from along it",
            light(),
            on_sphere_2,
            on_sphere_2 + grazing,
        )
        .path(Path::BackFaces),
        // The far plane 4 ahead: the volume's back faces (up to 5 away) reach beyond it,
        // the lit ground and box do not.
        Case::new(
            "point, camera inside, far plane cutting the volume",
            light(),
            DVec3::new(-1.0, 1.2, 1.5),
            DVec3::new(1.0, 0.3, -0.5),
        )
        .projection(Projection::Perspective {
            yfov: 50f32.to_radians(),
            znear: 0.05,
            zfar: Some(4.0),
        })
        .path(Path::FullScreen),
        Case::new(
            "point, orthographic camera well outside",
            light(),
            DVec3::new(5.0, 6.0, 9.0),
            DVec3::new(0.5, 0.3, 0.0),
        )
        .orthographic()
        .path(Path::FrontFaces),
        // The eye 3.2 from the light, outside the sphere, but the near plane 0.5 ahead
        // and 6 wide cuts it.
        Case::new(
            "point, orthographic camera whose near plane cuts the sphere",
            light(),
            POINT_AT + DVec3::new(1.0, 1.0, 3.0).normalize() * 3.2,
            DVec3::new(0.5, 0.0, 0.0),
        )
        .orthographic()
        .path(Path::BackFaces),
    ];
    assert_cases(&cases);
}

/// A spot light (cone volume: apex (0, 4, 0), axis (0.3, -1, -0.2), cones 25° / 35°,
/// range 5.5) with the camera well outside, inside, exactly on the cone's side (looking
/// in, and looking along the side), at the apex (along the axis, and 50° off it so part
/// of the view is outside the cone), beside the cone but within its bounding sphere
/// (back faces seen from outside), and behind the apex.
#[test]
fn spot_light_volume_matches_full_screen_from_every_camera_position() {
    let light = || spot_light(SPOT_AT, spot_axis(), (SPOT_INNER, SPOT_OUTER), SPOT_RANGE);
    let axis = spot_axis();
    let ground_spot = SPOT_AT + axis * 4.2;
    // 50° from the axis towards the ground below the apex: the cone's edge crosses the view.
    let (cos, sin) = (50f64.to_radians().cos(), 50f64.to_radians().sin());
    let off_axis = axis * cos - spot_up() * sin;
    let beside = SPOT_AT + axis * 3.0 + spot_up() * 2.7;
    let cases = [
        Case::new(
            "spot, camera well outside",
            light(),
            OUTSIDE_EYE,
            OUTSIDE_TARGET,
        )
        .path(Path::FrontFaces),
        Case::new(
            "spot, camera inside",
            light(),
            SPOT_AT + axis * 2.5 + spot_up() * 0.4,
            ground_spot,
        )
        .path(Path::BackFaces),
        Case::new(
            "spot, camera on the cone's side looking in",
            light(),
            on_spot_side(0.5),
            SPOT_AT + axis * 4.0,
        )
        .path(Path::BackFaces),
        Case::new(
            "spot, camera on the cone's side looking along it",
            light(),
            on_spot_side(0.5),
            on_spot_side(0.95),
        )
        .path(Path::BackFaces),
        Case::new(
            "spot, camera at the apex looking along the axis",
            light(),
            SPOT_AT,
            SPOT_AT + axis,
        )
        .path(Path::BackFaces),
        Case::new(
            "spot, camera at the apex looking 50° off the axis",
            light(),
            SPOT_AT,
            SPOT_AT + off_axis,
        )
        .path(Path::BackFaces),
        Case::new(
            "spot, camera beside the cone within its bounds",
            light(),
            beside,
            ground_spot,
        )
        .path(Path::BackFaces),
        Case::new(
            "spot, camera behind the apex",
            light(),
            SPOT_AT - axis * 2.0,
            ground_spot,
        )
        .path(Path::FrontFaces),
    ];
    assert_cases(&cases);
}

/// The ground point sample 0 of pixel (x, y) sees from the "well outside" camera.
fn ground_seen_by(x: u32, y: u32) -> DVec3 {
    let parts = world();
    let rays = Rays::new(&camera(OUTSIDE_EYE, OUTSIDE_TARGET, PERSPECTIVE));
    let (dx, dy) = SAMPLES_4X[0];
    let (origin, dir) = rays.at(f64::from(x) + dx, f64::from(y) + dy);
    let hit = parts.cast(origin, dir).expect("the pixel sees the scene");
    assert_eq!(
        hit.polygon, 0,
        "pixel ({x}, {y}) must see the ground for this case"
    );
    hit.point
}

/// Extreme shapes, camera well outside: spot cones of 0.3° (aimed at one sample: its
/// footprint is about a tenth of a pixel wide), 89.5° and exactly 90° (the largest glTF
/// allows), and a point light of range 0.007 (about a twentieth of a pixel) hovering
/// just above the ground point one sample sees.
#[test]
fn extreme_spot_angles_and_sub_pixel_lights_match_full_screen() {
    let pixel = (24, 44);
    let target = ground_seen_by(pixel.0, pixel.1);
    let thin_axis = target - SPOT_AT;
    let tiny_range = 0.007;
    let mut cases = vec![
        Case::new(
            "spot of 0.3°",
            spot_light(SPOT_AT, thin_axis, (0.0, 0.3), 6.0),
            OUTSIDE_EYE,
            OUTSIDE_TARGET,
        ),
        Case::new(
            "spot of 89.5°",
            spot_light(SPOT_AT, spot_axis(), (70.0, 89.5), SPOT_RANGE),
            OUTSIDE_EYE,
            OUTSIDE_TARGET,
        ),
        Case::new(
            "spot of 90°",
            Light {
                kind: LightKind::Spot {
                    inner_cone: 60f32.to_radians(),
                    outer_cone: std::f32::consts::FRAC_PI_2,
                },
                ..spot_light(SPOT_AT, spot_axis(), (0.0, 1.0), SPOT_RANGE)
            },
            OUTSIDE_EYE,
            OUTSIDE_TARGET,
        ),
        Case::new(
            "point light of a twentieth of a pixel",
            point_light(
                target + DVec3::Y * (0.3 * tiny_range),
                tiny_range as f32,
                1e-3,
            ),
            OUTSIDE_EYE,
            OUTSIDE_TARGET,
        )
        .path(Path::FrontFaces),
    ];
    for case in &mut cases[..] {
        if case.name.contains("0.3°") || case.name.contains("twentieth") {
            case.min_lit = 1;
            case.lit_pixel = Some(pixel);
        }
    }
    assert_cases(&cases);
}
