//! Graph errors. Every message names the pass and the resource involved, so that a RON
//! loader can point at both and an engine log reads without a debugger.

use thiserror::Error;

/// Something wrong with a graph, found while declaring or compiling it (no GPU involved).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum GraphError {
    #[error("pass \"{pass}\" reads \"{resource}\", which no pass writes")]
    ReadBeforeWrite { pass: String, resource: String },

    #[error(
        "passes \"{first}\" and \"{second}\" both write over version {version} of \"{resource}\"; \
         a version has one writer (write through the handle \"{first}\" returned)"
    )]
    ConflictingWriters {
        first: String,
        second: String,
        resource: String,
        version: u32,
    },

    #[error("pass \"{pass}\" uses \"{resource}\", which belongs to another graph")]
    ForeignHandle { pass: String, resource: String },

    #[error("{kind} pass \"{pass}\" cannot use \"{resource}\" as a {role}")]
    RoleNotAllowed {
        pass: String,
        kind: String,
        role: &'static str,
        resource: String,
    },

    #[error("pass \"{pass}\" uses \"{resource}\" both as a {first} and as a {second}")]
    UsageConflict {
        pass: String,
        resource: String,
        first: &'static str,
        second: &'static str,
    },

    #[error(
        "pass \"{pass}\" samples depth-stencil texture \"{resource}\" while writing it; \
         attach it read-only in both aspects to sample it in the same pass"
    )]
    SampledWhileWritable { pass: String, resource: String },

    #[error("texture \"{resource}\" is zero-sized ({width}x{height})")]
    ZeroSize {
        resource: String,
        width: u32,
        height: u32,
    },

    #[error("buffer \"{resource}\" has size 0")]
    ZeroSizedBuffer { resource: String },

    #[error("\"{resource}\": {what}")]
    InvalidResource { resource: String, what: String },

    #[error("pass \"{pass}\": compute entry point \"{entry}\" {what} on {profile}")]
    WorkgroupLimit {
        pass: String,
        entry: String,
        what: String,
        profile: String,
    },

    #[error(
        "texture \"{resource}\" ({width}x{height}) exceeds the maximum dimension {max} of {profile}"
    )]
    TooLarge {
        resource: String,
        width: u32,
        height: u32,
        max: u32,
        profile: String,
    },

    #[error(
        "texture \"{resource}\": {format} does not support {samples}x multisampling on {profile} \
         (supported: {supported})"
    )]
    UnsupportedSampleCount {
        resource: String,
        format: String,
        samples: u32,
        supported: String,
        profile: String,
    },

    #[error("pass \"{pass}\": \"{resource}\" ({format}) cannot be a {role}: {why}")]
    FormatRole {
        pass: String,
        resource: String,
        format: String,
        role: &'static str,
        why: String,
    },

    /// A buffer larger than the device binds in its role (the whole buffer is bound).
    #[error(
        "pass \"{pass}\": buffer \"{resource}\" ({size} bytes) is bound as a {role}, but \
         {profile} binds at most {max} bytes there ({limit}); make it smaller or split it"
    )]
    BindingTooLarge {
        pass: String,
        resource: String,
        size: u64,
        role: &'static str,
        max: u64,
        limit: &'static str,
        profile: String,
    },

    #[error(
        "pass \"{pass}\": color attachments ({resources}) take {bytes} bytes per sample, over \
         the limit of {limit} on {profile}"
    )]
    ColorBytesPerSample {
        pass: String,
        resources: String,
        bytes: u32,
        limit: u32,
        profile: String,
    },

    #[error(
        "pass \"{pass}\" has {count} color attachments, over the limit of {limit} on {profile}"
    )]
    TooManyColorAttachments {
        pass: String,
        count: u32,
        limit: u32,
        profile: String,
    },

    #[error(
        "pass \"{pass}\": attachment \"{resource}\" is {this}, but \"{other}\" is {that}; the \
         attachments of one pass must agree in size and sample count"
    )]
    AttachmentMismatch {
        pass: String,
        resource: String,
        this: String,
        other: String,
        that: String,
    },

    #[error("pass \"{pass}\" resolves into \"{resource}\": {why}")]
    BadResolve {
        pass: String,
        resource: String,
        why: String,
    },

    #[error("render pass \"{pass}\" has no attachment")]
    NoAttachment { pass: String },

    #[error(
        "render pass \"{pass}\" attaches both \"{first}\" and \"{second}\" as depth-stencil; \
         a render pass has one depth-stencil attachment"
    )]
    TwoDepthStencil {
        pass: String,
        first: String,
        second: String,
    },

    #[error(
        "pass \"{pass}\": condition \"{condition}\" names feature \"{feature}\", which the \
         graph does not declare (declared: {declared})"
    )]
    UnknownPassFeature {
        pass: String,
        condition: String,
        feature: String,
        declared: String,
    },

    #[error(
        "resource \"{resource}\": condition \"{condition}\" names feature \"{feature}\", \
         which the graph does not declare (declared: {declared})"
    )]
    UnknownResourceFeature {
        resource: String,
        condition: String,
        feature: String,
        declared: String,
    },

    #[error(
        "resource \"{resource}\": the condition \"{condition}\" of a conditional format names \
         feature \"{feature}\", which the graph does not declare (declared: {declared})"
    )]
    UnknownFormatFeature {
        resource: String,
        condition: String,
        feature: String,
        declared: String,
    },

    #[error(
        "pass \"{pass}\" uses \"{resource}\", which is dropped ({why}); give \"{pass}\" a \
         condition that implies the resource's"
    )]
    UsesDroppedResource {
        pass: String,
        resource: String,
        why: String,
    },

    #[error(
        "pass \"{reader}\" reads \"{resource}\" as pass \"{dropped}\" writes it, but \
         \"{dropped}\" is dropped ({why}); give \"{reader}\" a condition that implies \
         \"{dropped}\"'s, or write \"{resource}\" in a pass that stays"
    )]
    DroppedWriter {
        reader: String,
        dropped: String,
        resource: String,
        why: String,
    },

    #[error(
        "output \"{resource}\" is written by pass \"{dropped}\", which is dropped ({why}); \
         give \"{resource}\" the same condition"
    )]
    DroppedOutput {
        resource: String,
        dropped: String,
        why: String,
    },

    #[error(
        "cycle: passes {} must each run before the other (through {})",
        quote_list(passes),
        quote_list(resources)
    )]
    Cycle {
        passes: Vec<String>,
        /// Every resource whose versions order one pass of the cycle against another.
        resources: Vec<String>,
    },
}

fn quote_list(names: &[String]) -> String {
    names
        .iter()
        .map(|n| format!("\"{n}\""))
        .collect::<Vec<_>>()
        .join(", ")
}

impl GraphError {
    /// The pass the error is about, when there is one.
    pub fn pass(&self) -> Option<&str> {
        use GraphError::*;
        match self {
            ReadBeforeWrite { pass, .. }
            | ForeignHandle { pass, .. }
            | RoleNotAllowed { pass, .. }
            | UsageConflict { pass, .. }
            | SampledWhileWritable { pass, .. }
            | FormatRole { pass, .. }
            | BindingTooLarge { pass, .. }
            | ColorBytesPerSample { pass, .. }
            | TooManyColorAttachments { pass, .. }
            | AttachmentMismatch { pass, .. }
            | BadResolve { pass, .. }
            | NoAttachment { pass }
            | TwoDepthStencil { pass, .. }
            | UnknownPassFeature { pass, .. }
            | UsesDroppedResource { pass, .. }
            | WorkgroupLimit { pass, .. } => Some(pass),
            ConflictingWriters { second, .. } => Some(second),
            DroppedWriter { reader, .. } => Some(reader),
            Cycle { passes, .. } => passes.first().map(String::as_str),
            ZeroSize { .. }
            | ZeroSizedBuffer { .. }
            | InvalidResource { .. }
            | TooLarge { .. }
            | UnsupportedSampleCount { .. }
            | UnknownResourceFeature { .. }
            | UnknownFormatFeature { .. }
            | DroppedOutput { .. } => None,
        }
    }

    /// The resource the error is about, when there is one.
    pub fn resource(&self) -> Option<&str> {
        use GraphError::*;
        match self {
            ReadBeforeWrite { resource, .. }
            | ConflictingWriters { resource, .. }
            | ForeignHandle { resource, .. }
            | RoleNotAllowed { resource, .. }
            | UsageConflict { resource, .. }
            | SampledWhileWritable { resource, .. }
            | ZeroSize { resource, .. }
            | ZeroSizedBuffer { resource }
            | InvalidResource { resource, .. }
            | TooLarge { resource, .. }
            | UnsupportedSampleCount { resource, .. }
            | FormatRole { resource, .. }
            | BindingTooLarge { resource, .. }
            | AttachmentMismatch { resource, .. }
            | BadResolve { resource, .. }
            | UnknownResourceFeature { resource, .. }
            | UnknownFormatFeature { resource, .. }
            | UsesDroppedResource { resource, .. }
            | DroppedWriter { resource, .. }
            | DroppedOutput { resource, .. } => Some(resource),
            Cycle { resources, .. } => resources.first().map(String::as_str),
            TwoDepthStencil { second, .. } => Some(second),
            ColorBytesPerSample { .. }
            | TooManyColorAttachments { .. }
            | WorkgroupLimit { .. }
            | NoAttachment { .. }
            | UnknownPassFeature { .. } => None,
        }
    }
}

/// All the errors one compile found, in the order found.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{}", self.0.iter().map(|e| e.to_string()).collect::<Vec<_>>().join("\n"))]
pub struct GraphErrors(pub Vec<GraphError>);
