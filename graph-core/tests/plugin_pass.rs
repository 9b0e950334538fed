//! Plugin passes declared from code go through the same slot checks as graph files and
//! yield the versions they write.

use rgraph_core::file::{PluginError, PluginPassError};
use rgraph_core::plugins::{Blit, BlitParams, Clear, ClearParams, Fullscreen, FullscreenParams};
use rgraph_core::types::TextureFormat;
use rgraph_core::{CompileOptions, GraphBuilder, TextureDesc};

fn clear_params() -> ClearParams {
    ron::from_str("(color: (0.25, 0.5, 0.75, 1.0))").expect("clear params")
}

#[test]
fn a_plugin_pass_writes_a_new_version_that_later_passes_read() {
    let mut graph = GraphBuilder::new();
    let hdr = graph.create_texture("hdr", TextureDesc::new(TextureFormat::Rgba16Float));
    let target = graph.import_texture("target", TextureDesc::new(TextureFormat::Rgba8Unorm));
    let cleared = graph
        .add_plugin_pass(
            "clear",
            &Clear,
            clear_params(),
            &[],
            &[("target", hdr.into())],
        )
        .expect("clear declares");
    let hdr_v1 = cleared.texture("target").expect("clear wrote a texture");
    assert_eq!((hdr_v1.id(), hdr_v1.version()), (hdr.id(), 1));

    let params: BlitParams = ron::from_str("()").expect("blit params");
    let blitted = graph
        .add_plugin_pass(
            "present",
            &Blit,
            params,
            &[("src", hdr_v1.into())],
            &[("dst", target.into())],
        )
        .expect("blit declares");
    let target_v1 = blitted.texture("dst").expect("blit wrote the target");
    graph.export(target_v1);

    let plan = graph
        .build()
        .compile(&CompileOptions::default())
        .unwrap_or_else(|e| panic!("expected a valid graph, got:\n{e}"));
    let order: Vec<&str> = plan.passes.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(order, ["clear", "present"]);
}

#[test]
fn a_slot_listed_in_inputs_and_outputs_modifies_what_it_reads() {
    let mut graph = GraphBuilder::new();
    let color = graph.create_texture("color", TextureDesc::new(TextureFormat::Rgba8Unorm));
    let v1 = graph
        .add_plugin_pass(
            "clear",
            &Clear,
            clear_params(),
            &[],
            &[("target", color.into())],
        )
        .expect("clear declares")
        .texture("target")
        .expect("v1");
    let v2 = graph
        .add_plugin_pass(
            "clear again",
            &Clear,
            clear_params(),
            &[("target", v1.into())],
            &[("target", v1.into())],
        )
        .expect("modifying clear declares")
        .texture("target")
        .expect("v2");
    assert_eq!(v2.version(), 2);
}

#[test]
fn a_missing_slot_names_the_pass_plugin_and_slot() {
    let mut graph = GraphBuilder::new();
    let params: FullscreenParams =
        ron::from_str(r#"(shader: "../shaders/gradient.wgsl", bindings: [Uniform(binding: 0, values: [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0])])"#)
            .expect("fullscreen params");
    let hdr = graph.create_texture("hdr", TextureDesc::new(TextureFormat::Rgba16Float));
    let written = graph
        .add_plugin_pass("sky", &Fullscreen, params, &[], &[("color", hdr.into())])
        .expect("the gradient shader fits one color output");
    assert!(written.texture("color").is_some());

    let error = graph
        .add_plugin_pass("present", &Blit, ron::from_str("()").unwrap(), &[], &[])
        .expect_err("blit needs src and dst");
    assert!(
        matches!(
            &error,
            PluginPassError::Setup { error, .. } if matches!(**error, PluginError::MissingSlot { .. })
        ),
        "{error:?}"
    );
    assert_eq!(
        error.to_string(),
        r#"pass "present" (plugin "blit"): needs slot "dst" in its outputs"#
    );
}

#[test]
fn a_slot_the_plugin_does_not_take_is_an_error() {
    let mut graph = GraphBuilder::new();
    let a = graph.create_texture("a", TextureDesc::new(TextureFormat::Rgba8Unorm));
    let extra = graph.import_texture("extra", TextureDesc::new(TextureFormat::Rgba8Unorm));
    let error = graph
        .add_plugin_pass(
            "clear",
            &Clear,
            clear_params(),
            &[("mystery", extra.into())],
            &[("target", a.into())],
        )
        .expect_err("clear has no slot \"mystery\"");
    assert_eq!(
        error.to_string(),
        r#"pass "clear": plugin "clear" has no use for slot "mystery" ("extra")"#
    );
}

/// Answers `Slots::modifies` for its slots as it sets up, copying `src` to `dst`.
struct ModifiesProbe(std::sync::Mutex<Vec<(&'static str, bool)>>);

impl rgraph_core::file::Plugin for ModifiesProbe {
    const NAME: &'static str = "modifies_probe";
    type Params = ();

    fn kind(&self, _: &()) -> rgraph_core::PassKind {
        rgraph_core::PassKind::Transfer
    }

    fn setup(
        &self,
        _: (),
        pass: &mut rgraph_core::PassBuilder<'_>,
        slots: &mut rgraph_core::file::Slots<'_>,
    ) -> Result<(), PluginError> {
        let answers = ["src", "dst", "absent"].map(|slot| (slot, slots.modifies(slot)));
        self.0.lock().unwrap().extend(answers);
        let src = slots.input::<rgraph_core::Texture>("src")?;
        pass.copy_src(src);
        slots.write::<rgraph_core::Texture>("dst", |t| pass.copy_dst(t.handle))?;
        Ok(())
    }
}

/// `Slots::modifies` says which slots the pass lists in both its inputs and its outputs
/// (so that a plugin can tell, before writing any, whether it draws over what it reads):
/// not an input-only slot, not an output-only one, not one the pass does not list.
#[test]
fn slots_say_which_outputs_the_pass_also_reads() {
    let mut graph = GraphBuilder::new();
    let a = graph.create_texture("a", TextureDesc::new(TextureFormat::Rgba8Unorm));
    let b = graph.create_texture("b", TextureDesc::new(TextureFormat::Rgba8Unorm));
    let a1 = graph
        .add_plugin_pass(
            "fill a",
            &Clear,
            clear_params(),
            &[],
            &[("target", a.into())],
        )
        .expect("clear declares")
        .texture("target")
        .expect("a1");
    let b1 = graph
        .add_plugin_pass(
            "fill b",
            &Clear,
            clear_params(),
            &[],
            &[("target", b.into())],
        )
        .expect("clear declares")
        .texture("target")
        .expect("b1");
    let probe = ModifiesProbe(std::sync::Mutex::new(Vec::new()));
    graph
        .add_plugin_pass(
            "probe",
            &probe,
            (),
            &[("src", a1.into()), ("dst", b1.into())],
            &[("dst", b1.into())],
        )
        .expect("the probe declares");
    assert_eq!(
        *probe.0.lock().unwrap(),
        [("src", false), ("dst", true), ("absent", false)]
    );
}
