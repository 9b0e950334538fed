//! Rendering a plan for people: a text report, a Graphviz drawing, JSON, and a
//! comparison of two plans of one graph.

mod compare;
pub mod page;
mod units;

pub use compare::compare;
pub use units::bytes;

use std::fmt::Write;

use wgpu_types::{BufferUsages, TextureUsages};

use crate::handle::ResourceId;
use crate::plan::{ColorAttachment, DepthStencilAttachment, Load, Ops, Plan, Store};
use crate::resource::format_name;
use crate::resource::Origin;
use crate::resource::TextureShape;

/// The plan as a report: order and attachments, what was culled and why, every resource's
/// lifetime, usages and physical texture, and the memory saved by sharing.
pub fn text(plan: &Plan) -> String {
    let mut out = String::new();
    let (w, h) = plan.output_size;
    let _ = writeln!(out, "plan at {w}x{h} for {}", plan.profile);
    if !plan.features.is_empty() {
        let _ = writeln!(out, "features: {}", plan.features.join(", "));
    }
    let _ = writeln!(out, "\npasses, in execution order:");
    for (i, pass) in plan.passes.iter().enumerate() {
        let _ = writeln!(out, "  {i:>3}. {} ({})", pass.name, pass.kind);
        if let Some(origin) = &pass.origin {
            let _ = writeln!(out, "         from    {origin}");
        }
        // Passes at a fraction of the output (off-screen particles, downsampling) say so.
        let area = pass
            .color
            .first()
            .map(|c| c.resource)
            .or(pass.depth_stencil.as_ref().map(|d| d.resource))
            .and_then(|r| plan.resource(r).texture.as_ref())
            .map(|t| (t.width, t.height));
        if let Some((aw, ah)) = area.filter(|&a| a != plan.output_size) {
            let _ = writeln!(
                out,
                "         renders at {aw}x{ah}, not the output's {w}x{h}"
            );
        }
        let list = |versions: &[(crate::handle::ResourceId, u32)]| {
            versions
                .iter()
                .map(|(r, v)| format!("{}@{v}", plan.resource(*r).name))
                .collect::<Vec<_>>()
                .join(", ")
        };
        if !pass.reads.is_empty() {
            let _ = writeln!(out, "         reads   {}", list(&pass.reads));
        }
        if !pass.writes.is_empty() {
            let _ = writeln!(out, "         writes  {}", list(&pass.writes));
        }
        for d in &pass.dropped_reads {
            let _ = writeln!(
                out,
                "         skips   {}@{} (an optional {}): {}",
                plan.resource(d.resource).name,
                d.version,
                if d.writes { "write" } else { "read" },
                d.why
            );
        }
        for (location, c) in pass.color.iter().enumerate() {
            let _ = writeln!(out, "         color {location}: {}", color_ops(plan, c));
        }
        if !pass.color.is_empty() {
            let _ = writeln!(
                out,
                "         color bytes per sample: {} (limit accounting); stored, depth included: {}",
                pass.color_bytes_per_sample, pass.stored_bytes_per_sample
            );
        } else if pass.stored_bytes_per_sample > 0 {
            // Without color attachments, what a sample stores is the depth-stencil's (a
            // depth-only pass) or buffers sized per sample (a compute rasteriser's).
            let what = match pass.depth_stencil {
                Some(_) => "the depth-stencil",
                None => "buffers sized per sample",
            };
            let _ = writeln!(
                out,
                "         stored bytes per sample: {} ({what})",
                pass.stored_bytes_per_sample
            );
        }
        for w in &pass.workgroups {
            let [x, y, z] = w.size;
            let _ = writeln!(
                out,
                "         workgroup: {x}x{y}x{z} ({}), {} bytes of workgroup memory",
                w.entry, w.memory_bytes
            );
        }
        if let Some(ds) = &pass.depth_stencil {
            let _ = writeln!(
                out,
                "         depth-stencil: {}",
                depth_stencil_ops(plan, ds)
            );
        }
    }
    for (dropped, title) in [(true, "dropped passes"), (false, "culled passes")] {
        let mut passes = plan
            .culled
            .iter()
            .filter(|c| c.dropped == dropped)
            .peekable();
        if passes.peek().is_some() {
            let _ = writeln!(out, "\n{title}:");
        }
        for c in passes {
            let _ = writeln!(out, "  - {}: {}", c.name, c.reason);
        }
    }
    let _ = writeln!(out, "\nresources:");
    for r in &plan.resources {
        let what = match (&r.texture, r.buffer_size) {
            (Some(shape), _) => describe_shape(shape),
            (None, Some(size)) => format!("buffer {}", bytes(size)),
            (None, None) => String::new(),
        };
        let origin = match (r.origin, r.exported) {
            (Origin::Imported, _) => " imported".to_owned(),
            (Origin::History { of }, _) => {
                format!(
                    " history of {} (the previous frame's)",
                    plan.resource(of).name
                )
            }
            (Origin::Transient, true) => match plan.history_edge(r.id) {
                Some(e) => format!(
                    " exported, to the next frame as {}",
                    plan.resource(e.history).name
                ),
                None => " exported".to_owned(),
            },
            (Origin::Transient, false) => String::new(),
        };
        let _ = writeln!(out, "  {}{origin}: {what}", r.name);
        if let Some(because) = &r.format_because {
            let _ = writeln!(out, "      format {because}");
        }
        if let Some(reason) = &r.culled {
            let _ = writeln!(out, "      not allocated: {reason}");
            continue;
        }
        if let Some((first, last)) = r.lifetime {
            let _ = writeln!(
                out,
                "      lives {} .. {}",
                plan.passes[first].name, plan.passes[last].name
            );
        }
        let usage = if r.texture.is_some() {
            texture_usages(r.texture_usage)
        } else {
            buffer_usages(r.buffer_usage)
        };
        let _ = writeln!(out, "      usage {usage}");
        if plan.history_edge(r.id).is_some() {
            let _ = writeln!(out, "      physical: its history's pair (below)");
        }
        if let Some(p) = r.physical {
            let kind = if r.texture.is_some() {
                "texture"
            } else {
                "buffer"
            };
            let _ = writeln!(out, "      physical {kind} #{p}");
        }
    }
    let _ = writeln!(out, "\nphysical textures:");
    for (i, t) in plan.textures.iter().enumerate() {
        let _ = writeln!(
            out,
            "  #{i} {} {} [{}] holds {}",
            describe_shape(&t.shape),
            bytes(t.bytes),
            texture_usages(t.usage),
            names(plan, &t.holds)
        );
    }
    if !plan.buffers.is_empty() {
        let _ = writeln!(out, "\nphysical buffers:");
        for (i, b) in plan.buffers.iter().enumerate() {
            let _ = writeln!(
                out,
                "  #{i} {} [{}] holds {}",
                bytes(b.size),
                buffer_usages(b.usage),
                names(plan, &b.holds)
            );
        }
    }
    history(plan, &mut out);
    let m = &plan.memory;
    let saved = m.logical_bytes.saturating_sub(m.physical_bytes);
    let percent = if m.logical_bytes > 0 {
        100.0 * saved as f64 / m.logical_bytes as f64
    } else {
        0.0
    };
    let _ = writeln!(
        out,
        "\nmemory: {} logical, {} physical ({} saved, {percent:.0}%)",
        bytes(m.logical_bytes),
        bytes(m.physical_bytes),
        bytes(saved)
    );
    out
}

/// The edges to the next frame, and the pair of textures each keeps:
/// `accum@1 (written by "counter") -> next frame's accum_prev (read by "counter")`.
fn history(plan: &Plan, out: &mut String) {
    if plan.history.is_empty() {
        return;
    }
    let _ = writeln!(out, "\nto the next frame:");
    for e in &plan.history {
        let readers = match e.readers.as_slice() {
            [] => "read by no pass in this plan".to_owned(),
            names => format!("read by {}", crate::error::quote_list(names)),
        };
        let _ = writeln!(
            out,
            "  {}@{} (written by \"{}\") -> next frame's {} ({readers})",
            plan.resource(e.source).name,
            e.version,
            e.writer,
            plan.resource(e.history).name,
        );
        let _ = writeln!(
            out,
            "      pair of 2 textures {} {} each [{}], swapped after each frame; reset to \
             zeros on the first frame and after a change of plan",
            describe_shape(&e.shape),
            bytes(e.bytes),
            texture_usages(e.usage)
        );
    }
}

/// The plan as a Graphviz digraph: passes are boxes, resource versions ellipses, culled
/// passes and the versions only they touch drawn grey.
pub fn dot(plan: &Plan) -> String {
    let mut out = String::from("digraph plan {\n  rankdir=LR;\n  node [fontname=\"Helvetica\"];\n");
    let version = |r: crate::handle::ResourceId, v: u32| {
        format!("\"{}@{v}\"", plan.resource(r).name.replace('"', "'"))
    };
    let mut live_versions = std::collections::BTreeSet::new();
    for (i, p) in plan.passes.iter().enumerate() {
        let _ = writeln!(out, "  \"pass:{}\" [shape=box, style=filled, fillcolor=\"#cfe3ff\", label=\"{}. {}\\n{}\"];", p.name, i, p.name, p.kind);
        for &(r, v) in &p.reads {
            live_versions.insert((r, v));
            let _ = writeln!(out, "  {} -> \"pass:{}\";", version(r, v), p.name);
        }
        for &(r, v) in &p.writes {
            live_versions.insert((r, v));
            let _ = writeln!(out, "  \"pass:{}\" -> {};", p.name, version(r, v));
        }
    }
    for c in &plan.culled {
        let reason = c.reason.replace('"', "'");
        let what = if c.dropped { "dropped" } else { "culled" };
        let _ = writeln!(out, "  \"pass:{}\" [shape=box, style=\"filled,dashed\", fillcolor=\"#dddddd\", fontcolor=\"#777777\", label=\"{}\\n{what}\", tooltip=\"{reason}\"];", c.name, c.name);
        for &(r, v) in &c.reads {
            let _ = writeln!(
                out,
                "  {} -> \"pass:{}\" [color=\"#aaaaaa\"];",
                version(r, v),
                c.name
            );
        }
        for &(r, v) in &c.writes {
            let _ = writeln!(
                out,
                "  \"pass:{}\" -> {} [color=\"#aaaaaa\"];",
                c.name,
                version(r, v)
            );
            if !live_versions.contains(&(r, v)) {
                let _ = writeln!(
                    out,
                    "  {} [color=\"#aaaaaa\", fontcolor=\"#777777\"];",
                    version(r, v)
                );
            }
        }
    }
    for e in &plan.history {
        let _ = writeln!(
            out,
            "  {} -> {} [style=dashed, label=\"next frame\"];",
            version(e.source, e.version),
            version(e.history, 0)
        );
    }
    out.push_str("}\n");
    out
}

/// The plan as pretty-printed JSON: the same data, for tools.
pub fn json(plan: &Plan) -> String {
    serde_json::to_string_pretty(plan).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
}

/// A color attachment as explain's formats write it: `hdr clear (0, 0, 0, 1) -> store,
/// resolves into resolved`.
fn color_ops(plan: &Plan, c: &ColorAttachment) -> String {
    let resolve = c
        .resolve_target
        .map(|t| format!(", resolves into {}", plan.resource(t).name))
        .unwrap_or_default();
    let value = |c: [f64; 4]| format!("({}, {}, {}, {})", c[0], c[1], c[2], c[3]);
    format!(
        "{} {}{resolve}",
        plan.resource(c.resource).name,
        ops(&c.ops, value)
    )
}

/// A depth-stencil attachment: `depth depth clear 1 -> store, stencil read-only`.
fn depth_stencil_ops(plan: &Plan, ds: &DepthStencilAttachment) -> String {
    let aspect = |o: Option<String>| o.unwrap_or_else(|| "read-only".into());
    format!(
        "{} depth {}, stencil {}",
        plan.resource(ds.resource).name,
        aspect(ds.depth.as_ref().map(|o| ops(o, |d| d.to_string()))),
        aspect(ds.stencil.as_ref().map(|o| ops(o, |s| format!("{s:#04x}")))),
    )
}

fn ops<T: Copy>(ops: &Ops<T>, value: impl Fn(T) -> String) -> String {
    let load = match ops.load {
        Load::Clear(v) => format!("clear {}", value(v)),
        Load::Load => "load".into(),
        Load::Overwrite => "overwrite (not cleared)".into(),
    };
    let store = match ops.store {
        Store::Store => "store",
        Store::Discard => "discard",
    };
    format!("{load} -> {store}")
}

/// The names of `resources`, comma-separated.
fn names(plan: &Plan, resources: &[ResourceId]) -> String {
    let names: Vec<&str> = resources
        .iter()
        .map(|&r| plan.resource(r).name.as_str())
        .collect();
    names.join(", ")
}

pub(crate) fn describe_shape(s: &TextureShape) -> String {
    let mut out = format!("{} {}x{}", format_name(s.format), s.width, s.height);
    if s.samples > 1 {
        let _ = write!(out, " {}x MSAA", s.samples);
    }
    if s.mips > 1 {
        let _ = write!(out, " {} mips", s.mips);
    }
    if s.layers > 1 {
        let _ = write!(out, " {} layers", s.layers);
    }
    out
}

pub(crate) fn texture_usages(u: TextureUsages) -> String {
    flag_names(u.iter_names().map(|(n, _)| n))
}

pub(crate) fn buffer_usages(u: BufferUsages) -> String {
    flag_names(u.iter_names().map(|(n, _)| n))
}

fn flag_names<'a>(names: impl Iterator<Item = &'a str>) -> String {
    let names: Vec<&str> = names.collect();
    if names.is_empty() {
        "none".into()
    } else {
        names.join(" | ")
    }
}
