//! The graph file format, as serde reads it. Every name borrows from the file's text, so
//! its position in the file is where its bytes are; plugin parameters stay raw RON until
//! the plugin named next to them deserializes them into its own type.

use std::borrow::Cow;
use std::collections::HashMap;

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
use crate::error::GraphError;
use crate::resource::{format_name, BufferDesc, Size, TextureDesc};

/// A whole graph file: `Graph(features: [..], resources: {..}, passes: [..], outputs:
/// [..])`. As read ([`GraphText`]) a pass may be a use of a part; loading writes the parts
/// out ([`GraphFile`], see `compose`), which the rest of loading reads as if the file had
/// been written that way.
#[derive(Debug, Deserialize)]
#[serde(rename = "Graph", deny_unknown_fields)]
pub(crate) struct Graph<'a, P> {
    /// The feature names `when` conditions may use.
    #[serde(borrow, default)]
    pub features: Vec<Name<'a>>,
    #[serde(borrow, default)]
    pub resources: Pairs<Name<'a>, ResourceDecl<'a>>,
    #[serde(default = "Vec::new")]
    pub passes: Vec<P>,
    /// Names of the versions kept past the frame.
    #[serde(borrow, default)]
    pub outputs: Vec<Name<'a>>,
}

/// A graph file as written: its passes may be uses of parts.
pub(crate) type GraphText<'a> = Graph<'a, Entry<'a>>;

/// A graph file with its parts written out.
pub(crate) type GraphFile<'a> = Graph<'a, PassDecl<'a>>;

/// A part: passes and resources a graph uses by the part file's name, through an
/// interface of the resources it takes and gives:
/// `Part(takes: { "hdr": Texture(format: "rgba16float") }, gives: { "color": Texture(format:
/// "rgba8unorm-srgb") }, features: ["auto_exposure"], resources: {..}, passes: [..])`.
#[derive(Debug, Deserialize)]
#[serde(rename = "Part", deny_unknown_fields)]
pub(crate) struct PartFile<'a> {
    /// Slot -> what a use must bind to it: a version its passes read.
    #[serde(borrow, default)]
    pub takes: Pairs<Name<'a>, Interface<'a>>,
    /// Slot -> what the part writes under that name: a resource the graph declares
    /// (`Texture(..)`, `Buffer(..)`, its shape), one the part declares in `resources`, or a
    /// version of one it takes (`Any` for either).
    #[serde(borrow, default)]
    pub gives: Pairs<Name<'a>, Interface<'a>>,
    /// The features its conditions use, which a graph using it must declare.
    #[serde(borrow, default)]
    pub features: Vec<Name<'a>>,
    /// Resources of its own, which each use declares under its prefix.
    #[serde(borrow, default)]
    pub resources: Pairs<Name<'a>, ResourceDecl<'a>>,
    #[serde(borrow, default)]
    pub passes: Vec<Entry<'a>>,
}

/// One resource of a part's interface.
#[derive(Debug, Clone, Deserialize)]
pub(crate) enum Interface<'a> {
    /// A texture; the bound version's texture has this format (or its `fallback`). A part
    /// checked on its own gets one of this shape.
    #[serde(borrow)]
    Texture(TextureDecl<'a>),
    /// A buffer.
    #[serde(borrow)]
    Buffer(BufferDecl<'a>),
    /// Any resource.
    Any,
}

impl<'a> Interface<'a> {
    /// What a part checked on its own reads (`imported`: an import) or writes for a slot
    /// of this shape, in its first format; `Any`: an `rgba16float` texture.
    pub fn placeholder(&self, imported: bool) -> ResourceDecl<'a> {
        // The interface's fallback is a format it also accepts, not one a device may need.
        let texture = |t: TextureDecl<'a>| {
            let t = TextureDecl {
                fallback: None,
                ..t
            };
            match imported {
                true => ResourceDecl::ImportedTexture(t),
                false => ResourceDecl::Texture(t),
            }
        };
        match self {
            Interface::Texture(t) => texture(t.clone()),
            Interface::Buffer(b) if imported => ResourceDecl::ImportedBuffer(b.clone()),
            Interface::Buffer(b) => ResourceDecl::Buffer(b.clone()),
            Interface::Any => texture(TextureDecl {
                format: TextureFormat::Rgba16Float,
                fallback: None,
                format_if: Vec::new(),
                size: SizeDecl::default(),
                samples: Count::one(),
                mips: Count::one(),
                layers: Count::one(),
                when: None,
            }),
        }
    }

    /// What the interface asks for, in words.
    pub fn shown(&self) -> String {
        match self {
            Interface::Texture(t) => match t.fallback {
                Some(other) => format!(
                    "a texture of format {} or {}",
                    format_name(t.format),
                    format_name(other)
                ),
                None => format!("a texture of format {}", format_name(t.format)),
            },
            Interface::Buffer(_) => "a buffer".into(),
            Interface::Any => "any resource".into(),
        }
    }

    /// `found`, in words, where it is not what the interface asks for.
    pub fn mismatch(&self, found: &ResourceDecl<'_>) -> Option<String> {
        match (self, found) {
            (Interface::Any, _) => None,
            (
                Interface::Texture(wanted),
                ResourceDecl::Texture(t) | ResourceDecl::ImportedTexture(t),
            ) => (wanted.format != t.format && wanted.fallback != Some(t.format))
                .then(|| format!("a texture of format {}", format_name(t.format))),
            (Interface::Buffer(_), ResourceDecl::Buffer(_) | ResourceDecl::ImportedBuffer(_)) => {
                None
            }
            // Its source's format, which the bindings of the source are checked against.
            (Interface::Texture(_), ResourceDecl::History(_)) => None,
            (Interface::Buffer(_), ResourceDecl::History(_)) => Some("a history texture".into()),
            (_, ResourceDecl::Texture(_) | ResourceDecl::ImportedTexture(_)) => {
                Some("a texture".into())
            }
            (_, ResourceDecl::Buffer(_) | ResourceDecl::ImportedBuffer(_)) => {
                Some("a buffer".into())
            }
        }
    }
}

/// One entry of a `passes` list: a pass, `(name: "..", plugin: "..", ..)`, or a use of a
/// part, `(part: "parts/fxaa.ron", inputs: {..}, outputs: {..})`. Read as one struct so
/// that both kinds share the fields they share; `compose` tells them apart, with errors
/// at the field at fault.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Entry<'a> {
    #[serde(borrow, default)]
    pub name: Option<Name<'a>>,
    #[serde(borrow, default)]
    pub plugin: Option<Name<'a>>,
    /// The part file, relative to the file that uses it.
    #[serde(borrow, default)]
    pub part: Option<Name<'a>>,
    /// Put before the names of a use's passes and own resources, so that two uses of one
    /// part have names of their own.
    #[serde(borrow, default)]
    pub prefix: Option<Name<'a>>,
    #[serde(borrow, default)]
    pub when: Option<Name<'a>>,
    #[serde(borrow, default)]
    pub params: Option<PluginParams<'a>>,
    /// A use's values for the part's parameters (`{ "msaa": 1 }`): its `Param` uses with
    /// these names take them, in this use only.
    #[serde(borrow, default)]
    pub values: Pairs<Name<'a>, u32>,
    /// A pass's slots, or a use's bindings of what the part takes.
    #[serde(borrow, default)]
    pub inputs: Pairs<Name<'a>, Name<'a>>,
    /// A pass's slots, or a use's bindings of what the part gives.
    #[serde(borrow, default)]
    pub outputs: Pairs<Name<'a>, Name<'a>>,
    /// A pass's input slots whose reads are optional, and output slots whose fresh writes
    /// are: dropped, rather than an error, where a condition drops what they read (or the
    /// resource they write).
    #[serde(borrow, default)]
    pub optional: Vec<Name<'a>>,
}

/// A preset: a graph file named by `base` (relative to the preset's folder) with some
/// passes' parameters, inputs, outputs or optional slots replaced, passes removed or
/// added, outputs rebound to new writers, features declared beside the base's, and its
/// parameters given other values, for files that differ from another in those only:
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
    /// Features declared beside the base's, for the conditions of what the preset adds:
    /// the base's own plans do not test them.
    #[serde(borrow, default)]
    pub features: Vec<Name<'a>>,
    /// Resources added to the base's.
    #[serde(borrow, default)]
    pub resources: Pairs<Name<'a>, ResourceDecl<'a>>,
    /// Pass name -> what replaces its parameters, inputs and outputs.
    #[serde(borrow, default)]
    pub passes: Pairs<Name<'a>, PassChange<'a>>,
    /// Passes of the base left out.
    #[serde(borrow, default)]
    pub remove: Vec<Name<'a>>,
    /// Name -> new name, in the base's resources and passes but not its outputs: what the
    /// base wrote as an output is renamed, and the preset's passes write the output
    /// (`{ "color": "ldr" }` before a post filter that reads "ldr" and writes "color").
    #[serde(borrow, default)]
    pub rebind: Pairs<Name<'a>, Name<'a>>,
    /// Pass name -> passes and part uses added right after it.
    #[serde(borrow, default)]
    pub after: Pairs<Name<'a>, Vec<Entry<'a>>>,
    /// The graph's outputs, replacing the base's.
    #[serde(borrow, default)]
    pub outputs: Option<Vec<Name<'a>>>,
}

/// What a preset replaces in one pass: each part given replaces the base's whole part.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PassChange<'a> {
    #[serde(borrow, default)]
    pub params: Option<PluginParams<'a>>,
    #[serde(borrow, default)]
    pub inputs: Option<Pairs<Name<'a>, Name<'a>>>,
    #[serde(borrow, default)]
    pub outputs: Option<Pairs<Name<'a>, Name<'a>>>,
    /// The pass's optional slots (a pass's `optional`), replacing the base's list: what
    /// a change that adds a slot the preset's conditions may drop marks.
    #[serde(borrow, default)]
    pub optional: Option<Vec<Name<'a>>>,
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
    /// The previous frame's contents of another texture: [`HistoryDecl`].
    #[serde(borrow)]
    History(HistoryDecl<'a>),
}

/// `History(of: "color")`: the previous frame's contents of the graph-owned texture
/// `of`, which passes read (and do not write) under this resource's name, while the one
/// pass that writes `of` writes what the next frame reads here. It has `of`'s
/// description, and exists where `of` does unless `when` says otherwise (see
/// [`GraphBuilder::history_texture`]). Its own name, rather than a flag on `of`, because
/// the two are different contents in different textures, read and written by different
/// slots: every name in a file still denotes one version with one writer.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct HistoryDecl<'a> {
    /// The texture carried to the next frame.
    #[serde(borrow)]
    pub of: Name<'a>,
    #[serde(borrow, default)]
    when: Option<Name<'a>>,
}

/// A [`TextureDesc`] as a file writes it, with its condition. The fields repeat
/// `TextureDesc`'s because serde cannot flatten into a struct that denies unknown
/// fields, and unknown fields must stay errors.
#[derive(Debug, Clone, Deserialize)]
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

/// A texture's size as written: [`Size`]'s `Absolute(w, h)` (each side a number or a
/// parameter: `Absolute(Param(name: "shadow_map", default: 4096), ..)`, for a target whose
/// resolution is the trade being measured) and `Relative(scale)`, or `Divided(n)`, the
/// output size divided by a whole number that may be a parameter
/// (`Divided(Param(name: "scale", default: 2))`): `Relative(1 / n)`, for targets at a
/// fraction of the output that one file serves at every fraction.
#[derive(Debug, Clone, Deserialize)]
pub(crate) enum SizeDecl<'a> {
    Absolute(#[serde(borrow)] Count<'a>, #[serde(borrow)] Count<'a>),
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
            SizeDecl::Absolute(w, h) => Size::Absolute(w.value(values), h.value(values)),
            SizeDecl::Relative(scale) => Size::Relative(*scale),
            SizeDecl::Divided(n) => match n.value(values) {
                0 => Size::Relative(0.0),
                n => Size::Relative((1.0 / f64::from(n)) as f32),
            },
        }
    }
}

/// A texture's `samples`, `mips` or `layers` (or the sides or divisor of its size, or a
/// buffer's texels) as written: a number, or a parameter whose
/// value the loader is given (see [`GraphParams`](super::GraphParams)):
/// `Param(name: "msaa", default: 4)`.
#[derive(Debug, Clone)]
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

    /// A buffer's `texels` when it gives none.
    fn none() -> (Self, Self) {
        (Count::Value(0), Count::Value(0))
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
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BufferDecl<'a> {
    #[serde(default)]
    size: u64,
    /// Bytes per sample of each pixel of the output, with `samples` samples per pixel.
    #[serde(default)]
    per_sample: u64,
    #[serde(borrow, default = "Count::one")]
    samples: Count<'a>,
    /// Bytes per texel of a grid of `texels` (width, height), added to `size`: a buffer
    /// holding a value per texel of a texture of a size the file gives, such as the
    /// shadow raster's keys for the atlas (`per_texel: 4, texels: (Param(name:
    /// "shadow_map", default: 4096), Param(name: "shadow_map", default: 4096))`), so that
    /// one parameter sizes both.
    #[serde(default)]
    per_texel: u64,
    #[serde(borrow, default = "Count::none")]
    texels: (Count<'a>, Count<'a>),
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
        match &self.size {
            SizeDecl::Divided(n) => counts.push(("size divisor", n)),
            SizeDecl::Absolute(w, h) => counts.extend([("width", w), ("height", h)]),
            SizeDecl::Relative(_) => {}
        }
        counts
    }
}

impl<'a> BufferDecl<'a> {
    /// The description, with parameters at their `values`.
    fn desc(&self, values: &GraphParams) -> BufferDesc {
        let (width, height) = (self.texels.0.value(values), self.texels.1.value(values));
        let texels = u64::from(width) * u64::from(height);
        BufferDesc {
            size: self
                .size
                .saturating_add(self.per_texel.saturating_mul(texels)),
            per_sample: self.per_sample,
            samples: self.samples.value(values),
            extra_usage: self.extra_usage,
        }
    }

    /// The counts as written, with their field names.
    pub fn counts(&self) -> Vec<(&'static str, &Count<'a>)> {
        vec![
            ("samples", &self.samples),
            ("texels width", &self.texels.0),
            ("texels height", &self.texels.1),
        ]
    }
}

impl<'a> ResourceDecl<'a> {
    /// Declares the resource in `graph`, returning its version-0 handle. `format_if` are
    /// a texture's conditional formats, their conditions parsed; `values` the value of
    /// every parameter the file declares; `declared` the resources declared so far, by
    /// name, where a history finds its source (so histories are declared last). A
    /// history of what is not a declared texture is an error about the history.
    pub fn declare(
        &self,
        graph: &mut GraphBuilder,
        name: &str,
        format_if: Vec<(Condition, TextureFormat)>,
        values: &GraphParams,
        declared: &HashMap<&str, AnyHandle>,
    ) -> Result<AnyHandle, GraphError> {
        Ok(match self {
            ResourceDecl::History(h) => match declared.get(h.of.as_str()) {
                Some(AnyHandle::Texture(of)) => graph.history_texture(name, *of).into(),
                found => {
                    return Err(GraphError::HistorySource {
                        resource: name.to_owned(),
                        of: h.of.as_str().to_owned(),
                        why: match found {
                            Some(_) => "it is a buffer; histories are textures".into(),
                            None => "no resource has that name".into(),
                        },
                    })
                }
            },
            ResourceDecl::Texture(t) => {
                graph.create_texture(name, t.desc(format_if, values)).into()
            }
            ResourceDecl::ImportedTexture(t) => {
                graph.import_texture(name, t.desc(format_if, values)).into()
            }
            ResourceDecl::Buffer(b) => graph.create_buffer(name, b.desc(values)).into(),
            ResourceDecl::ImportedBuffer(b) => graph.import_buffer(name, b.desc(values)).into(),
        })
    }

    /// Whether version 0 holds contents no pass of this frame writes (the engine's, or
    /// the previous frame's), so reading it needs no writer.
    pub fn imported(&self) -> bool {
        matches!(
            self,
            ResourceDecl::ImportedTexture(_)
                | ResourceDecl::ImportedBuffer(_)
                | ResourceDecl::History(_)
        )
    }

    /// The texture a history carries, for a history.
    pub fn history_of(&self) -> Option<&Name<'a>> {
        match self {
            ResourceDecl::History(h) => Some(&h.of),
            _ => None,
        }
    }

    /// [`history_of`](Self::history_of), to rename it.
    pub fn history_of_mut(&mut self) -> Option<&mut Name<'a>> {
        match self {
            ResourceDecl::History(h) => Some(&mut h.of),
            _ => None,
        }
    }

    /// The counts a file may give as parameters, with their field names.
    pub fn counts(&self) -> Vec<(&'static str, &Count<'a>)> {
        match self {
            ResourceDecl::Texture(t) | ResourceDecl::ImportedTexture(t) => t.counts(),
            ResourceDecl::Buffer(b) | ResourceDecl::ImportedBuffer(b) => b.counts(),
            ResourceDecl::History(_) => Vec::new(),
        }
    }

    /// A texture's conditional formats, as written (none for a buffer).
    pub fn format_if(&self) -> &[(Name<'a>, TextureFormat)] {
        match self {
            ResourceDecl::Texture(t) | ResourceDecl::ImportedTexture(t) => &t.format_if,
            ResourceDecl::Buffer(_)
            | ResourceDecl::ImportedBuffer(_)
            | ResourceDecl::History(_) => &[],
        }
    }

    /// Replaces the resource's `when` condition (a use's joined to a part's).
    pub fn set_when(&mut self, when: Option<Name<'a>>) {
        match self {
            ResourceDecl::Texture(t) | ResourceDecl::ImportedTexture(t) => t.when = when,
            ResourceDecl::Buffer(b) | ResourceDecl::ImportedBuffer(b) => b.when = when,
            ResourceDecl::History(h) => h.when = when,
        }
    }

    /// The resource's `when` condition, as written.
    pub fn when(&self) -> Option<&Name<'a>> {
        match self {
            ResourceDecl::Texture(t) | ResourceDecl::ImportedTexture(t) => t.when.as_ref(),
            ResourceDecl::Buffer(b) | ResourceDecl::ImportedBuffer(b) => b.when.as_ref(),
            ResourceDecl::History(h) => h.when.as_ref(),
        }
    }
}

/// One pass: `(name: "..", plugin: "..", params: (..), inputs: {..}, outputs: {..})`.
#[derive(Debug)]
pub(crate) struct PassDecl<'a> {
    pub name: Name<'a>,
    pub plugin: Name<'a>,
    /// The features under which the pass runs: `"spot_lights & !unlit_only"`.
    pub when: Option<Name<'a>>,
    pub params: Option<PluginParams<'a>>,
    /// Slot name -> name of the version read.
    pub inputs: Pairs<Name<'a>, Name<'a>>,
    /// Slot name -> name of the version written. A slot also in `inputs` modifies what it
    /// reads, and this names the new version.
    pub outputs: Pairs<Name<'a>, Name<'a>>,
    /// Input slots whose reads are optional, and output-only slots whose writes are
    /// ([`PassBuilder::optional`](crate::PassBuilder::optional)): `optional: ["shadows"]`.
    pub optional: Vec<Name<'a>>,
    /// The uses of parts it came from, outermost first (none when the graph's file
    /// writes it), for `explain` and messages.
    pub used: Vec<Used>,
}

/// Where a pass came from: the part file and the place of its use.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Used {
    /// The part file, as its use names it (resolved from the using file's folder).
    pub part: String,
    /// The `part:` of the use.
    pub at: super::error::Location,
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
/// A name made from another (a part's name under its use's prefix, a use's condition
/// joined to its pass's) keeps the place of the one it was made from.
#[derive(Debug, Clone, Deserialize)]
#[serde(transparent)]
pub(crate) struct Name<'a> {
    #[serde(borrow)]
    text: Cow<'a, str>,
    /// The name this one was made from, and how many characters were put before it.
    #[serde(skip)]
    made_from: Option<(&'a str, usize)>,
}

impl<'a> Name<'a> {
    pub fn as_str(&self) -> &str {
        &self.text
    }

    /// `text`, placed where `from` is written; `shift` characters of `text` come before
    /// `from`'s (a prefix), so a column in `text` past them is that column less `shift`
    /// in `from`.
    pub fn made_from(text: String, from: &Name<'a>, shift: usize) -> Name<'a> {
        let made_from = from
            .written()
            .map(|(written, earlier)| (written, earlier + shift));
        Name {
            text: Cow::Owned(text),
            made_from,
        }
    }

    /// The text this name was read from, if it borrows from a file, and the characters put
    /// before it since.
    fn written(&self) -> Option<(&'a str, usize)> {
        match (&self.text, self.made_from) {
            (_, Some(from)) => Some(from),
            (Cow::Borrowed(s), None) => Some((s, 0)),
            (Cow::Owned(_), None) => None,
        }
    }

    /// Where the name's text starts in `text`, if it borrows from it.
    pub fn offset(&self, text: &str) -> Option<usize> {
        self.written().and_then(|(s, _)| offset_in(text, s))
    }

    /// The text the name was read from (see [`Name::offset`]), for finding its file.
    pub fn written_text(&self) -> &str {
        self.written().map_or(self.as_str(), |(s, _)| s)
    }

    /// The character of the written text at `column` of this name's, if it is in it.
    pub fn written_column(&self, column: usize) -> Option<usize> {
        let shift = self.written().map_or(0, |(_, shift)| shift);
        column.checked_sub(shift)
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
pub(crate) fn parse(text: &str) -> Result<GraphText<'_>, ron::error::SpannedError> {
    options().from_str(text)
}

/// Reads a part file.
pub(crate) fn parse_part(text: &str) -> Result<PartFile<'_>, ron::error::SpannedError> {
    options().from_str(text)
}

pub(crate) fn parse_preset(text: &str) -> Result<PresetFile<'_>, ron::error::SpannedError> {
    options().from_str(text)
}

/// What a file holds, by its first word past comments and blanks.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum FileKind {
    Graph,
    Preset,
    Part,
}

/// Whether the file's value is a `Graph(..)` (or anything else, which parsing reports), a
/// `Preset(..)` or a `Part(..)`.
pub(crate) fn kind(text: &str) -> FileKind {
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
            return match word {
                Some("Preset") => FileKind::Preset,
                Some("Part") => FileKind::Part,
                _ => FileKind::Graph,
            };
        }
    }
}
