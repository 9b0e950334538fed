//! Putting a graph's rgba8 output on the window: the output is copied into a texture the
//! blitter can sample and drawn onto the surface's texture, whose bytes then equal the
//! output's (a non-sRGB view on both sides, so no encoding or decoding happens on the
//! way), and read back from there for `--screenshot`.

use std::sync::Arc;

use image::RgbaImage;
use rgraph_core::gpu::{read_texture, Gpu};
use wgpu::util::TextureBlitter;
use wgpu::TextureFormat;
use winit::window::Window;

use super::ViewError;

/// The window's surface, configured for the device, and what drawing onto it needs.
pub struct Presenter {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    /// The format the surface's texture is viewed (and blitted into) as: the non-sRGB
    /// variant of its format.
    view_format: TextureFormat,
    blitter: TextureBlitter,
    /// The output's copy the blitter samples (`Rgba8Unorm`, so its bytes are read as
    /// they are), remade when the output's size changes.
    copy: Option<wgpu::Texture>,
}

impl Presenter {
    /// Makes `window`'s surface on `gpu`'s instance and configures it at the window's
    /// size. `readable`: its textures can be copied from, for `--screenshot` (an error
    /// when the surface does not allow it).
    pub fn new(gpu: &Gpu, window: Arc<Window>, readable: bool) -> Result<Presenter, ViewError> {
        let adapter = gpu.info.name.clone();
        let surface_error = |reason: String| ViewError::Surface {
            adapter: adapter.clone(),
            reason,
        };
        let surface = gpu
            .instance
            .create_surface(window.clone())
            .map_err(|e| surface_error(e.to_string()))?;
        let caps = surface.get_capabilities(&gpu.adapter);
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| {
                matches!(
                    f.remove_srgb_suffix(),
                    TextureFormat::Bgra8Unorm | TextureFormat::Rgba8Unorm
                )
            })
            .ok_or_else(|| {
                surface_error(format!(
                    "the surface offers no 8-bit RGBA or BGRA format (it offers {:?})",
                    caps.formats
                ))
            })?;
        let mut usage = wgpu::TextureUsages::RENDER_ATTACHMENT;
        if readable {
            if !caps.usages.contains(wgpu::TextureUsages::COPY_SRC) {
                return Err(ViewError::Unreadable {
                    usages: format!("{:?}", caps.usages),
                });
            }
            usage |= wgpu::TextureUsages::COPY_SRC;
        }
        let view_format = format.remove_srgb_suffix();
        let size = window.inner_size();
        let config = wgpu::SurfaceConfiguration {
            usage,
            format,
            width: size.width.max(1),
            height: size.height.max(1),
            present_mode: wgpu::PresentMode::AutoNoVsync,
            desired_maximum_frame_latency: 2,
            alpha_mode: caps.alpha_modes[0],
            view_formats: vec![view_format],
            color_space: wgpu::SurfaceColorSpace::Auto,
        };
        surface.configure(&gpu.device, &config);
        Ok(Presenter {
            blitter: TextureBlitter::new(&gpu.device, view_format),
            window,
            surface,
            config,
            view_format,
            copy: None,
        })
    }

    pub fn window(&self) -> &Window {
        &self.window
    }

    /// The size the surface is configured at, the window's inner size.
    pub fn size(&self) -> (u32, u32) {
        (self.config.width, self.config.height)
    }

    /// Reconfigures the surface at `size` (ignored while either side is 0: a minimised
    /// window).
    pub fn resize(&mut self, device: &wgpu::Device, (width, height): (u32, u32)) {
        if width > 0 && height > 0 && (width, height) != self.size() {
            self.config.width = width;
            self.config.height = height;
            self.surface.configure(device, &self.config);
        }
    }

    /// Draws `output` (an `Rgba8UnormSrgb` or `Rgba8Unorm` texture with `COPY_SRC`)
    /// stretched over the window and presents it. With `read`, returns the presented
    /// image as read back from the surface's texture. `Ok(None)` without `read`, or when
    /// the surface had no texture to give this time (it is reconfigured and the frame
    /// skipped).
    pub fn present(
        &mut self,
        gpu: &Gpu,
        output: &wgpu::Texture,
        read: bool,
    ) -> Result<Option<RgbaImage>, ViewError> {
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame)
            | wgpu::CurrentSurfaceTexture::Suboptimal(frame) => frame,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.surface.configure(&gpu.device, &self.config);
                return Ok(None);
            }
            _ => return Ok(None),
        };
        let copy = self.copy_of(&gpu.device, output);
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("rgraph view present"),
            });
        encoder.copy_texture_to_texture(
            output.as_image_copy(),
            copy.as_image_copy(),
            output.size(),
        );
        let source = copy.create_view(&wgpu::TextureViewDescriptor::default());
        let target = frame.texture.create_view(&wgpu::TextureViewDescriptor {
            format: Some(self.view_format),
            ..Default::default()
        });
        self.blitter
            .copy(&gpu.device, &mut encoder, &source, &target);
        gpu.queue.submit([encoder.finish()]);
        let image = match read {
            true => Some(read_rgba(gpu, &frame.texture)?),
            false => None,
        };
        self.window.pre_present_notify();
        gpu.queue.present(frame);
        Ok(image)
    }

    /// The texture `output` is copied into, made (or remade) at its size.
    fn copy_of(&mut self, device: &wgpu::Device, output: &wgpu::Texture) -> wgpu::Texture {
        let fits = |t: &wgpu::Texture| t.size() == output.size();
        match &self.copy {
            Some(copy) if fits(copy) => copy.clone(),
            _ => {
                let copy = device.create_texture(&wgpu::TextureDescriptor {
                    label: Some("rgraph view output copy"),
                    size: output.size(),
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: TextureFormat::Rgba8Unorm,
                    usage: wgpu::TextureUsages::COPY_DST | wgpu::TextureUsages::TEXTURE_BINDING,
                    view_formats: &[],
                });
                self.copy = Some(copy.clone());
                copy
            }
        }
    }
}

/// A surface texture's bytes as RGBA (BGRA formats swizzled).
fn read_rgba(gpu: &Gpu, texture: &wgpu::Texture) -> Result<RgbaImage, ViewError> {
    let mut bytes = read_texture(&gpu.device, &gpu.queue, texture)
        .map_err(|e| ViewError::Screenshot(e.to_string()))?;
    if texture.format().remove_srgb_suffix() == TextureFormat::Bgra8Unorm {
        for texel in bytes.chunks_exact_mut(4) {
            texel.swap(0, 2);
        }
    }
    RgbaImage::from_raw(texture.width(), texture.height(), bytes)
        .ok_or_else(|| ViewError::Screenshot("the surface's texels do not fill it".into()))
}
