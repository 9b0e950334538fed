//! Validation: everything that would make wgpu reject the graph, or make it read garbage,
//! reported before any GPU work with the pass and resource named.

use crate::access::{Access, Aspect, AspectAccess, BufferRole, Role, TextureRole};
use crate::error::GraphError;
use crate::graph::Graph;
use crate::pass::{PassKind, PassNode, Workgroup};
use crate::profile::{color_bytes_per_sample, DeviceProfile};
use crate::resource::{format_name, same_kind, Origin, ResourceDesc, TextureShape};

use super::conditions::Conditioned;
use super::versions::Versions;

/// Checks every texture and buffer description against the profile. Dropped resources
/// are not in this graph and are not checked; a texture whose every user was dropped
/// (`declared` says who uses it) is checked as a description, not against the device.
pub(super) fn resources(
    declared: &Graph,
    conditioned: &Conditioned,
    shapes: &[Option<TextureShape>],
    versions: &Versions,
    profile: &DeviceProfile,
    errors: &mut Vec<GraphError>,
) {
    let carried = super::history::carried(&conditioned.graph);
    let kept = (0..shapes.len()).filter(|&r| !conditioned.resource_dropped(r));
    for r in kept {
        let (resource, shape) = (&conditioned.graph.resources[r], &shapes[r]);
        let name = || resource.name.clone();
        let invalid = |what: String| GraphError::InvalidResource {
            resource: resource.name.clone(),
            what,
        };
        match (&resource.desc, shape) {
            (ResourceDesc::Texture(t), Some(s)) => {
                if let Some(fallback) = t.fallback.filter(|&f| !same_kind(f, t.format)) {
                    errors.push(invalid(format!(
                        "fallback {} is not the same kind of format as {} (aspects and \
                         sample type must agree, since passes are written for both)",
                        format_name(fallback),
                        format_name(t.format)
                    )));
                }
                if s.width == 0 || s.height == 0 {
                    errors.push(GraphError::ZeroSize {
                        resource: name(),
                        width: s.width,
                        height: s.height,
                    });
                }
                let max_mips = 32 - s.width.max(s.height).leading_zeros();
                if s.mips == 0 || s.layers == 0 {
                    errors.push(invalid("mip and layer counts must be at least 1".into()));
                } else if s.mips > max_mips && max_mips > 0 {
                    errors.push(invalid(format!(
                        "{}x{} has at most {max_mips} mips, {} were asked for",
                        s.width, s.height, s.mips
                    )));
                }
                if s.samples > 1 && s.mips > 1 {
                    errors.push(invalid("a multisampled texture has exactly one mip".into()));
                }
                if s.samples > 1 && s.layers > 1 {
                    errors.push(invalid(
                        "a multisampled texture has exactly one layer".into(),
                    ));
                }
                // A texture whose every user a condition dropped is never made for these
                // features: whether this device could make it does not matter (a file's
                // branch for other devices may use one that only they can make, such as
                // a depth buffer at 2x, which lavapipe cannot).
                let unmade = versions.users[r].is_empty()
                    && declared
                        .passes
                        .iter()
                        .any(|p| p.accesses.iter().any(|a| a.resource.index() == r));
                if !unmade {
                    device_misfits(&resource.name, s, profile, errors);
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
        // An import holds the engine's contents; a graph-owned resource holds nothing
        // until a pass writes it, so exporting it unwritten hands out garbage.
        // A history's source unwritten is the history's error (`history::check`).
        if resource.exported
            && resource.origin == Origin::Transient
            && resource.versions == 1
            && carried[r].is_none()
        {
            errors.push(invalid(
                "is exported, but no pass writes it, so its contents would be undefined".into(),
            ));
        }
    }
}

/// What `profile` cannot make of a texture of shape `s`, named `resource`.
fn device_misfits(
    resource: &str,
    s: &TextureShape,
    profile: &DeviceProfile,
    errors: &mut Vec<GraphError>,
) {
    let invalid = |what: String| GraphError::InvalidResource {
        resource: resource.to_owned(),
        what,
    };
    let max = profile.limits.max_texture_dimension_2d;
    if s.width > max || s.height > max {
        errors.push(GraphError::TooLarge {
            resource: resource.to_owned(),
            width: s.width,
            height: s.height,
            max,
            profile: profile.name.clone(),
        });
    }
    let missing = s.format.required_features() - profile.features;
    if !missing.is_empty() {
        errors.push(invalid(format!(
            "{} needs {missing}, which {} lacks",
            format_name(s.format),
            profile.name
        )));
    }
    if s.layers > profile.limits.max_texture_array_layers {
        errors.push(invalid(format!(
            "{} layers exceed the limit of {} on {}",
            s.layers, profile.limits.max_texture_array_layers, profile.name
        )));
    }
    if !profile.supports_samples(s.format, s.samples) {
        let supported = profile.sample_counts(s.format);
        errors.push(GraphError::UnsupportedSampleCount {
            resource: resource.to_owned(),
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

/// Checks every pass's accesses: roles its kind allows, data that exists, formats that fit
/// their roles, and render-pass attachment rules. Dropped passes are not checked.
pub(super) fn passes(
    conditioned: &Conditioned,
    shapes: &[Option<TextureShape>],
    versions: &Versions,
    profile: &DeviceProfile,
    errors: &mut Vec<GraphError>,
) {
    let graph = &conditioned.graph;
    let kept = (0..graph.passes.len()).filter(|&p| !conditioned.pass_dropped(p));
    for pass in kept.map(|p| &graph.passes[p]) {
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
            check.binding_fits(access, errors);
        }
        check.no_conflicts(errors);
        if pass.kind == PassKind::Render {
            check.attachments(errors);
        }
        for workgroup in &pass.workgroups {
            check.workgroup(workgroup, errors);
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
    /// The compute limits a workgroup needs: its memory, its invocations and each
    /// dimension of its size.
    fn workgroup(&self, workgroup: &Workgroup, errors: &mut Vec<GraphError>) {
        let limits = &self.profile.limits;
        let [x, y, z] = workgroup.size;
        let invocations = u64::from(x) * u64::from(y) * u64::from(z);
        let mut fail = |what: String| {
            errors.push(GraphError::WorkgroupLimit {
                pass: self.pass.name.clone(),
                entry: workgroup.entry.clone(),
                what,
                profile: self.profile.name.clone(),
            })
        };
        if workgroup.memory_bytes > limits.max_compute_workgroup_storage_size {
            fail(format!(
                "uses {} bytes of workgroup memory, more than the limit of {}",
                workgroup.memory_bytes, limits.max_compute_workgroup_storage_size
            ));
        }
        if invocations > u64::from(limits.max_compute_invocations_per_workgroup) {
            fail(format!(
                "runs {invocations} invocations per workgroup ({x}x{y}x{z}), more than the \
                 limit of {}",
                limits.max_compute_invocations_per_workgroup
            ));
        }
        let dims = [
            ("x", x, limits.max_compute_workgroup_size_x),
            ("y", y, limits.max_compute_workgroup_size_y),
            ("z", z, limits.max_compute_workgroup_size_z),
        ];
        for (axis, size, max) in dims.into_iter().filter(|(_, size, max)| size > max) {
            fail(format!(
                "has a workgroup size of {size} in {axis}, more than the limit of {max}"
            ));
        }
    }

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
        // Version 0 of an import is the engine's contents, of a history the last frame's.
        let given = self.graph.resources[access.resource.index()].origin != Origin::Transient;
        if versions.writer((access.resource, v)).is_none() && !(v == 0 && given) {
            errors.push(GraphError::ReadBeforeWrite {
                pass: self.pass.name.clone(),
                resource: self.name(access),
            });
        }
    }

    /// A buffer bound as a uniform or storage buffer must fit the device's binding limit,
    /// which is smaller than its largest buffer (128 MiB against 256 MiB by default):
    /// otherwise creating the bind group fails on the device.
    fn binding_fits(&self, access: &Access, errors: &mut Vec<GraphError>) {
        let resource = &self.graph.resources[access.resource.index()];
        let (Role::Buffer(role), ResourceDesc::Buffer(buffer)) = (access.role, &resource.desc)
        else {
            return;
        };
        let limits = &self.profile.limits;
        let (max, limit) = match role {
            BufferRole::Uniform => (
                limits.max_uniform_buffer_binding_size,
                "max_uniform_buffer_binding_size",
            ),
            BufferRole::Storage { .. } => (
                limits.max_storage_buffer_binding_size,
                "max_storage_buffer_binding_size",
            ),
            _ => return,
        };
        if buffer.size > max {
            errors.push(GraphError::BindingTooLarge {
                pass: self.pass.name.clone(),
                resource: resource.name.clone(),
                size: buffer.size,
                role: access.role.describe(),
                max,
                limit,
                profile: self.profile.name.clone(),
            });
        }
    }

    fn format_fits(&self, access: &Access, errors: &mut Vec<GraphError>) {
        let (Role::Texture(role), Some(shape)) = (access.role, self.shape(access)) else {
            return;
        };
        if let Some(why) = self.role_misfit(role, &shape) {
            errors.push(GraphError::FormatRole {
                pass: self.pass.name.clone(),
                resource: self.name(access),
                format: format_name(shape.format),
                role: access.role.describe(),
                why,
            });
        }
    }

    /// Why a texture of `shape` cannot serve in `role`, if it cannot.
    fn role_misfit(&self, role: TextureRole, shape: &TextureShape) -> Option<String> {
        let f = shape.format;
        let profile = &self.profile.name;
        match role {
            TextureRole::Color { .. } | TextureRole::Resolve { .. } => {
                if f.is_depth_stencil_format() {
                    Some("it is a depth-stencil format".into())
                } else if !self.profile.can_render(f) {
                    Some(format!("it is not renderable on {profile}"))
                } else {
                    None
                }
            }
            TextureRole::DepthStencil { depth, stencil } => {
                if !f.is_depth_stencil_format() {
                    Some("it is not a depth-stencil format".into())
                } else {
                    aspect_misfit(stencil, f.has_stencil_aspect(), "stencil")
                        .or_else(|| aspect_misfit(depth, f.has_depth_aspect(), "depth"))
                }
            }
            TextureRole::Sampled { aspect } => match aspect {
                Aspect::DepthOnly | Aspect::StencilOnly if !f.is_depth_stencil_format() => {
                    Some("only depth-stencil formats have depth or stencil aspects".into())
                }
                Aspect::DepthOnly if !f.has_depth_aspect() => {
                    Some("the format has no depth aspect".into())
                }
                Aspect::StencilOnly if !f.has_stencil_aspect() => {
                    Some("the format has no stencil aspect".into())
                }
                Aspect::All if f.is_combined_depth_stencil_format() => Some(
                    "sample one aspect of a combined depth-stencil format \
                     (Aspect::DepthOnly or Aspect::StencilOnly)"
                        .into(),
                ),
                _ => None,
            },
            TextureRole::Storage { read, write } => {
                if !self.profile.can_store(f) {
                    Some(format!("it is not a storage format on {profile}"))
                } else if shape.samples > 1 {
                    Some("it is multisampled".into())
                } else if !self.profile.storage_access(f, read, write) {
                    let access = match (read, write) {
                        (true, true) => "read-write",
                        (true, false) => "read-only",
                        _ => "write-only",
                    };
                    Some(format!(
                        "it does not support {access} storage access on {profile}"
                    ))
                } else {
                    None
                }
            }
            TextureRole::CopySrc | TextureRole::CopyDst => None,
        }
    }

    /// One resource in two incompatible roles in the same pass. The one combination wgpu
    /// allows is a depth-stencil attachment read-only in both aspects plus sampling.
    /// Passes declare a handful of accesses, so a scan of the earlier ones beats a map.
    fn no_conflicts(&self, errors: &mut Vec<GraphError>) {
        let accesses = &self.pass.accesses;
        for (i, access) in accesses.iter().enumerate() {
            let Some(first) = accesses[..i].iter().find(|a| a.resource == access.resource) else {
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
                    let read_only = !depth.writes() && !stencil.writes();
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
        let mut depth_stencil: Option<&Access> = None;
        let mut resolved: Vec<(u32, &Access)> = Vec::new();
        for access in &self.pass.accesses {
            let Some(shape) = self.shape(access) else {
                continue;
            };
            match access.role {
                Role::Texture(TextureRole::Color { .. }) => {
                    colors.push((access, shape));
                    all.push((access, shape));
                }
                Role::Texture(TextureRole::DepthStencil { .. }) => {
                    if let Some(first) = depth_stencil {
                        errors.push(GraphError::TwoDepthStencil {
                            pass: pass(),
                            first: self.name(first),
                            second: self.name(access),
                        });
                    }
                    depth_stencil.get_or_insert(access);
                    all.push((access, shape));
                }
                Role::Texture(TextureRole::Resolve { location }) => {
                    let source = colors.get(location as usize).copied();
                    let earlier = resolved.iter().find(|(l, _)| *l == location);
                    match (source, earlier) {
                        (Some((color, _)), Some(&(_, first))) => {
                            errors.push(GraphError::BadResolve {
                                pass: pass(),
                                resource: self.name(access),
                                why: format!(
                                    "\"{}\" already resolves into \"{}\"",
                                    self.name(color),
                                    self.name(first)
                                ),
                            })
                        }
                        _ => self.resolve(access, shape, source, errors),
                    }
                    resolved.push((location, access));
                }
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
        let bytes = color_bytes_per_sample(colors.iter().map(|(_, shape)| shape.format));
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

/// Why an aspect access does not fit a format that has (`present`) or lacks the aspect.
fn aspect_misfit<T>(access: AspectAccess<T>, present: bool, aspect: &str) -> Option<String> {
    match access {
        AspectAccess::Absent if present => Some(format!(
            "the format has a {aspect} aspect; attach it read-only instead"
        )),
        a if a.writes() && !present => Some(format!("the format has no {aspect} aspect to write")),
        _ => None,
    }
}

fn describe_extent(s: &TextureShape) -> String {
    format!("{}x{} with {} sample(s)", s.width, s.height, s.samples)
}
