//! Measuring one pipeline on one scene: warmup frames, measured frames, the plan's memory,
//! the final image, and the edge mask rendered in the same setup.

use std::sync::Arc;
use std::time::{Duration, Instant};

use graph_core::gpu::FrameReport;
use image::RgbaImage;
use passes_deferred_msaa::scene::{AssetPolicy, Lighting};
use passes_deferred_msaa::Host;

use super::candidates::{Candidate, COLOR};
use super::figures::{Figures, PassFigures};
use super::memory::Memory;
use super::particle_work::{ParticleWork, PARTICLE_EDGES_OUTPUT};
use super::specialisation::{PlanShape, Specialisation};
use super::stats::Spread;
use super::work::{edge_share, sampling, Work, EDGES_OUTPUT, FRAGMENTS_OUTPUT};
use crate::frame::{FrameError, Prepared, Session, Specialise};

/// What every measurement of one run shares.
pub struct Setup<'a> {
    pub session: &'a Session,
    pub size: (u32, u32),
    pub frames: u32,
    pub warmup: u32,
    /// What glTF scenes may read (`--asset-root`, `--max-asset-bytes`).
    pub assets: AssetPolicy,
    /// How every scene is lit (`--lights`).
    pub lighting: Lighting,
}

/// The least time warmup frames run: a GPU clocks down while the bench computes FLIP on
/// the CPU between pipelines (seconds at 2160p), and on the H200 frames of a few
/// milliseconds then took up to five times as long until its clocks came back, which two
/// warmup frames did not wait for.
const WARM_FOR: Duration = Duration::from_millis(500);

/// The figures, the last measured frame's image, and the debug.edges view when there is
/// one.
pub struct Measured {
    pub figures: Figures,
    pub color: RgbaImage,
    pub edges: Option<RgbaImage>,
}

impl Setup<'_> {
    /// Times `candidate`'s "color" (only the passes it needs run) as compiled for the
    /// scene, and as compiled for every feature when that plan differs; then renders its
    /// "debug.edges", when it has one, in another graph of the same size (and its
    /// "debug.fragments", for a pipeline that shades edge pixels per fragment).
    pub fn measure(&self, candidate: &Candidate, host: &Arc<Host>) -> Result<Measured, FrameError> {
        let pipeline = candidate.load(host.clone(), &[COLOR], Specialise::ToScene)?;
        let offers = |output: &str| pipeline.offered.iter().any(|o| o == output);
        let (has_edges, has_fragments) = (offers(EDGES_OUTPUT), offers(FRAGMENTS_OUTPUT));
        let has_particle_edges = offers(PARTICLE_EDGES_OUTPUT);
        let plugins: Vec<(String, String)> = pipeline
            .loaded
            .graph
            .passes()
            .iter()
            .filter_map(|p| Some((p.name.clone(), pipeline.loaded.plugin(&p.name)?.to_owned())))
            .collect();
        let mut prepared = self.session.prepare(pipeline, self.size)?;
        let reports = self.time(&mut prepared)?;
        let color = prepared.read(COLOR)?;
        let (samples, supersampling) = sampling(prepared.plan());
        let memory = Memory::of(prepared.plan(), &reports);
        let shape = PlanShape::of(&prepared);
        let features = prepared.plan().features.clone();
        let plan = prepared.plan().clone();
        drop(prepared);
        let particle_edge_share = match has_particle_edges {
            true => Some(edge_share(&self.render(
                candidate,
                host,
                PARTICLE_EDGES_OUTPUT,
            )?)),
            false => None,
        };
        let plugin = |pass: &str| {
            plugins
                .iter()
                .find(|(name, _)| name == pass)
                .map(|(_, plugin)| plugin.clone())
        };
        let particles = ParticleWork::of(&plan, plugin, &host.scene, particle_edge_share);
        let specialisation = self.general(candidate, host, shape, features)?;

        // A file may drop its edge view for some scenes (no lighting to split on an
        // unlit-only scene): the row then says why it has no edge figures.
        let (edges, dropped) = match has_edges {
            true => match self.render(candidate, host, EDGES_OUTPUT) {
                Ok(view) => (Some(view), None),
                Err(FrameError::NotForScene { why, .. }) => (None, Some(why)),
                Err(e) => return Err(e),
            },
            false => (None, None),
        };
        let work = match (&edges, dropped) {
            (Some(view), _) if has_fragments => {
                Work::from_fragments(view, &self.render(candidate, host, FRAGMENTS_OUTPUT)?)
            }
            (Some(view), _) => Work::from_edges(edge_share(view), samples),
            (None, Some(why)) => Work::not_made(&why),
            (None, None) => Work::from_kind(&candidate.stem(), samples, supersampling),
        };
        let mut figures = figures(&reports, samples, memory, work);
        figures.specialisation = specialisation;
        figures.particles = particles;
        Ok(Measured {
            figures,
            color,
            edges,
        })
    }

    /// The warmup frames, for at least [`WARM_FOR`] when there are any, then the
    /// measured ones' reports.
    fn time(&self, prepared: &mut Prepared<'_>) -> Result<Vec<FrameReport>, FrameError> {
        let start = Instant::now();
        prepared.run(self.warmup as usize)?;
        while self.warmup > 0 && start.elapsed() < WARM_FOR {
            prepared.run(1)?;
        }
        prepared.run(self.frames as usize)
    }

    /// `candidate` compiled for every feature with the general shaders and timed like
    /// the scene's plan, unless the scene's plan (`special`, compiled for `features`)
    /// is the same; and the scene's plan with the general shaders, when both the plan
    /// and the shaders differ.
    fn general(
        &self,
        candidate: &Candidate,
        host: &Arc<Host>,
        special: PlanShape,
        features: Vec<String>,
    ) -> Result<Option<Specialisation>, FrameError> {
        let pipeline = candidate.load(host.clone(), &[COLOR], Specialise::General)?;
        let mut prepared = match self.session.prepare(pipeline, self.size) {
            // A file that makes its output only for some scenes (under a condition that
            // every feature at once fails) has no general plan to set beside the scene's.
            Err(FrameError::NotForScene { .. }) => return Ok(None),
            prepared => prepared?,
        };
        let general = PlanShape::of(&prepared);
        if general == special {
            return Ok(None);
        }
        let reports = self.time(&mut prepared)?;
        let general_gpu_frame_ms = frame_ms(&reports);
        let general_memory = Memory::of(prepared.plan(), &reports);
        drop(prepared);
        let both_differ = !special.same_plan(&general) && special.variants() != general.variants();
        let plan_only_gpu_frame_ms = if both_differ {
            self.plan_only(candidate, host)?
        } else {
            None
        };
        Ok(Some(Specialisation {
            features,
            shader_variants: special.variants().to_vec(),
            passes: special.passes(),
            general_passes: general.passes(),
            general_memory,
            general_gpu_frame_ms,
            plan_only_gpu_frame_ms,
        }))
    }

    /// The GPU frame time of `candidate` compiled for the scene with the general shaders.
    fn plan_only(
        &self,
        candidate: &Candidate,
        host: &Arc<Host>,
    ) -> Result<Option<Spread>, FrameError> {
        let pipeline = candidate.load(host.clone(), &[COLOR], Specialise::PlanOnly)?;
        let mut prepared = self.session.prepare(pipeline, self.size)?;
        Ok(frame_ms(&self.time(&mut prepared)?))
    }

    /// `output` of one frame of `candidate`: the reference, edge masks, measurements.
    pub fn render(
        &self,
        candidate: &Candidate,
        host: &Arc<Host>,
        output: &str,
    ) -> Result<RgbaImage, FrameError> {
        let pipeline = candidate.load(host.clone(), &[output], Specialise::ToScene)?;
        let mut prepared = self.session.prepare(pipeline, self.size)?;
        prepared.run(1)?;
        prepared.read(output)
    }
}

/// The spread of the GPU frame times of `reports`, `None` without timestamps.
fn frame_ms(reports: &[FrameReport]) -> Option<Spread> {
    Spread::of_ns(reports.iter().filter_map(|r| r.gpu_total_ns))
}

/// Per-frame and per-pass spreads over the measured frames.
fn figures(reports: &[FrameReport], samples: u32, memory: Memory, work: Work) -> Figures {
    let passes = reports.first().map_or(Vec::new(), |first| {
        first
            .passes
            .iter()
            .enumerate()
            .map(|(i, pass)| {
                let timings = || reports.iter().filter_map(move |r| r.passes.get(i));
                PassFigures {
                    name: pass.name.clone(),
                    kind: pass.kind.to_string(),
                    gpu_ms: Spread::of_ns(timings().filter_map(|t| t.gpu_ns)),
                    cpu_ms: Spread::of_ns(timings().map(|t| t.cpu_ns)),
                }
            })
            .collect()
    });
    Figures {
        samples,
        gpu_frame_ms: frame_ms(reports),
        cpu_record_ms: Spread::of_ns(
            reports
                .iter()
                .map(|r| r.passes.iter().map(|p| p.cpu_ns).sum()),
        ),
        ratio_to_noaa: None,
        passes,
        memory,
        work,
        image_error: None,
        specialisation: None,
        particles: None,
    }
}
