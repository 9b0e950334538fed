//! Writing only the parts of a buffer a frame changed: an animation that moves a few
//! meshes rewrites their per-mesh data, not every mesh's.

use std::ops::Range;

/// Bytes compared as one piece: a few meshes' data (128 bytes each). Smaller pieces mean
/// fewer bytes written, more writes queued; whole runs of changed pieces are one write.
const PIECE: usize = 512;

/// Writes to `buffer`, which holds `old`, the byte runs where `new` differs from it:
/// everything when their lengths differ, nothing when they are equal.
pub(super) fn write_changed(queue: &wgpu::Queue, buffer: &wgpu::Buffer, new: &[u8], old: &[u8]) {
    for run in changed_runs(new, old) {
        queue.write_buffer(buffer, run.start as u64, &new[run]);
    }
}

/// The byte ranges of `new`, in whole [`PIECE`]s (the last may be shorter), where it
/// differs from `old`, adjacent pieces merged. Buffer sizes are multiples of 4, and so are
/// the ranges, as `write_buffer` requires.
fn changed_runs(new: &[u8], old: &[u8]) -> Vec<Range<usize>> {
    if new.len() != old.len() {
        return std::iter::once(0..new.len()).collect();
    }
    let mut runs: Vec<Range<usize>> = Vec::new();
    let pieces = new.chunks(PIECE).zip(old.chunks(PIECE));
    for (index, (a, b)) in pieces.enumerate() {
        if a == b {
            continue;
        }
        let piece = index * PIECE..index * PIECE + a.len();
        match runs.last_mut() {
            Some(last) if last.end == piece.start => last.end = piece.end,
            _ => runs.push(piece),
        }
    }
    runs
}

#[cfg(test)]
mod tests {
    use super::{changed_runs, PIECE};

    #[test]
    fn only_the_changed_pieces_are_written_adjacent_ones_as_one_run() {
        let old = vec![0u8; PIECE * 4 + 64];
        let mut new = old.clone();
        assert!(changed_runs(&new, &old).is_empty());
        new[PIECE + 3] = 1;
        new[PIECE * 2] = 1;
        new[PIECE * 4 + 60] = 1;
        let end = old.len();
        assert_eq!(changed_runs(&new, &old), [PIECE..PIECE * 3, PIECE * 4..end]);
        let resized = changed_runs(&new[..PIECE], &old);
        assert_eq!((resized.len(), resized[0].clone()), (1, 0..PIECE));
    }
}
