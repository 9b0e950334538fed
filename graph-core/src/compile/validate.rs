//! Validation: everything that would make wgpu reject the graph, or make it read garbage,
//! reported before any GPU work with the pass and resource named.

use std::collections::HashMap;

use wgpu_types::TextureFormat;

use crate::access::{Access, Aspect, AspectAccess, BufferRole, Role, TextureRole};
use crate::error::GraphError;
use crate::graph::Graph;
use crate::pass::{PassKind, PassNode};
use crate::plan::TextureShape;
use crate::profile::{color_target_cost, DeviceProfile};
use crate::resource::{Origin, ResourceDesc};

use super::versions::Versions;

/// Checks every texture and buffer description against the profile.
pub(super) fn resources(
    graph: &Graph,
    shapes: &[Option<TextureShape>],
    profile: &DeviceProfile,
    errors: &mut Vec<GraphError>,
) {
    for (resource, shape) in graph.resources.iter().zip(shapes) {
        let name = || resource.name.clone();
        let invalid = |what: String| GraphError::InvalidResource {
            resource: resource.name.clone(),
            what,
        };
        match (&resource.desc, shape) {
            (ResourceDesc::Texture(_), Some(s)) => {
                if s.width == 0 || s.height == 0 {
                    errors.push(GraphError::ZeroSize {
                        resource: name(),
                        width: s.width,
                        height: s.height,
                    });
                }
                let max = profile.limits.max_texture_dimension_2d;
                if s.width > max || s.height > max {
                    errors.push(GraphError::TooLarge {
                        resource: name(),
                        width: s.width,
                        height: s.height,
                        max,
                        profile: profile.name.clone(),
                    });
                }
                if s.mips == 0 || s.layers == 0 {
                    errors.push(invalid("mip and layer counts must be at least 1".into()));
                }
                if s.layers > profile.limits.max_texture_array_layers {
                    errors.push(invalid(format!(
                        "{} layers exceed the limit of {} on {}",
                        s.layers, profile.limits.max_texture_array_layers, profile.name
                    )));
                }
                if s.samples > 1 && s.mips > 1 {
                    errors.push(invalid("a multisampled texture has exactly one mip".into()));
                }
                let supported = profile.sample_counts(s.format);
                if !supported.contains(&s.samples) {
                    errors.push(GraphError::UnsupportedSampleCount {
                        resource: name(),
                        format: format_name(s.format),
                        samples: s.samples,
                        supported: supported
                            .iter()
                            .map(|n| format!("{n}x"))
                            .collect::<Vec<_>>()
                            .join(", "),
                        profile: profile.name.clone(),
                    });
                }
            }
            (ResourceDesc::Buffer(b), _) => {
                if b.size == 0 {
                    errors.push(GraphError::ZeroSizedBuffer { resource: name() });
                } else if b.size > profile.limits.max_buffer_size {
                    errors.push(invalid(format!(
                        "{} bytes exceed the buffer size limit of {} on {}",
                        b.size, profile.limits.max_buffer_size, profile.name
                    )));
                }
            }
            (ResourceDesc::Texture(_), None) => {}
        }
    }
}

/// Checks every pass's accesses: roles its kind allows, data that exists, formats that fit
/// their roles, and render-pass attachment rules.
pub(super) fn passes(
    graph: &Graph,
    shapes: &[Option<TextureShape>],
    versions: &Versions,
    profile: &DeviceProfile,
    errors: &mut Vec<GraphError>,
) {
    for pass in &graph.passes {
        let check = PassCheck {
            graph,
            pass,
            shapes,
            profile,
        };
        for access in &pass.accesses {
            check.role_allowed(access, errors);
            check.input_exists(access, versions, errors);
            check.format_fits(access, errors);
        }
        check.no_conflicts(errors);
        if pass.kind == PassKind::Render {
            check.attachments(errors);
        }
    }
}

struct PassCheck<'a> {
    graph: &'a Graph,
    pass: &'a PassNode,
    shapes: &'a [Option<TextureShape>],
    profile: &'a DeviceProfile,
}

impl PassCheck<'_> {
    fn name(&self, access: &Access) -> String {
        self.graph.resources[access.resource.index()].name.clone()
    }

    fn shape(&self, access: &Access) -> Option<TextureShape> {
        self.shapes[access.resource.index()]
    }

    fn role_allowed(&self, access: &Access, errors: &mut Vec<GraphError>) {
        use PassKind::*;
        let allowed = match (self.pass.kind, access.role) {
            (Transfer, Role::Texture(TextureRole::CopySrc | TextureRole::CopyDst)) => true,
            (Transfer, Role::Buffer(BufferRole::CopySrc | BufferRole::CopyDst)) => true,
            (Transfer, _) => false,
            (_, Role::Texture(TextureRole::CopySrc | TextureRole::CopyDst)) => false,
            (_, Role::Buffer(BufferRole::CopySrc | BufferRole::CopyDst)) => false,
            (Render, _) => true,
            (Compute, role) => {
                !role.is_attachment()
                    && !matches!(role, Role::Buffer(BufferRole::Vertex | BufferRole::Index))
            }
        };
        if !allowed {
            errors.push(GraphError::RoleNotAllowed {
                pass: self.pass.name.clone(),
                kind: self.pass.kind.to_string(),
                role: access.role.describe(),
                resource: self.name(access),
            });
        }
    }

    fn input_exists(&self, access: &Access, versions: &Versions, errors: &mut Vec<GraphError>) {
        let Some(v) = access.read_version() else {
            return;
        };
        let imported = self.graph.resources[access.resource.index()].origin == Origin::Imported;
        if !versions.writer.contains_key(&(access.resource, v)) && !(v == 0 && imported) {
            errors.push(GraphError::ReadBeforeWrite {
                pass: self.pass.name.clone(),
                resource: self.name(access),
            });
        }
    }

    fn format_fits(&self, access: &Access, errors: &mut Vec<GraphError>) {
        let (Role::Texture(role), Some(shape)) = (access.role, self.shape(access)) else {
            return;
        };
        let f = shape.format;
        let why = match role {
            TextureRole::Color { .. } | TextureRole::Resolve { .. }
                if f.is_depth_stencil_format() =>
            {
                Some("it is a depth-stencil format".to_string())
            }
            TextureRole::Color { .. } | TextureRole::Resolve { .. }
                if !self.profile.can_render(f) =>
            {
                Some(format!("it is not renderable on {}", self.profile.name))
            }
            TextureRole::DepthStencil { .. } if !f.is_depth_stencil_format() => {
                Some("it is not a depth-stencil format".to_string())
            }
            TextureRole::DepthStencil { stencil, .. }
                if stencil.writes() && !f.has_stencil_aspect() =>
            {
                Some("the format has no stencil aspect to write".to_string())
            }
            TextureRole::DepthStencil { depth, .. } if depth.writes() && !f.has_depth_aspect() => {
                Some("the format has no depth aspect to write".to_string())
            }
            TextureRole::Sampled {
                aspect: Aspect::DepthOnly | Aspect::StencilOnly,
            } if !f.is_depth_stencil_format() => {
                Some("only depth-stencil formats have depth or stencil aspects".to_string())
            }
            TextureRole::Storage { .. } if !self.profile.can_store(f) => Some(format!(
                "it is not a storage format on {}",
                self.profile.name
            )),
            _ => None,
        };
        if let Some(why) = why {
            errors.push(GraphError::FormatRole {
                pass: self.pass.name.clone(),
                resource: self.name(access),
                format: format_name(f),
                role: access.role.describe(),
                why,
            });
        }
    }

    /// One resource in two incompatible roles in the same pass. The one combination wgpu
    /// allows is a depth-stencil attachment read-only in both aspects plus sampling.
    fn no_conflicts(&self, errors: &mut Vec<GraphError>) {
        let mut first_role: HashMap<_, &Access> = HashMap::new();
        for access in &self.pass.accesses {
            let Some(first) = first_role.get(&access.resource).copied() else {
                first_role.insert(access.resource, access);
                continue;
            };
            let pair = (first.role, access.role);
            let error = match pair {
                (
                    Role::Texture(TextureRole::DepthStencil { depth, stencil }),
                    Role::Texture(TextureRole::Sampled { .. }),
                )
                | (
                    Role::Texture(TextureRole::Sampled { .. }),
                    Role::Texture(TextureRole::DepthStencil { depth, stencil }),
                ) => {
                    let read_only = matches!(
                        (depth, stencil),
                        (AspectAccess::ReadOnly, AspectAccess::ReadOnly)
                    );
                    (!read_only).then(|| GraphError::SampledWhileWritable {
                        pass: self.pass.name.clone(),
                        resource: self.name(access),
                    })
                }
                (a, b) if !a.writes() && !b.writes() => None,
                (a, b) => Some(GraphError::UsageConflict {
                    pass: self.pass.name.clone(),
                    resource: self.name(access),
                    first: a.describe(),
                    second: b.describe(),
                }),
            };
            errors.extend(error);
        }
    }

    fn attachments(&self, errors: &mut Vec<GraphError>) {
        let pass = || self.pass.name.clone();
        let mut colors: Vec<(&Access, TextureShape)> = Vec::new();
        let mut all: Vec<(&Access, TextureShape)> = Vec::new();
        for access in &self.pass.accesses {
            let Some(shape) = self.shape(access) else {
                continue;
            };
            match access.role {
                Role::Texture(TextureRole::Color { .. }) => {
                    colors.push((access, shape));
                    all.push((access, shape));
                }
                Role::Texture(TextureRole::DepthStencil { .. }) => all.push((access, shape)),
                Role::Texture(TextureRole::Resolve { location }) => self.resolve(
                    access,
                    shape,
                    colors.get(location as usize).copied(),
                    errors,
                ),
                _ => {}
            }
        }
        if all.is_empty() {
            errors.push(GraphError::NoAttachment { pass: pass() });
            return;
        }
        let (first, a) = all[0];
        for &(access, b) in &all[1..] {
            if (a.width, a.height, a.samples) != (b.width, b.height, b.samples) {
                errors.push(GraphError::AttachmentMismatch {
                    pass: pass(),
                    resource: self.name(access),
                    this: describe_extent(&b),
                    other: self.name(first),
                    that: describe_extent(&a),
                });
            }
        }
        let limits = &self.profile.limits;
        if colors.len() as u32 > limits.max_color_attachments {
            errors.push(GraphError::TooManyColorAttachments {
                pass: pass(),
                count: colors.len() as u32,
                limit: limits.max_color_attachments,
                profile: self.profile.name.clone(),
            });
        }
        let bytes = colors.iter().fold(0u32, |total, (_, shape)| {
            let (cost, align) = color_target_cost(shape.format);
            total.next_multiple_of(align.max(1)) + cost
        });
        if bytes > limits.max_color_attachment_bytes_per_sample {
            errors.push(GraphError::ColorBytesPerSample {
                pass: pass(),
                resources: colors
                    .iter()
                    .map(|(a, _)| format!("\"{}\"", self.name(a)))
                    .collect::<Vec<_>>()
                    .join(", "),
                bytes,
                limit: limits.max_color_attachment_bytes_per_sample,
                profile: self.profile.name.clone(),
            });
        }
    }

    fn resolve(
        &self,
        target: &Access,
        t: TextureShape,
        source: Option<(&Access, TextureShape)>,
        errors: &mut Vec<GraphError>,
    ) {
        let why = match source {
            None => Some(
                "the color handle it names is not a color attachment written by this pass".into(),
            ),
            Some((_, s)) if s.samples == 1 => Some(format!(
                "its source \"{}\" is not multisampled",
                self.name(source.unwrap().0)
            )),
            Some(_) if t.samples != 1 => Some(format!(
                "a resolve target must have 1 sample, it has {}",
                t.samples
            )),
            Some((_, s)) if s.format != t.format => Some(format!(
                "the formats differ ({} into {})",
                format_name(s.format),
                format_name(t.format)
            )),
            Some((_, s)) if (s.width, s.height) != (t.width, t.height) => Some(format!(
                "the sizes differ ({}x{} into {}x{})",
                s.width, s.height, t.width, t.height
            )),
            Some(_) if !self.profile.can_resolve(t.format) => Some(format!(
                "{} is not resolvable on {}",
                format_name(t.format),
                self.profile.name
            )),
            Some(_) => None,
        };
        if let Some(why) = why {
            errors.push(GraphError::BadResolve {
                pass: self.pass.name.clone(),
                resource: self.name(target),
                why,
            });
        }
    }
}

fn describe_extent(s: &TextureShape) -> String {
    format!("{}x{} with {} sample(s)", s.width, s.height, s.samples)
}

/// The WebGPU name of a format (`rgba16float`), the spelling graph files use.
pub(crate) fn format_name(format: TextureFormat) -> String {
    ron::to_string(&format)
        .map(|s| s.trim_matches('"').to_owned())
        .unwrap_or_else(|_| format!("{format:?}"))
}
