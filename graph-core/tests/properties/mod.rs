//! Properties of every compiled plan, checked on random graphs (valid or not) and on the
//! synthetic frames the benchmark compiles: compiling never panics, and a plan that comes
//! out runs every access in version order, keeps what roots need, and never shares memory
//! between resources alive at once or of different shape and usage.

mod checks;
mod recipe;

use proptest::prelude::*;
use rgraph_core::CompileOptions;

use checks::check_plan;
use recipe::recipe;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn random_graphs_compile_to_sound_plans_or_fail_cleanly(recipe in recipe()) {
        let graph = recipe.build();
        if let Ok(plan) = graph.compile(&CompileOptions::default()) {
            check_plan(&graph, &plan);
        }
    }
}

#[test]
fn synthetic_frames_compile_to_sound_plans() {
    for passes in [1, 10, 37, 100, 1000] {
        let graph = rgraph_core::synthetic::frame(passes);
        let plan = graph
            .compile(&CompileOptions::default())
            .unwrap_or_else(|e| panic!("synthetic frame of {passes} passes:\n{e}"));
        check_plan(&graph, &plan);
        assert_eq!(graph.resources().len(), 2 * passes);
    }
}
