//! Load/store inference: each attachment clears on a fresh write, loads when the pass
//! builds on earlier contents, and stores only what a later pass or the outside world
//! reads. A clear value that depends on the format ([`ByFormat`]) is resolved here,
//! against the format the compile picked.

use wgpu_types::TextureFormat;

#[cfg(doc)]
use crate::access::ByFormat;
use crate::access::{AspectAccess, ColorLoad, Role, TextureRole};
use crate::graph::Graph;
use crate::handle::{PassId, ResourceId};
use crate::pass::PassKind;
use crate::plan::{ColorAttachment, DepthStencilAttachment, Load, Ops, Store};
use crate::resource::TextureShape;

use super::cull::Live;
use super::versions::Versions;

/// The attachments of one render pass, as the executor begins it.
#[derive(Default)]
pub(super) struct Attachments {
    pub color: Vec<ColorAttachment>,
    pub depth_stencil: Option<DepthStencilAttachment>,
}

/// Attachments for every pass, indexed by pass id (empty for non-render passes).
/// `shapes` are the textures' resolved shapes, for clear values that depend on the format.
pub(super) fn infer(
    graph: &Graph,
    versions: &Versions,
    live: &Live,
    shapes: &[Option<TextureShape>],
) -> Vec<Attachments> {
    graph
        .passes
        .iter()
        .enumerate()
        .map(|(i, pass)| {
            let id = PassId(i as u32);
            if pass.kind != PassKind::Render || !live.pass(id) {
                return Attachments::default();
            }
            let store = |resource: ResourceId, written: Option<u32>| match written {
                Some(v) if is_needed_after(graph, versions, live, id, resource, v) => Store::Store,
                _ => Store::Discard,
            };
            let mut out = Attachments::default();
            for access in &pass.accesses {
                let Role::Texture(role) = access.role else {
                    continue;
                };
                let r = access.resource;
                match role {
                    TextureRole::Color { load, .. } => out.color.push(ColorAttachment {
                        resource: r,
                        ops: Ops {
                            load: match load {
                                ColorLoad::Clear(c) => Load::Clear(c),
                                ColorLoad::Load => Load::Load,
                                ColorLoad::Overwrite => Load::Overwrite,
                            },
                            store: store(r, access.written),
                        },
                        resolve_target: None,
                    }),
                    TextureRole::Resolve { location } => {
                        if let Some(color) = out.color.get_mut(location as usize) {
                            color.resolve_target = Some(r);
                        }
                    }
                    TextureRole::DepthStencil { depth, stencil } => {
                        let stored = store(r, access.written);
                        // Validation has rejected a depth-stencil role on a buffer.
                        let Some(shape) = shapes[r.index()] else {
                            continue;
                        };
                        out.depth_stencil = Some(DepthStencilAttachment {
                            resource: r,
                            depth: aspect_ops(depth, shape.format, stored),
                            stencil: aspect_ops(stencil, shape.format, stored),
                        });
                    }
                    _ => {}
                }
            }
            out
        })
        .collect()
}

fn aspect_ops<T>(access: AspectAccess<T>, format: TextureFormat, store: Store) -> Option<Ops<T>> {
    match access {
        AspectAccess::ReadOnly | AspectAccess::Absent => None,
        AspectAccess::Clear(v) => Some(Ops {
            load: Load::Clear(v),
            store,
        }),
        AspectAccess::ClearByFormat(by) => Some(Ops {
            load: Load::Clear(by.value(format)),
            store,
        }),
        AspectAccess::Load => Some(Ops {
            load: Load::Load,
            store,
        }),
        AspectAccess::Overwrite => Some(Ops {
            load: Load::Overwrite,
            store,
        }),
    }
}

/// Whether version `v` of `resource`, written by `pass`, is read by another live pass or
/// must survive the frame.
fn is_needed_after(
    graph: &Graph,
    versions: &Versions,
    live: &Live,
    pass: PassId,
    resource: ResourceId,
    v: u32,
) -> bool {
    let read_later = versions
        .readers((resource, v))
        .iter()
        .any(|&reader| reader != pass && live.pass(reader));
    let kept = graph.resources[resource.index()].is_root() && v == versions.final_version(resource);
    read_later || kept
}
