//! What the commands write goes where the user asked and nowhere else: through temporary
//! files of random names created exclusively, renamed into place, so a link another user
//! planted in a shared output folder (at the old predictable `.NAME.partial`, or at the
//! output's own name) is never written through: its target keeps its bytes. And a
//! `--out` pattern's width has a bound instead of a panic.

use std::path::Path;

use crate::cli_support::rgraph;

/// What a planted link points at, and what it must still hold afterwards.
const VICTIM: &str = "another user's file\n";

/// A victim file in `dir` and links to it at `names`.
fn plant(dir: &Path, names: &[&str]) -> std::path::PathBuf {
    let victim = dir.join("victim.txt");
    std::fs::write(&victim, VICTIM).expect("a writable temporary folder");
    for name in names {
        std::os::unix::fs::symlink(&victim, dir.join(name)).expect("a link");
    }
    victim
}

/// `victim` untouched, `path` a plain file, and no temporary file left in `dir`.
fn assert_written_beside_links(dir: &Path, victim: &Path, path: &Path) {
    assert_eq!(
        std::fs::read_to_string(victim).expect("the victim is still there"),
        VICTIM,
        "a planted link's target was written"
    );
    let meta = std::fs::symlink_metadata(path).expect("the output exists");
    assert!(
        meta.file_type().is_file(),
        "{} is not a plain file",
        path.display()
    );
    // Temporary files, not the links planted at their old names.
    let leftovers: Vec<String> = std::fs::read_dir(dir)
        .expect("the folder lists")
        .filter_map(|e| e.ok())
        .filter(|e| e.file_type().is_ok_and(|t| !t.is_symlink()))
        .filter_map(|e| e.file_name().into_string().ok())
        .filter(|name| name.ends_with(".partial"))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");
}

#[test]
fn render_writes_beside_planted_links_and_replaces_a_link_at_its_name() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let victim = plant(dir.path(), &[".x.png.partial", "x.png"]);
    let out = dir.path().join("x.png");
    let out_arg = out.to_str().expect("temp paths are UTF-8");
    rgraph(&["render", "--width", "8", "--height", "8", "--out", out_arg]).expect(0);
    assert_written_beside_links(dir.path(), &victim, &out);
    let png = image::open(&out).expect("x.png is a PNG").into_rgba8();
    assert_eq!(png.dimensions(), (8, 8));
    // The link at the old temporary name is left as it was.
    let planted = dir.path().join(".x.png.partial");
    assert!(std::fs::symlink_metadata(&planted)
        .expect("the planted link is still there")
        .file_type()
        .is_symlink());
}

#[test]
fn render_output_files_get_the_permissions_of_any_new_file() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().expect("a temporary folder");
    let out = dir.path().join("x.png");
    let out_arg = out.to_str().expect("temp paths are UTF-8");
    rgraph(&["render", "--width", "8", "--height", "8", "--out", out_arg]).expect(0);
    // A file created the ordinary way, under the same umask.
    let plain = dir.path().join("plain");
    std::fs::write(&plain, b"").expect("a writable temporary folder");
    let mode = |p: &Path| std::fs::metadata(p).expect("exists").permissions().mode() & 0o777;
    assert_eq!(mode(&out), mode(&plain), "x.png's mode");
}

#[test]
fn adapters_save_profile_writes_beside_planted_links() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let victim = plant(dir.path(), &[".profile.json.partial", "profile.json"]);
    let out = dir.path().join("profile.json");
    let out_arg = out.to_str().expect("temp paths are UTF-8");
    rgraph(&["adapters", "--save-profile", out_arg]).expect(0);
    assert_written_beside_links(dir.path(), &victim, &out);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).expect("readable"))
            .expect("the profile is JSON");
    assert!(json.get("limits").is_some(), "{json}");
}

#[test]
fn bench_out_dir_writes_beside_planted_links() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let victim = plant(
        dir.path(),
        &[".results.json.partial", "results.json", "results.md"],
    );
    let out = dir.path().to_str().expect("temp paths are UTF-8");
    // An unknown scene: nothing is measured (exit 1), and the results are still written.
    rgraph(&[
        "bench",
        "--scene",
        "builtin:no_such_scene",
        "--pipeline",
        "pipelines/deferred_noaa.ron",
        "--out-dir",
        out,
    ])
    .expect(1);
    for name in ["results.json", "results.md"] {
        assert_written_beside_links(dir.path(), &victim, &dir.path().join(name));
    }
}

#[test]
fn bench_refuses_a_link_where_its_scene_folder_goes() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let elsewhere = tempfile::tempdir().expect("a temporary folder");
    std::os::unix::fs::symlink(elsewhere.path(), dir.path().join("builtin_unlit")).expect("a link");
    let out = dir.path().to_str().expect("temp paths are UTF-8");
    let run = rgraph(&[
        "bench",
        "--scene",
        "builtin:unlit",
        "--pipeline",
        "pipelines/deferred_noaa.ron",
        "--no-reference",
        "--width",
        "8",
        "--height",
        "8",
        "--frames",
        "1",
        "--warmup",
        "0",
        "--out-dir",
        out,
    ]);
    assert_ne!(run.code, 0, "bench wrote through the link:\n{}", run.stderr);
    run.stderr_has("builtin_unlit")
        .stderr_has("not a folder (a link or a file)");
    let written: Vec<_> = std::fs::read_dir(elsewhere.path())
        .expect("the link's target lists")
        .collect();
    assert!(written.is_empty(), "written through the link: {written:?}");
}

#[test]
fn a_frame_number_padded_beyond_the_bound_is_an_error_not_a_panic() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let out = dir.path().join("f%065536d.png");
    let out_arg = out.to_str().expect("temp paths are UTF-8");
    rgraph(&["render", "--width", "8", "--height", "8", "--out", out_arg])
        .expect(2)
        .stderr_has("%065536d pads the frame number to 65536 digits; at most 32");
    let written: Vec<_> = std::fs::read_dir(dir.path()).expect("lists").collect();
    assert!(written.is_empty(), "{written:?}");
}
