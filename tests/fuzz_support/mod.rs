//! A small mutation fuzzer on stable Rust, run as ordinary tests so CI runs it on every
//! submission for a fixed budget (see `tests/fuzz.rs`).
//!
//! Each target replays its seeds (committed files: `pipelines/`, the test fixtures and
//! `tests/fuzz_corpus/<target>/`), then runs mutations (see [`mutate`]) on a worker thread.
//! A mutated input the target accepted (it parsed, so later stages ran on it) joins the
//! pool that mutations start from, up to [`POOL_LIMIT`] inputs: without coverage feedback,
//! that is what lets mutations reach past the parsers. A panic is a crash and an input that runs longer than [`HANG_LIMIT`] a hang;
//! either is saved under the test binary's temporary directory, and the run fails with its
//! path. `RGRAPH_FUZZ_ITERATIONS` sets the number of mutated inputs per target (the longer
//! run in the README) and `RGRAPH_FUZZ_SEED` the generator's seed.

pub mod mutate;

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use mutate::{mutate, Rng};

/// The longest one input may run before it counts as a hang: far above the slowest seed
/// (a full deferred pipeline compiled in a debug build takes well under a second).
pub const HANG_LIMIT: Duration = Duration::from_secs(20);

/// The function that takes one input, made on the worker thread. It returns whether the
/// input was accepted (parsed, so the later stages ran on it).
pub type Target = Box<dyn FnMut(&[u8]) -> bool>;

/// The most accepted inputs kept to mutate, besides the seeds; past it a random one is
/// replaced.
pub const POOL_LIMIT: usize = 1_000;

/// A run stops after this many crashes: they are usually one bug, and each prints its
/// panic.
pub const MAX_CRASHES: usize = 5;

/// What one target's run found.
pub struct Report {
    pub target: &'static str,
    pub executions: usize,
    /// Mutated inputs the target accepted.
    pub accepted: usize,
    pub crashes: Vec<String>,
    pub hangs: Vec<String>,
    pub elapsed: Duration,
}

impl Report {
    /// Fails, naming the saved inputs, when anything crashed or hung.
    pub fn assert_clean(&self) {
        println!(
            "fuzz {}: {} inputs ({} mutations accepted) in {:.1} s, {} crashes, {} hangs",
            self.target,
            self.executions,
            self.accepted,
            self.elapsed.as_secs_f64(),
            self.crashes.len(),
            self.hangs.len()
        );
        assert!(
            self.crashes.is_empty() && self.hangs.is_empty(),
            "fuzz {}: crashes {:#?}, hangs {:#?}",
            self.target,
            self.crashes,
            self.hangs
        );
    }
}

/// Every regular file directly in each of `dirs` (relative to the repository root) whose
/// name ends with one of `extensions`, sorted, as seeds.
pub fn seeds(dirs: &[&str], extensions: &[&str]) -> Vec<Vec<u8>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files: Vec<PathBuf> = dirs
        .iter()
        .flat_map(|dir| {
            std::fs::read_dir(root.join(dir))
                .unwrap_or_else(|e| panic!("seed directory {dir}: {e}"))
                .filter_map(|e| Some(e.ok()?.path()))
        })
        .filter(|p| p.is_file())
        .filter(|p| {
            let name = p.to_string_lossy();
            extensions.iter().any(|e| name.ends_with(e))
        })
        .collect();
    files.sort();
    files
        .iter()
        .map(|f| std::fs::read(f).unwrap_or_else(|e| panic!("{}: {e}", f.display())))
        .collect()
}

/// How many mutated inputs each target runs: `RGRAPH_FUZZ_ITERATIONS`, else `budget`.
pub fn iterations(budget: usize) -> usize {
    std::env::var("RGRAPH_FUZZ_ITERATIONS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(budget)
}

/// Runs `target` on every seed, then on `iterations` mutations of them. `setup` runs once
/// on the worker thread and returns the function that takes one input (a panic in it is a
/// crash).
pub fn fuzz(
    target: &'static str,
    seeds: Vec<Vec<u8>>,
    iterations: usize,
    setup: fn() -> Target,
) -> Report {
    assert!(!seeds.is_empty(), "fuzz {target}: no seeds");
    let seed = std::env::var("RGRAPH_FUZZ_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0x5eed_2026);
    let mut rng = Rng::new(seed);
    let (inputs, work) = mpsc::channel::<Vec<u8>>();
    let (done, results) = mpsc::channel::<Result<bool, String>>();
    // The worker outlives a hang (a thread cannot be stopped): the run ends there.
    std::thread::spawn(move || {
        let mut run = setup();
        for input in work {
            let outcome = catch_unwind(AssertUnwindSafe(|| run(&input))).map_err(|panic| {
                panic
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_else(|| "a panic without a message".to_owned())
            });
            if done.send(outcome).is_err() {
                break;
            }
        }
    });
    let started = Instant::now();
    let mut report = Report {
        target,
        executions: 0,
        accepted: 0,
        crashes: Vec::new(),
        hangs: Vec::new(),
        elapsed: Duration::ZERO,
    };
    let total = seeds.len() + iterations;
    let mut pool = seeds.clone();
    for i in 0..total {
        let input = match seeds.get(i) {
            Some(seed) => seed.clone(),
            None => {
                let (base, other) = (rng.below(pool.len()), rng.below(pool.len()));
                mutate(&mut rng, &pool[base], &pool[other])
            }
        };
        inputs.send(input.clone()).expect("the worker runs");
        report.executions += 1;
        match results.recv_timeout(HANG_LIMIT) {
            Ok(Ok(accepted)) => {
                if accepted && i >= seeds.len() {
                    report.accepted += 1;
                    if pool.len() < seeds.len() + POOL_LIMIT {
                        pool.push(input);
                    } else {
                        let replaced = seeds.len() + rng.below(POOL_LIMIT);
                        pool[replaced] = input;
                    }
                }
            }
            Ok(Err(message)) => {
                let saved = save(target, "crash", report.crashes.len(), &input);
                report
                    .crashes
                    .push(format!("{}: {message}", saved.display()));
                if report.crashes.len() == MAX_CRASHES {
                    break;
                }
            }
            Err(_) => {
                let saved = save(target, "hang", 0, &input);
                report.hangs.push(saved.display().to_string());
                break;
            }
        }
    }
    report.elapsed = started.elapsed();
    report
}

/// Saves an input that crashed or hung, for replaying and for the corpus.
fn save(target: &str, kind: &str, n: usize, input: &[u8]) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("fuzz-findings")
        .join(target);
    std::fs::create_dir_all(&dir).expect("a findings directory");
    let path = dir.join(format!("{kind}-{n}"));
    std::fs::write(&path, input).expect("the finding is saved");
    path
}
