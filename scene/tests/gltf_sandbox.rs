//! A glTF file reads only inside its folder (or the policy's root), only regular files, and
//! only up to the size cap: each refusal names the URI or the file.

use crate::common;

use std::path::{Path, PathBuf};

use common::{temp_dir, Gltf};
use rgraph_scene::{AssetPolicy, Scene, SceneError};

/// A one-triangle glTF at `dir/asset/scene.gltf` whose buffer URI is `uri`, plus its bytes in
/// `dir/outside.bin` (outside the asset folder) and `dir/asset/scene.bin`.
fn asset_with_uri(dir: &Path, uri: &str) -> PathBuf {
    let mut gltf = Gltf::default();
    gltf.triangle(None);
    let folder = dir.join("asset");
    std::fs::create_dir_all(&folder).unwrap();
    let path = folder.join("scene.gltf");
    gltf.write_external(&path, "scene.bin", uri);
    std::fs::write(dir.join("outside.bin"), &gltf.bin).unwrap();
    path
}

fn load(path: &Path, policy: &AssetPolicy) -> Result<Scene, SceneError> {
    Scene::from_gltf_with(path, policy)
}

/// The message of an `InvalidBuffer` error for buffer 0 of `path`.
fn refused_buffer(path: &Path, policy: &AssetPolicy) -> String {
    let error = load(path, policy).expect_err("the URI must be refused");
    assert!(
        matches!(error, SceneError::InvalidBuffer { buffer: 0, .. }),
        "{error:?}"
    );
    error.to_string()
}

#[test]
fn an_absolute_uri_is_refused_naming_it() {
    let dir = temp_dir("sandbox_absolute");
    let path = asset_with_uri(&dir, "/etc/passwd");
    let message = refused_buffer(&path, &AssetPolicy::default());
    let folder = dir.join("asset").canonicalize().unwrap();
    assert_eq!(
        message,
        format!(
            "{}: buffer 0: URI `/etc/passwd` points to /etc/passwd, outside the asset folder \
             {}; assets only read files inside their folder unless it is widened \
             (--asset-root DIR)",
            path.display(),
            folder.display()
        )
    );
}

#[test]
fn a_uri_climbing_out_is_refused_unless_the_root_allows_it() {
    let dir = temp_dir("sandbox_parent");
    let path = asset_with_uri(&dir, "../outside.bin");
    let message = refused_buffer(&path, &AssetPolicy::default());
    assert!(
        message.contains("URI `../outside.bin` points to ")
            && message.contains("outside.bin, outside the asset folder"),
        "{message}"
    );
    // Percent-encoding does not hide the climb.
    let encoded = asset_with_uri(&dir, "%2E%2E/outside.bin");
    let message = refused_buffer(&encoded, &AssetPolicy::default());
    assert!(message.contains("URI `%2E%2E/outside.bin`"), "{message}");

    let widened = AssetPolicy {
        root: Some(dir.clone()),
        ..AssetPolicy::default()
    };
    let scene = load(&path, &widened).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.meshes.len(), 1);
}

#[test]
fn a_missing_file_outside_is_refused_like_an_existing_one() {
    let dir = temp_dir("sandbox_missing_outside");
    let path = asset_with_uri(&dir, "../../nowhere/secret.bin");
    let message = refused_buffer(&path, &AssetPolicy::default());
    assert!(message.contains("outside the asset folder"), "{message}");
}

#[cfg(unix)]
#[test]
fn a_symbolic_link_leading_out_is_refused() {
    let dir = temp_dir("sandbox_symlink");
    let path = asset_with_uri(&dir, "link.bin");
    std::os::unix::fs::symlink(dir.join("outside.bin"), dir.join("asset/link.bin")).unwrap();
    let message = refused_buffer(&path, &AssetPolicy::default());
    assert!(
        message.contains("URI `link.bin` leads (through a symbolic link) to ")
            && message.contains("outside.bin, outside the asset folder"),
        "{message}"
    );
}

#[cfg(unix)]
#[test]
fn devices_and_fifos_are_refused_without_reading() {
    let dir = temp_dir("sandbox_special");
    let everywhere = AssetPolicy {
        root: Some(PathBuf::from("/")),
        ..AssetPolicy::default()
    };
    let path = asset_with_uri(&dir, "/dev/zero");
    let error = load(&path, &everywhere).expect_err("/dev/zero must be refused");
    assert_eq!(
        error.to_string(),
        format!(
            "{}: buffer 0: cannot read /dev/zero: not a regular file (it is a character device)",
            path.display()
        )
    );

    // Nobody ever writes to the FIFO: opening it for reading would block forever.
    let path = asset_with_uri(&dir, "pipe.bin");
    let fifo = dir.join("asset/pipe.bin");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo failed");
    let error = load(&path, &AssetPolicy::default()).expect_err("a FIFO must be refused");
    assert_eq!(
        error.to_string(),
        format!(
            "{}: buffer 0: cannot read {}: not a regular file (it is a FIFO)",
            path.display(),
            fifo.display()
        )
    );
    // The glTF file itself too.
    let error = load(&fifo, &AssetPolicy::default()).expect_err("a FIFO must be refused");
    assert!(error
        .to_string()
        .ends_with("not a regular file (it is a FIFO)"));
}

#[test]
fn reads_over_the_cap_are_refused_naming_the_file_and_the_cap() {
    let dir = temp_dir("sandbox_cap");
    let path = asset_with_uri(&dir, "scene.bin");
    let bin = dir.join("asset/scene.bin");
    let gltf_len = std::fs::metadata(&path).unwrap().len();
    let bin_len = std::fs::metadata(&bin).unwrap().len();
    assert!(
        bin_len < gltf_len,
        "the test needs the buffer to be smaller"
    );

    let cap = |max_bytes| AssetPolicy {
        max_bytes,
        ..AssetPolicy::default()
    };
    let error = load(&path, &cap(gltf_len - 1)).expect_err("the glTF file is over the cap");
    assert_eq!(
        error.to_string(),
        format!(
            "cannot read {}: larger than the maximum of {} bytes",
            path.display(),
            gltf_len - 1
        )
    );
    std::fs::write(&bin, vec![0u8; gltf_len as usize + 1]).unwrap();
    let error = load(&path, &cap(gltf_len)).expect_err("the buffer is over the cap");
    assert!(
        matches!(error, SceneError::InvalidBuffer { buffer: 0, .. }),
        "{error:?}"
    );
    assert_eq!(
        error.to_string(),
        format!(
            "{}: buffer 0: cannot read {}: larger than the maximum of {gltf_len} bytes",
            path.display(),
            bin.display()
        )
    );
}
