//! Graph errors. Every message names the pass and the resource involved, so that a RON
//! loader can point at both and an engine log reads without a debugger.

use thiserror::Error;

/// Something wrong with a graph, found while declaring or compiling it (no GPU involved).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum GraphError {
    /// A pass reads a version no pass writes (other than an imported resource's version
    /// 0, the engine's contents): its contents would be undefined.
    #[error("pass \"{pass}\" reads \"{resource}\", which no pass writes")]
    ReadBeforeWrite {
        /// The pass, by name.
        pass: String,
        /// The resource, by name.
        resource: String,
    },

    /// Two passes write over the same version of a resource; one of them should write
    /// through the handle the other returned.
    #[error(
        "passes \"{first}\" and \"{second}\" both write over version {version} of \"{resource}\"; \
         a version has one writer (write through the handle \"{first}\" returned)"
    )]
    ConflictingWriters {
        /// The pass declared first.
        first: String,
        /// The pass declared second.
        second: String,
        /// The resource, by name.
        resource: String,
        /// The version both write over.
        version: u32,
    },

    /// A pass was handed a handle this graph did not make (a resource or version it never
    /// handed out).
    #[error("pass \"{pass}\" uses \"{resource}\", which belongs to another graph")]
    ForeignHandle {
        /// The pass, by name.
        pass: String,
        /// The handle, as its `Debug` form shows it.
        resource: String,
    },

    /// [`PassBuilder::optional`](crate::PassBuilder::optional) (a file's `optional:`) marked
    /// what cannot be optional: a modification (an access that reads and writes the
    /// version), or none at all.
    #[error("pass \"{pass}\" marks \"{resource}\" optional, but {why}")]
    OptionalAccess {
        /// The pass, by name.
        pass: String,
        /// The resource, by name.
        resource: String,
        /// What is wrong: "the pass modifies it: only a read or a fresh write can be
        /// optional".
        why: String,
    },

    /// An access role the pass's kind cannot have: copies outside transfer passes, anything
    /// but copies in them, attachments and vertex or index buffers in compute passes.
    #[error("{kind} pass \"{pass}\" cannot use \"{resource}\" as a {role}")]
    RoleNotAllowed {
        /// The pass, by name.
        pass: String,
        /// The pass's kind: render, compute or transfer.
        kind: String,
        /// The role, as `Role::describe` names it.
        role: &'static str,
        /// The resource, by name.
        resource: String,
    },

    /// One pass accesses a resource twice, at least once writing (a color attachment that
    /// it also samples, say).
    #[error("pass \"{pass}\" uses \"{resource}\" both as a {first} and as a {second}")]
    UsageConflict {
        /// The pass, by name.
        pass: String,
        /// The resource, by name.
        resource: String,
        /// The first role, as `Role::describe` names it.
        first: &'static str,
        /// The second role.
        second: &'static str,
    },

    /// A pass samples a depth-stencil texture it also attaches with a written aspect.
    #[error(
        "pass \"{pass}\" samples depth-stencil texture \"{resource}\" while writing it; \
         attach it read-only in both aspects to sample it in the same pass"
    )]
    SampledWhileWritable {
        /// The pass, by name.
        pass: String,
        /// The resource, by name.
        resource: String,
    },

    /// A texture resolves to zero texels in a dimension (an empty output, a zero or
    /// non-finite scale).
    #[error("texture \"{resource}\" is zero-sized ({width}x{height})")]
    ZeroSize {
        /// The resource, by name.
        resource: String,
        /// Resolved width in texels.
        width: u32,
        /// Resolved height in texels.
        height: u32,
    },

    /// A buffer resolves to 0 bytes.
    #[error("buffer \"{resource}\" has size 0")]
    ZeroSizedBuffer {
        /// The resource, by name.
        resource: String,
    },

    /// A description no device can make (zero samples, mips or layers, a fallback of
    /// another kind of format, ...).
    #[error("\"{resource}\": {what}")]
    InvalidResource {
        /// The resource, by name.
        resource: String,
        /// What is wrong with it.
        what: String,
    },

    /// A compute entry point declared with `PassBuilder::workgroup` exceeds the profile's
    /// compute limits.
    #[error("pass \"{pass}\": compute entry point \"{entry}\" {what} on {profile}")]
    WorkgroupLimit {
        /// The pass, by name.
        pass: String,
        /// The entry point.
        entry: String,
        /// Which limit it exceeds, with the figures.
        what: String,
        /// The device profile's name.
        profile: String,
    },

    /// A texture is larger than the profile's `max_texture_dimension_2d`.
    #[error(
        "texture \"{resource}\" ({width}x{height}) exceeds the maximum dimension {max} of {profile}"
    )]
    TooLarge {
        /// The resource, by name.
        resource: String,
        /// Resolved width in texels.
        width: u32,
        /// Resolved height in texels.
        height: u32,
        /// The profile's maximum dimension in texels.
        max: u32,
        /// The device profile's name.
        profile: String,
    },

    /// A texture's format does not support its sample count on the profile.
    #[error(
        "texture \"{resource}\": {format} does not support {samples}x multisampling on {profile} \
         (supported: {supported})"
    )]
    UnsupportedSampleCount {
        /// The resource, by name.
        resource: String,
        /// The format, as graph files spell it.
        format: String,
        /// The sample count asked for.
        samples: u32,
        /// The sample counts the format supports there, comma-separated.
        supported: String,
        /// The device profile's name.
        profile: String,
    },

    /// A texture's format cannot be used in a role a pass declared (a storage binding of a
    /// format that is not a storage format, a depth attachment of a color format).
    #[error("pass \"{pass}\": \"{resource}\" ({format}) cannot be a {role}: {why}")]
    FormatRole {
        /// The pass, by name.
        pass: String,
        /// The resource, by name.
        resource: String,
        /// The format, as graph files spell it.
        format: String,
        /// The role, as `Role::describe` names it.
        role: &'static str,
        /// Why, in words.
        why: String,
    },

    /// A buffer larger than the device binds in its role (the whole buffer is bound).
    #[error(
        "pass \"{pass}\": buffer \"{resource}\" ({size} bytes) is bound as a {role}, but \
         {profile} binds at most {max} bytes there ({limit}); make it smaller or split it"
    )]
    BindingTooLarge {
        /// The pass, by name.
        pass: String,
        /// The resource, by name.
        resource: String,
        /// The buffer's size in bytes.
        size: u64,
        /// The role, as `Role::describe` names it.
        role: &'static str,
        /// The most bytes the device binds in that role.
        max: u64,
        /// The name of the limit (`max_storage_buffer_binding_size`, ...).
        limit: &'static str,
        /// The device profile's name.
        profile: String,
    },

    /// A render pass's color attachments exceed the profile's
    /// `max_color_attachment_bytes_per_sample`.
    #[error(
        "pass \"{pass}\": color attachments ({resources}) take {bytes} bytes per sample, over \
         the limit of {limit} on {profile}"
    )]
    ColorBytesPerSample {
        /// The pass, by name.
        pass: String,
        /// The attachments, comma-separated.
        resources: String,
        /// Their bytes per sample, as WebGPU counts them.
        bytes: u32,
        /// The device's limit.
        limit: u32,
        /// The device profile's name.
        profile: String,
    },

    /// A render pass has more color attachments than the profile's `max_color_attachments`.
    #[error(
        "pass \"{pass}\" has {count} color attachments, over the limit of {limit} on {profile}"
    )]
    TooManyColorAttachments {
        /// The pass, by name.
        pass: String,
        /// The pass's color attachments.
        count: u32,
        /// The device's limit.
        limit: u32,
        /// The device profile's name.
        profile: String,
    },

    /// Two attachments of one render pass differ in size or sample count.
    #[error(
        "pass \"{pass}\": attachment \"{resource}\" is {this}, but \"{other}\" is {that}; the \
         attachments of one pass must agree in size and sample count"
    )]
    AttachmentMismatch {
        /// The pass, by name.
        pass: String,
        /// The resource, by name.
        resource: String,
        /// Its size and samples.
        this: String,
        /// The attachment it disagrees with.
        other: String,
        /// That attachment's size and samples.
        that: String,
    },

    /// A resolve target that cannot take its color attachment's resolve (multisampled
    /// itself, another format or size, a single-sampled source, a format that cannot
    /// resolve).
    #[error("pass \"{pass}\" resolves into \"{resource}\": {why}")]
    BadResolve {
        /// The pass, by name.
        pass: String,
        /// The resource, by name.
        resource: String,
        /// Why, in words.
        why: String,
    },

    /// A render pass with neither a color nor a depth-stencil attachment.
    #[error("render pass \"{pass}\" has no attachment")]
    NoAttachment {
        /// The pass, by name.
        pass: String,
    },

    /// A render pass attaches two depth-stencil textures.
    #[error(
        "render pass \"{pass}\" attaches both \"{first}\" and \"{second}\" as depth-stencil; \
         a render pass has one depth-stencil attachment"
    )]
    TwoDepthStencil {
        /// The pass, by name.
        pass: String,
        /// The first one attached.
        first: String,
        /// The second one attached.
        second: String,
    },

    /// A pass's condition names a feature the graph did not declare (a misspelling would
    /// otherwise silently drop the pass).
    #[error(
        "pass \"{pass}\": condition \"{condition}\" names feature \"{feature}\", which the \
         graph does not declare (declared: {declared})"
    )]
    UnknownPassFeature {
        /// The pass, by name.
        pass: String,
        /// The condition, as written.
        condition: String,
        /// The undeclared feature.
        feature: String,
        /// The features the graph declares, comma-separated.
        declared: String,
    },

    /// A resource's condition names a feature the graph did not declare.
    #[error(
        "resource \"{resource}\": condition \"{condition}\" names feature \"{feature}\", \
         which the graph does not declare (declared: {declared})"
    )]
    UnknownResourceFeature {
        /// The resource, by name.
        resource: String,
        /// The condition, as written.
        condition: String,
        /// The undeclared feature.
        feature: String,
        /// The features the graph declares, comma-separated.
        declared: String,
    },

    /// A conditional format's condition names a feature the graph did not declare.
    #[error(
        "resource \"{resource}\": the condition \"{condition}\" of a conditional format names \
         feature \"{feature}\", which the graph does not declare (declared: {declared})"
    )]
    UnknownFormatFeature {
        /// The resource, by name.
        resource: String,
        /// The condition, as written.
        condition: String,
        /// The undeclared feature.
        feature: String,
        /// The features the graph declares, comma-separated.
        declared: String,
    },

    /// A pass that stays uses a resource whose condition is false for the compiled
    /// features.
    #[error(
        "pass \"{pass}\" uses \"{resource}\", which is dropped ({why}); give \"{pass}\" a \
         condition that implies the resource's"
    )]
    UsesDroppedResource {
        /// The pass, by name.
        pass: String,
        /// The resource, by name.
        resource: String,
        /// Why the resource is dropped: its condition.
        why: String,
    },

    /// A pass that stays reads a version written by a pass that is dropped, and no other
    /// pass writes that version.
    #[error(
        "pass \"{reader}\" reads \"{resource}\" as pass \"{dropped}\" writes it, but \
         \"{dropped}\" is dropped ({why}); give \"{reader}\" a condition that implies \
         \"{dropped}\"'s, or write \"{resource}\" in a pass that stays"
    )]
    DroppedWriter {
        /// The reading pass, by name.
        reader: String,
        /// The dropped pass, by name.
        dropped: String,
        /// The resource, by name.
        resource: String,
        /// Why the writer is dropped: its condition or the omission's reason.
        why: String,
    },

    /// An exported or imported resource's final version is written by a dropped pass.
    #[error(
        "output \"{resource}\" is written by pass \"{dropped}\", which is dropped ({why}); \
         give \"{resource}\" the same condition"
    )]
    DroppedOutput {
        /// The resource, by name.
        resource: String,
        /// The dropped pass, by name.
        dropped: String,
        /// Why the pass is dropped.
        why: String,
    },

    /// A pass writes a history resource: it holds the previous frame's contents of its
    /// source, which this frame only reads.
    #[error(
        "pass \"{pass}\" writes \"{resource}\", the previous frame's \"{of}\", which passes \
         only read; write \"{of}\" instead, and the next frame reads it as \"{resource}\""
    )]
    HistoryWritten {
        /// The pass, by name.
        pass: String,
        /// The history resource, by name.
        resource: String,
        /// Its source, by name.
        of: String,
    },

    /// No pass that runs writes the source of a history, so the next frame would read
    /// contents no pass made.
    #[error(
        "history \"{resource}\" carries \"{of}\" to the next frame, but no pass writes \
         \"{of}\"; a history's source is written exactly once per frame"
    )]
    HistoryNeverWritten {
        /// The history resource, by name.
        resource: String,
        /// Its source, by name.
        of: String,
    },

    /// More than one pass writes the source of a history (two writers, or a pass that
    /// modifies what another wrote): which version the next frame reads would depend on
    /// their order.
    #[error(
        "passes \"{first}\" and \"{second}\" both write \"{of}\", which history \
         \"{history}\" carries to the next frame; a history's source is written exactly \
         once per frame, by one pass"
    )]
    HistoryWrittenTwice {
        /// The source, by name.
        of: String,
        /// The history resource, by name.
        history: String,
        /// The first writer, in declaration order.
        first: String,
        /// The second writer.
        second: String,
    },

    /// A history whose source cannot be carried: not a texture the graph owns, a history
    /// itself, or the source of another history.
    #[error("history \"{resource}\" of \"{of}\": {why}")]
    HistorySource {
        /// The history resource, by name.
        resource: String,
        /// Its source, by name.
        of: String,
        /// Why, in words.
        why: String,
    },

    /// Passes that each must run before another: their accesses order them in a loop.
    #[error(
        "cycle: passes {} must each run before the other (through {})",
        quote_list(passes),
        quote_list(resources)
    )]
    Cycle {
        /// The passes of the cycle, in its order.
        passes: Vec<String>,
        /// Every resource whose versions order one pass of the cycle against another.
        resources: Vec<String>,
    },
}

/// `"a", "b"`: names quoted, comma-separated, as messages write lists.
pub(crate) fn quote_list(names: &[String]) -> String {
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
            | OptionalAccess { pass, .. }
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
            | WorkgroupLimit { pass, .. }
            | HistoryWritten { pass, .. } => Some(pass),
            ConflictingWriters { second, .. } | HistoryWrittenTwice { second, .. } => Some(second),
            DroppedWriter { reader, .. } => Some(reader),
            Cycle { passes, .. } => passes.first().map(String::as_str),
            ZeroSize { .. }
            | ZeroSizedBuffer { .. }
            | InvalidResource { .. }
            | TooLarge { .. }
            | UnsupportedSampleCount { .. }
            | UnknownResourceFeature { .. }
            | UnknownFormatFeature { .. }
            | DroppedOutput { .. }
            | HistoryNeverWritten { .. }
            | HistorySource { .. } => None,
        }
    }

    /// The resource the error is about, when there is one.
    pub fn resource(&self) -> Option<&str> {
        use GraphError::*;
        match self {
            ReadBeforeWrite { resource, .. }
            | ConflictingWriters { resource, .. }
            | ForeignHandle { resource, .. }
            | OptionalAccess { resource, .. }
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
            | DroppedOutput { resource, .. }
            | HistoryWritten { resource, .. }
            | HistoryNeverWritten { resource, .. }
            | HistorySource { resource, .. } => Some(resource),
            HistoryWrittenTwice { of, .. } => Some(of),
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
