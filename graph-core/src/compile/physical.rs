//! Physical plan: graph-owned resources with the same shape and usages share one texture
//! or buffer when their lifetimes do not overlap. wgpu has no placed resources, so
//! sharing by descriptor is the memory saving available (see the README). Histories and
//! their sources are not planned here: they never share (see `history`).

use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap};
use std::hash::Hash;

use wgpu_types::{BufferUsages, TextureUsages};

use crate::graph::Graph;
use crate::plan::{HistoryEdge, PhysicalBuffer, PhysicalTexture};
use crate::resource::Origin;
use crate::resource::TextureShape;

use super::usage::Usages;

pub(super) struct Physical {
    pub textures: Vec<PhysicalTexture>,
    pub buffers: Vec<PhysicalBuffer>,
    /// For each resource, its index into `textures` or `buffers`.
    pub assignment: Vec<Option<usize>>,
}

pub(super) fn plan(
    graph: &Graph,
    shapes: &[Option<TextureShape>],
    lifetimes: &[Option<(usize, usize)>],
    usages: &Usages,
    history: &[HistoryEdge],
) -> Physical {
    // A history's source lives in a pair of textures of its own (see `history`), where an
    // edge carries it; a history is never transient.
    let in_pair = |r: usize| history.iter().any(|e| e.source.index() == r);
    let mut by_start: Vec<usize> = (0..graph.resources.len())
        .filter(|&r| graph.resources[r].origin == Origin::Transient && lifetimes[r].is_some())
        .filter(|&r| !in_pair(r))
        .collect();
    by_start.sort_by_key(|&r| (lifetimes[r].map(|l| l.0), r));

    let mut texture_slots: Slots<(TextureShape, TextureUsages)> = HashMap::new();
    let mut buffer_slots: Slots<(u64, BufferUsages)> = HashMap::new();
    let mut out = Physical {
        textures: Vec::new(),
        buffers: Vec::new(),
        assignment: vec![None; graph.resources.len()],
    };
    for r in by_start {
        let resource = &graph.resources[r];
        let (first, last) = lifetimes[r].unwrap_or_default();
        let id = crate::handle::ResourceId(r as u32);
        let slot = match (shapes[r], resource.buffer()) {
            (Some(shape), _) => {
                let key = (shape, usages.texture[r]);
                let fresh = out.textures.len();
                let slot = assign(
                    &mut texture_slots,
                    key,
                    fresh,
                    (first, last),
                    resource.exported,
                );
                if slot == out.textures.len() {
                    out.textures.push(PhysicalTexture {
                        shape,
                        usage: key.1,
                        bytes: shape.bytes(),
                        holds: Vec::new(),
                    });
                }
                out.textures[slot].holds.push(id);
                slot
            }
            (None, Some(desc)) => {
                let key = (desc.size, usages.buffer[r]);
                let fresh = out.buffers.len();
                let slot = assign(
                    &mut buffer_slots,
                    key,
                    fresh,
                    (first, last),
                    resource.exported,
                );
                if slot == out.buffers.len() {
                    out.buffers.push(PhysicalBuffer {
                        size: desc.size,
                        usage: key.1,
                        holds: Vec::new(),
                    });
                }
                out.buffers[slot].holds.push(id);
                slot
            }
            (None, None) => continue,
        };
        out.assignment[r] = Some(slot);
    }
    out
}

/// For each key, the physical objects that may take another holder, as
/// `(last position used, index)`: the one free earliest comes first, then the lowest index.
type Slots<K> = HashMap<K, BinaryHeap<Reverse<(usize, usize)>>>;

/// The index of a physical object with this key that is free before `first`, or `fresh`
/// (the next new index) when none is. Taking the one free earliest keeps the search
/// logarithmic however many objects of one key are alive at once.
fn assign<K: Hash + Eq>(
    slots: &mut Slots<K>,
    key: K,
    fresh: usize,
    (first, last): (usize, usize),
    exported: bool,
) -> usize {
    let free = slots.entry(key).or_default();
    let index = match free.peek() {
        Some(&Reverse((free_after, index))) if free_after < first => {
            free.pop();
            index
        }
        _ => fresh,
    };
    // Exported contents must survive the frame: nothing may move in after them.
    if !exported {
        free.push(Reverse((last, index)));
    }
    index
}
