//! Measuring one pipeline on one scene, in two halves around the interleaved rounds
//! (rounds.rs): [`Setup::prepare`] compiles the plans to time (the scene's, and the
//! general ones where they differ); [`Setup::finish`] turns their timings into the row's
//! figures, with the final image, the plan's memory, and the edge mask and other views
//! rendered afterwards in graphs of the same size.

use std::sync::Arc;

use image::RgbaImage;
use rgraph_core::explain::page::Setting;
use rgraph_core::Plan;
use rgraph_passes::{Host, Shadows};
use rgraph_scene::{AssetPolicy, Lighting};

use super::candidates::{Candidate, COLOR};
use super::clocks::ClockSource;
use super::figures::Figures;
use super::memory::Memory;
use super::particle_work::{ParticleWork, PARTICLE_EDGES_OUTPUT};
use super::specialisation::{PlanShape, Specialisation};
use super::timing::{Times, Timing};
use super::work::{edge_share, sampling, Work, EDGES_OUTPUT, FRAGMENTS_OUTPUT};
use crate::commands::explain::page::parameters;
use crate::frame::{FrameError, Prepared, Session, Specialise};

/// What every measurement of one step of a run shares.
pub struct Setup<'a> {
    pub session: &'a Session,
    pub size: (u32, u32),
    /// Measured frames of each pipeline per round.
    pub frames: u32,
    pub rounds: u32,
    /// Warmup frames of each pipeline before round 1.
    pub warmup: u32,
    /// The most pooled memory the plans of one interleaved group may ask for.
    pub group_bytes: u64,
    pub clocks: &'a ClockSource,
    /// The round [`FAKE_SLOW_ROUND`](super::rounds::FAKE_SLOW_ROUND) slows, if set.
    pub fake_slow_round: Option<u32>,
    /// The sweep value this step measures, as the round log names it.
    pub sweep: Option<String>,
    /// What glTF scenes may read (`--asset-root`, `--max-asset-bytes`).
    pub assets: AssetPolicy,
    /// How every scene is lit (`--lights`).
    pub lighting: Lighting,
    /// How its lights cast shadows (`--shadows`, `--shadowed-lights`).
    pub shadows: Shadows,
}

/// The plans of one pipeline to time: the scene's, compiled for its features, and, where
/// that differs, the general plan and the scene's plan with the general shaders.
pub struct Plans<'s> {
    pub scene: Prepared<'s>,
    pub general: Option<Prepared<'s>>,
    pub plan_only: Option<Prepared<'s>>,
    pub about: About,
}

/// What [`Setup::finish`] needs to know of a pipeline besides its timings.
pub struct About {
    has_edges: bool,
    has_fragments: bool,
    has_particle_edges: bool,
    /// Each pass of the file and the plugin it runs.
    plugins: Vec<(String, String)>,
    special: PlanShape,
    general: Option<PlanShape>,
    features: Vec<String>,
    /// The parameters and the scene's features, for the plan's page.
    setting: Setting,
}

/// A timed plan once its rounds are over: what was measured and the plan.
pub struct Closed {
    pub timing: Timing,
    pub plan: Plan,
    /// The last frame's "color", for the scene's plan.
    pub color: Option<RgbaImage>,
}

impl Closed {
    /// `timing` of `prepared`, reading its "color" back when `read_color`.
    pub fn of(prepared: &Prepared, timing: Timing, read_color: bool) -> Result<Closed, FrameError> {
        Ok(Closed {
            color: read_color.then(|| prepared.read(COLOR)).transpose()?,
            plan: prepared.plan().clone(),
            timing,
        })
    }
}

/// The figures, the last measured frame's image, the debug.edges view when there is
/// one, and the timed plan with what it was compiled for.
pub struct Measured {
    pub figures: Figures,
    pub color: RgbaImage,
    pub edges: Option<RgbaImage>,
    pub plan: Plan,
    pub setting: Setting,
}

impl Setup<'_> {
    /// `candidate`'s "color" (only the passes it needs run) compiled for the scene; and,
    /// when that plan differs from the one compiled for every feature, the general plan;
    /// and when both the plan and the shaders differ, the scene's plan with the general
    /// shaders. Nothing runs yet.
    pub fn prepare(
        &self,
        candidate: &Candidate,
        host: &Arc<Host>,
    ) -> Result<Plans<'_>, FrameError> {
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
        let setting = Setting {
            scene_features: pipeline
                .features
                .names()
                .iter()
                .map(str::to_owned)
                .collect(),
            ..parameters(&pipeline.loaded, &candidate.params)
        };
        let scene = self.session.prepare(pipeline, self.size)?;
        let special = PlanShape::of(&scene);
        let features = scene.plan().features.clone();
        let (general, plan_only, general_shape) = match self.general(candidate, host, &special)? {
            Some((general, shape)) => {
                let both_differ =
                    !special.same_plan(&shape) && special.variants() != shape.variants();
                let plan_only = match both_differ {
                    true => {
                        let pipeline =
                            candidate.load(host.clone(), &[COLOR], Specialise::PlanOnly)?;
                        Some(self.session.prepare(pipeline, self.size)?)
                    }
                    false => None,
                };
                (Some(general), plan_only, Some(shape))
            }
            None => (None, None, None),
        };
        Ok(Plans {
            scene,
            general,
            plan_only,
            about: About {
                has_edges,
                has_fragments,
                has_particle_edges,
                plugins,
                special,
                general: general_shape,
                features,
                setting,
            },
        })
    }

    /// `candidate` compiled for every feature with the general shaders, unless the
    /// scene's plan (`special`) is the same.
    fn general(
        &self,
        candidate: &Candidate,
        host: &Arc<Host>,
        special: &PlanShape,
    ) -> Result<Option<(Prepared<'_>, PlanShape)>, FrameError> {
        let pipeline = candidate.load(host.clone(), &[COLOR], Specialise::General)?;
        let prepared = match self.session.prepare(pipeline, self.size) {
            // A file that makes its output only for some scenes (under a condition that
            // every feature at once fails) has no general plan to set beside the scene's.
            Err(FrameError::NotForScene { .. }) => return Ok(None),
            prepared => prepared?,
        };
        let shape = PlanShape::of(&prepared);
        Ok((shape != *special).then_some((prepared, shape)))
    }

    /// The row's figures from the timed plans (`general` and `plan_only` where
    /// [`prepare`](Self::prepare) made them); then renders its "debug.edges", when it has
    /// one, in another graph of the same size (and its "debug.fragments", for a pipeline
    /// that shades edge pixels per fragment, and its particle edges).
    pub fn finish(
        &self,
        candidate: &Candidate,
        host: &Arc<Host>,
        about: About,
        scene: Closed,
        general: Option<Closed>,
        plan_only: Option<Closed>,
    ) -> Result<Measured, FrameError> {
        let plan = &scene.plan;
        let (samples, supersampling) = sampling(plan);
        let reports: Vec<_> = scene.timing.frames().cloned().collect();
        let memory = Memory::of(plan, &reports);
        let particle_edge_share = match about.has_particle_edges {
            true => Some(edge_share(&self.render(
                candidate,
                host,
                PARTICLE_EDGES_OUTPUT,
            )?)),
            false => None,
        };
        let plugin = |pass: &str| {
            about
                .plugins
                .iter()
                .find(|(name, _)| name == pass)
                .map(|(_, plugin)| plugin.clone())
        };
        let particles = ParticleWork::of(plan, plugin, &host.scene, particle_edge_share);
        let specialisation = match (general, &about.general) {
            (Some(general), Some(shape)) => Some(specialisation(&about, shape, general, plan_only)),
            _ => None,
        };

        // A file may drop its edge view for some scenes (no lighting to split on an
        // unlit-only scene): the row then says why it has no edge figures.
        let (edges, dropped) = match about.has_edges {
            true => match self.render(candidate, host, EDGES_OUTPUT) {
                Ok(view) => (Some(view), None),
                Err(FrameError::NotForScene { why, .. }) => (None, Some(why)),
                Err(e) => return Err(e),
            },
            false => (None, None),
        };
        let work = match (&edges, dropped) {
            (Some(view), _) if about.has_fragments => {
                Work::from_fragments(view, &self.render(candidate, host, FRAGMENTS_OUTPUT)?)
            }
            (Some(view), _) => Work::from_edges(edge_share(view), samples),
            (None, Some(why)) => Work::not_made(&why),
            (None, None) => Work::from_kind(&candidate.stem(), samples, supersampling),
        };
        let mut figures = figures(&scene.timing, samples, memory, work);
        figures.specialisation = specialisation;
        figures.particles = particles;
        // Closed::of reads the scene plan's "color" back after its rounds.
        let color = scene.color.expect("the scene's plan's color was read");
        Ok(Measured {
            figures,
            color,
            edges,
            plan: scene.plan,
            setting: about.setting,
        })
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

/// The general plan's figures beside the scene's (`about.special`).
fn specialisation(
    about: &About,
    general_shape: &PlanShape,
    general: Closed,
    plan_only: Option<Closed>,
) -> Specialisation {
    let general_reports: Vec<_> = general.timing.frames().cloned().collect();
    Specialisation {
        features: about.features.clone(),
        shader_variants: about.special.variants().to_vec(),
        passes: about.special.passes(),
        general_passes: general_shape.passes(),
        general_memory: Memory::of(&general.plan, &general_reports),
        general_gpu_frame_ms: general.timing.frame_ms(),
        plan_only_gpu_frame_ms: plan_only.and_then(|p| p.timing.frame_ms()),
    }
}

/// The row's figures: the times over the rounds, and what else was measured.
fn figures(timing: &Timing, samples: u32, memory: Memory, work: Work) -> Figures {
    let Times {
        gpu_frame_ms,
        flag,
        created_while_measured,
        cpu_record_ms,
        passes,
    } = timing.times();
    Figures {
        samples,
        gpu_frame_ms,
        flag,
        created_while_measured,
        cpu_record_ms,
        ratio_to_noaa: None,
        passes,
        memory,
        work,
        image_error: None,
        specialisation: None,
        particles: None,
    }
}
