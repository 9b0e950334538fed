//! `rgraph render --frames N --orbit DEGREES --out DIR/%04d.png`: N frames through one
//! executor, the camera orbiting the scene, one PNG and one timing line per frame.

use std::path::Path;

use crate::cli_support::rgraph;

fn read_png(path: &Path) -> image::RgbaImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{} is not a readable PNG: {e}", path.display()))
        .into_rgba8()
}

fn temp_dir() -> tempfile::TempDir {
    tempfile::tempdir().expect("a temporary directory")
}

#[test]
fn frames_orbit_the_camera_one_png_each_and_frame_0_is_the_plain_render() {
    let dir = temp_dir();
    let pattern = dir.path().join("orbit_%04d.png");
    let size = ["--width", "64", "--height", "48"];
    let pattern_arg = pattern.to_str().expect("temp paths are UTF-8");
    let run = rgraph(
        &[
            &[
                "render",
                "--frames",
                "2",
                "--orbit",
                "30",
                "--out",
                pattern_arg,
            ][..],
            &size,
        ]
        .concat(),
    )
    .expect(0);
    let frames = [0, 1].map(|i| dir.path().join(format!("orbit_{i:04}.png")));
    assert_eq!(
        run.stdout,
        format!("{}\n{}\n", frames[0].display(), frames[1].display()),
        "stdout: one path per frame"
    );
    run.stderr_has("render 2 frames, the camera orbiting 30°")
        .stderr_has("frame 0000: record+submit ")
        .stderr_has("frame 0001: record+submit ")
        .stderr_has(" ms, GPU ");

    let plain = dir.path().join("plain.png");
    let plain_arg = plain.to_str().expect("temp paths are UTF-8");
    rgraph(&[&["render", "--out", plain_arg][..], &size].concat()).expect(0);
    let (first, second) = (read_png(&frames[0]), read_png(&frames[1]));
    assert!(
        first == read_png(&plain),
        "frame 0 differs from a plain render"
    );
    assert!(first != second, "the orbited frame 1 equals frame 0");
}

#[test]
fn several_frames_need_a_frame_number_pattern() {
    let dir = temp_dir();
    let out = dir.path().join("frame.png");
    let out_arg = out.to_str().expect("temp paths are UTF-8");
    rgraph(&["render", "--frames", "3", "--out", out_arg])
        .expect(2)
        .stderr_has("--frames 3 writes one PNG per frame; put %04d");
    assert!(!out.exists());
}
