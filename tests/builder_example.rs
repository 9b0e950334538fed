//! The builder-only example (examples/builder_only.rs, compiled into this binary) run as a
//! test: a graph declared in code with two passes of its own, executed into a texture the
//! engine owns, whose every texel is checked exactly.

use crate::builder_only::{expected, render, SIZE};
use crate::common::gpu;

#[test]
fn two_passes_declared_in_code_fill_the_engine_target_exactly() {
    let gpu = gpu();
    let texels = render(&gpu.device, &gpu.queue, SIZE, false).expect("the example runs");
    assert_eq!(texels.len(), (SIZE.0 * SIZE.1) as usize);
    let wrong: Vec<String> = (0..SIZE.1)
        .flat_map(|y| (0..SIZE.0).map(move |x| (x, y)))
        .filter_map(|(x, y)| {
            let found = texels[(y * SIZE.0 + x) as usize];
            let wanted = expected(SIZE, x, y);
            (found != wanted).then(|| format!("({x}, {y}): {found:?}, expected {wanted:?}"))
        })
        .collect();
    assert!(
        wrong.is_empty(),
        "{} of {} texels differ, the first: {}",
        wrong.len(),
        texels.len(),
        wrong.iter().take(8).cloned().collect::<Vec<_>>().join("; ")
    );
    // The corners, spelt out: the mirror put column 0 of the pattern on the right.
    assert_eq!(texels[0], [255 - 63, 0, 64, 255]);
    assert_eq!(texels[(SIZE.0 * SIZE.1 - 1) as usize], [255, 31, 64, 255]);
}
