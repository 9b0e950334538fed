//! Resource descriptions: what a texture or buffer is, before any GPU object exists.

use serde::{Deserialize, Serialize};
use wgpu_types::{BufferUsages, TextureFormat};

use crate::condition::Condition;
use crate::handle::ResourceId;

/// A texture's width and height, fixed or relative to the graph's output size.
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Size {
    /// Exactly this many texels.
    Absolute(u32, u32),
    /// The output size times this scale, rounded down (at least 1 texel when the scale is
    /// positive). `Relative(1.0)` is the output size.
    Relative(f32),
}

impl Default for Size {
    fn default() -> Self {
        Size::Relative(1.0)
    }
}

impl Size {
    /// Width and height for an output of `output` texels. A zero or non-finite scale,
    /// or an empty output, resolves to 0, which validation reports as a zero-sized
    /// texture; a small scale of a real output keeps at least one texel.
    pub fn resolve(self, output: (u32, u32)) -> (u32, u32) {
        match self {
            Size::Absolute(w, h) => (w, h),
            Size::Relative(s) if s.is_finite() && s > 0.0 => {
                let scale = |v: u32| match v {
                    0 => 0,
                    v => ((v as f64 * s as f64).floor() as u32).max(1),
                };
                (scale(output.0), scale(output.1))
            }
            Size::Relative(_) => (0, 0),
        }
    }
}

/// Everything the graph needs to know to create a texture, except its usages, which the
/// compiler derives from the passes that access it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TextureDesc {
    /// The format passes are written for; a fallback or conditional format may replace
    /// it in a plan ([`PlannedResource::texture`](crate::PlannedResource::texture) says
    /// which was chosen).
    pub format: TextureFormat,
    /// Used instead of `format` on devices that cannot make `format` with this sample
    /// count (`depth32float-stencil8` needs a feature, say). Plugins must accept both, so
    /// the fallback should be of the same kind (aspects and sample type).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fallback: Option<TextureFormat>,
    /// Formats that depend on the compiled features: the first entry whose condition
    /// holds replaces `format` and `fallback`. A pipeline states what its passes need
    /// (`depth32float-stencil8` with reversed-Z for any scene) and what suffices where
    /// the scene allows it (`depth24plus-stencil8` under `shallow_depth`); the plan says
    /// which was chosen and why. Unlike a fallback, it may be another kind of format
    /// (a depth format where a raster writes the texture, a color one where a compute
    /// pass stores it): each pass accepts the formats it may meet where it runs
    /// ([`formats_where`](Self::formats_where)), or is an error naming them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub format_if: Vec<(Condition, TextureFormat)>,
    /// Width and height, fixed or relative to the output size compiled for.
    #[serde(default)]
    pub size: Size,
    /// Samples per texel: 1, or 4 for MSAA (others as the device's formats allow).
    #[serde(default = "one")]
    pub samples: u32,
    /// Mip levels, at least 1.
    #[serde(default = "one")]
    pub mips: u32,
    /// Array layers, at least 1 (6 for a cube map's faces).
    #[serde(default = "one")]
    pub layers: u32,
}

fn one() -> u32 {
    1
}

impl TextureDesc {
    /// A single-sampled, single-mip texture the size of the output.
    pub fn new(format: TextureFormat) -> Self {
        Self {
            format,
            fallback: None,
            format_if: Vec::new(),
            size: Size::Relative(1.0),
            samples: 1,
            mips: 1,
            layers: 1,
        }
    }
    /// See [`TextureDesc::fallback`].
    pub fn or(mut self, fallback: TextureFormat) -> Self {
        self.fallback = Some(fallback);
        self
    }
    /// See [`TextureDesc::format_if`]: adds a format used where `condition` holds and
    /// no earlier one's does.
    pub fn format_if(mut self, condition: Condition, format: TextureFormat) -> Self {
        self.format_if.push((condition, format));
        self
    }
    /// The formats the texture may have: `format`, the fallback, then the conditional
    /// formats. Passes must accept each.
    pub fn formats(&self) -> impl Iterator<Item = TextureFormat> + '_ {
        std::iter::once(self.format)
            .chain(self.fallback)
            .chain(self.format_if.iter().map(|&(_, f)| f))
    }

    /// The formats the texture may have in plans where `condition` holds (a pass's: what
    /// that pass must accept): a conditional format whose condition `condition` excludes
    /// is never chosen there, and one whose condition it implies is always chosen unless
    /// an earlier one is, so neither `format`, its fallback nor any later one is.
    pub fn formats_where(&self, condition: Option<&Condition>) -> Vec<TextureFormat> {
        let mut formats = Vec::new();
        for (chosen_if, format) in &self.format_if {
            if condition.is_some_and(|holds| holds.excludes(chosen_if)) {
                continue;
            }
            formats.push(*format);
            if condition.is_some_and(|holds| holds.implies(chosen_if)) {
                return formats;
            }
        }
        // No conditional format is certain: the declared ones may stay.
        formats.splice(0..0, std::iter::once(self.format).chain(self.fallback));
        formats
    }
    /// This description with [`size`](Self::size) set.
    pub fn size(mut self, size: Size) -> Self {
        self.size = size;
        self
    }
    /// This description with [`samples`](Self::samples) set.
    pub fn samples(mut self, samples: u32) -> Self {
        self.samples = samples;
        self
    }
    /// This description with [`mips`](Self::mips) set.
    pub fn mips(mut self, mips: u32) -> Self {
        self.mips = mips;
        self
    }
    /// This description with [`layers`](Self::layers) set.
    pub fn layers(mut self, layers: u32) -> Self {
        self.layers = layers;
        self
    }

    /// Bytes the texture occupies at `extent`: every mip, layer and sample. Compressed
    /// formats count whole blocks, as a mip smaller than a block still takes one.
    ///
    ///
    /// Any description is counted, also one validation refuses (a texture a condition
    /// drops is still described in the plan): from mip 32 on every mip is one block, and
    /// sizes past `u64` saturate.
    pub fn bytes(&self, extent: (u32, u32)) -> u64 {
        let block = texel_bytes(self.format);
        let (bw, bh) = self.format.block_dimensions();
        let shifted = self.mips.min(32);
        let one_block = u64::from(self.mips - shifted) * block;
        (0..shifted)
            .map(|m| {
                let w = (extent.0 >> m).max(1).div_ceil(bw) as u64;
                let h = (extent.1 >> m).max(1).div_ceil(bh) as u64;
                w.saturating_mul(h).saturating_mul(block)
            })
            .fold(one_block, u64::saturating_add)
            .saturating_mul(self.layers as u64)
            .saturating_mul(self.samples as u64)
    }
}

/// Bytes per texel block (per texel for uncompressed formats), counting both aspects of
/// combined depth-stencil formats as a driver typically lays them out (D24S8 and D32S8
/// take 4 and 8 bytes).
pub fn texel_bytes(format: TextureFormat) -> u64 {
    match format {
        TextureFormat::Depth24PlusStencil8 | TextureFormat::Depth24Plus => 4,
        TextureFormat::Depth32FloatStencil8 => 8,
        f => f
            .block_copy_size(None)
            .or_else(|| f.block_copy_size(Some(wgpu_types::TextureAspect::DepthOnly)))
            .unwrap_or(4) as u64,
    }
}

/// The WebGPU name of a format (`rgba16float`), the spelling graph files use.
pub(crate) fn format_name(format: TextureFormat) -> String {
    ron::to_string(&format)
        .map(|s| s.trim_matches('"').to_owned())
        .unwrap_or_else(|_| format!("{format:?}"))
}

/// Whether passes written for one format can use the other: same aspects, same sample
/// type.
pub(crate) fn same_kind(a: TextureFormat, b: TextureFormat) -> bool {
    a.has_depth_aspect() == b.has_depth_aspect()
        && a.has_stencil_aspect() == b.has_stencil_aspect()
        && a.sample_type(None, None) == b.sample_type(None, None)
}

/// The resolved description of a texture.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize)]
pub struct TextureShape {
    /// The format chosen for the plan: the declared one, its fallback or a conditional
    /// one.
    pub format: TextureFormat,
    /// Width of mip 0 in texels, resolved against the output size.
    pub width: u32,
    /// Height of mip 0 in texels.
    pub height: u32,
    /// Samples per texel.
    pub samples: u32,
    /// Mip levels.
    pub mips: u32,
    /// Array layers.
    pub layers: u32,
}

impl TextureShape {
    /// Bytes a texture of this shape occupies ([`TextureDesc::bytes`]).
    pub fn bytes(&self) -> u64 {
        TextureDesc::new(self.format)
            .samples(self.samples)
            .mips(self.mips)
            .layers(self.layers)
            .bytes((self.width, self.height))
    }
}

/// A buffer's size and any usages the graph cannot see from pass accesses (for example
/// `MAP_READ` on a readback buffer).
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BufferDesc {
    /// Bytes, plus `per_sample` for each of `samples` samples of each pixel of the
    /// output.
    pub size: u64,
    /// Bytes per sample of each pixel of the graph's output: a buffer that holds
    /// something per pixel or sample (a software rasteriser's samples, per-pixel lists)
    /// follows the output as a `Relative` texture does. 0 for a fixed size. Compiling
    /// settles it: the compiled graph's buffers have their size in bytes and
    /// `per_sample` 0 (the plan's passes still count it in their stored bytes per
    /// sample).
    #[serde(default)]
    pub per_sample: u64,
    /// Samples per pixel of a buffer sized per sample.
    #[serde(default = "one")]
    pub samples: u32,
    /// Usages added to those the passes' accesses imply, for uses outside the graph
    /// (`MAP_READ` for a readback, say).
    #[serde(default = "BufferUsages::empty")]
    pub extra_usage: BufferUsages,
}

impl BufferDesc {
    /// A buffer of `size` bytes whatever the output size.
    pub fn new(size: u64) -> Self {
        Self {
            size,
            per_sample: 0,
            samples: 1,
            extra_usage: BufferUsages::empty(),
        }
    }

    /// `per_sample` bytes for each of `samples` samples of each pixel of the output.
    pub fn per_sample(per_sample: u64, samples: u32) -> Self {
        Self {
            per_sample,
            samples,
            ..Self::new(0)
        }
    }

    /// The size in bytes for an output of `(width, height)` (saturating: validation
    /// rejects what exceeds the device's limit).
    pub fn bytes(&self, (width, height): (u32, u32)) -> u64 {
        let samples = u64::from(width) * u64::from(height) * u64::from(self.samples);
        self.per_sample
            .saturating_mul(samples)
            .saturating_add(self.size)
    }
}

/// Who owns a resource and how long it lives.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Origin {
    /// Created by the graph from its pool; contents undefined before the first write.
    Transient,
    /// Owned by the engine and bound at execution; version 0 holds the engine's contents
    /// and the final version is kept.
    Imported,
    /// The previous frame's contents of the graph-owned texture `of` (its history): this
    /// frame's final version of `of` is what the next frame reads here. Passes only read
    /// it (version 0); it is defined anywhere in the frame, because the executor keeps it
    /// and `of` in two textures of their own, never shared with other resources, and swaps
    /// them after each frame. The first frame, and the first after a resize, a change of
    /// plan or [`Executor::reset_history`](crate::gpu::Executor::reset_history), reads
    /// zeros, and the passes can tell ([`FrameResources::history_reset`]).
    ///
    /// [`FrameResources::history_reset`]: crate::gpu::FrameResources::history_reset
    History {
        /// The resource whose previous contents this is.
        of: ResourceId,
    },
}

impl Origin {
    /// The resource whose previous frame's contents a history resource holds.
    pub fn history_of(self) -> Option<ResourceId> {
        match self {
            Origin::History { of } => Some(of),
            Origin::Transient | Origin::Imported => None,
        }
    }
}

/// A resource's description, by kind.
#[derive(Clone, Debug, PartialEq)]
pub enum ResourceDesc {
    /// A texture.
    Texture(TextureDesc),
    /// A buffer.
    Buffer(BufferDesc),
}

/// A declared resource.
#[derive(Clone, Debug)]
pub struct ResourceNode {
    /// The name it was declared with: what messages, plans and
    /// [`Imports`](crate::gpu::Imports) by name use.
    pub name: String,
    /// What it is, before compiling resolves sizes and formats.
    pub desc: ResourceDesc,
    /// Who owns it: the graph's pool or the engine.
    pub origin: Origin,
    /// Exported: the final version outlives the frame (readback, history). Exports are
    /// culling roots, like imports.
    pub exported: bool,
    /// The resource exists only where this holds for the compiled features.
    pub condition: Option<Condition>,
    /// Versions handed out so far; the next write creates `versions`.
    pub(crate) versions: u32,
}

impl ResourceNode {
    /// The description when the resource is a texture.
    pub fn texture(&self) -> Option<&TextureDesc> {
        match &self.desc {
            ResourceDesc::Texture(t) => Some(t),
            ResourceDesc::Buffer(_) => None,
        }
    }
    /// The description when the resource is a buffer.
    pub fn buffer(&self) -> Option<&BufferDesc> {
        match &self.desc {
            ResourceDesc::Buffer(b) => Some(b),
            ResourceDesc::Texture(_) => None,
        }
    }
    /// Kept past the graph's last pass: its final contents matter to someone outside.
    pub fn is_root(&self) -> bool {
        self.exported || self.origin == Origin::Imported
    }
}
