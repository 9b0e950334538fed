//! Loading grows linearly with the size of a graph file: positions of names are found with
//! an index of the text built once, not by rescanning the text for each name.

use std::time::{Duration, Instant};

use rgraph_core::file::{load_str, Registry};

/// A chain of `n` copy passes from an imported texture through `n` more, each name on its own line, or all on
/// one line (as a minified file would be).
fn chain(n: usize, one_line: bool) -> String {
    let newline = if one_line { " " } else { "\n" };
    let mut text = format!(
        "Graph(resources: {{{newline}\"t0\": ImportedTexture(format: \"rgba8unorm\"),{newline}"
    );
    for i in 1..=n {
        text += &format!("\"t{i}\": Texture(format: \"rgba8unorm\"),{newline}");
    }
    text += &format!("}}, passes: [{newline}");
    for i in 0..n {
        text += &format!(
            "(name: \"p{i}\", plugin: \"copy\", inputs: {{ \"src\": \"t{i}\" }}, \
             outputs: {{ \"dst\": \"t{}\" }}),{newline}",
            i + 1
        );
    }
    text += &format!("], outputs: [\"t{n}\"])");
    text
}

fn load_time(n: usize, one_line: bool) -> Duration {
    let text = chain(n, one_line);
    let registry = Registry::with_builtins();
    let started = Instant::now();
    load_str("chain.ron", &text, &registry).unwrap_or_else(|e| panic!("{e}"));
    started.elapsed()
}

#[test]
fn forty_thousand_names_load_in_linear_time() {
    for one_line in [false, true] {
        let small = load_time(2_000, one_line);
        let large = load_time(20_000, one_line);
        println!("one line {one_line}: 4,000 names {small:?}, 40,000 names {large:?}");
        // Ten times the names: linear is 10x; the quadratic scan was 100x. 30x leaves room
        // for noise on a busy machine.
        assert!(
            large < small * 30 + Duration::from_millis(200),
            "one line {one_line}: 4,000 names took {small:?}, 40,000 took {large:?}"
        );
    }
}
