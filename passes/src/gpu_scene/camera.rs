//! The camera uniform: camera-relative view-projection for the output's aspect ratio, one
//! buffer per depth convention, rewritten only when the output size or the frame's camera
//! changes.

use std::sync::Mutex;

use glam::{DMat4, Mat4};

use rgraph_scene::{Camera, DepthConvention};

/// The output size, the frame inputs' generation (see `Host::set_frame`) and the bits of
/// the jitter a camera buffer was written for.
type WrittenFor = ((u32, u32), u64, [u32; 2]);

/// `Camera` in scene.wgsl.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct CameraUniform {
    view_proj: [[f32; 4]; 4],
    inv_view_proj: [[f32; 4]; 4],
    forward: [f32; 3],
    _pad0: f32,
    viewport: [f32; 2],
    _pad1: [f32; 2],
}

/// Both conventions' camera buffers. Each holds the camera with the translation left out:
/// geometry arrives camera-relative (see [`super::mesh`]), so the matrix only rotates and
/// projects and keeps full f32 precision however far the scene is from the origin.
pub(super) struct Cameras {
    pub reversed: wgpu::Buffer,
    pub standard: wgpu::Buffer,
    /// What the buffers were last written for.
    written_for: Mutex<Option<WrittenFor>>,
}

impl Cameras {
    pub fn new(device: &wgpu::Device) -> Cameras {
        let buffer = |label| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: std::mem::size_of::<CameraUniform>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        Cameras {
            reversed: buffer("deferred camera (reversed Z)"),
            standard: buffer("deferred camera"),
            written_for: Mutex::new(None),
        }
    }

    /// Writes both buffers for `camera` (of frame inputs `generation`) at `size`, its
    /// projection offset by `jitter` pixels, unless they hold it already. The write lands
    /// before the next submission, i.e. before the frame being recorded runs.
    pub fn prepare(
        &self,
        queue: &wgpu::Queue,
        (camera, generation): (&Camera, u64),
        size: (u32, u32),
        jitter: [f32; 2],
    ) {
        let mut written = self.written_for.lock().unwrap_or_else(|e| e.into_inner());
        let key = (size, generation, jitter.map(f32::to_bits));
        if *written == Some(key) {
            return;
        }
        for (buffer, convention) in [
            (&self.reversed, DepthConvention::ReversedZ),
            (&self.standard, DepthConvention::Standard),
        ] {
            let uniform = uniform(camera, size, convention, jitter);
            queue.write_buffer(buffer, 0, bytemuck::bytes_of(&uniform));
        }
        *written = Some(key);
    }
}

/// The clip-from-camera-relative-world matrix for an output of `size`.
pub fn view_projection(camera: &Camera, size: (u32, u32), convention: DepthConvention) -> Mat4 {
    let aspect = size.0.max(1) as f32 / size.1.max(1) as f32;
    camera.projection_matrix(aspect, convention) * camera.view_rotation()
}

/// [`view_projection`] with the image moved by `jitter` pixels (x right, y down): clip
/// x and y offset in proportion to w, so every point moves by the same pixels.
fn jittered(
    camera: &Camera,
    size: (u32, u32),
    convention: DepthConvention,
    jitter: [f32; 2],
) -> Mat4 {
    let (width, height) = (size.0.max(1) as f32, size.1.max(1) as f32);
    // Normalised device y points up, pixel y down.
    let offset = glam::Vec3::new(2.0 * jitter[0] / width, -2.0 * jitter[1] / height, 0.0);
    Mat4::from_translation(offset) * view_projection(camera, size, convention)
}

fn uniform(
    camera: &Camera,
    size: (u32, u32),
    convention: DepthConvention,
    jitter: [f32; 2],
) -> CameraUniform {
    let view_proj = jittered(camera, size, convention, jitter);
    // Inverted in f64: the projection of a small near plane is badly conditioned in f32.
    let inverse = view_proj.as_dmat4().inverse();
    CameraUniform {
        view_proj: view_proj.to_cols_array_2d(),
        inv_view_proj: DMat4::as_mat4(&inverse).to_cols_array_2d(),
        forward: camera.forward().as_vec3().to_array(),
        _pad0: 0.0,
        viewport: [size.0 as f32, size.1 as f32],
        _pad1: [0.0; 2],
    }
}
