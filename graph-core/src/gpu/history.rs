//! Histories across frames: for each [`HistoryEdge`] of the executing plan, a pair of
//! textures that no other resource shares. Each frame one holds the previous frame's
//! contents (what the history resource reads) and the other takes this frame's (what the
//! source's writer writes); after a frame that ran, they swap.
//!
//! A pair is made fresh, so zeroed by wgpu (which initialises every texture before its
//! first use), whenever the plan's [`fingerprint`](Plan::fingerprint) differs from the
//! last frame's (the first frame, a resize, other features, another graph) or the engine
//! asked for a reset: that frame's history reads zeros and its passes are told
//! ([`FrameResources::history_reset`](crate::gpu::FrameResources::history_reset)).

use crate::handle::ResourceId;
use crate::plan::{HistoryEdge, Plan};

/// One history's textures.
struct Pair {
    textures: [wgpu::Texture; 2],
    /// Which of `textures` holds the previous frame's contents.
    previous: usize,
    /// Whether the previous one holds a frame's contents, rather than the zeros it was
    /// made with.
    valid: bool,
}

/// This frame's textures of one history (handles: wgpu counts the references).
pub(crate) struct Carried {
    pub source: ResourceId,
    pub history: ResourceId,
    /// The previous frame's contents, which the history resource reads.
    pub previous: wgpu::Texture,
    /// What this frame's writer of the source writes.
    pub current: wgpu::Texture,
    /// The previous texture holds zeros, not a frame's contents.
    pub reset: bool,
}

/// The executor's histories, kept across frames for one plan at a time.
#[derive(Default)]
pub(crate) struct Histories {
    /// The fingerprint of the plan the pairs were made for.
    fingerprint: u64,
    /// One per edge of that plan, in its order.
    pairs: Vec<Pair>,
}

impl Histories {
    /// The pairs for `plan`'s edges, kept from the last frame when the plan is the same,
    /// made (zeroed) otherwise.
    pub fn begin(&mut self, device: &wgpu::Device, plan: &Plan) -> Vec<Carried> {
        if plan.fingerprint != self.fingerprint || self.pairs.len() != plan.history.len() {
            self.fingerprint = plan.fingerprint;
            self.pairs = plan
                .history
                .iter()
                .map(|e| Pair::new(device, plan, e))
                .collect();
        }
        plan.history
            .iter()
            .zip(&self.pairs)
            .map(|(edge, pair)| Carried {
                source: edge.source,
                history: edge.history,
                previous: pair.textures[pair.previous].clone(),
                current: pair.textures[1 - pair.previous].clone(),
                reset: !pair.valid,
            })
            .collect()
    }

    /// After a frame that was submitted: what it wrote becomes the previous frame's.
    pub fn end_frame(&mut self) {
        for pair in &mut self.pairs {
            pair.previous = 1 - pair.previous;
            pair.valid = true;
        }
    }

    /// Forgets every history: the next frame reads zeros and is told it is a reset.
    pub fn reset(&mut self) {
        self.pairs.clear();
    }

    /// The texture holding what the last frame wrote into `source`, once a frame ran.
    pub fn written(&self, plan: &Plan, source: ResourceId) -> Option<&wgpu::Texture> {
        if plan.fingerprint != self.fingerprint {
            return None;
        }
        let i = plan.history.iter().position(|e| e.source == source)?;
        let pair = self.pairs.get(i).filter(|p| p.valid)?;
        Some(&pair.textures[pair.previous])
    }
}

impl Pair {
    fn new(device: &wgpu::Device, plan: &Plan, edge: &HistoryEdge) -> Self {
        let name = |id: ResourceId| plan.resource(id).name.clone();
        let make = |role: &str| {
            let s = edge.shape;
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(&format!(
                    "{} | {} (history {role})",
                    name(edge.source),
                    name(edge.history)
                )),
                size: wgpu::Extent3d {
                    width: s.width,
                    height: s.height,
                    depth_or_array_layers: s.layers,
                },
                mip_level_count: s.mips,
                sample_count: s.samples,
                dimension: wgpu::TextureDimension::D2,
                format: s.format,
                usage: edge.usage,
                view_formats: &[],
            })
        };
        Pair {
            textures: [make("a"), make("b")],
            previous: 0,
            valid: false,
        }
    }
}
