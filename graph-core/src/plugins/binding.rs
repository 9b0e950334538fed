//! Shader bindings declared in graph files, checked against the shader by reflection
//! before any GPU exists: every binding the entry point uses must be declared, every
//! declared binding must be used, and each must fit what the shader wants.

use serde::Deserialize;
use wgpu_types::{
    BindingType, BufferBindingType, SamplerBindingType, StorageTextureAccess, TextureFormat,
    TextureSampleType, TextureViewDimension,
};

use crate::access::{Aspect, BufferRole};
use crate::builder::PassBuilder;
use crate::file::{PluginError, Slots};
use crate::handle::{Buffer, BufferHandle, Texture, TextureHandle};
use crate::resource::format_name;
use crate::resource::{ResourceDesc, TextureDesc};
use crate::shader::{BindingKind, Entry, SampleKind, Shader, ShaderBinding};

/// One binding of a shader, as a graph file declares it (`group` defaults to 0):
///
/// ```ron
/// bindings: [
///     Slot(binding: 0, slot: "src"),         // the resource in slot "src"
///     Sampler(binding: 1, filter: Linear),   // a sampler the plugin creates
///     Uniform(group: 1, binding: 0, values: [1.0, 0.5, 0.25, 1.0]),
/// ]
/// ```
///
/// A slot's role follows the shader: a sampled texture or read-only buffer is read (the
/// slot is an input); a writable storage texture or buffer is written (an output slot,
/// which modifies when it is also an input). `values` (finite) are the uniform's bytes as `f32`s,
/// padding included, so their count times 4 must equal the shader's uniform size.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum BindingDecl {
    /// A texture or buffer from one of the pass's slots, bound where the shader declares
    /// it.
    Slot {
        /// `@group(n)`; 0 when left out.
        #[serde(default)]
        group: u32,
        /// `@binding(n)`.
        binding: u32,
        /// The slot's name, as the pass's `inputs` and `outputs` use it.
        slot: String,
    },
    /// A sampler the plugin creates (clamped to edge) with `filter`.
    Sampler {
        /// `@group(n)`; 0 when left out.
        #[serde(default)]
        group: u32,
        /// `@binding(n)`.
        binding: u32,
        /// Magnification and minification filter.
        #[serde(default)]
        filter: Filter,
    },
    /// A uniform buffer the plugin fills with `values`.
    Uniform {
        /// `@group(n)`; 0 when left out.
        #[serde(default)]
        group: u32,
        /// `@binding(n)`.
        binding: u32,
        /// The uniform's bytes as `f32`s, padding included.
        values: Vec<f32>,
    },
}

impl BindingDecl {
    fn at(&self) -> (u32, u32) {
        match *self {
            BindingDecl::Slot { group, binding, .. }
            | BindingDecl::Sampler { group, binding, .. }
            | BindingDecl::Uniform { group, binding, .. } => (group, binding),
        }
    }

    fn slot(&self) -> Option<&str> {
        match self {
            BindingDecl::Slot { slot, .. } => Some(slot),
            _ => None,
        }
    }
}

/// How a sampler filters.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
pub enum Filter {
    /// Bilinear: the format must be filterable.
    #[default]
    Linear,
    /// The nearest texel.
    Nearest,
}

/// A checked binding: its layout entry type and where its resource comes from.
#[derive(Clone, Debug)]
#[cfg_attr(not(feature = "gpu"), allow(dead_code))] // Read at execution only.
pub(crate) struct Bound {
    pub group: u32,
    pub binding: u32,
    pub ty: BindingType,
    pub source: Source,
    /// The slot bound here, if a slot is.
    pub slot: Option<String>,
}

/// Where a bound resource comes from at execution.
#[derive(Clone, Debug)]
#[cfg_attr(not(feature = "gpu"), allow(dead_code))] // Read at execution only.
pub(crate) enum Source {
    Texture(TextureHandle, Aspect),
    Buffer(BufferHandle),
    /// A sampler the plugin creates.
    Sampler(Filter),
    /// A uniform buffer the plugin creates with these bytes.
    Uniform(Vec<u8>),
}

/// Checks `decls` against what `entry` of `shader` uses and declares each slot's access
/// on `pass`. Returns the bindings sorted by group and binding.
pub(crate) fn bind(
    shader: &Shader,
    entry: &Entry<'_>,
    decls: &[BindingDecl],
    pass: &mut PassBuilder<'_>,
    slots: &mut Slots<'_>,
) -> Result<Vec<Bound>, PluginError> {
    let used = entry.bindings();
    let error = |at: (u32, u32), slot: Option<&str>, why: String| PluginError::Binding {
        shader: shader.path().to_owned(),
        group: at.0,
        binding: at.1,
        slot: slot.map(str::to_owned),
        why,
    };
    for (i, decl) in decls.iter().enumerate() {
        let twice = decls[..i].iter().find(|d| d.at() == decl.at());
        if twice.is_some() {
            return Err(error(decl.at(), decl.slot(), "is declared twice".into()));
        }
        let slot_twice = decl
            .slot()
            .filter(|s| decls[..i].iter().any(|d| d.slot() == Some(s)));
        if let Some(slot) = slot_twice {
            let why = format!("binds slot \"{slot}\", which another binding binds already");
            return Err(error(decl.at(), Some(slot), why));
        }
        if !used.iter().any(|u| (u.group, u.binding) == decl.at()) {
            let why = format!(
                "declared in the graph file, but entry point \"{}\" does not use it",
                entry.name()
            );
            return Err(error(decl.at(), decl.slot(), why));
        }
    }
    let mut bound = Vec::with_capacity(used.len());
    for wanted in &used {
        let at = (wanted.group, wanted.binding);
        let Some(decl) = decls.iter().find(|d| d.at() == at) else {
            let why = format!(
                "the shader's `{}` ({}) is not bound in the graph file",
                wanted.name, wanted.kind
            );
            return Err(error(at, None, why));
        };
        let (ty, source) =
            bind_one(decl, wanted, pass, slots).map_err(|why| error(at, decl.slot(), why))?;
        bound.push(Bound {
            group: at.0,
            binding: at.1,
            ty,
            source,
            slot: decl.slot().map(str::to_owned),
        });
    }
    Ok(bound)
}

/// Binds one declaration to what the shader wants there, or says why it cannot.
fn bind_one(
    decl: &BindingDecl,
    wanted: &ShaderBinding,
    pass: &mut PassBuilder<'_>,
    slots: &mut Slots<'_>,
) -> Result<(BindingType, Source), String> {
    let shader_wants = || format!("the shader's `{}` is {}", wanted.name, wanted.kind);
    match (decl, &wanted.kind) {
        (BindingDecl::Slot { slot, .. }, kind) => {
            bind_slot(slot, kind, pass, slots).map_err(|e| match e {
                SlotMisfit::Plugin(e) => e.to_string(),
                SlotMisfit::Shape(what) => {
                    format!("slot \"{slot}\" binds {what}, but {}", shader_wants())
                }
            })
        }
        (BindingDecl::Sampler { filter, .. }, BindingKind::Sampler { comparison: false }) => {
            let ty = match filter {
                Filter::Linear => SamplerBindingType::Filtering,
                Filter::Nearest => SamplerBindingType::NonFiltering,
            };
            Ok((BindingType::Sampler(ty), Source::Sampler(*filter)))
        }
        (BindingDecl::Uniform { values, .. }, BindingKind::Uniform { size }) => {
            // NaN and infinity in a uniform poison every result that uses it, silently.
            if let Some((i, v)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
                return Err(format!("uniform value #{i} is {v}; values must be finite"));
            }
            let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
            if bytes.len() as u64 != *size {
                return Err(format!(
                    "{} values ({} bytes) are given, but {}",
                    values.len(),
                    bytes.len(),
                    shader_wants()
                ));
            }
            Ok((uniform_type(), Source::Uniform(bytes)))
        }
        (BindingDecl::Sampler { .. }, _) => {
            Err(format!("a sampler is declared, but {}", shader_wants()))
        }
        (BindingDecl::Uniform { .. }, _) => Err(format!(
            "uniform values are declared, but {}",
            shader_wants()
        )),
    }
}

/// Why a slot cannot be bound: a slot error (missing, wrong side or kind), or a
/// resource whose shape (described) does not fit the shader.
enum SlotMisfit {
    Plugin(PluginError),
    Shape(String),
}

impl From<PluginError> for SlotMisfit {
    fn from(e: PluginError) -> Self {
        SlotMisfit::Plugin(e)
    }
}

fn bind_slot(
    slot: &str,
    kind: &BindingKind,
    pass: &mut PassBuilder<'_>,
    slots: &mut Slots<'_>,
) -> Result<(BindingType, Source), SlotMisfit> {
    let resource = slots.resource(slot).unwrap_or(slot).to_owned();
    match *kind {
        BindingKind::Texture {
            sample,
            multisampled,
        } => {
            let handle = slots.input::<Texture>(slot)?;
            let desc = texture_desc(pass, handle)?;
            // One binding for every format the texture may have where the pass runs.
            let formats = desc.formats_where(pass.condition());
            let mut bindings = formats.iter().map(|&format| sampled(format, sample));
            let fits = bindings
                .next()
                .flatten()
                .filter(|&first| bindings.all(|other| other == Some(first)))
                .filter(|_| multisampled == (desc.samples > 1));
            let Some((aspect, sample_type)) = fits else {
                return Err(SlotMisfit::Shape(describe(&resource, &desc)));
            };
            pass.sampled_aspect(handle, aspect);
            let sample_type = match sample_type {
                // Multisampled textures are never filtered.
                TextureSampleType::Float { .. } if multisampled => {
                    TextureSampleType::Float { filterable: false }
                }
                other => other,
            };
            let ty = BindingType::Texture {
                sample_type,
                view_dimension: TextureViewDimension::D2,
                multisampled,
            };
            Ok((ty, Source::Texture(handle, aspect)))
        }
        BindingKind::StorageTexture {
            format,
            read,
            write,
        } => {
            let handle = if write {
                slots.write::<Texture>(slot, |t| {
                    if t.modifies {
                        pass.storage_read_write(t.handle)
                    } else {
                        pass.storage_write(t.handle)
                    }
                })?
            } else {
                let handle = slots.input::<Texture>(slot)?;
                pass.storage_read(handle)
            };
            let desc = texture_desc(pass, handle)?;
            let formats = desc.formats_where(pass.condition());
            if formats.iter().any(|&f| f != format) || desc.samples > 1 {
                return Err(SlotMisfit::Shape(describe(&resource, &desc)));
            }
            let access = match (read, write) {
                (true, true) => StorageTextureAccess::ReadWrite,
                (true, false) => StorageTextureAccess::ReadOnly,
                _ => StorageTextureAccess::WriteOnly,
            };
            let ty = BindingType::StorageTexture {
                access,
                format,
                view_dimension: TextureViewDimension::D2,
            };
            Ok((ty, Source::Texture(handle, Aspect::All)))
        }
        BindingKind::Uniform { size } => {
            let handle = slots.input::<Buffer>(slot)?;
            let have = buffer_size(pass, handle);
            if have < size {
                let what = format!("\"{resource}\" ({have} bytes)");
                return Err(SlotMisfit::Shape(what));
            }
            pass.buffer(handle, BufferRole::Uniform);
            Ok((uniform_type(), Source::Buffer(handle)))
        }
        BindingKind::Storage { writable } => {
            let handle = if writable {
                slots.write::<Buffer>(slot, |t| {
                    let role = BufferRole::Storage {
                        read: t.modifies,
                        write: true,
                    };
                    pass.buffer(t.handle, role)
                })?
            } else {
                let handle = slots.input::<Buffer>(slot)?;
                let role = BufferRole::Storage {
                    read: true,
                    write: false,
                };
                pass.buffer(handle, role)
            };
            let ty = BindingType::Buffer {
                ty: BufferBindingType::Storage {
                    read_only: !writable,
                },
                has_dynamic_offset: false,
                min_binding_size: None,
            };
            Ok((ty, Source::Buffer(handle)))
        }
        BindingKind::Sampler { .. } | BindingKind::Unsupported(_) => {
            Err(SlotMisfit::Shape(format!("\"{resource}\"")))
        }
    }
}

/// The view aspect and layout sample type for sampling `format` as `sample`, if it can be.
fn sampled(format: TextureFormat, sample: SampleKind) -> Option<(Aspect, TextureSampleType)> {
    if format.is_depth_stencil_format() {
        let depth = format.has_depth_aspect();
        return match sample {
            SampleKind::Depth if depth => Some((Aspect::DepthOnly, TextureSampleType::Depth)),
            // WebGPU reads depth as unfilterable floats too.
            SampleKind::Float if depth => Some((
                Aspect::DepthOnly,
                TextureSampleType::Float { filterable: false },
            )),
            SampleKind::Uint if format.has_stencil_aspect() => {
                Some((Aspect::StencilOnly, TextureSampleType::Uint))
            }
            _ => None,
        };
    }
    let ty = format.sample_type(None, None)?;
    let fits = matches!(
        (sample, ty),
        (SampleKind::Float, TextureSampleType::Float { .. })
            | (SampleKind::Uint, TextureSampleType::Uint)
            | (SampleKind::Sint, TextureSampleType::Sint)
    );
    fits.then_some((Aspect::All, ty))
}

fn uniform_type() -> BindingType {
    BindingType::Buffer {
        ty: BufferBindingType::Uniform,
        has_dynamic_offset: false,
        min_binding_size: None,
    }
}

fn describe(resource: &str, desc: &TextureDesc) -> String {
    let samples = match desc.samples {
        1 => "1 sample".to_owned(),
        n => format!("{n} samples"),
    };
    format!("\"{resource}\" ({}, {samples})", format_name(desc.format))
}

/// The description of a texture handle that [`Slots`] typed as a texture.
pub(crate) fn texture_desc(
    pass: &PassBuilder<'_>,
    handle: TextureHandle,
) -> Result<TextureDesc, PluginError> {
    match &pass.resource(handle).desc {
        ResourceDesc::Texture(desc) => Ok(desc.clone()),
        ResourceDesc::Buffer(_) => Err(PluginError::Invalid(format!(
            "\"{}\" is a buffer",
            pass.resource(handle).name
        ))),
    }
}

/// The least the buffer holds: a buffer sized per sample at a 1x1 output.
fn buffer_size(pass: &PassBuilder<'_>, handle: BufferHandle) -> u64 {
    pass.resource(handle)
        .buffer()
        .map_or(0, |b| b.bytes((1, 1)))
}
