//! What differs between the page's plan and another, matched by pass and resource name:
//! what a reviewer of a graph-file change, or of one scene's plan against another's,
//! needs to see highlighted.

use std::collections::{BTreeSet, HashMap};

use maud::{html, Markup};

use super::super::units::{bytes, counted};
use super::super::{color_ops, depth_stencil_ops, describe_shape};
use crate::handle::ResourceId;
use crate::plan::{Plan, PlannedPass, PlannedResource};

/// How a pass or resource of the page's plan stands against the other plan.
pub(super) enum Mark {
    /// Runs (or is allocated) here and not there, with why not there.
    Added(String),
    /// Both have it, differently: what differs, one line each.
    Changed(Vec<String>),
}

impl Mark {
    pub fn class(&self) -> &'static str {
        match self {
            Mark::Added(_) => "added",
            Mark::Changed(_) => "changed",
        }
    }

    pub fn lines(&self) -> Vec<String> {
        match self {
            Mark::Added(why) => vec![why.clone()],
            Mark::Changed(lines) => lines.clone(),
        }
    }
}

pub(super) struct Diff<'a> {
    pub label: &'a str,
    passes: HashMap<String, Mark>,
    resources: HashMap<String, Mark>,
    /// Passes that run there and not here, with why not here.
    gone_passes: Vec<(String, String)>,
    /// Resources allocated there and not here (bytes there), with why not here.
    gone_resources: Vec<(String, u64, String)>,
}

impl<'a> Diff<'a> {
    pub fn of(plan: &Plan, other: &Plan, label: &'a str) -> Diff<'a> {
        let mut passes = HashMap::new();
        for pass in &plan.passes {
            let mark = match other.pass(&pass.name) {
                None => Some(Mark::Added(format!(
                    "runs here, not in {label}: {}",
                    culled_reason(other, &pass.name)
                ))),
                Some(then) => {
                    let lines = pass_changes(plan, pass, other, then);
                    (!lines.is_empty()).then_some(Mark::Changed(lines))
                }
            };
            if let Some(mark) = mark {
                passes.insert(pass.name.clone(), mark);
            }
        }
        // A pass culled here that runs there differs too: its chip says so.
        for culled in &plan.culled {
            if other.pass(&culled.name).is_some() {
                let line = format!("runs in {label}");
                passes.insert(culled.name.clone(), Mark::Changed(vec![line]));
            }
        }
        let gone_passes = other
            .passes
            .iter()
            .filter(|p| plan.pass(&p.name).is_none())
            .map(|p| (p.name.clone(), culled_reason(plan, &p.name)))
            .collect();
        let mut resources = HashMap::new();
        for resource in &plan.resources {
            let mark = match other.find(&resource.name) {
                None => Some(Mark::Added(format!("not declared in {label}"))),
                Some(then) => {
                    let lines = resource_changes(plan, resource, other, then, label);
                    (!lines.is_empty()).then_some(Mark::Changed(lines))
                }
            };
            if let Some(mark) = mark {
                resources.insert(resource.name.clone(), mark);
            }
        }
        let gone_resources = other
            .resources
            .iter()
            .filter(|r| r.physical.is_some())
            .filter(|r| {
                plan.find(&r.name)
                    .is_none_or(|here| here.physical.is_none())
            })
            .map(|r| {
                let why = match plan.find(&r.name) {
                    Some(here) => here.culled.clone().unwrap_or_else(|| "unused".into()),
                    None => "not declared here".into(),
                };
                (r.name.clone(), r.bytes, why)
            })
            .collect();
        Diff {
            label,
            passes,
            resources,
            gone_passes,
            gone_resources,
        }
    }

    pub fn pass(&self, name: &str) -> Option<&Mark> {
        self.passes.get(name)
    }

    pub fn resource(&self, name: &str) -> Option<&Mark> {
        self.resources.get(name)
    }

    /// The comparison's own section: counts, memory, and what the other plan runs and
    /// allocates that this one does not (which the timeline, being this plan's, cannot
    /// show).
    pub fn summary(&self, plan: &Plan, other: Option<&Plan>) -> Markup {
        let count = |marks: &HashMap<String, Mark>, class: &str| {
            marks.values().filter(|m| m.class() == class).count()
        };
        let (now, then) = (
            plan.memory.physical_bytes,
            other.map_or(0, |o| o.memory.physical_bytes),
        );
        let memory = match now.cmp(&then) {
            std::cmp::Ordering::Less => format!("{} less", bytes(then - now)),
            std::cmp::Ordering::Greater => format!("{} more", bytes(now - then)),
            std::cmp::Ordering::Equal => "the same".into(),
        };
        html! {
            section #compare aria-labelledby="compare-h" {
                h2 #compare-h { "Compared with " (self.label) }
                p {
                    (counted(plan.passes.len(), "pass runs", "passes run")) " here, "
                    (other.map_or(0, |o| o.passes.len())) " there; physical memory "
                    (bytes(now)) " here, " (bytes(then)) " there (" (memory) ")."
                }
                p {
                    span.badge.added { "added" } " "
                    (counted(count(&self.passes, "added"), "pass", "passes")) " and "
                    (counted(count(&self.resources, "added"), "resource", "resources")) "; "
                    span.badge.changed { "changed" } " "
                    (counted(count(&self.passes, "changed"), "pass", "passes")) " and "
                    (counted(count(&self.resources, "changed"), "resource", "resources"))
                    ": marked in the timeline, with what changed on hover or focus."
                }
                @if !self.gone_passes.is_empty() {
                    h3 { "Run there, not here" }
                    ul.gone #gone-passes {
                        @for (name, why) in &self.gone_passes {
                            li { span.badge.removed { "removed" } " " strong { (name) } ": " (why) }
                        }
                    }
                }
                @if !self.gone_resources.is_empty() {
                    h3 { "Allocated there, not here" }
                    ul.gone #gone-resources {
                        @for (name, size, why) in &self.gone_resources {
                            li { span.badge.removed { "removed" } " " strong { (name) } " (" (bytes(*size)) "): " (why) }
                        }
                    }
                }
            }
        }
    }
}

/// Why `plan` does not run the pass called `name`.
fn culled_reason(plan: &Plan, name: &str) -> String {
    plan.culled
        .iter()
        .find(|c| c.name == name)
        .map_or("not in that graph".into(), |c| c.reason.clone())
}

/// What differs between one pass in two plans: its kind, what it reads and writes, and
/// its attachments' load and store.
fn pass_changes(plan: &Plan, now: &PlannedPass, other: &Plan, then: &PlannedPass) -> Vec<String> {
    let mut lines = Vec::new();
    if now.kind != then.kind {
        lines.push(format!("a {} pass (was {})", now.kind, then.kind));
    }
    let names = |plan: &Plan, versions: &[(ResourceId, u32)]| -> BTreeSet<String> {
        versions
            .iter()
            .map(|(r, _)| plan.resource(*r).name.clone())
            .collect()
    };
    for (verb, here, there) in [
        ("reads", names(plan, &now.reads), names(other, &then.reads)),
        (
            "writes",
            names(plan, &now.writes),
            names(other, &then.writes),
        ),
    ] {
        let added: Vec<&str> = here.difference(&there).map(String::as_str).collect();
        let removed: Vec<&str> = there.difference(&here).map(String::as_str).collect();
        if !added.is_empty() {
            lines.push(format!("now {verb} {}", added.join(", ")));
        }
        if !removed.is_empty() {
            lines.push(format!("no longer {verb} {}", removed.join(", ")));
        }
    }
    let attachments = |plan: &Plan, pass: &PlannedPass| -> Vec<String> {
        let color = pass
            .color
            .iter()
            .map(|c| format!("color {}", color_ops(plan, c)));
        let depth = pass
            .depth_stencil
            .iter()
            .map(|ds| format!("depth-stencil {}", depth_stencil_ops(plan, ds)));
        color.chain(depth).collect()
    };
    let (here, there) = (attachments(plan, now), attachments(other, then));
    let only = |a: &[String], b: &[String]| -> Vec<String> {
        a.iter().filter(|l| !b.contains(l)).cloned().collect()
    };
    let (new, old) = (only(&here, &there), only(&there, &here));
    if !new.is_empty() {
        lines.push(format!("attaches {}", new.join("; ")));
    }
    if !old.is_empty() {
        lines.push(format!("attached {} before", old.join("; ")));
    }
    lines
}

/// What differs between one resource in two plans: whether it is allocated, its shape or
/// size, when it lives and what it shares memory with.
fn resource_changes(
    plan: &Plan,
    now: &PlannedResource,
    other: &Plan,
    then: &PlannedResource,
    label: &str,
) -> Vec<String> {
    let mut lines = Vec::new();
    match (now.physical.is_some(), then.physical.is_some()) {
        (true, false) => lines.push(format!(
            "allocated here; not in {label}: {}",
            then.culled.as_deref().unwrap_or("unused")
        )),
        (false, true) => lines.push(format!(
            "not allocated here ({}); {label} allocates {}",
            now.culled.as_deref().unwrap_or("unused"),
            bytes(then.bytes)
        )),
        _ => {}
    }
    match (&now.texture, &then.texture) {
        (Some(a), Some(b)) if a != b => {
            lines.push(format!("{} (was {})", describe_shape(a), describe_shape(b)))
        }
        _ => {}
    }
    if now.buffer_size != then.buffer_size {
        if let (Some(a), Some(b)) = (now.buffer_size, then.buffer_size) {
            lines.push(format!("buffer {} (was {})", bytes(a), bytes(b)));
        }
    }
    let lives = |plan: &Plan, r: &PlannedResource| {
        r.lifetime.map(|(first, last)| {
            format!("{} .. {}", plan.passes[first].name, plan.passes[last].name)
        })
    };
    if let (Some(a), Some(b)) = (lives(plan, now), lives(other, then)) {
        if a != b {
            lines.push(format!("lives {a} (was {b})"));
        }
    }
    let (a, b) = (sharers(plan, now), sharers(other, then));
    if now.physical.is_some() && then.physical.is_some() && a != b {
        let list = |s: &BTreeSet<String>| match s.is_empty() {
            true => "nothing".to_owned(),
            false => s.iter().cloned().collect::<Vec<_>>().join(", "),
        };
        lines.push(format!(
            "shares memory with {} (was {})",
            list(&a),
            list(&b)
        ));
    }
    lines
}

/// The names of the other resources in `resource`'s physical texture or buffer.
fn sharers(plan: &Plan, resource: &PlannedResource) -> BTreeSet<String> {
    let Some(p) = resource.physical else {
        return BTreeSet::new();
    };
    let holds = match resource.texture {
        Some(_) => plan.textures.get(p).map(|t| &t.holds),
        None => plan.buffers.get(p).map(|b| &b.holds),
    };
    holds
        .into_iter()
        .flatten()
        .filter(|&&r| r != resource.id)
        .map(|&r| plan.resource(r).name.clone())
        .collect()
}
