//! Usage derivation: every resource gets exactly the usages its live accesses need, so a
//! texture is never created with flags that cost memory or compression for nothing.

use wgpu_types::{BufferUsages, TextureUsages};

use crate::graph::Graph;
use crate::handle::PassId;
use crate::plan::{Load, Ops, Store};
use crate::profile::DeviceProfile;
use crate::resource::Origin;

use super::cull::Live;
use super::load_store::Attachments;
use super::versions::Versions;

pub(super) struct Usages {
    pub texture: Vec<TextureUsages>,
    pub buffer: Vec<BufferUsages>,
}

/// Exported resources also get `COPY_SRC`, because the one thing an export promises is
/// that its contents can be read after the frame.
pub(super) fn derive(
    graph: &Graph,
    versions: &Versions,
    live: &Live,
    attachments: &[Attachments],
    profile: &DeviceProfile,
) -> Usages {
    let mut texture = vec![TextureUsages::empty(); graph.resources.len()];
    let mut buffer = vec![BufferUsages::empty(); graph.resources.len()];
    for (i, pass) in graph.passes.iter().enumerate() {
        if !live.pass(PassId(i as u32)) {
            continue;
        }
        for access in &pass.accesses {
            texture[access.resource.index()] |= access.role.texture_usage();
            buffer[access.resource.index()] |= access.role.buffer_usage();
        }
    }
    for (r, resource) in graph.resources.iter().enumerate() {
        if let Some(desc) = resource.buffer() {
            buffer[r] |= desc.extra_usage;
        }
        if resource.exported {
            match resource.texture() {
                Some(_) => texture[r] |= TextureUsages::COPY_SRC,
                None => buffer[r] |= BufferUsages::COPY_SRC,
            }
        }
    }
    if profile.transient_attachments {
        for (r, usage) in texture.iter_mut().enumerate() {
            if never_leaves_its_pass(graph, versions, live, attachments, r) {
                *usage |= TextureUsages::TRANSIENT_ATTACHMENT;
            }
        }
    }
    Usages { texture, buffer }
}

/// A graph-owned attachment used by one live pass only, cleared there and discarded at its
/// end (typically a multisampled target resolved in the same pass): its memory can stay on
/// chip. wgpu allows `TRANSIENT_ATTACHMENT` only with `RENDER_ATTACHMENT`, a clear and a
/// discard. Culled passes do not count: they never run.
fn never_leaves_its_pass(
    graph: &Graph,
    versions: &Versions,
    live: &Live,
    attachments: &[Attachments],
    r: usize,
) -> bool {
    let resource = &graph.resources[r];
    let mut users = versions.users[r].iter().filter(|&&p| live.pass(p));
    let (Some(desc), Some(pass), None) = (resource.texture(), users.next(), users.next()) else {
        return false;
    };
    if resource.origin != Origin::Transient || resource.exported {
        return false;
    }
    let only_attachments = graph.passes[pass.index()]
        .accesses
        .iter()
        .filter(|a| a.resource.index() == r)
        .all(|a| a.role.is_attachment());
    let att = &attachments[pass.index()];
    let colors_ok = att
        .color
        .iter()
        .filter(|c| c.resource.index() == r)
        .all(|c| cleared_and_discarded(Some(&c.ops)));
    let is_resolve_target = att
        .color
        .iter()
        .any(|c| c.resolve_target.is_some_and(|t| t.index() == r));
    let depth_stencil_ok = match &att.depth_stencil {
        Some(ds) if ds.resource.index() == r => {
            (!desc.format.has_depth_aspect() || cleared_and_discarded(ds.depth.as_ref()))
                && (!desc.format.has_stencil_aspect() || cleared_and_discarded(ds.stencil.as_ref()))
        }
        _ => true,
    };
    only_attachments && colors_ok && depth_stencil_ok && !is_resolve_target
}

fn cleared_and_discarded<T>(ops: Option<&Ops<T>>) -> bool {
    matches!(
        ops,
        Some(Ops {
            load: Load::Clear(_),
            store: Store::Discard
        })
    )
}
