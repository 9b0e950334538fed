//! The plan page in a real headless Chromium (browser_support): the page of every shipped
//! pipeline opens with no console message, exception or request; every pass and resource
//! of the plan `--format json` prints is visible on it; hovering a culled pass, and
//! reaching it with Tab, shows its reason, Enter pins it and Escape closes it; nothing
//! scrolls sideways at 1280 px; text keeps its contrast in light and dark mode; hostile
//! names run nothing. Takes the screenshot the README shows (see [`SCREENSHOT`]).
//!
//! No GPU: `explain` compiles the plans on the CPU. A missing browser fails the tests with
//! what to install; they never skip.

use std::path::{Path, PathBuf};

use serde_json::{json, Value};

use crate::browser_support::{find_chromium, Browser, Tab};
use crate::explain_page::{
    plan_json, rgraph_without_gpu, shipped_pipelines, H200_TIMINGS, HOSTILE,
};

/// The viewport the page must fit without sideways scrolling.
const WIDTH: u32 = 1280;

/// Where the screenshot is written: target/graph-page.png, or docs/graph-page.png (the
/// README's) with RGRAPH_UPDATE_SCREENSHOT=1.
const SCREENSHOT: &str = "target/graph-page.png";
const README_SCREENSHOT: &str = "docs/graph-page.png";
const DARK_SCREENSHOT: &str = "target/graph-page-dark.png";

fn launch() -> Browser {
    let chromium = find_chromium().unwrap_or_else(|e| panic!("{e}"));
    Browser::launch(&chromium).unwrap_or_else(|e| panic!("{e}"))
}

/// Writes the page of `args` to `dir/NAME.html` and returns its path.
fn write_page(dir: &Path, name: &str, args: &[&str]) -> PathBuf {
    let out = dir.join(format!("{name}.html"));
    let out_arg = out.to_str().expect("UTF-8 paths");
    rgraph_without_gpu(&[&["explain", "--format", "html", "--out", out_arg], args].concat())
        .expect(0);
    out
}

fn check(tab: &Tab, browser: &mut Browser, expression: &str) -> Value {
    tab.eval(browser, expression)
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The console messages, exceptions, log entries, dialogs and requests for anything but
/// the page itself, among `events`.
fn complaints(events: &[Value], page: &Path) -> Vec<String> {
    let own = format!("file://{}", page.display());
    events
        .iter()
        .filter(|e| match e["method"].as_str().unwrap_or("") {
            "Runtime.consoleAPICalled" | "Runtime.exceptionThrown" | "Log.entryAdded" => true,
            "Page.javascriptDialogOpening" => true,
            "Network.requestWillBeSent" => e["params"]["request"]["url"] != json!(own),
            _ => false,
        })
        .map(|e| e.to_string())
        .collect()
}

/// What the page shows of each pass and resource of `plan`: the ids whose element is
/// missing, hidden, or lacks the name in its text.
const MISSING: &str = r#"(plan) => {
  const missing = [];
  const visible = (el) => { const r = el.getBoundingClientRect(); return r.width > 0 && r.height > 0; };
  const expect = (id, name) => {
    const el = document.getElementById(id);
    if (!el || !visible(el) || !el.textContent.includes(name)) missing.push(id + " " + name);
  };
  for (const p of plan.passes) expect("pass-" + p.id, p.name);
  for (const p of plan.culled) expect("pass-" + p.id, p.name);
  for (const r of plan.resources) expect("res-" + r.id, r.name);
  plan.textures.forEach((t, i) => expect("phys-t" + i, "texture #" + i));
  plan.buffers.forEach((b, i) => expect("phys-b" + i, "buffer #" + i));
  return missing;
}"#;

/// The contrast ratio of the body's text and of the pass names against the background.
const CONTRAST: &str = r#"(() => {
  const rgb = (c) => c.match(/[\d.]+/g).slice(0, 3).map(Number);
  const lum = (c) => {
    const [r, g, b] = rgb(c).map((v) => { v /= 255; return v <= 0.03928 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4; });
    return 0.2126 * r + 0.7152 * g + 0.0722 * b;
  };
  const ratio = (a, b) => { const [x, y] = [lum(a), lum(b)].sort((p, q) => q - p); return (x + 0.05) / (y + 0.05); };
  const bg = getComputedStyle(document.body).backgroundColor;
  const name = document.querySelector(".pass-h .name");
  return {
    background: lum(bg),
    body: ratio(getComputedStyle(document.body).color, bg),
    pass: name ? ratio(getComputedStyle(name).color, bg) : 21,
  };
})()"#;

/// The culled pass `id`'s tooltip: whether it shows, and its text.
fn tip(tab: &Tab, browser: &mut Browser, id: &str) -> (bool, String) {
    let state = check(
        tab,
        browser,
        &format!(
            "(() => {{ const t = document.getElementById('tip-{id}');
               return [getComputedStyle(t).display !== 'none' && t.getBoundingClientRect().height > 0,
                       t.innerText]; }})()"
        ),
    );
    (
        state[0] == json!(true),
        state[1].as_str().unwrap_or("").to_owned(),
    )
}

/// The centre of element `selector`, scrolled into view, in viewport pixels.
fn centre(tab: &Tab, browser: &mut Browser, selector: &str) -> (f64, f64) {
    let at = check(
        tab,
        browser,
        &format!(
            "(() => {{ const el = document.querySelector({selector:?}); el.scrollIntoView({{block: 'center'}});
               const r = el.getBoundingClientRect(); return [r.x + r.width / 2, r.y + r.height / 2]; }})()"
        ),
    );
    (at[0].as_f64().unwrap(), at[1].as_f64().unwrap())
}

/// Hovering, Tab, Enter and Escape on the first culled pass of the open page.
fn culled_pass_shows_its_reason(tab: &Tab, browser: &mut Browser, culled: &Value, what: &str) {
    let id = format!("pass-{}", culled["id"]);
    let reason = culled["reason"].as_str().unwrap();
    assert!(
        !tip(tab, browser, &id).0,
        "{what}: {id}'s reason shows before anything"
    );

    let (x, y) = centre(tab, browser, &format!("#{id} > button"));
    tab.hover(browser, x, y).unwrap();
    let (shown, text) = tip(tab, browser, &id);
    assert!(
        shown && text.contains(reason),
        "{what}: hovering {id} shows {text:?}, not {reason:?}"
    );
    tab.hover(browser, 1.0, 1.0).unwrap();
    assert!(
        !tip(tab, browser, &id).0,
        "{what}: the reason stays after the mouse left"
    );

    // Tab through the page from its start until the culled pass has the focus.
    check(
        tab,
        browser,
        "document.activeElement && document.activeElement.blur(); window.scrollTo(0, 0)",
    );
    let focused = format!("document.activeElement === document.querySelector('#{id} > button')");
    let mut presses = 0;
    while check(tab, browser, &focused) != json!(true) {
        presses += 1;
        assert!(presses < 400, "{what}: Tab never reaches {id}");
        tab.press(browser, "Tab", false).unwrap();
    }
    let (shown, text) = tip(tab, browser, &id);
    assert!(
        shown && text.contains(reason),
        "{what}: focusing {id} shows {text:?}"
    );
    let described = check(
        tab,
        browser,
        &format!("document.querySelector('#{id} > button').getAttribute('aria-describedby')"),
    );
    assert_eq!(
        described,
        json!(format!("tip-{id}")),
        "{what}: a screen reader hears the reason"
    );

    // Enter pins it: it stays when the focus moves on, until Escape.
    tab.press(browser, "Enter", false).unwrap();
    tab.press(browser, "Tab", false).unwrap();
    assert!(
        tip(tab, browser, &id).0,
        "{what}: Enter did not pin {id}'s reason"
    );
    tab.press(browser, "Escape", false).unwrap();
    assert!(
        !tip(tab, browser, &id).0,
        "{what}: Escape did not close {id}'s reason"
    );

    // A click pins it too: it stays when the mouse leaves, until a second click.
    let (x, y) = centre(tab, browser, &format!("#{id} > button"));
    tab.click(browser, x, y).unwrap();
    tab.hover(browser, 1.0, 1.0).unwrap();
    check(tab, browser, "document.activeElement.blur()");
    let (shown, text) = tip(tab, browser, &id);
    assert!(
        shown && text.contains(reason),
        "{what}: a click did not pin {id}'s reason"
    );
    tab.click(browser, x, y).unwrap();
    check(tab, browser, "document.activeElement.blur()");
    tab.hover(browser, 1.0, 1.0).unwrap();
    assert!(
        !tip(tab, browser, &id).0,
        "{what}: a second click did not close {id}'s reason"
    );
}

#[test]
fn every_shipped_pipeline_s_page_works_in_a_browser() {
    let dir = tempfile::tempdir().unwrap();
    let mut browser = launch();
    let tab = browser.tab(WIDTH, 900).unwrap_or_else(|e| panic!("{e}"));
    let mut culled_checked = 0;
    for pipeline in shipped_pipelines() {
        let path = pipeline.to_str().unwrap();
        let name = pipeline.file_stem().unwrap().to_str().unwrap();
        let page = write_page(dir.path(), name, &["--pipeline", path]);
        let plan = plan_json(&["--pipeline", path]);
        browser.take_events();
        tab.open(&mut browser, &page)
            .unwrap_or_else(|e| panic!("{e}"));
        let missing = check(&tab, &mut browser, &format!("({MISSING})({plan})"));
        assert_eq!(missing, json!([]), "{name}: not on the page");
        let sideways = check(
            &tab,
            &mut browser,
            "[document.documentElement.scrollWidth, document.documentElement.clientWidth]",
        );
        assert!(
            sideways[0].as_f64() <= sideways[1].as_f64(),
            "{name} scrolls sideways at {WIDTH} px: {sideways}"
        );
        if let Some(culled) = plan["culled"].as_array().and_then(|c| c.first()) {
            culled_pass_shows_its_reason(&tab, &mut browser, culled, name);
            culled_checked += 1;
        }
        let complaints = complaints(&browser.take_events(), &page);
        assert!(complaints.is_empty(), "{name}: {complaints:#?}");
    }
    assert!(
        culled_checked >= 20,
        "only {culled_checked} pages had a culled pass to check"
    );
}

/// The README's picture: deferred_noaa_fxaa's plan for its final image on builtin:lights at
/// 4K, where the lit HDR target and the tonemapped one share memory, with an H200's times;
/// light and dark, text keeping at least 4.5:1 contrast in both.
#[test]
fn the_page_reads_in_light_and_dark_mode_and_is_photographed() {
    let dir = tempfile::tempdir().unwrap();
    let page = write_page(
        dir.path(),
        "deferred_noaa_fxaa",
        &[
            "--pipeline",
            "pipelines/deferred_noaa_fxaa.ron",
            "--scene",
            "builtin:lights",
            "--output",
            "color",
            "--size",
            "3840x2160",
            "--timings",
            H200_TIMINGS,
        ],
    );
    let mut browser = launch();
    let tab = browser.tab(WIDTH, 900).unwrap_or_else(|e| panic!("{e}"));
    for dark in [true, false] {
        tab.prefer_dark(&mut browser, dark).unwrap();
        tab.open(&mut browser, &page)
            .unwrap_or_else(|e| panic!("{e}"));
        let contrast = check(&tab, &mut browser, CONTRAST);
        let background = contrast["background"].as_f64().unwrap();
        assert_eq!(
            background < 0.2,
            dark,
            "dark {dark}: background luminance {background}"
        );
        for text in ["body", "pass"] {
            let ratio = contrast[text].as_f64().unwrap();
            assert!(ratio >= 4.5, "dark {dark}: {text} text contrast {ratio:.2}");
        }
        if dark {
            // Not the README's, for a look at the dark scheme: target/graph-page-dark.png.
            let png = tab
                .screenshot(&mut browser, WIDTH)
                .unwrap_or_else(|e| panic!("{e}"));
            let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(DARK_SCREENSHOT);
            std::fs::write(&path, &png).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        }
        let bars = check(
            &tab,
            &mut browser,
            "document.querySelectorAll('.tbar.gpu').length",
        );
        assert_eq!(bars, json!(4), "the GPU time bars");
        let shared = check(
            &tab,
            &mut browser,
            "document.querySelectorAll('tr.phys .bar.named').length",
        );
        assert!(
            shared.as_u64() > Some(4),
            "no physical texture holds two resources: {shared}"
        );
    }
    let complaints = complaints(&browser.take_events(), &page);
    assert!(complaints.is_empty(), "{complaints:#?}");
    let png = tab
        .screenshot(&mut browser, WIDTH)
        .unwrap_or_else(|e| panic!("{e}"));
    let image = image::load_from_memory(&png).expect("the screenshot is a PNG");
    assert_eq!(image.width(), WIDTH);
    assert!(
        image.height() > 600,
        "the page is {} px tall",
        image.height()
    );
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let path = match std::env::var_os("RGRAPH_UPDATE_SCREENSHOT") {
        Some(_) => root.join(README_SCREENSHOT),
        None => root.join(SCREENSHOT),
    };
    std::fs::write(&path, &png).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
}

#[test]
fn hostile_names_run_nothing_in_a_browser() {
    let dir = tempfile::tempdir().unwrap();
    let page = write_page(dir.path(), "hostile", &["--pipeline", HOSTILE]);
    let plan = plan_json(&["--pipeline", HOSTILE]);
    let mut browser = launch();
    let tab = browser.tab(WIDTH, 900).unwrap_or_else(|e| panic!("{e}"));
    tab.open(&mut browser, &page)
        .unwrap_or_else(|e| panic!("{e}"));
    let missing = check(&tab, &mut browser, &format!("({MISSING})({plan})"));
    assert_eq!(
        missing,
        json!([]),
        "the hostile names are not on the page as text"
    );
    let elements = check(
        &tab,
        &mut browser,
        "[document.images.length, document.scripts.length, document.querySelectorAll('b').length]",
    );
    assert_eq!(
        elements,
        json!([0, 2, 0]),
        "images, scripts and bold elements on the page"
    );
    culled_pass_shows_its_reason(&tab, &mut browser, &plan["culled"][0], "hostile");
    // The pass named with an onmouseover handler, hovered.
    let (x, y) = centre(&tab, &mut browser, "#pass-0 > button");
    tab.hover(&mut browser, x, y).unwrap();
    let complaints = complaints(&browser.take_events(), &page);
    assert!(complaints.is_empty(), "{complaints:#?}");
}

#[test]
fn a_missing_browser_fails_with_what_to_install() {
    let error = Browser::launch(Path::new("/nonexistent/chromium"))
        .err()
        .expect("no browser there");
    for expected in [
        "/nonexistent/chromium does not exist",
        "chromium",
        "apt-get install chromium",
        "RGRAPH_CHROMIUM",
    ] {
        assert!(error.contains(expected), "{expected:?} not in {error:?}");
    }
}
