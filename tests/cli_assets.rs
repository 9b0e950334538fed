//! What a glTF scene may read, from the command line: `--asset-root` widens the folder its
//! URIs may reach, `--max-asset-bytes` caps each file read; and what the loader warns of,
//! after the file's name. Checked through `explain --scene`, which loads the scene without
//! a GPU.

use crate::cli_support;

use std::path::{Path, PathBuf};

use cli_support::{rgraph, Run};

const PIPELINE: &str = "pipelines/deferred_msaa_4x.ron";

/// The committed external-buffer fixture copied to `dir/asset/scene.gltf`, its buffer moved
/// to `dir/lights_cameras.bin` and named by the URI `../lights_cameras.bin`.
fn asset_reaching_out(dir: &Path) -> PathBuf {
    let fixtures = Path::new("scene/tests/fixtures/external");
    let text = std::fs::read_to_string(fixtures.join("lights_cameras.gltf")).unwrap();
    let text = text.replace("\"lights_cameras.bin\"", "\"../lights_cameras.bin\"");
    std::fs::create_dir_all(dir.join("asset")).unwrap();
    let gltf = dir.join("asset/scene.gltf");
    std::fs::write(&gltf, text).unwrap();
    std::fs::copy(
        fixtures.join("lights_cameras.bin"),
        dir.join("lights_cameras.bin"),
    )
    .unwrap();
    gltf
}

fn explain(scene: &Path, extra: &[&str]) -> Run {
    let scene = scene.to_str().expect("temp paths are UTF-8");
    rgraph(
        &[
            &["explain", "--pipeline", PIPELINE, "--scene", scene],
            extra,
        ]
        .concat(),
    )
}

#[test]
fn a_uri_leaving_the_asset_folder_needs_asset_root() {
    let dir = tempfile::tempdir().unwrap();
    let gltf = asset_reaching_out(dir.path());
    explain(&gltf, &[])
        .expect(1)
        .stderr_has(&format!(
            "{}: buffer 0: URI `../lights_cameras.bin` points to ",
            gltf.display()
        ))
        .stderr_has("outside the asset folder")
        .stderr_has("(--asset-root DIR)");
    let root = dir.path().to_str().unwrap();
    let run = explain(&gltf, &["--asset-root", root]).expect(0);
    assert!(run.stdout.contains("scene "), "{}", run.stdout);
}

#[test]
fn max_asset_bytes_caps_each_file_read() {
    let dir = tempfile::tempdir().unwrap();
    let gltf = asset_reaching_out(dir.path());
    let root = dir.path().to_str().unwrap();
    explain(&gltf, &["--asset-root", root, "--max-asset-bytes", "100"])
        .expect(2)
        .stderr_has(&format!(
            "cannot read {}: larger than the maximum of 100 bytes",
            gltf.display()
        ));
    explain(&gltf, &["--max-asset-bytes", "0"])
        .expect(2)
        .stderr_has("--max-asset-bytes");
}

#[test]
fn bench_takes_the_same_asset_flags() {
    let dir = tempfile::tempdir().unwrap();
    let gltf = asset_reaching_out(dir.path());
    let bench = |extra: &[&str]| {
        let out = dir.path().join("out");
        let args = [
            "bench",
            "--scene",
            gltf.to_str().unwrap(),
            "--pipeline",
            "pipelines/deferred_noaa.ron",
            "--width",
            "32",
            "--height",
            "24",
            "--frames",
            "1",
            "--warmup",
            "0",
            "--no-reference",
            "--out-dir",
            out.to_str().unwrap(),
        ];
        rgraph(&[&args[..], extra].concat())
    };
    // The only row cannot be measured: exit 1, the reason in the row.
    bench(&[])
        .expect(1)
        .stderr_has("URI `../lights_cameras.bin` points to ");
    let root = dir.path().to_str().unwrap();
    bench(&["--asset-root", root]).expect(0);
}

/// A loader's warning names the file it is about, as a compiler's do (`FILE: warning:
/// ...`): here an extension the file uses that the renderer does not implement.
#[test]
fn a_loader_warning_names_its_file() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string("tests/fixtures/points_lines/mixed.gltf").unwrap();
    let used = "\"KHR_materials_unlit\"";
    assert!(text.contains(used));
    let text = text.replacen(used, "\"KHR_materials_unlit\", \"KHR_materials_volume\"", 1);
    let gltf = dir.path().join("volume.gltf");
    std::fs::write(&gltf, text).unwrap();
    explain(&gltf, &[]).expect(0).stderr_has(&format!(
        "{}: warning: glTF extension KHR_materials_volume is not implemented",
        gltf.display()
    ));
}
