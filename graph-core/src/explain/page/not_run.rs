//! The passes that do not run, greyed above the timeline (they have no place in the
//! execution order): each a button whose tooltip, on hover, focus or click, says why, as
//! `explain` prints it, and what it would have read and written.

use maud::{html, Markup};

use super::diff::Diff;
use super::timeline::{mark_lines, names};
use crate::plan::Plan;

pub(super) fn list(plan: &Plan, diff: Option<&Diff>) -> Markup {
    html! {
        @if !plan.culled.is_empty() {
            div.not-run {
                h3 #not-run-h { "Not run (" (plan.culled.len()) ")" }
                ul.chips aria-labelledby="not-run-h" {
                    @for c in &plan.culled {
                        @let id = format!("pass-{}", c.id.index());
                        @let tip = format!("tip-{id}");
                        @let what = if c.dropped { "dropped" } else { "culled" };
                        @let mark = diff.and_then(|d| d.pass(&c.name));
                        li.has-tip.pass-culled class=(if mark.is_some() { "diff-changed" } else { "" }) id=(id) data-name=(c.name) {
                            button type="button" aria-describedby=(tip) aria-expanded="false" aria-controls=(tip) {
                                span.name { (c.name) } " " span.badge.plain { (what) }
                                @if mark.is_some() { " " span.badge.changed { "changed" } }
                            }
                            div.tip role="tooltip" id=(tip) {
                                p { strong { (c.name) } ", a " (c.kind) " pass, " (what) ":" }
                                p.reason { (c.reason) }
                                @if !c.reads.is_empty() { p { "Would read " (names(plan, &c.reads)) "." } }
                                @if !c.writes.is_empty() { p { "Would write " (names(plan, &c.writes)) "." } }
                                (mark_lines(mark, diff))
                            }
                        }
                    }
                }
            }
        }
    }
}
