//! The page's timeline: one column per pass in execution order, one row per resource with
//! a bar from the first pass that uses it to the last, marked where passes write (W) and
//! read (R) it, coloured by the physical texture or buffer it occupies; then one row per
//! physical texture and buffer with the bars of the resources that take turns in it.
//!
//! A table with fixed layout: the pass columns share the width left by the names, so the
//! page never scrolls sideways, and a screen reader reads rows and column headers.

use maud::{html, Markup};

use super::super::{
    buffer_usages, color_ops, depth_stencil_ops, describe_shape, texture_usages,
    units::{bytes, counted},
};
use super::diff::{Diff, Mark};
use super::hues::hue;
use super::timings::{Clock, Timings};
use crate::handle::ResourceId;
use crate::plan::{Plan, PlannedPass, PlannedResource};
use crate::resource::Origin;

/// A texture or buffer the executor allocates, as its row and its resources' bars show it.
struct Allocation<'p> {
    /// `texture #3`, `buffer #0`.
    name: String,
    /// The row's element id: `phys-t3`, `phys-b0`.
    id: String,
    /// Shape and bytes.
    what: String,
    /// Hue of its bars: the golden angle apart, so that neighbours differ; buffers are
    /// striped besides.
    hue: u32,
    class: &'static str,
    holds: &'p [ResourceId],
}

fn texture(plan: &Plan, i: usize) -> Allocation<'_> {
    let t = &plan.textures[i];
    Allocation {
        name: format!("texture #{i}"),
        id: format!("phys-t{i}"),
        what: format!("{} · {}", describe_shape(&t.shape), bytes(t.bytes)),
        hue: hue(i, 200.0),
        class: "bar",
        holds: &t.holds,
    }
}

fn buffer(plan: &Plan, i: usize) -> Allocation<'_> {
    let b = &plan.buffers[i];
    Allocation {
        name: format!("buffer #{i}"),
        id: format!("phys-b{i}"),
        what: format!("buffer · {}", bytes(b.size)),
        hue: hue(i, 20.0),
        class: "bar buf",
        holds: &b.holds,
    }
}

/// Where `r` lives, `None` for a resource the graph does not allocate.
fn allocation<'p>(plan: &'p Plan, r: &PlannedResource) -> Option<Allocation<'p>> {
    let p = r.physical?;
    Some(match r.texture {
        Some(_) => texture(plan, p),
        None => buffer(plan, p),
    })
}

/// What the bars mean, above the timeline.
pub(super) fn legend(plan: &Plan, timed: bool, compared: bool) -> Markup {
    let shared = plan.textures.iter().filter(|t| t.holds.len() > 1).count()
        + plan.buffers.iter().filter(|b| b.holds.len() > 1).count();
    html! {
        p.legend {
            "Columns are the passes that run, in execution order. A bar is when a resource \
             lives, from the first pass that uses it to the last; "
            span.acc.inline { "W" } " the pass writes it, " span.acc.inline { "R" } " reads it. "
            "A bar's colour is the physical texture or buffer it occupies: rows of one colour \
             share memory ("
            @match shared {
                0 => "none do here",
                1 => "one allocation is shared here",
                n => { (n) " allocations are shared here" }
            }
            "; the rows under Physical memory show them). Grey is what does not run or is not \
             allocated; an outlined bar is imported. Hover, focus or click a name for details."
            @if timed { " Bars under the passes are their median GPU and CPU times." }
            @if compared {
                " Names and columns marked added or changed differ from the compared plan: \
                 hover or focus them for what differs."
            }
        }
    }
}

/// The table: pass headers, time rows, resource rows, physical rows.
pub(super) fn table(plan: &Plan, timings: Option<&Timings>, diff: Option<&Diff>) -> Markup {
    let columns = plan.passes.len().max(1);
    html! {
        table.timeline style=(format!("--n:{columns}")) {
            caption.sr-only {
                "Timeline: passes in execution order as columns; resources, then physical \
                 allocations, as rows."
            }
            colgroup { col.label; col span=(columns); }
            thead {
                tr {
                    th.corner scope="col" { "Resource \\ pass" }
                    @for (i, pass) in plan.passes.iter().enumerate() {
                        (pass_header(plan, i, pass, timings, diff))
                    }
                    @if plan.passes.is_empty() { th scope="col" { "no pass runs" } }
                }
                @if let Some(timings) = timings {
                    (timings.row(plan, Clock::Gpu))
                    (timings.row(plan, Clock::Cpu))
                }
            }
            tbody.resources {
                tr.group { th colspan=(columns + 1) scope="rowgroup" { "Resources (" (plan.resources.len()) ")" } }
                @for r in lifetime_order(plan) {
                    (resource_row(plan, r, columns, diff))
                }
            }
            tbody.physical {
                tr.group {
                    th colspan=(columns + 1) scope="rowgroup" {
                        "Physical memory (" (bytes(plan.memory.physical_bytes)) " in "
                        (allocations(plan)) "): resources in one row take turns in its memory"
                    }
                }
                @for i in 0..plan.textures.len() { (physical_row(plan, &texture(plan, i), columns)) }
                @for i in 0..plan.buffers.len() { (physical_row(plan, &buffer(plan, i), columns)) }
            }
        }
    }
}

/// Resources by when they start living, those never allocated last, declaration order
/// breaking ties.
fn lifetime_order(plan: &Plan) -> Vec<&PlannedResource> {
    let mut rows: Vec<&PlannedResource> = plan.resources.iter().collect();
    rows.sort_by_key(|r| r.lifetime.map_or(usize::MAX, |(first, _)| first));
    rows
}

/// A tooltip's position: under its cell, from the cell's right edge in the right half of
/// the table so that it never runs past the page.
fn tip_class(column: usize, columns: usize) -> &'static str {
    match column * 2 >= columns {
        true => "tip end",
        false => "tip",
    }
}

fn mark_class(mark: Option<&Mark>) -> &'static str {
    mark.map_or("", |m| match m {
        Mark::Added(_) => " diff-added",
        Mark::Changed(_) => " diff-changed",
    })
}

/// The badge and the lines of a diff mark, for a tooltip.
fn mark_badge(mark: Option<&Mark>) -> Markup {
    html! {
        @if let Some(mark) = mark {
            " " span class=(format!("badge {}", mark.class())) { (mark.class()) }
        }
    }
}

pub(super) fn mark_lines(mark: Option<&Mark>, diff: Option<&Diff>) -> Markup {
    html! {
        @if let (Some(mark), Some(diff)) = (mark, diff) {
            p.diffnote {
                strong { "Against " (diff.label) ": " }
                (mark.lines().join("; "))
            }
        }
    }
}

/// The names of `versions`' resources, each once, in order.
pub(super) fn names(plan: &Plan, versions: &[(ResourceId, u32)]) -> String {
    let mut names: Vec<&str> = Vec::new();
    for (r, _) in versions {
        let name = plan.resource(*r).name.as_str();
        if !names.contains(&name) {
            names.push(name);
        }
    }
    match names.is_empty() {
        true => "nothing".into(),
        false => names.join(", "),
    }
}

fn pass_header(
    plan: &Plan,
    column: usize,
    pass: &PlannedPass,
    timings: Option<&Timings>,
    diff: Option<&Diff>,
) -> Markup {
    let id = format!("pass-{}", pass.id.index());
    let tip = format!("tip-{id}");
    let mark = diff.and_then(|d| d.pass(&pass.name));
    html! {
        th.pass-h.has-tip class=(mark_class(mark)) scope="col" id=(id) data-name=(pass.name) {
            button type="button" aria-describedby=(tip) aria-expanded="false" aria-controls=(tip) {
                span.idx { (column) }
                span.name { (pass.name) }
                span.kind { (pass.kind) }
                (mark_badge(mark))
            }
            div class=(tip_class(column, plan.passes.len())) role="tooltip" id=(tip) {
                p { strong { (pass.name) } ", a " (pass.kind) " pass, " (ordinal(column)) " to run" }
                @if let Some(origin) = &pass.origin { p.origin { "From " (origin) "." } }
                p { "Reads " (names(plan, &pass.reads)) "; writes " (names(plan, &pass.writes)) "." }
                @for d in &pass.dropped_reads {
                    p { "Skips the optional " (if d.writes { "write" } else { "read" }) " of " (plan.resource(d.resource).name) ": " (d.why) "." }
                }
                @if !pass.color.is_empty() || pass.depth_stencil.is_some() {
                    ul {
                        @for (location, c) in pass.color.iter().enumerate() {
                            li { "color " (location) ": " (color_ops(plan, c)) }
                        }
                        @if let Some(ds) = &pass.depth_stencil {
                            li { "depth-stencil: " (depth_stencil_ops(plan, ds)) }
                        }
                    }
                }
                @if pass.stored_bytes_per_sample > 0 {
                    p { (pass.stored_bytes_per_sample) " bytes stored per sample" }
                }
                @for w in &pass.workgroups {
                    p {
                        "workgroup " (w.size[0]) "×" (w.size[1]) "×" (w.size[2]) " (" (w.entry)
                        "), " (w.memory_bytes) " bytes of workgroup memory"
                    }
                }
                @if let Some(timings) = timings { p { (timings.describe(&pass.name)) } }
                (mark_lines(mark, diff))
            }
        }
    }
}

fn ordinal(index: usize) -> String {
    let n = index + 1;
    let suffix = match (n % 10, n % 100) {
        (_, 11..=13) => "th",
        (1, _) => "st",
        (2, _) => "nd",
        (3, _) => "rd",
        _ => "th",
    };
    format!("{n}{suffix}")
}

/// What a resource is: `rgba16float 1920x1080 4x MSAA · 31.6 MiB`, `buffer 4.0 KiB`.
fn shape(r: &PlannedResource) -> String {
    match (&r.texture, r.buffer_size) {
        (Some(shape), _) => format!("{} · {}", describe_shape(shape), bytes(r.bytes)),
        (None, Some(size)) => format!("buffer · {}", bytes(size)),
        (None, None) => bytes(r.bytes),
    }
}

fn resource_row(plan: &Plan, r: &PlannedResource, columns: usize, diff: Option<&Diff>) -> Markup {
    let id = format!("res-{}", r.id.index());
    let tip = format!("tip-{id}");
    let mark = diff.and_then(|d| d.resource(&r.name));
    let allocation = allocation(plan, r);
    let state = match (&r.culled, r.origin, r.lifetime) {
        (Some(_), _, _) => " dropped",
        (None, Origin::Imported, _) => " imported",
        (None, _, None) => " unused",
        _ => "",
    };
    let sharers: Vec<&str> = allocation
        .iter()
        .flat_map(|a| a.holds)
        .filter(|&&other| other != r.id)
        .map(|&other| plan.resource(other).name.as_str())
        .collect();
    let origin = match (r.origin, r.exported) {
        (Origin::Imported, _) => Some("imported"),
        (Origin::History { .. }, _) => Some("previous frame"),
        (Origin::Transient, true) if plan.history_edge(r.id).is_some() => Some("next frame"),
        (Origin::Transient, true) => Some("exported"),
        (Origin::Transient, false) => None,
    };
    html! {
        tr class=(format!("res{state}{}", mark_class(mark))) id=(id) data-name=(r.name) {
            th.has-tip scope="row" {
                button type="button" aria-describedby=(tip) aria-expanded="false" aria-controls=(tip) {
                    span.name { (r.name) }
                    @if let Some(origin) = origin { " " span.badge.plain { (origin) } }
                    (mark_badge(mark))
                }
                span.meta {
                    (shape(r))
                    @if let Some(a) = &allocation {
                        " · " (a.name)
                        @if !sharers.is_empty() { ", shared with " (sharers.join(", ")) }
                    }
                }
                div.tip role="tooltip" id=(tip) {
                    p { strong { (r.name) } ": " (shape(r)) }
                    @if let Some(because) = &r.format_because { p { "Format " (because) "." } }
                    @if let Some(reason) = &r.culled { p.why { "Not allocated: " (reason) } }
                    @if let Some((first, last)) = r.lifetime {
                        p { "Lives from " (plan.passes[first].name) " to " (plan.passes[last].name) "." }
                    }
                    @if r.culled.is_none() {
                        p {
                            "Usage "
                            @if r.texture.is_some() { (texture_usages(r.texture_usage)) }
                            @else { (buffer_usages(r.buffer_usage)) }
                        }
                    }
                    @match (&allocation, sharers.is_empty()) {
                        (Some(a), true) => { p { "Has " (a.name) " to itself." } }
                        (Some(a), false) => {
                            p { "Shares " (a.name) " with " (sharers.join(", ")) "." }
                        }
                        (None, _) => {}
                    }
                    (mark_lines(mark, diff))
                }
            }
            td.lane colspan=(columns) {
                div.lanegrid {
                    @match (r.lifetime, &r.culled) {
                        (_, Some(reason)) => { span.why { "not allocated: " (reason) } }
                        (Some((first, last)), None) => {
                            @let (class, hue) = allocation.as_ref().map_or(("bar outline", 0), |a| (a.class, a.hue));
                            span class=(class) style=(bar_style(first, last, hue)) {
                                span.sr-only {
                                    "lives from " (plan.passes[first].name) " to " (plan.passes[last].name)
                                    @if let Some(a) = &allocation { ", in " (a.name) }
                                }
                            }
                            @for (i, pass) in plan.passes.iter().enumerate() {
                                @let reads = pass.reads_resource(r.id);
                                @let writes = pass.writes_resource(r.id);
                                @if reads || writes {
                                    span.acc style=(format!("grid-column:{}", i + 1)) {
                                        span aria-hidden="true" {
                                            @if writes { "W" } @if reads { "R" }
                                        }
                                        span.sr-only {
                                            (pass.name) @if writes { " writes" } @if writes && reads { " and" } @if reads { " reads" } " it"
                                        }
                                    }
                                }
                            }
                        }
                        (None, None) => { span.why { "unused: no pass that runs touches it" } }
                    }
                }
            }
        }
    }
}

fn physical_row(plan: &Plan, a: &Allocation, columns: usize) -> Markup {
    html! {
        tr.phys id=(a.id) {
            th scope="row" {
                span.name { (a.name) }
                span.meta { (a.what) " · holds " (a.holds.len()) }
            }
            td.lane colspan=(columns) {
                div.lanegrid {
                    @for r in a.holds.iter().map(|&r| plan.resource(r)) {
                        @if let Some((first, last)) = r.lifetime {
                            span class=(format!("{} named", a.class)) style=(bar_style(first, last, a.hue)) data-res=(r.id.index()) {
                                (r.name)
                            }
                        }
                    }
                }
            }
        }
    }
}

/// A bar from pass `first` to pass `last` in hue `hue`.
fn bar_style(first: usize, last: usize, hue: u32) -> String {
    format!("grid-column:{}/{};--h:{hue}", first + 1, last + 2)
}

/// What the executor allocates: `7 textures and 1 buffer`.
pub(super) fn allocations(plan: &Plan) -> String {
    format!(
        "{} and {}",
        counted(plan.textures.len(), "texture", "textures"),
        counted(plan.buffers.len(), "buffer", "buffers")
    )
}
