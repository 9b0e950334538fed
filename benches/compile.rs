//! Compile time of synthetic frames of 10, 100 and 1,000 passes (two resources each): the
//! GPU-free compile must stay cheap enough to run on every graph change, and grow linearly.
//! Run with `cargo bench --bench compile`.

use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use rgraph_core::{synthetic, CompileOptions};

fn compile(c: &mut Criterion) {
    let options = CompileOptions::default();
    let mut group = c.benchmark_group("compile");
    // 100 samples of the largest frame take about 10 s.
    group.measurement_time(Duration::from_secs(10));
    for passes in [10, 100, 1000] {
        let graph = synthetic::frame(passes);
        group.throughput(Throughput::Elements(passes as u64));
        group.bench_with_input(BenchmarkId::new("passes", passes), &graph, |b, graph| {
            b.iter(|| graph.compile(&options).expect("synthetic frames compile"))
        });
    }
    group.finish();
}

criterion_group!(benches, compile);
criterion_main!(benches);
