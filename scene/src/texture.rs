//! Decoded texture images and how they are sampled.

/// A decoded image, tightly packed RGBA8 rows, top row first (as glTF and wgpu expect).
#[derive(Clone, Debug, PartialEq)]
pub struct TextureImage {
    /// The glTF image name or URI, or a description for generated images; for messages only.
    pub name: String,
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// `width * height * 4` bytes.
    pub rgba8: Vec<u8>,
    /// Whether the bytes are sRGB-encoded (color data) rather than linear (data maps).
    pub srgb: bool,
}

/// How texture coordinates outside `[0, 1]` wrap (glTF sampler `wrapS` / `wrapT`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum WrapMode {
    /// Tiles the image (glTF REPEAT, the default).
    Repeat,
    /// Tiles it, mirroring every other tile.
    MirroredRepeat,
    /// Repeats the edge texels outward.
    ClampToEdge,
}

/// Texel filtering between texels or between mip levels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FilterMode {
    /// The nearest texel or level.
    Nearest,
    /// A linear blend of the neighbouring texels or levels.
    Linear,
}

/// A glTF sampler, split the way wgpu's `SamplerDescriptor` is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Sampler {
    /// Wrapping across the image's width (glTF `wrapS`).
    pub wrap_u: WrapMode,
    /// Wrapping across its height (glTF `wrapT`).
    pub wrap_v: WrapMode,
    /// Filter where a texel covers several pixels.
    pub mag_filter: FilterMode,
    /// Filter within a mip level where a pixel covers several texels.
    pub min_filter: FilterMode,
    /// `None` when the glTF minification filter uses no mipmaps (NEAREST or LINEAR).
    pub mipmap_filter: Option<FilterMode>,
}

impl Default for Sampler {
    /// glTF leaves missing filters to the implementation: trilinear with repeat, the common
    /// choice of viewers.
    fn default() -> Self {
        Sampler {
            wrap_u: WrapMode::Repeat,
            wrap_v: WrapMode::Repeat,
            mag_filter: FilterMode::Linear,
            min_filter: FilterMode::Linear,
            mipmap_filter: Some(FilterMode::Linear),
        }
    }
}

/// A material's use of a texture: which image and how to sample it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureRef {
    /// Index into `Scene::textures`.
    pub image: usize,
    /// How it is sampled.
    pub sampler: Sampler,
    /// Which texture coordinates it is sampled with: 0 ([`Vertex::uv`]) or 1
    /// ([`Vertex::uv1`]).
    ///
    /// [`Vertex::uv`]: super::Vertex::uv
    /// [`Vertex::uv1`]: super::Vertex::uv1
    pub tex_coord: u32,
    /// KHR_texture_transform, as the columns of a 2x3 matrix: the texture is sampled at
    /// `uv_transform[0] * u + uv_transform[1] * v + uv_transform[2]`;
    /// [`TextureRef::IDENTITY_UV`] without the extension.
    pub uv_transform: [[f32; 2]; 3],
}

impl TextureRef {
    /// The UV transform that changes nothing.
    pub const IDENTITY_UV: [[f32; 2]; 3] = [[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]];
}
