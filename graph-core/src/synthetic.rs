//! Synthetic graphs shaped like a real frame, at any size: for compile benchmarks and for
//! checking the compiler's invariants on graphs larger than anyone writes by hand.

use wgpu_types::TextureFormat;

use crate::access::{AspectAccess, BufferRole, ColorLoad};
use crate::builder::{GraphBuilder, PassBuilder};
use crate::graph::Graph;
use crate::handle::{BufferHandle, TextureHandle};
use crate::resource::{BufferDesc, Size, TextureDesc};

/// A frame of `passes` passes that each create two resources. In every ten passes:
/// - six render passes with a color and a depth-stencil target, sampling the latest output
///   and one older output; one in three also blends onto an older full-size output, which
///   orders it after that output's readers;
/// - two compute passes writing a half-size storage texture and a buffer that the next
///   pass reads;
/// - one render pass into a 4x target resolved in the same pass;
/// - one render pass whose outputs nothing reads, which the compiler culls.
///
/// The same `passes` always gives the same graph, and it compiles on the WebGPU defaults.
pub fn frame(passes: usize) -> Graph {
    let mut frame = Frame::default();
    for i in 0..passes {
        match i % 10 {
            4 | 8 => frame.compute(i),
            3 => frame.msaa(i),
            9 => frame.dead_branch(i),
            _ => frame.render(i),
        }
    }
    if let Some(last) = frame.outputs.last() {
        frame.g.export(last.handle);
    }
    frame.g.build()
}

#[derive(Default)]
struct Frame {
    g: GraphBuilder,
    /// Every live output so far, latest version of each.
    outputs: Vec<Output>,
    /// A buffer the previous pass wrote for the next one to read.
    buffer: Option<BufferHandle>,
}

#[derive(Copy, Clone)]
struct Output {
    handle: TextureHandle,
    /// Full-size single-sampled color, so a render pass can blend onto it.
    blendable: bool,
}

const CLEAR: ColorLoad = ColorLoad::Clear([0.0; 4]);

impl Frame {
    /// An older output, spread over the whole history rather than only the recent past.
    fn older(&self, i: usize) -> Option<usize> {
        let n = self.outputs.len();
        (n > 1).then(|| (i * 7919) % (n - 1))
    }

    fn render(&mut self, i: usize) {
        let format = if i.is_multiple_of(2) {
            TextureFormat::Rgba16Float
        } else {
            TextureFormat::Rgba8Unorm
        };
        let color = self
            .g
            .create_texture(format!("color{i}"), TextureDesc::new(format));
        let depth = self.g.create_texture(
            format!("depth{i}"),
            TextureDesc::new(TextureFormat::Depth24PlusStencil8),
        );
        let older = self.older(i);
        let blend = older
            .filter(|&o| i.is_multiple_of(3) && self.outputs[o].blendable)
            .map(|o| (o, self.outputs[o].handle));
        let sampled: Vec<TextureHandle> = self.inputs(older, blend.map(|b| b.0));
        let buffer = self.buffer.take();
        let mut p = self.g.add_render_pass(format!("render{i}"));
        read_all(&mut p, &sampled, buffer);
        let color = p.color_output(color, CLEAR);
        p.depth_stencil(depth, AspectAccess::Clear(1.0), AspectAccess::Clear(0));
        let blended = blend.map(|(o, h)| (o, p.color_output(h, ColorLoad::Load)));
        if let Some((o, handle)) = blended {
            self.outputs[o].handle = handle;
        }
        self.outputs.push(Output {
            handle: color,
            blendable: true,
        });
    }

    fn compute(&mut self, i: usize) {
        let half = TextureDesc::new(TextureFormat::Rgba16Float).size(Size::Relative(0.5));
        let texture = self.g.create_texture(format!("storage{i}"), half);
        let buffer = self
            .g
            .create_buffer(format!("buffer{i}"), BufferDesc::new(64 << 10));
        let sampled = self.inputs(self.older(i), None);
        let previous = self.buffer.take();
        let mut p = self.g.add_compute_pass(format!("compute{i}"));
        read_all(&mut p, &sampled, previous);
        let texture = p.storage_write(texture);
        let write = BufferRole::Storage {
            read: false,
            write: true,
        };
        self.buffer = Some(p.buffer(buffer, write));
        self.outputs.push(Output {
            handle: texture,
            blendable: false,
        });
    }

    fn msaa(&mut self, i: usize) {
        let msaa = self.g.create_texture(
            format!("msaa{i}"),
            TextureDesc::new(TextureFormat::Rgba8Unorm).samples(4),
        );
        let resolved = self.g.create_texture(
            format!("resolved{i}"),
            TextureDesc::new(TextureFormat::Rgba8Unorm),
        );
        let sampled = self.inputs(None, None);
        let buffer = self.buffer.take();
        let mut p = self.g.add_render_pass(format!("msaa{i}"));
        read_all(&mut p, &sampled, buffer);
        let msaa = p.color_output(msaa, CLEAR);
        let resolved = p.resolve_output(msaa, resolved);
        self.outputs.push(Output {
            handle: resolved,
            blendable: true,
        });
    }

    fn dead_branch(&mut self, i: usize) {
        let debug = self.g.create_texture(
            format!("debug{i}"),
            TextureDesc::new(TextureFormat::Rgba8Unorm),
        );
        let depth = self.g.create_texture(
            format!("debug_depth{i}"),
            TextureDesc::new(TextureFormat::Depth32Float),
        );
        let sampled = self.inputs(None, None);
        let mut p = self.g.add_render_pass(format!("debug{i}"));
        read_all(&mut p, &sampled, None);
        p.color_output(debug, CLEAR);
        p.depth_stencil(depth, AspectAccess::Clear(1.0), AspectAccess::ReadOnly);
    }

    /// The latest output and the `older` one, leaving out the one the pass blends onto.
    fn inputs(&self, older: Option<usize>, blended: Option<usize>) -> Vec<TextureHandle> {
        let latest = self.outputs.len().checked_sub(1);
        [latest, older]
            .into_iter()
            .flatten()
            .filter(|&o| Some(o) != blended)
            .map(|o| self.outputs[o].handle)
            .collect()
    }
}

fn read_all(p: &mut PassBuilder<'_>, sampled: &[TextureHandle], buffer: Option<BufferHandle>) {
    for &t in sampled {
        p.sampled(t);
    }
    if let Some(b) = buffer {
        p.buffer(
            b,
            BufferRole::Storage {
                read: true,
                write: false,
            },
        );
    }
}
