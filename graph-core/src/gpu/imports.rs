//! Binding engine-owned objects to a graph's imported resources for one execution.
//!
//! The engine keeps ownership: [`Imports`] holds clones of wgpu handles (reference
//! counted), and the executor never destroys or reuses what was imported. The graph's
//! passes write the final version into the engine's object itself.

use std::collections::HashMap;

use wgpu::TextureUsages;

use crate::explain::{buffer_usages, describe_shape, texture_usages};
use crate::graph::Graph;
use crate::handle::{Handle, ResourceId, ResourceKind};
use crate::plan::Plan;
use crate::resource::Origin;
use crate::resource::TextureShape;

/// How a binding names its resource.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ImportKey {
    /// By id, as a handle or [`Graph::resource_id`] gives it.
    Id(ResourceId),
    /// Resolved with [`Graph::resource_id`] at execution.
    Name(String),
}

impl From<ResourceId> for ImportKey {
    fn from(id: ResourceId) -> Self {
        ImportKey::Id(id)
    }
}

impl<K: ResourceKind> From<Handle<K>> for ImportKey {
    fn from(handle: Handle<K>) -> Self {
        ImportKey::Id(handle.id())
    }
}

impl From<&str> for ImportKey {
    fn from(name: &str) -> Self {
        ImportKey::Name(name.to_string())
    }
}

impl From<String> for ImportKey {
    fn from(name: String) -> Self {
        ImportKey::Name(name)
    }
}

/// An engine-owned object bound to an imported resource.
#[derive(Clone, Debug)]
pub(crate) enum Binding {
    /// The executor makes the views passes need, aspects included.
    Texture(wgpu::Texture),
    /// Used as given for every access; passes that need one aspect of a depth-stencil
    /// texture cannot use it.
    View(wgpu::TextureView),
    Buffer(wgpu::Buffer),
}

impl Binding {
    fn kind(&self) -> &'static str {
        match self {
            Binding::Texture(_) | Binding::View(_) => "texture",
            Binding::Buffer(_) => "buffer",
        }
    }
}

/// The engine's objects for one execution, by resource id, handle or name. Binding the
/// same resource twice keeps the later binding.
#[derive(Clone, Debug, Default)]
pub struct Imports {
    bindings: Vec<(ImportKey, Binding)>,
}

impl Imports {
    /// No bindings: enough for a graph that imports nothing.
    pub fn new() -> Self {
        Self::default()
    }

    /// Binds a texture; the executor creates the views (and aspect views) passes need.
    pub fn texture(
        &mut self,
        resource: impl Into<ImportKey>,
        texture: &wgpu::Texture,
    ) -> &mut Self {
        self.bind(resource.into(), Binding::Texture(texture.clone()))
    }

    /// Binds a ready-made view (a swap-chain view, say). Every access uses it as is, so
    /// no pass may sample one aspect of it.
    pub fn view(&mut self, resource: impl Into<ImportKey>, view: &wgpu::TextureView) -> &mut Self {
        self.bind(resource.into(), Binding::View(view.clone()))
    }

    /// Binds a buffer, which must be at least as large as the plan declares.
    pub fn buffer(&mut self, resource: impl Into<ImportKey>, buffer: &wgpu::Buffer) -> &mut Self {
        self.bind(resource.into(), Binding::Buffer(buffer.clone()))
    }

    fn bind(&mut self, key: ImportKey, binding: Binding) -> &mut Self {
        self.bindings.push((key, binding));
        self
    }

    /// The binding of every imported resource a live pass uses, checked against the plan:
    /// kind, format, size, sample count, mips, layers and usages.
    pub(crate) fn resolve(
        &self,
        graph: &Graph,
        plan: &Plan,
    ) -> Result<HashMap<ResourceId, Binding>, ImportError> {
        let mut bound = HashMap::new();
        for (key, binding) in &self.bindings {
            let id = match key {
                ImportKey::Id(id) => Some(*id).filter(|id| id.index() < graph.resources.len()),
                ImportKey::Name(name) => graph.resource_id(name),
            }
            .ok_or_else(|| ImportError::Unknown {
                key: match key {
                    ImportKey::Id(id) => format!("resource #{}", id.0),
                    ImportKey::Name(name) => format!("\"{name}\""),
                },
            })?;
            let node = &graph.resources[id.index()];
            if node.origin != Origin::Imported {
                return Err(ImportError::NotImported {
                    resource: node.name.clone(),
                });
            }
            let declared = if node.texture().is_some() {
                "texture"
            } else {
                "buffer"
            };
            if declared != binding.kind() {
                return Err(ImportError::WrongKind {
                    resource: node.name.clone(),
                    declared,
                    bound: binding.kind(),
                });
            }
            bound.insert(id, binding.clone());
        }
        for planned in &plan.resources {
            let Some((first, _)) = planned.lifetime else {
                continue;
            };
            if planned.origin != Origin::Imported {
                continue;
            }
            let resource = planned.name.clone();
            let Some(binding) = bound.get(&planned.id) else {
                let pass = plan.passes.get(first).map(|p| p.name.clone());
                return Err(ImportError::Missing {
                    resource,
                    pass: pass.unwrap_or_default(),
                });
            };
            match (binding, planned.texture) {
                (Binding::Texture(texture), Some(shape)) => {
                    check_texture(&resource, texture, shape, true, planned.texture_usage)?
                }
                (Binding::View(view), Some(shape)) => check_texture(
                    &resource,
                    view.texture(),
                    shape,
                    false,
                    planned.texture_usage,
                )?,
                (Binding::Buffer(buffer), None) => {
                    let needed = planned.buffer_size.unwrap_or(0);
                    if buffer.size() < needed {
                        return Err(ImportError::BufferSize {
                            resource,
                            size: buffer.size(),
                            needed,
                        });
                    }
                    let missing = planned.buffer_usage - buffer.usage();
                    if !missing.is_empty() {
                        return Err(ImportError::Usage {
                            resource,
                            missing: buffer_usages(missing),
                        });
                    }
                }
                // Kinds were matched against the declaration above.
                _ => {}
            }
        }
        Ok(bound)
    }
}

/// The engine's texture must be what the graph declared, with at least the usages the
/// plan derived. A view's mips and layers are its own business: only its texture's
/// format, size and sample count are checked.
fn check_texture(
    resource: &str,
    texture: &wgpu::Texture,
    shape: TextureShape,
    whole: bool,
    usage: TextureUsages,
) -> Result<(), ImportError> {
    let found = TextureShape {
        format: texture.format(),
        width: texture.width(),
        height: texture.height(),
        samples: texture.sample_count(),
        mips: if whole {
            texture.mip_level_count()
        } else {
            shape.mips
        },
        layers: if whole {
            texture.depth_or_array_layers()
        } else {
            shape.layers
        },
    };
    if found != shape {
        return Err(ImportError::Shape {
            resource: resource.to_string(),
            expected: describe_shape(&shape),
            found: describe_shape(&found),
        });
    }
    // Transient memory is the graph's choice for its own textures, never asked of the engine.
    let missing = (usage - TextureUsages::TRANSIENT_ATTACHMENT) - texture.usage();
    if !missing.is_empty() {
        return Err(ImportError::Usage {
            resource: resource.to_string(),
            missing: texture_usages(missing),
        });
    }
    Ok(())
}

/// A binding that does not fit the graph or plan.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ImportError {
    /// A pass of the plan uses an imported resource that the imports do not bind.
    #[error(
        "imported resource \"{resource}\" is used by pass \"{pass}\" but was not bound; bind \
         it with Imports::texture, Imports::view or Imports::buffer"
    )]
    Missing {
        /// The imported resource, by name.
        resource: String,
        /// The pass, by name.
        pass: String,
    },

    /// The imports bind a name or id the graph does not declare.
    #[error("Imports binds {key}, which the graph does not declare")]
    Unknown {
        /// The name (quoted) or id bound.
        key: String,
    },

    /// The imports bind a resource the graph creates itself.
    #[error(
        "Imports binds \"{resource}\", which the graph creates itself; only resources declared \
         with import_texture or import_buffer can be bound"
    )]
    NotImported {
        /// The imported resource, by name.
        resource: String,
    },

    /// A texture bound to a buffer resource, or the other way round.
    #[error("\"{resource}\" is declared as a {declared}, but a {bound} was bound to it")]
    WrongKind {
        /// The imported resource, by name.
        resource: String,
        /// What the graph declares: "texture" or "buffer".
        declared: &'static str,
        /// What was bound.
        bound: &'static str,
    },

    /// A bound texture's format, size, sample count, mips or layers differ from the plan's.
    #[error("imported texture \"{resource}\" is {found}, but the graph declares {expected}")]
    Shape {
        /// The imported resource, by name.
        resource: String,
        /// The plan's shape, described.
        expected: String,
        /// The bound texture's shape, described.
        found: String,
    },

    /// A bound object lacks usages the plan's passes need.
    #[error("imported \"{resource}\" lacks usages the graph needs: {missing}")]
    Usage {
        /// The imported resource, by name.
        resource: String,
        /// The usages it lacks.
        missing: String,
    },

    /// A bound buffer is smaller than the plan needs.
    #[error("imported buffer \"{resource}\" has {size} bytes, but the graph declares {needed}")]
    BufferSize {
        /// The imported resource, by name.
        resource: String,
        /// The bound buffer's bytes.
        size: u64,
        /// The bytes the plan declares.
        needed: u64,
    },

    /// A pass samples one aspect of a depth-stencil texture bound as a view (the executor
    /// cannot make an aspect view of a view).
    #[error(
        "pass \"{pass}\" samples the {aspect} aspect of \"{resource}\", which was bound as a \
         view; bind the texture (Imports::texture) so the executor can make aspect views"
    )]
    ViewAspect {
        /// The pass, by name.
        pass: String,
        /// The imported resource, by name.
        resource: String,
        /// "depth" or "stencil".
        aspect: &'static str,
    },
}
