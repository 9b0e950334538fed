//! Reflection: what an entry point binds and what it passes between stages, as plain data
//! that plugins compare with the resources a graph file binds.

use std::fmt;

use naga::{
    AddressSpace, Binding, ImageClass, ImageDimension, ScalarKind, StorageAccess, TypeInner,
};
use wgpu_types::TextureFormat;

use super::wgsl::Shader;
use crate::resource::format_name;

/// A pipeline stage whose entry points plugins look up.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Stage {
    /// `@vertex`.
    Vertex,
    /// `@fragment`.
    Fragment,
    /// `@compute`.
    Compute,
}

impl Stage {
    fn naga(self) -> naga::ShaderStage {
        match self {
            Stage::Vertex => naga::ShaderStage::Vertex,
            Stage::Fragment => naga::ShaderStage::Fragment,
            Stage::Compute => naga::ShaderStage::Compute,
        }
    }
}

impl fmt::Display for Stage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Stage::Vertex => "vertex",
            Stage::Fragment => "fragment",
            Stage::Compute => "compute",
        })
    }
}

/// What reading a texture binding returns.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum SampleKind {
    /// `texture_2d<f32>`: filterable or not, as the format decides.
    Float,
    /// `texture_depth_*`: depth values, comparable.
    Depth,
    /// `texture_2d<i32>`.
    Sint,
    /// `texture_2d<u32>` (the stencil aspect reads as one).
    Uint,
}

/// The number type of a stage input or output.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Number {
    /// `f32` components.
    Float,
    /// `i32` components.
    Sint,
    /// `u32` components.
    Uint,
}

impl fmt::Display for Number {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Number::Float => "f32",
            Number::Sint => "i32",
            Number::Uint => "u32",
        })
    }
}

/// What a binding is, as the shader declares it. Only 2D, non-array textures are bound by
/// graph files; anything else is [`BindingKind::Unsupported`].
#[derive(Clone, Debug, PartialEq)]
pub enum BindingKind {
    /// `var<uniform>` of `size` bytes.
    Uniform {
        /// The uniform's size in bytes, as WGSL lays it out.
        size: u64,
    },
    /// `var<storage, read>` or `var<storage, read_write>`.
    Storage {
        /// `read_write` rather than `read`.
        writable: bool,
    },
    /// `sampler` or `sampler_comparison`.
    Sampler {
        /// `sampler_comparison` rather than `sampler`.
        comparison: bool,
    },
    /// `texture_2d<T>`, `texture_multisampled_2d<T>`, `texture_depth_2d`,
    /// `texture_depth_multisampled_2d`.
    Texture {
        /// What sampling it returns.
        sample: SampleKind,
        /// A `texture_multisampled_2d` or `texture_depth_multisampled_2d`.
        multisampled: bool,
    },
    /// `texture_storage_2d<format, access>`.
    StorageTexture {
        /// The texel format the shader declares.
        format: TextureFormat,
        /// The access includes `read`.
        read: bool,
        /// The access includes `write`.
        write: bool,
    },
    /// Any other binding, named as WGSL spells its type.
    Unsupported(String),
}

impl fmt::Display for BindingKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BindingKind::Uniform { size } => write!(f, "var<uniform> of {size} bytes"),
            BindingKind::Storage { writable: false } => f.write_str("var<storage, read>"),
            BindingKind::Storage { writable: true } => f.write_str("var<storage, read_write>"),
            BindingKind::Sampler { comparison: false } => f.write_str("sampler"),
            BindingKind::Sampler { comparison: true } => f.write_str("sampler_comparison"),
            BindingKind::Texture {
                sample,
                multisampled,
            } => {
                let ms = if *multisampled { "multisampled_" } else { "" };
                match sample {
                    SampleKind::Depth => write!(f, "texture_depth_{ms}2d"),
                    SampleKind::Float => write!(f, "texture_{ms}2d<f32>"),
                    SampleKind::Sint => write!(f, "texture_{ms}2d<i32>"),
                    SampleKind::Uint => write!(f, "texture_{ms}2d<u32>"),
                }
            }
            BindingKind::StorageTexture {
                format,
                read,
                write,
            } => {
                let access = match (read, write) {
                    (true, true) => "read_write",
                    (true, false) => "read",
                    _ => "write",
                };
                write!(f, "texture_storage_2d<{}, {access}>", format_name(*format))
            }
            BindingKind::Unsupported(wgsl) => f.write_str(wgsl),
        }
    }
}

/// One resource binding an entry point uses.
#[derive(Clone, Debug, PartialEq)]
pub struct ShaderBinding {
    /// `@group(n)`.
    pub group: u32,
    /// `@binding(n)`.
    pub binding: u32,
    /// The variable's name in the shader.
    pub name: String,
    /// What the shader declares there.
    pub kind: BindingKind,
}

/// A user-defined stage input or output (`@location(n)`).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Io {
    /// `@location(n)`.
    pub location: u32,
    /// The component type.
    pub number: Number,
    /// 1 for a scalar, else the vector size.
    pub components: u32,
}

/// One entry point of a [`Shader`].
#[derive(Copy, Clone, Debug)]
pub struct Entry<'s> {
    shader: &'s Shader,
    index: usize,
}

impl Shader {
    /// The entry point called `name` for `stage`, if the shader has one.
    pub fn entry(&self, name: &str, stage: Stage) -> Option<Entry<'_>> {
        let index = self
            .module()
            .entry_points
            .iter()
            .position(|e| e.name == name && e.stage == stage.naga())?;
        Some(Entry {
            shader: self,
            index,
        })
    }

    /// The names of the entry points for `stage`, for messages that suggest one.
    pub fn entry_names(&self, stage: Stage) -> Vec<&str> {
        self.module()
            .entry_points
            .iter()
            .filter(|e| e.stage == stage.naga())
            .map(|e| e.name.as_str())
            .collect()
    }
}

impl Entry<'_> {
    /// The entry point's name.
    pub fn name(&self) -> &str {
        &self.point().name
    }

    /// The bindings this entry point uses, by group and binding. Bindings the shader
    /// declares but this entry point never touches are left out, as wgpu's layout
    /// derivation leaves them out.
    pub fn bindings(&self) -> Vec<ShaderBinding> {
        let module = self.shader.module();
        let uses = self.shader.info().get_entry_point(self.index);
        let mut bindings: Vec<ShaderBinding> = module
            .global_variables
            .iter()
            .filter(|(handle, _)| !uses[*handle].is_empty())
            .filter_map(|(_, var)| {
                let at = var.binding.as_ref()?;
                Some(ShaderBinding {
                    group: at.group,
                    binding: at.binding,
                    name: var.name.clone().unwrap_or_default(),
                    kind: binding_kind(module, var),
                })
            })
            .collect();
        bindings.sort_by_key(|b| (b.group, b.binding));
        bindings
    }

    /// `@workgroup_size` of a compute entry point (1, 1, 1 for other stages).
    pub fn workgroup_size(&self) -> [u32; 3] {
        self.point().workgroup_size.map(|n| n.max(1))
    }

    /// The bytes of workgroup memory this entry point uses: every `var<workgroup>` it
    /// touches, each rounded up to 16 bytes as WebGPU counts them against
    /// `max_compute_workgroup_storage_size`.
    pub fn workgroup_memory(&self) -> u32 {
        let module = self.shader.module();
        let uses = self.shader.info().get_entry_point(self.index);
        let mut layouter = naga::proc::Layouter::default();
        // The module passed validation, so every type has a layout.
        if layouter.update(module.to_ctx()).is_err() {
            return 0;
        }
        module
            .global_variables
            .iter()
            .filter(|(handle, var)| {
                var.space == AddressSpace::WorkGroup && !uses[*handle].is_empty()
            })
            .map(|(_, var)| layouter[var.ty].size.next_multiple_of(16))
            .sum()
    }

    /// What the entry point needs of a device's compute limits, for
    /// [`PassBuilder::workgroup`](crate::PassBuilder::workgroup).
    pub fn workgroup(&self) -> crate::pass::Workgroup {
        crate::pass::Workgroup {
            entry: self.name().to_owned(),
            size: self.workgroup_size(),
            memory_bytes: self.workgroup_memory(),
        }
    }

    /// The `@location` inputs, by location.
    pub fn inputs(&self) -> Vec<Io> {
        let module = self.shader.module();
        let mut io: Vec<Io> = self
            .point()
            .function
            .arguments
            .iter()
            .flat_map(|a| locations(module, a.ty, a.binding.as_ref()))
            .collect();
        io.sort_by_key(|i| i.location);
        io
    }

    /// The `@location` outputs, by location.
    pub fn outputs(&self) -> Vec<Io> {
        let module = self.shader.module();
        let mut io: Vec<Io> = self
            .point()
            .function
            .result
            .iter()
            .flat_map(|r| locations(module, r.ty, r.binding.as_ref()))
            .collect();
        io.sort_by_key(|i| i.location);
        io
    }

    fn point(&self) -> &naga::EntryPoint {
        &self.shader.module().entry_points[self.index]
    }
}

fn binding_kind(module: &naga::Module, var: &naga::GlobalVariable) -> BindingKind {
    let inner = &module.types[var.ty].inner;
    match (var.space, inner) {
        (AddressSpace::Uniform, ty) => BindingKind::Uniform {
            size: ty.size(module.to_ctx()) as u64,
        },
        (AddressSpace::Storage { access }, _) => BindingKind::Storage {
            writable: access.contains(StorageAccess::STORE),
        },
        (_, TypeInner::Sampler { comparison }) => BindingKind::Sampler {
            comparison: *comparison,
        },
        (
            _,
            TypeInner::Image {
                dim: ImageDimension::D2,
                arrayed: false,
                class,
            },
        ) => image_kind(class),
        (_, TypeInner::Image { dim, arrayed, .. }) => {
            let dim = match dim {
                ImageDimension::D1 => "1d",
                ImageDimension::D2 => "2d",
                ImageDimension::D3 => "3d",
                ImageDimension::Cube => "cube",
            };
            let array = if *arrayed { "_array" } else { "" };
            BindingKind::Unsupported(format!("texture_{dim}{array}"))
        }
        (_, TypeInner::BindingArray { .. }) => BindingKind::Unsupported("binding_array".into()),
        (_, other) => BindingKind::Unsupported(format!("{other:?}")),
    }
}

fn image_kind(class: &ImageClass) -> BindingKind {
    let sampled = |sample, multisampled| BindingKind::Texture {
        sample,
        multisampled,
    };
    match *class {
        ImageClass::Sampled { kind, multi } => match kind {
            ScalarKind::Sint => sampled(SampleKind::Sint, multi),
            ScalarKind::Uint => sampled(SampleKind::Uint, multi),
            _ => sampled(SampleKind::Float, multi),
        },
        ImageClass::Depth { multi } => sampled(SampleKind::Depth, multi),
        ImageClass::Storage { format, access } => BindingKind::StorageTexture {
            format: wgpu_naga_bridge::map_storage_format_from_naga(format),
            read: access.contains(StorageAccess::LOAD),
            write: access.contains(StorageAccess::STORE),
        },
        ImageClass::External => BindingKind::Unsupported("texture_external".into()),
    }
}

/// The `@location` values of one argument or result: itself, or its struct's members.
fn locations(
    module: &naga::Module,
    ty: naga::Handle<naga::Type>,
    binding: Option<&Binding>,
) -> Vec<Io> {
    match binding {
        Some(Binding::Location { location, .. }) => number(&module.types[ty].inner)
            .map(|(number, components)| Io {
                location: *location,
                number,
                components,
            })
            .into_iter()
            .collect(),
        Some(Binding::BuiltIn(_)) => Vec::new(),
        None => match &module.types[ty].inner {
            TypeInner::Struct { members, .. } => members
                .iter()
                .flat_map(|m| locations(module, m.ty, m.binding.as_ref()))
                .collect(),
            _ => Vec::new(),
        },
    }
}

fn number(inner: &TypeInner) -> Option<(Number, u32)> {
    let (scalar, components) = match inner {
        TypeInner::Scalar(s) => (s, 1),
        TypeInner::Vector { size, scalar } => (scalar, *size as u32),
        _ => return None,
    };
    let number = match scalar.kind {
        ScalarKind::Float => Number::Float,
        ScalarKind::Sint => Number::Sint,
        ScalarKind::Uint => Number::Uint,
        _ => return None,
    };
    Some((number, components))
}
