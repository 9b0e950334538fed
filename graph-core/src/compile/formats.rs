//! Conditional formats ([`TextureDesc::format_if`]), part of the conditions phase: each
//! texture gets the format its first holding condition names, and the plan keeps why.
//!
//! A conditional format may be another kind of format than the one it replaces (a
//! depth32float written by a raster where `cpu_device` holds, an r32float a compute pass
//! stores otherwise): each pass checks the formats it may meet where it runs
//! ([`TextureDesc::formats_where`] of its condition), and a pass that binds both kinds
//! alike says so by accepting them, as the generic plugins' bindings do not. That a
//! conditional format names declared features only is checked with every other
//! condition's features (`conditions::undeclared_features`).

use crate::condition::Features;
use crate::resource::{format_name, ResourceDesc, ResourceNode};

/// Gives `resource` the format its conditions pick for `features`, leaving no
/// conditional formats behind. Returns why the format changed (`None` where none holds
/// and the declared format and fallback stay).
pub(super) fn choose(resource: &mut ResourceNode, features: &Features) -> Option<String> {
    let ResourceDesc::Texture(texture) = &mut resource.desc else {
        return None;
    };
    let conditional = std::mem::take(&mut texture.format_if);
    let (condition, format) = conditional
        .into_iter()
        .find(|(condition, _)| condition.holds(features))?;
    let why = format!(
        "{} instead of {}: condition \"{condition}\" holds",
        format_name(format),
        format_name(texture.format)
    );
    texture.format = format;
    texture.fallback = None;
    Some(why)
}

#[cfg(test)]
mod tests {
    use wgpu_types::TextureFormat as F;

    use super::choose;
    use crate::builder::GraphBuilder;
    use crate::compile::conditions;
    use crate::condition::{Condition, Features};
    use crate::error::GraphError;
    use crate::resource::{ResourceNode, TextureDesc};

    fn depth() -> TextureDesc {
        TextureDesc::new(F::Depth32FloatStencil8)
            .or(F::Depth24PlusStencil8)
            .format_if(Condition::feature("tiny"), F::Depth16Unorm)
            .format_if(Condition::feature("shallow"), F::Depth24PlusStencil8)
    }

    fn node(desc: TextureDesc) -> ResourceNode {
        let mut graph = GraphBuilder::new();
        graph.create_texture("depth", desc);
        graph.build().resources.remove(0)
    }

    #[test]
    fn the_first_holding_condition_replaces_format_and_fallback() {
        let mut resource = node(depth());
        let why = choose(&mut resource, &Features::from_iter(["shallow"]));
        assert_eq!(
            why.as_deref(),
            Some(
                "depth24plus-stencil8 instead of depth32float-stencil8: condition \
                 \"shallow\" holds"
            )
        );
        let texture = resource.texture().unwrap();
        assert_eq!(
            (texture.format, texture.fallback),
            (F::Depth24PlusStencil8, None)
        );
        assert!(texture.format_if.is_empty());
    }

    #[test]
    fn without_a_holding_condition_the_declared_formats_stay() {
        let mut resource = node(depth());
        assert_eq!(choose(&mut resource, &Features::new()), None);
        let texture = resource.texture().unwrap();
        assert_eq!(
            (texture.format, texture.fallback),
            (F::Depth32FloatStencil8, Some(F::Depth24PlusStencil8))
        );
        assert!(texture.format_if.is_empty());
    }

    /// A pass under a condition accepts the formats the texture may have where it runs:
    /// conditional formats it excludes drop out, and one it implies replaces the declared
    /// formats and every later conditional one.
    #[test]
    fn a_pass_s_condition_narrows_the_formats_it_must_accept() {
        let depth = depth();
        let formats = |condition: Option<Condition>| depth.formats_where(condition.as_ref());
        let all = vec![
            F::Depth32FloatStencil8,
            F::Depth24PlusStencil8,
            F::Depth16Unorm,
            F::Depth24PlusStencil8,
        ];
        assert_eq!(formats(None), all);
        assert_eq!(formats(Some(Condition::feature("other"))), all);
        assert_eq!(
            formats(Some(Condition::not("tiny"))),
            vec![
                F::Depth32FloatStencil8,
                F::Depth24PlusStencil8,
                F::Depth24PlusStencil8
            ]
        );
        assert_eq!(
            formats(Some(Condition::not("tiny").and(Condition::not("shallow")))),
            vec![F::Depth32FloatStencil8, F::Depth24PlusStencil8]
        );
        assert_eq!(
            formats(Some(
                Condition::feature("tiny").and(Condition::feature("shallow"))
            )),
            vec![F::Depth16Unorm]
        );
        assert_eq!(
            formats(Some(
                Condition::not("tiny").and(Condition::feature("shallow"))
            )),
            vec![F::Depth24PlusStencil8]
        );
    }

    #[test]
    fn undeclared_features_are_errors_and_other_kinds_of_format_are_not() {
        let mut graph = GraphBuilder::new();
        graph.declare_features(["shallow"]);
        graph.create_texture(
            "depth",
            TextureDesc::new(F::Depth32FloatStencil8)
                .format_if(Condition::feature("shalow"), F::Depth24PlusStencil8)
                .format_if(Condition::feature("shallow"), F::Depth32Float),
        );
        let errors = conditions::apply(&graph.build(), &Features::new()).errors;
        assert_eq!(
            errors[0],
            GraphError::UnknownFormatFeature {
                resource: "depth".into(),
                condition: "shalow".into(),
                feature: "shalow".into(),
                declared: "shallow".into(),
            }
        );
        assert_eq!(errors.len(), 1);
    }
}
