//! `rgraph compare`: two images' share of pixels within a tolerance, decided by the exit
//! status, with the sizes, the unreadable file and the out-of-range flag named. No GPU.

use crate::cli_support;

use std::path::Path;

use cli_support::rgraph;
use image::{Rgba, RgbaImage};

fn save(dir: &Path, name: &str, image: &RgbaImage) -> String {
    let path = dir.join(name);
    image.save(&path).unwrap();
    path.to_str().expect("temporary paths are UTF-8").to_owned()
}

#[test]
fn the_share_within_the_tolerance_decides_the_exit_status() {
    let dir = tempfile::tempdir().unwrap();
    let grey = RgbaImage::from_pixel(10, 10, Rgba([128, 128, 128, 255]));
    let mut off = grey.clone();
    // One pixel 1/255 off (within the default tolerance), one 40/255 off.
    off.put_pixel(2, 3, Rgba([129, 128, 128, 255]));
    off.put_pixel(7, 5, Rgba([128, 88, 128, 255]));
    let (a, b) = (
        save(dir.path(), "a.png", &grey),
        save(dir.path(), "b.png", &off),
    );
    let same = rgraph(&["compare", &a, &b, "--at-least", "99"]).expect(0);
    assert!(
        same.stdout.contains("99.000% of 100 pixels within 1/255")
            && same.stdout.contains("worst 40/255 at (7, 5)"),
        "{}",
        same.stdout
    );
    let strict = rgraph(&["compare", &a, &b]).expect(1);
    assert!(
        strict.stderr.contains("fewer than --at-least 100%"),
        "{}",
        strict.stderr
    );
    rgraph(&["compare", &a, &b, "--tolerance", "40"]).expect(0);
}

#[test]
fn sizes_unreadable_files_and_flags_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let small = save(dir.path(), "small.png", &RgbaImage::new(4, 4));
    let large = save(dir.path(), "large.png", &RgbaImage::new(8, 4));
    let sizes = rgraph(&["compare", &small, &large]).expect(1);
    assert!(
        sizes.stderr.contains("small.png is 4x4 but") && sizes.stderr.contains("large.png is 8x4"),
        "{}",
        sizes.stderr
    );
    let text = dir.path().join("not.png");
    std::fs::write(&text, "not an image").unwrap();
    let unreadable = rgraph(&["compare", &small, text.to_str().unwrap()]).expect(2);
    assert!(unreadable.stderr.contains("cannot read") && unreadable.stderr.contains("not.png"));
    let missing = rgraph(&["compare", &small, "no-such.png"]).expect(2);
    assert!(
        missing.stderr.contains("cannot read no-such.png"),
        "{}",
        missing.stderr
    );
    let range = rgraph(&["compare", &small, &small, "--at-least", "101"]).expect(2);
    assert!(
        range.stderr.contains("--at-least is 101"),
        "{}",
        range.stderr
    );
}
