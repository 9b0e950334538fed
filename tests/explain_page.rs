//! `rgraph explain --format html` read as HTML, without a browser or a GPU: every shipped
//! pipeline's page holds every pass and resource of its plan under its id, embeds the plan
//! `--format json` prints, loads nothing from elsewhere and stays under 1 MB; hostile
//! names stay text; `--timings` picks the pipeline's row of a bench result or names the
//! rows there are; `--compare-scene` and `--compare` mark what differs. (A real browser
//! opens the pages in page_browser.rs.)

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

use crate::cli_support::Run;

/// The hostile names' graph file.
pub const HOSTILE: &str = "tests/fixtures/hostile_names.ron";
/// A bench result's rows of deferred_msaa_4x and deferred_noaa_fxaa on builtin:lights and
/// builtin:unlit, measured on an H200 at 3840x2160 (trimmed from the `variants-more` run's
/// results.json, summarised in docs/design/post-aa-ssao-light-prepass.md).
pub const H200_TIMINGS: &str = "tests/fixtures/bench_h200.json";

/// `rgraph ARGS` where no GPU adapter can exist: the Vulkan loader is given no driver.
pub fn rgraph_without_gpu(args: &[&str]) -> Run {
    let output = Command::new(env!("CARGO_BIN_EXE_rgraph"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("VK_DRIVER_FILES", "/nonexistent/no_driver.json")
        .env("VK_ICD_FILENAMES", "/nonexistent/no_driver.json")
        .output()
        .expect("the rgraph binary runs");
    Run {
        code: output.status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&output.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
    }
}

/// Every graph file in pipelines/, sorted.
pub fn shipped_pipelines() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("pipelines");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("pipelines/ is readable")
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    files.sort();
    assert!(
        files.len() >= 20,
        "only {} pipelines in {}",
        files.len(),
        dir.display()
    );
    files
}

/// The plan `--format json` prints for `args`.
pub fn plan_json(args: &[&str]) -> Value {
    let run = rgraph_without_gpu(&[&["explain", "--format", "json"], args].concat()).expect(0);
    serde_json::from_str(&run.stdout).expect("explain prints JSON")
}

fn page(args: &[&str]) -> String {
    rgraph_without_gpu(&[&["explain", "--format", "html"], args].concat())
        .expect(0)
        .stdout
}

/// Text as maud escapes it into HTML.
fn escaped(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The page's embedded data (`<script type="application/json" id="page-data">`).
fn data(html: &str) -> Value {
    let open = "<script type=\"application/json\" id=\"page-data\">";
    let start = html.find(open).expect("the page embeds its data") + open.len();
    let end = start + html[start..].find("</script>").expect("the data ends");
    serde_json::from_str(&html[start..end]).expect("the data is JSON")
}

/// The element with `id`'s opening tag.
fn tag<'a>(html: &'a str, id: &str) -> &'a str {
    let at = html
        .find(&format!(" id=\"{id}\""))
        .unwrap_or_else(|| panic!("no element with id {id}"));
    let start = html[..at].rfind('<').expect("an opening tag");
    let end = at + html[at..].find('>').expect("the tag ends");
    &html[start..=end]
}

fn items(value: &Value, key: &str) -> Vec<Value> {
    value[key].as_array().cloned().unwrap_or_default()
}

#[test]
fn every_shipped_pipeline_s_page_holds_its_plan_in_one_small_file() {
    for pipeline in shipped_pipelines() {
        let path = pipeline.to_str().expect("UTF-8 paths");
        let plan = plan_json(&["--pipeline", path]);
        let html = page(&["--pipeline", path]);
        assert!(
            html.len() < 1 << 20,
            "{path}: the page is {} bytes",
            html.len()
        );
        assert!(html.starts_with("<!DOCTYPE html>"), "{path}");
        // Nothing is fetched: no URL of any scheme, no stylesheet or font links.
        for outside in ["://", "<link", "@import", "url(", "<img", "<iframe"] {
            assert!(!html.contains(outside), "{path}: the page has {outside:?}");
        }
        assert_eq!(
            data(&html)["plan"],
            plan,
            "{path}: the embedded plan is not --format json's"
        );
        for pass in items(&plan, "passes").iter().chain(&items(&plan, "culled")) {
            let name = pass["name"].as_str().unwrap();
            let tag = tag(&html, &format!("pass-{}", pass["id"]));
            assert!(
                tag.contains(&format!("data-name=\"{}\"", escaped(name))),
                "{path}: {tag}"
            );
        }
        for culled in items(&plan, "culled") {
            let reason = escaped(culled["reason"].as_str().unwrap());
            assert!(html.contains(&reason), "{path}: no reason {reason}");
        }
        for r in items(&plan, "resources") {
            let name = r["name"].as_str().unwrap();
            let tag = tag(&html, &format!("res-{}", r["id"]));
            assert!(
                tag.contains(&format!("data-name=\"{}\"", escaped(name))),
                "{path}: {tag}"
            );
        }
        for i in 0..items(&plan, "textures").len() {
            tag(&html, &format!("phys-t{i}"));
        }
        for i in 0..items(&plan, "buffers").len() {
            tag(&html, &format!("phys-b{i}"));
        }
    }
}

#[test]
fn hostile_names_are_escaped_text() {
    let html = page(&["--pipeline", HOSTILE]);
    for raw in [
        "<img src=x",
        "<script>alert",
        "</script><script>alert",
        "<b onmouseover",
        "'too' <!--",
    ] {
        assert!(!html.contains(raw), "{raw:?} reached the page unescaped");
    }
    for name in [
        "<img src=x onerror=alert(1)>",
        "</script><script>alert(2)</script>",
        "<b onmouseover=alert(3)>clear</b>",
        "<script>alert(4)</script>",
        "blit \"'<>& ]]> {{x}}",
    ] {
        assert!(
            html.contains(&escaped(name)),
            "{name:?} is not on the page as text"
        );
    }
    // Two scripts: the data and the tooltips'; the data parses back to the raw names.
    assert_eq!(html.matches("<script").count(), 2);
    let data = data(&html);
    let culled = &data["plan"]["culled"][0];
    assert_eq!(culled["name"], "<script>alert(4)</script>");
    let reason = culled["reason"].as_str().unwrap();
    assert!(
        html.contains(&escaped(reason)),
        "the culled pass's reason {reason:?}"
    );
}

/// The page is built without a GPU: the Vulkan loader has no driver, as in CI validation.
#[test]
fn the_page_needs_no_gpu_and_out_writes_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("plan.html");
    let run = rgraph_without_gpu(&[
        "explain",
        "--pipeline",
        "pipelines/deferred_msaa_4x.ron",
        "--scene",
        "builtin:spheres",
        "--format",
        "html",
        "--out",
        out.to_str().unwrap(),
    ])
    .expect(0);
    assert_eq!(run.stdout, "", "with --out nothing goes to stdout");
    let html = std::fs::read_to_string(&out).unwrap();
    let data = data(&html);
    assert_eq!(data["setting"]["scene"], "builtin:spheres");
    assert!(html.contains("ambient, directional_lights, lit, point_lights, shadows, shallow_depth"));
    assert!(
        html.contains("<code>msaa = 4</code> (the file's default)"),
        "parameters"
    );
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        1,
        "no partial file left"
    );
}

#[test]
fn timings_come_from_the_pipeline_s_row() {
    let html = page(&[
        "--pipeline",
        "pipelines/deferred_msaa_4x.ron",
        "--scene",
        "builtin:lights",
        "--size",
        "3840x2160",
        "--timings",
        H200_TIMINGS,
        // The timings were measured before shadows: the plan without them.
        "--shadows",
        "off",
    ]);
    let timings = &data(&html)["timings"];
    assert_eq!(timings["passes"][0]["name"], "gbuffer");
    assert_eq!(timings["passes"][0]["gpu_ms"], 26.930672);
    assert!(timings["source"]
        .as_str()
        .unwrap()
        .contains("deferred_msaa_4x on builtin:lights, measured at 3840×2160 on NVIDIA H200"));
    // The bars: light the rest, the slowest pass, at full height with its time.
    assert!(html.contains("<th scope=\"row\">GPU ms<span class=\"meta\">median</span></th>"));
    assert!(
        html.contains("style=\"--v:1.000\"></div><span class=\"val\">76.0</span>"),
        "the slowest bar"
    );
    assert!(
        html.contains("GPU 26.9 ms, CPU 0.241 ms (medians)"),
        "gbuffer's tooltip"
    );
    // Passes of this plan the measured plan lacks (the debug views) say so.
    assert!(html.contains("not timed: the measured plan has no pass of this name"));
    // The strip of the frame: each timed pass's share.
    assert!(
        html.contains("light the rest 76.0 ms (52%)"),
        "the strip's label"
    );
}

#[test]
fn timings_without_the_row_name_the_rows_there_are() {
    let explain = |args: &[&str]| {
        rgraph_without_gpu(
            &[
                &["explain", "--format", "html", "--timings", H200_TIMINGS],
                args,
            ]
            .concat(),
        )
    };
    explain(&["--pipeline", "pipelines/deferred_msaa_4x.ron"])
        .expect(2)
        .stderr_has("has 2 rows for pipelines/deferred_msaa_4x.ron: deferred_msaa_4x on builtin:lights, deferred_msaa_4x on builtin:unlit; name the scene with --scene");
    explain(&["--pipeline", "pipelines/deferred_msaa_4x.ron", "--scene", "builtin:spheres"])
        .expect(2)
        .stderr_has("has no row for pipelines/deferred_msaa_4x.ron on builtin:spheres; it has deferred_msaa_4x on builtin:lights, deferred_msaa_4x on builtin:unlit");
    explain(&["--pipeline", "pipelines/forward_msaa_4x.ron", "--scene", "builtin:dense"])
        .expect(2)
        .stderr_has("has no row for pipelines/forward_msaa_4x.ron on builtin:dense; its rows: deferred_noaa_fxaa on builtin:lights, deferred_msaa_4x on builtin:lights,");

    let dir = tempfile::tempdir().unwrap();
    let error_row = dir.path().join("results.json");
    std::fs::write(
        &error_row,
        r#"{"resolution": [64, 48], "adapter": {"name": "llvmpipe"}, "rows": [{"scene": "builtin:dense",
            "pipeline": "deferred_noaa", "file": "pipelines/deferred_noaa.ron", "status": "error",
            "sweep": null, "message": "device lost", "figures": null}]}"#,
    )
    .unwrap();
    let args = [
        "explain",
        "--format",
        "html",
        "--pipeline",
        "pipelines/deferred_noaa.ron",
        "--timings",
    ];
    rgraph_without_gpu(&[&args[..], &[error_row.to_str().unwrap()]].concat())
        .expect(2)
        .stderr_has("the row for deferred_noaa on builtin:dense measured nothing: device lost");
    let not_json = dir.path().join("plan.ron");
    std::fs::write(&not_json, "Graph()").unwrap();
    rgraph_without_gpu(&[&args[..], &[not_json.to_str().unwrap()]].concat())
        .expect(1)
        .stderr_has("is not a results.json of `rgraph bench`");
    rgraph_without_gpu(&[&args[..], &["/nonexistent/results.json"]].concat())
        .expect(2)
        .stderr_has("--timings /nonexistent/results.json: cannot read it");
    rgraph_without_gpu(&[
        "explain",
        "--pipeline",
        "pipelines/deferred_noaa.ron",
        "--timings",
        H200_TIMINGS,
    ])
    .expect(2)
    .stderr_has("--timings is for --format html");
}

/// An unlit scene's plan against a lit scene's: the unlit G-buffer pass runs here only,
/// the lighting passes there only, the lit channels are allocated there only.
#[test]
fn compare_scene_marks_what_the_other_scene_s_plan_runs_and_allocates() {
    let html = page(&[
        "--pipeline",
        "pipelines/deferred_msaa_4x.ron",
        "--scene",
        "builtin:unlit",
        "--compare-scene",
        "builtin:spheres",
        "--size",
        "64x64",
    ]);
    let plan = plan_json(&[
        "--pipeline",
        "pipelines/deferred_msaa_4x.ron",
        "--scene",
        "builtin:unlit",
        "--size",
        "64x64",
    ]);
    let id = |name: &str| {
        items(&plan, "passes")
            .iter()
            .chain(&items(&plan, "culled"))
            .find(|p| p["name"] == name)
            .unwrap_or_else(|| panic!("no pass {name}"))["id"]
            .clone()
    };
    assert!(html.contains("Compared with the plan for builtin:spheres"));
    assert!(tag(&html, &format!("pass-{}", id("gbuffer (unlit)"))).contains("diff-added"));
    // gbuffer is dropped here and runs there: its chip says so.
    assert!(tag(&html, &format!("pass-{}", id("gbuffer"))).contains("diff-changed"));
    let gone = &html[html
        .find("id=\"gone-passes\"")
        .expect("the passes run there only")..];
    assert!(gone.contains(
        "<strong>light edges</strong>: condition &quot;!unlit_only &amp; !no_lights&quot; is \
         false"
    ));
    let gone = &html[html
        .find("id=\"gone-resources\"")
        .expect("resources allocated there only")..];
    assert!(gone.contains(
        "<strong>normal</strong> (64.0 KiB): condition &quot;!unlit_only&quot; is false"
    ));
}

/// A changed graph file against the original: a pass that writes what it read before.
#[test]
fn compare_marks_a_changed_pass_of_another_file() {
    let dir = tempfile::tempdir().unwrap();
    let original = std::fs::read_to_string("pipelines/postprocess_demo.ron").unwrap();
    // The changed file: present reads the HDR sky instead of the toned image, so the
    // tonemap pass is culled. It lives elsewhere, with the shaders it names beside it
    // (a graph file reads only its own tree).
    let shaders = Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
    std::fs::create_dir(dir.path().join("shaders")).unwrap();
    for shader in ["gradient.wgsl", "exposure.wgsl"] {
        std::fs::copy(
            shaders.join(shader),
            dir.path().join("shaders").join(shader),
        )
        .unwrap();
    }
    let changed = original.replace(
        "inputs: { \"src\": \"toned\" }",
        "inputs: { \"src\": \"hdr\" }",
    );
    assert_eq!(
        changed.matches("\"src\": \"hdr\"").count(),
        2,
        "the edit applies"
    );
    std::fs::create_dir(dir.path().join("pipelines")).unwrap();
    let changed_path = dir.path().join("pipelines/postprocess_changed.ron");
    let root = dir.path().to_str().unwrap();
    std::fs::write(&changed_path, changed).unwrap();
    let html = page(&[
        "--pipeline",
        changed_path.to_str().unwrap(),
        "--graph-root",
        root,
        "--compare",
        "pipelines/postprocess_demo.ron",
    ]);
    assert!(html.contains("Compared with pipelines/postprocess_demo.ron"));
    let present = html
        .find("data-name=\"present\"")
        .expect("the present pass");
    let header = &html[html[..present].rfind("<th").unwrap()..present];
    assert!(header.contains("diff-changed"), "{header}");
    assert!(
        html.contains("now reads hdr; no longer reads toned"),
        "what changed"
    );
    assert!(
        html.contains("<strong>tonemap</strong>"),
        "the pass that runs there only"
    );
}
