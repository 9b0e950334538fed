//! The graph file format, as serde reads it. Every name borrows from the file's text, so
//! its position in the file is where its bytes are; plugin parameters stay raw RON until
//! the plugin named next to them deserializes them into its own type.

use std::borrow::Cow;

use ron::extensions::Extensions;
use ron::value::RawValue;
use serde::de::{self, Visitor};
use serde::{Deserialize, Deserializer};
use wgpu_types::{BufferUsages, TextureFormat};

use super::any_handle::AnyHandle;
use super::pairs::Pairs;
use super::params::GraphParams;
use crate::builder::GraphBuilder;
use crate::condition::Condition;
use crate::resource::{BufferDesc, Size, TextureDesc};

/// A whole graph file:
/// `Graph(features: [..], resources: {..}, passes: [..], outputs: [..])`.
#[derive(Debug, Deserialize)]
#[serde(rename = "Graph", deny_unknown_fields)]
pub(crate) struct GraphFile<'a> {
    /// The feature names `when` conditions may use.
    #[serde(borrow, default)]
    pub features: Vec<Name<'a>>,
    #[serde(borrow, default)]
    pub resources: Pairs<Name<'a>, ResourceDecl<'a>>,
    #[serde(borrow, default)]
    pub passes: Vec<PassDecl<'a>>,
    /// Names of the versions kept past the frame.
    #[serde(borrow, default)]
    pub outputs: Vec<Name<'a>>,
}

/// A preset: a graph file named by `base` (relative to the preset's folder) with some
/// passes' parameters or inputs replaced and its parameters given other values, for files
/// that differ from another in those only:
/// `Preset(base: "deferred_msaa_4x.ron", passes: { "edges": (params: (detector: centroid),
/// inputs: { "material": "material", "depth": "depth" }) })`.
#[derive(Debug, Deserialize)]
#[serde(rename = "Preset", deny_unknown_fields)]
pub(crate) struct PresetFile<'a> {
    #[serde(borrow)]
    pub base: Name<'a>,
    /// Values for the base's parameters (`{ "msaa": 1 }`), which a loader's own replace.
    #[serde(borrow, default)]
    pub values: Pairs<Name<'a>, u32>,
    /// Pass name -> what replaces its parameters and inputs.
    #[serde(borrow, default)]
    pub passes: Pairs<Name<'a>, PassChange<'a>>,
}

/// What a preset replaces in one pass: each part given replaces the base's whole part.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PassChange<'a> {
    #[serde(borrow, default)]
    pub params: Option<PluginParams<'a>>,
    #[serde(borrow, default)]
    pub inputs: Option<Pairs<Name<'a>, Name<'a>>>,
}

/// A declared resource; its name (the map key) names the version its one writer produces.
#[derive(Debug, Deserialize)]
pub(crate) enum ResourceDecl<'a> {
    #[serde(borrow)]
    Texture(TextureDecl<'a>),
    #[serde(borrow)]
    ImportedTexture(TextureDecl<'a>),
    #[serde(borrow)]
    Buffer(BufferDecl<'a>),
    #[serde(borrow)]
    ImportedBuffer(BufferDecl<'a>),
}

/// A [`TextureDesc`] as a file writes it, with its condition. The fields repeat
/// `TextureDesc`'s because serde cannot flatten into a struct that denies unknown
/// fields, and unknown fields must stay errors.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct TextureDecl<'a> {
    format: TextureFormat,
    #[serde(default)]
    fallback: Option<TextureFormat>,
    /// `[(condition, format), ..]`: see [`TextureDesc::format_if`].
    #[serde(borrow, default)]
    pub format_if: Vec<(Name<'a>, TextureFormat)>,
    #[serde(borrow, default)]
    pub size: SizeDecl<'a>,
    #[serde(borrow, default = "Count::one")]
    pub samples: Count<'a>,
    #[serde(borrow, default = "Count::one")]
    pub mips: Count<'a>,
    #[serde(borrow, default = "Count::one")]
    pub layers: Count<'a>,
    #[serde(borrow, default)]
    when: Option<Name<'a>>,
}

/// A texture's size as written: [`Size`]'s `Absolute(w, h)` and `Relative(scale)`, or
/// `Divided(n)`, the output size divided by a whole number that may be a parameter
/// (`Divided(Param(name: "scale", default: 2))`): `Relative(1 / n)`, for targets at a
/// fraction of the output that one file serves at every fraction.
#[derive(Debug, Deserialize)]
pub(crate) enum SizeDecl<'a> {
    Absolute(u32, u32),
    Relative(f32),
    #[serde(borrow)]
    Divided(Count<'a>),
}

impl Default for SizeDecl<'_> {
    fn default() -> Self {
        SizeDecl::Relative(1.0)
    }
}

impl SizeDecl<'_> {
    /// The size, with a parameter at its value in `values`. `Divided(0)` is a size of
    /// zero, which validation reports.
    fn size(&self, values: &GraphParams) -> Size {
        match self {
            SizeDecl::Absolute(w, h) => Size::Absolute(*w, *h),
            SizeDecl::Relative(scale) => Size::Relative(*scale),
            SizeDecl::Divided(n) => match n.value(values) {
                0 => Size::Relative(0.0),
                n => Size::Relative((1.0 / f64::from(n)) as f32),
            },
        }
    }
}

/// A texture's `samples`, `mips` or `layers` (or the divisor of its size) as written: a number, or a parameter whose
/// value the loader is given (see [`GraphParams`](super::GraphParams)):
/// `Param(name: "msaa", default: 4)`.
#[derive(Debug)]
pub(crate) enum Count<'a> {
    Value(u32),
    Param(ParamUse<'a>),
}

/// By hand rather than `#[serde(untagged)]`: through serde's buffered content, `ron`
/// reads `Param(..)` as an enum variant, which no untagged struct matches.
impl<'de: 'a, 'a> Deserialize<'de> for Count<'a> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct CountVisitor<'a>(std::marker::PhantomData<&'a ()>);

        impl<'de: 'a, 'a> Visitor<'de> for CountVisitor<'a> {
            type Value = Count<'a>;

            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a count (4) or a parameter (Param(name: \"msaa\", default: 4))")
            }

            fn visit_u64<E: de::Error>(self, value: u64) -> Result<Count<'a>, E> {
                u32::try_from(value)
                    .map(Count::Value)
                    .map_err(|_| E::invalid_value(de::Unexpected::Unsigned(value), &self))
            }

            fn visit_i64<E: de::Error>(self, value: i64) -> Result<Count<'a>, E> {
                u32::try_from(value)
                    .map(Count::Value)
                    .map_err(|_| E::invalid_value(de::Unexpected::Signed(value), &self))
            }

            fn visit_map<A: de::MapAccess<'de>>(self, map: A) -> Result<Count<'a>, A::Error> {
                ParamUse::deserialize(de::value::MapAccessDeserializer::new(map)).map(Count::Param)
            }
        }

        deserializer.deserialize_any(CountVisitor(std::marker::PhantomData))
    }
}

/// `Param(name: "msaa", default: 4)`.
#[derive(Debug, Clone, Deserialize)]
#[serde(rename = "Param", deny_unknown_fields)]
pub(crate) struct ParamUse<'a> {
    #[serde(borrow)]
    pub name: Name<'a>,
    pub default: u32,
}

impl Count<'_> {
    fn one() -> Self {
        Count::Value(1)
    }

    /// The number, or the parameter's value in `values` (which holds every declared
    /// parameter once they are resolved).
    fn value(&self, values: &GraphParams) -> u32 {
        match self {
            Count::Value(n) => *n,
            Count::Param(p) => values.get(p.name.as_str()).unwrap_or(p.default),
        }
    }
}

/// A [`BufferDesc`] as a file writes it, with its condition.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BufferDecl<'a> {
    #[serde(default)]
    size: u64,
    /// Bytes per sample of each pixel of the output, with `samples` samples per pixel.
    #[serde(default)]
    per_sample: u64,
    #[serde(borrow, default = "Count::one")]
    samples: Count<'a>,
    #[serde(default = "BufferUsages::empty")]
    extra_usage: BufferUsages,
    #[serde(borrow, default)]
    when: Option<Name<'a>>,
}

impl<'a> TextureDecl<'a> {
    /// The description, with the conditional formats as read (and checked) apart and
    /// parameters at their `values`.
    fn desc(
        &self,
        format_if: Vec<(Condition, TextureFormat)>,
        values: &GraphParams,
    ) -> TextureDesc {
        TextureDesc {
            format: self.format,
            fallback: self.fallback,
            format_if,
            size: self.size.size(values),
            samples: self.samples.value(values),
            mips: self.mips.value(values),
            layers: self.layers.value(values),
        }
    }

    /// The counts as written, with their field names.
    pub fn counts(&self) -> Vec<(&'static str, &Count<'a>)> {
        let mut counts = vec![
            ("samples", &self.samples),
            ("mips", &self.mips),
            ("layers", &self.layers),
        ];
        if let SizeDecl::Divided(n) = &self.size {
            counts.push(("size divisor", n));
        }
        counts
    }
}

impl<'a> BufferDecl<'a> {
    /// The description, with parameters at their `values`.
    fn desc(&self, values: &GraphParams) -> BufferDesc {
        BufferDesc {
            size: self.size,
            per_sample: self.per_sample,
            samples: self.samples.value(values),
            extra_usage: self.extra_usage,
        }
    }

    /// The counts as written, with their field names.
    pub fn counts(&self) -> Vec<(&'static str, &Count<'a>)> {
        vec![("samples", &self.samples)]
    }
}

impl<'a> ResourceDecl<'a> {
    /// Declares the resource in `graph`, returning its version-0 handle. `format_if` are
    /// a texture's conditional formats, their conditions parsed; `values` the value of
    /// every parameter the file declares.
    pub fn declare(
        &self,
        graph: &mut GraphBuilder,
        name: &str,
        format_if: Vec<(Condition, TextureFormat)>,
        values: &GraphParams,
    ) -> AnyHandle {
        match self {
            ResourceDecl::Texture(t) => {
                graph.create_texture(name, t.desc(format_if, values)).into()
            }
            ResourceDecl::ImportedTexture(t) => {
                graph.import_texture(name, t.desc(format_if, values)).into()
            }
            ResourceDecl::Buffer(b) => graph.create_buffer(name, b.desc(values)).into(),
            ResourceDecl::ImportedBuffer(b) => graph.import_buffer(name, b.desc(values)).into(),
        }
    }

    /// Whether version 0 holds the engine's contents, so reading it needs no writer.
    pub fn imported(&self) -> bool {
        matches!(
            self,
            ResourceDecl::ImportedTexture(_) | ResourceDecl::ImportedBuffer(_)
        )
    }

    /// The counts a file may give as parameters, with their field names.
    pub fn counts(&self) -> Vec<(&'static str, &Count<'a>)> {
        match self {
            ResourceDecl::Texture(t) | ResourceDecl::ImportedTexture(t) => t.counts(),
            ResourceDecl::Buffer(b) | ResourceDecl::ImportedBuffer(b) => b.counts(),
        }
    }

    /// A texture's conditional formats, as written (none for a buffer).
    pub fn format_if(&self) -> &[(Name<'a>, TextureFormat)] {
        match self {
            ResourceDecl::Texture(t) | ResourceDecl::ImportedTexture(t) => &t.format_if,
            ResourceDecl::Buffer(_) | ResourceDecl::ImportedBuffer(_) => &[],
        }
    }

    /// The resource's `when` condition, as written.
    pub fn when(&self) -> Option<&Name<'a>> {
        match self {
            ResourceDecl::Texture(t) | ResourceDecl::ImportedTexture(t) => t.when.as_ref(),
            ResourceDecl::Buffer(b) | ResourceDecl::ImportedBuffer(b) => b.when.as_ref(),
        }
    }
}

/// One pass: `(name: "..", plugin: "..", params: (..), inputs: {..}, outputs: {..})`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PassDecl<'a> {
    #[serde(borrow)]
    pub name: Name<'a>,
    #[serde(borrow)]
    pub plugin: Name<'a>,
    /// The features under which the pass runs: `"spot_lights & !unlit_only"`.
    #[serde(borrow, default)]
    pub when: Option<Name<'a>>,
    #[serde(borrow, default)]
    pub params: Option<PluginParams<'a>>,
    /// Slot name -> name of the version read.
    #[serde(borrow, default)]
    pub inputs: Pairs<Name<'a>, Name<'a>>,
    /// Slot name -> name of the version written. A slot also in `inputs` modifies what it
    /// reads, and this names the new version.
    #[serde(borrow, default)]
    pub outputs: Pairs<Name<'a>, Name<'a>>,
}

impl<'a> PassDecl<'a> {
    /// The name a slot reads, if it is an input.
    pub fn input(&self, slot: &str) -> Option<&Name<'a>> {
        find(&self.inputs, slot)
    }

    /// The name a slot writes, if it is an output.
    pub fn output(&self, slot: &str) -> Option<&Name<'a>> {
        find(&self.outputs, slot)
    }
}

fn find<'p, 'a>(pairs: &'p Pairs<Name<'a>, Name<'a>>, slot: &str) -> Option<&'p Name<'a>> {
    pairs
        .0
        .iter()
        .find(|(k, _)| k.as_str() == slot)
        .map(|(_, v)| v)
}

/// A name as written in the file. Plain strings borrow from the file's text, which is how
/// their position is found; a string with escapes is a copy and has no position of its own.
#[derive(Debug, Clone, Deserialize)]
#[serde(transparent)]
pub(crate) struct Name<'a>(#[serde(borrow)] Cow<'a, str>);

impl Name<'_> {
    pub fn as_str(&self) -> &str {
        &self.0
    }

    /// Where the name's text starts in `text`, if it borrows from it.
    pub fn offset(&self, text: &str) -> Option<usize> {
        match &self.0 {
            Cow::Borrowed(s) => offset_in(text, s),
            Cow::Owned(_) => None,
        }
    }
}

/// A plugin's parameters, still as RON text borrowed from the file.
#[derive(Debug)]
pub(crate) struct PluginParams<'a>(pub &'a RawValue);

impl<'de: 'a, 'a> Deserialize<'de> for PluginParams<'a> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        <&RawValue>::deserialize(deserializer).map(PluginParams)
    }
}

/// Byte offset of `part` in `text`, when `part` is a slice of it.
pub(crate) fn offset_in(text: &str, part: &str) -> Option<usize> {
    let start = text.as_ptr() as usize;
    let at = part.as_ptr() as usize;
    (at >= start && at + part.len() <= start + text.len()).then(|| at - start)
}

/// The RON dialect of graph files and plugin parameters: `Texture(format: ..)` for a
/// variant holding a struct, and optional fields written without `Some(..)`.
pub(crate) fn options() -> ron::Options {
    ron::Options::default()
        .with_default_extension(Extensions::UNWRAP_VARIANT_NEWTYPES | Extensions::IMPLICIT_SOME)
}

/// Reads a graph file.
pub(crate) fn parse(text: &str) -> Result<GraphFile<'_>, ron::error::SpannedError> {
    options().from_str(text)
}

pub(crate) fn parse_preset(text: &str) -> Result<PresetFile<'_>, ron::error::SpannedError> {
    options().from_str(text)
}

/// Whether the file's value is a `Preset(..)`: its first word past comments and blanks.
pub(crate) fn is_preset(text: &str) -> bool {
    let mut rest = text;
    loop {
        rest = rest.trim_start();
        if let Some(comment) = rest.strip_prefix("//") {
            rest = comment.split_once('\n').map_or("", |(_, after)| after);
        } else if let Some(comment) = rest.strip_prefix("/*") {
            rest = comment.split_once("*/").map_or("", |(_, after)| after);
        } else {
            let word = rest
                .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .next();
            return word == Some("Preset");
        }
    }
}
