//! Random graphs: a recipe drawn by proptest, declared through the public builder.

use std::collections::HashSet;

use proptest::prelude::*;
use rgraph_core::types::TextureFormat;
use rgraph_core::{
    Aspect, AspectAccess, BufferDesc, BufferHandle, BufferRole, ColorLoad, Graph, GraphBuilder,
    PassBuilder, Role, Size, TextureDesc, TextureHandle,
};

/// A random graph. A careful recipe makes mostly valid graphs, so that plans get checked;
/// a sloppy one also makes every kind of mistake, so that errors come out cleanly.
#[derive(Clone, Debug)]
pub struct Recipe {
    sloppy: bool,
    resources: Vec<ResourceSpec>,
    passes: Vec<PassSpec>,
}

#[derive(Clone, Debug)]
enum ResourceSpec {
    Texture {
        format: TextureFormat,
        size: Size,
        samples: u32,
        imported: bool,
        exported: bool,
    },
    Buffer {
        size: u64,
        imported: bool,
        exported: bool,
    },
}

#[derive(Clone, Debug)]
struct PassSpec {
    kind: Kind,
    side_effect: bool,
    accesses: Vec<AccessSpec>,
}

#[derive(Clone, Debug)]
enum Kind {
    Render,
    Compute,
    Transfer,
}

/// One access: to which resource, in which role, through a stale handle (when it only
/// reads, or in sloppy recipes) and in a role that does not fit (sloppy recipes only).
#[derive(Clone, Debug)]
struct AccessSpec {
    resource: usize,
    role: usize,
    stale: bool,
    any_role: bool,
    depth: AspectAccess<f32>,
    stencil: AspectAccess<u32>,
}

/// Careful recipes give every texture one sample count, so that attachments fit together.
pub fn recipe() -> impl Strategy<Value = Recipe> {
    (any::<bool>(), prop_oneof![3 => Just(1), 1 => Just(4)]).prop_flat_map(|(sloppy, samples)| {
        (
            prop::collection::vec(resource(sloppy, samples), 2..6),
            prop::collection::vec(pass(), 1..16),
        )
            .prop_map(move |(resources, passes)| Recipe {
                sloppy,
                resources,
                passes,
            })
    })
}

fn resource(sloppy: bool, samples: u32) -> impl Strategy<Value = ResourceSpec> {
    let format = prop_oneof![
        4 => Just(TextureFormat::Rgba8Unorm),
        2 => Just(TextureFormat::Rgba16Float),
        1 => Just(TextureFormat::R32Float),
        2 => Just(TextureFormat::Depth24PlusStencil8),
        1 => Just(TextureFormat::Depth32Float),
    ];
    let odd = if sloppy { 1 } else { 0 };
    let size = prop_oneof![
        10 => Just(Size::Absolute(64, 64)),
        odd => Just(Size::Absolute(32, 64)),
        odd => Just(Size::Relative(1.0)),
        odd => Just(Size::Absolute(0, 4)),
    ];
    let samples = match sloppy {
        true => prop_oneof![10 => Just(1), 2 => Just(4), 1 => Just(3)].boxed(),
        false => Just(samples).boxed(),
    };
    let imported = prop::bool::weighted(0.5);
    let exported = prop::bool::weighted(0.2);
    let texture = (format, size, samples, imported, exported).prop_map(
        |(format, size, samples, imported, exported)| ResourceSpec::Texture {
            format,
            size,
            samples,
            imported,
            exported,
        },
    );
    let buffer_size = prop_oneof![10 => Just(256u64), 10 => Just(4096), odd => Just(0)];
    let buffer = (buffer_size, imported, exported).prop_map(|(size, imported, exported)| {
        ResourceSpec::Buffer {
            size,
            imported,
            exported,
        }
    });
    prop_oneof![4 => texture, 1 => buffer]
}

fn aspect<T: Clone + std::fmt::Debug + 'static>(
    clear: T,
) -> impl Strategy<Value = AspectAccess<T>> {
    prop_oneof![
        Just(AspectAccess::ReadOnly),
        Just(AspectAccess::Clear(clear)),
        Just(AspectAccess::Load),
    ]
}

fn pass() -> impl Strategy<Value = PassSpec> {
    let kind = prop_oneof![
        4 => Just(Kind::Render),
        2 => Just(Kind::Compute),
        1 => Just(Kind::Transfer),
    ];
    let access = (
        any::<usize>(),
        any::<usize>(),
        prop::bool::weighted(0.3),
        prop::bool::weighted(0.05),
        aspect(1.0f32),
        aspect(0u32),
    )
        .prop_map(
            |(resource, role, stale, any_role, depth, stencil)| AccessSpec {
                resource,
                role,
                stale,
                any_role,
                depth,
                stencil,
            },
        );
    (
        kind,
        prop::bool::weighted(0.15),
        prop::collection::vec(access, 1..5),
    )
        .prop_map(|(kind, side_effect, accesses)| PassSpec {
            kind,
            side_effect,
            accesses,
        })
}

#[derive(Copy, Clone, PartialEq)]
enum AnyHandle {
    Texture(TextureHandle),
    Buffer(BufferHandle),
}

#[derive(Copy, Clone)]
enum TextureUse {
    ColorClear,
    ColorBlend,
    Resolve,
    DepthStencil,
    DepthStencilClear,
    Sampled,
    SampledDepth,
    StorageRead,
    StorageWrite,
    StorageReadWrite,
    CopySrc,
    CopyDst,
}

use TextureUse::*;

const ALL_TEXTURE_USES: [TextureUse; 12] = [
    ColorClear,
    ColorBlend,
    Resolve,
    DepthStencil,
    DepthStencilClear,
    Sampled,
    SampledDepth,
    StorageRead,
    StorageWrite,
    StorageReadWrite,
    CopySrc,
    CopyDst,
];

/// The texture uses that fit a pass kind and a format, repeated where they should be more
/// common: with `fresh`, only those that need no earlier contents; with `attach`, only
/// attachments, which a render pass needs one of.
fn fitting_texture_uses(
    kind: &Kind,
    format: TextureFormat,
    samples: u32,
    fresh: bool,
    attach: bool,
) -> Vec<TextureUse> {
    let depth = format.is_depth_stencil_format();
    let storage = samples == 1;
    let read_write = storage && format == TextureFormat::R32Float;
    let uses: &[TextureUse] = match (kind, depth, fresh) {
        (Kind::Render, true, false) => &[DepthStencil, DepthStencil, SampledDepth],
        (Kind::Render, true, true) => &[DepthStencilClear],
        (Kind::Render, false, false) => &[ColorClear, ColorClear, ColorBlend, Sampled, StorageRead],
        (Kind::Render, false, true) => &[ColorClear],
        (Kind::Compute, true, false) => &[SampledDepth],
        (Kind::Compute, false, false) => &[Sampled, StorageRead, StorageWrite, StorageReadWrite],
        (Kind::Compute, false, true) => &[StorageWrite],
        (Kind::Transfer, _, false) => &[CopySrc, CopyDst],
        (Kind::Transfer, _, true) => &[CopyDst],
        (Kind::Compute, true, true) => &[],
    };
    uses.iter()
        .copied()
        .filter(|u| !matches!(u, StorageRead | StorageWrite) || storage)
        .filter(|u| !matches!(u, StorageReadWrite) || read_write)
        .filter(|u| {
            !attach
                || matches!(
                    u,
                    ColorClear | ColorBlend | DepthStencil | DepthStencilClear
                )
        })
        .collect()
}

const READ: BufferRole = BufferRole::Storage {
    read: true,
    write: false,
};
const WRITE: BufferRole = BufferRole::Storage {
    read: false,
    write: true,
};
const READ_WRITE: BufferRole = BufferRole::Storage {
    read: true,
    write: true,
};

fn fitting_buffer_roles(kind: &Kind, fresh: bool) -> &'static [BufferRole] {
    match (kind, fresh) {
        (Kind::Render, false) => &[
            BufferRole::Vertex,
            BufferRole::Index,
            BufferRole::Uniform,
            READ,
        ],
        (Kind::Render, true) => &[],
        (Kind::Compute, false) => &[
            BufferRole::Uniform,
            BufferRole::Indirect,
            READ,
            WRITE,
            READ_WRITE,
        ],
        (Kind::Compute, true) => &[WRITE],
        (Kind::Transfer, false) => &[BufferRole::CopySrc, BufferRole::CopyDst],
        (Kind::Transfer, true) => &[BufferRole::CopyDst],
    }
}

const ALL_BUFFER_ROLES: [BufferRole; 9] = [
    BufferRole::Vertex,
    BufferRole::Index,
    BufferRole::Uniform,
    BufferRole::Indirect,
    READ,
    WRITE,
    READ_WRITE,
    BufferRole::CopySrc,
    BufferRole::CopyDst,
];

impl Recipe {
    /// Declares the graph. Each access goes through the newest handle of its resource or,
    /// when stale, an older one, so rewrites of old versions and reads of them both occur.
    pub fn build(&self) -> Graph {
        let mut g = GraphBuilder::new();
        let mut handles: Vec<Vec<AnyHandle>> = self
            .resources
            .iter()
            .enumerate()
            .map(|(i, spec)| vec![declare(&mut g, i, spec)])
            .collect();
        for (i, spec) in self.passes.iter().enumerate() {
            let name = format!("p{i}");
            let mut p = match spec.kind {
                Kind::Render => g.add_render_pass(name),
                Kind::Compute => g.add_compute_pass(name),
                Kind::Transfer => g.add_transfer_pass(name),
            };
            if spec.side_effect {
                p.side_effect();
            }
            let mut pass = PassState::default();
            for (n, a) in spec.accesses.iter().enumerate() {
                // Careful render passes start with an attachment.
                let attach = !self.sloppy && n == 0 && matches!(spec.kind, Kind::Render);
                if let Some((r, written)) =
                    self.access(&mut p, spec, a, &handles, &mut pass, attach)
                {
                    handles[r].push(written);
                }
            }
        }
        for (spec, history) in self.resources.iter().zip(&handles) {
            match (spec.exported(), history[history.len() - 1]) {
                (true, AnyHandle::Texture(t)) => g.export(t),
                (true, AnyHandle::Buffer(b)) => g.export(b),
                (false, _) => {}
            }
        }
        g.build()
    }

    /// Declares one access; returns the resource and its new handle when it wrote one.
    fn access(
        &self,
        p: &mut PassBuilder<'_>,
        spec: &PassSpec,
        a: &AccessSpec,
        handles: &[Vec<AnyHandle>],
        pass: &mut PassState,
        attach: bool,
    ) -> Option<(usize, AnyHandle)> {
        let candidates: Vec<usize> = (0..handles.len())
            .filter(|&r| !attach || matches!(self.resources[r], ResourceSpec::Texture { .. }))
            .collect();
        let r = *candidates.get(a.resource % candidates.len().max(1))?;
        // Careful recipes touch a resource once per pass and never read what nothing
        // wrote yet; sloppy ones pick any role.
        if !pass.touched.insert(r) && !self.sloppy {
            return None;
        }
        let history = &handles[r];
        let resource = &self.resources[r];
        let fresh = !self.sloppy && history.len() == 1 && !resource.imported();
        let any_role = a.any_role && self.sloppy;
        let written = match (history[0], resource) {
            (
                AnyHandle::Texture(_),
                &ResourceSpec::Texture {
                    format, samples, ..
                },
            ) => {
                let uses = match any_role {
                    true => ALL_TEXTURE_USES.to_vec(),
                    false => fitting_texture_uses(&spec.kind, format, samples, fresh, attach),
                };
                let u = *uses.get(a.role % uses.len().max(1))?;
                if matches!(u, DepthStencil | DepthStencilClear)
                    && std::mem::replace(&mut pass.depth, true)
                    && !self.sloppy
                {
                    return None;
                }
                let reads_only = matches!(u, Sampled | SampledDepth | StorageRead | CopySrc);
                let AnyHandle::Texture(t) = self.handle(history, resource, a, reads_only) else {
                    unreachable!()
                };
                let out = texture_access(p, t, format, u, a, pass.last_color, self.sloppy);
                if matches!(u, ColorClear | ColorBlend) {
                    pass.last_color = Some(out);
                }
                (AnyHandle::Texture(t), AnyHandle::Texture(out))
            }
            (AnyHandle::Buffer(_), _) => {
                let roles = match any_role {
                    true => &ALL_BUFFER_ROLES[..],
                    false => fitting_buffer_roles(&spec.kind, fresh),
                };
                let role = *roles.get(a.role % roles.len().max(1))?;
                let reads_only = !Role::Buffer(role).writes();
                let AnyHandle::Buffer(b) = self.handle(history, resource, a, reads_only) else {
                    unreachable!()
                };
                (AnyHandle::Buffer(b), AnyHandle::Buffer(p.buffer(b, role)))
            }
            (AnyHandle::Texture(_), ResourceSpec::Buffer { .. }) => unreachable!(),
        };
        let (before, after) = written;
        (after != before).then_some((r, after))
    }

    /// The newest handle or, for a stale access, an older one. Careful recipes read older
    /// versions that hold contents (a valid graph may) and write only through the newest.
    fn handle(
        &self,
        history: &[AnyHandle],
        resource: &ResourceSpec,
        a: &AccessSpec,
        reads_only: bool,
    ) -> AnyHandle {
        let newest = history.len() - 1;
        let oldest = match self.sloppy || resource.imported() {
            true => 0,
            false => 1,
        };
        match a.stale && (self.sloppy || reads_only) && oldest < newest {
            true => history[oldest + a.role % (newest - oldest)],
            false => history[newest],
        }
    }
}

/// What one pass has declared so far.
#[derive(Default)]
struct PassState {
    touched: HashSet<usize>,
    depth: bool,
    last_color: Option<TextureHandle>,
}

impl ResourceSpec {
    fn imported(&self) -> bool {
        match *self {
            ResourceSpec::Texture { imported, .. } | ResourceSpec::Buffer { imported, .. } => {
                imported
            }
        }
    }

    fn exported(&self) -> bool {
        match *self {
            ResourceSpec::Texture { exported, .. } | ResourceSpec::Buffer { exported, .. } => {
                exported
            }
        }
    }
}

fn declare(g: &mut GraphBuilder, i: usize, spec: &ResourceSpec) -> AnyHandle {
    let name = format!("r{i}");
    match *spec {
        ResourceSpec::Texture {
            format,
            size,
            samples,
            imported,
            ..
        } => {
            let desc = TextureDesc::new(format).size(size).samples(samples);
            AnyHandle::Texture(if imported {
                g.import_texture(name, desc)
            } else {
                g.create_texture(name, desc)
            })
        }
        ResourceSpec::Buffer { size, imported, .. } => {
            let desc = BufferDesc::new(size);
            AnyHandle::Buffer(if imported {
                g.import_buffer(name, desc)
            } else {
                g.create_buffer(name, desc)
            })
        }
    }
}

fn texture_access(
    p: &mut PassBuilder<'_>,
    t: TextureHandle,
    format: TextureFormat,
    u: TextureUse,
    a: &AccessSpec,
    last_color: Option<TextureHandle>,
    sloppy: bool,
) -> TextureHandle {
    let stencil_clear = match format.has_stencil_aspect() {
        true => AspectAccess::Clear(0),
        false => AspectAccess::ReadOnly,
    };
    match u {
        ColorClear => p.color_output(t, ColorLoad::Clear([0.0; 4])),
        ColorBlend => p.color_output(t, ColorLoad::Load),
        Resolve => p.resolve_output(last_color.unwrap_or(t), t),
        // Careful recipes write only the stencil the format has.
        DepthStencil if !sloppy && !format.has_stencil_aspect() => {
            p.depth_stencil(t, a.depth, AspectAccess::ReadOnly)
        }
        DepthStencil => p.depth_stencil(t, a.depth, a.stencil),
        DepthStencilClear => p.depth_stencil(t, AspectAccess::Clear(1.0), stencil_clear),
        Sampled => p.sampled(t),
        SampledDepth => p.sampled_aspect(t, Aspect::DepthOnly),
        StorageRead => p.storage_read(t),
        StorageWrite => p.storage_write(t),
        StorageReadWrite => p.storage_read_write(t),
        CopySrc => p.copy_src(t),
        CopyDst => p.copy_dst(t),
    }
}
