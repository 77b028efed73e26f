//! The two priority queues: a binary heap (exact order, O(log n)) for the baselines, and
//! a bucket queue (O(1), order only up to the bucket width) for the tracks engine.

use super::frontier::Queue;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// A heap entry ordered so that the smallest distance pops first.
#[derive(Clone, Copy, PartialEq)]
struct Entry(f64, u32);

impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}

/// Dijkstra's binary heap with lazy deletion: an entry is stale once its node's distance
/// dropped below the entry's.
#[derive(Default)]
pub(super) struct HeapQueue {
    heap: BinaryHeap<Entry>,
    /// The key of the last entry popped: nothing queued later can go below it.
    floor: f64,
}

impl HeapQueue {
    /// Empties the queue, keeping its buffer.
    pub fn reset(&mut self) {
        self.heap.clear();
        self.floor = f64::NEG_INFINITY;
    }
}

impl Queue for HeapQueue {
    #[inline]
    fn push(&mut self, node: u32, value: f64, _previous: f64) -> bool {
        self.heap.push(Entry(value, node));
        true
    }

    #[inline]
    fn pop(&mut self, distance: &[f64]) -> Option<u32> {
        while let Some(Entry(d, q)) = self.heap.pop() {
            if d <= distance[q as usize] {
                self.floor = d;
                return Some(q);
            }
        }
        None
    }

    fn is_final(&self, value: f64) -> bool {
        value <= self.floor
    }
}

/// Buckets of width `width`: bucket `b` holds nodes with distance in
/// `[b·width, (b+1)·width)`, unsorted. Popping takes any node of the lowest non-empty
/// bucket, so a node may be settled before its final value; it is then queued again
/// when it improves, and the result is still exact. Improvements never fall below the
/// bucket being processed (costs are ≥ 0), so buckets are visited in order, once.
///
/// A node has at most one live entry: `pending` says it is queued in the bucket of its
/// current distance; an improvement within the same bucket adds nothing.
///
/// Only a window of `WINDOW` buckets is materialised; entries beyond it wait in `far`
/// and are re-bucketed when the window is used up, so a metric with a huge cost range
/// cannot make the queue allocate without bound.
#[derive(Default)]
pub(super) struct BucketQueue {
    inverse_width: f64,
    /// Absolute bucket number of `buckets[0]`.
    base: usize,
    buckets: Vec<Vec<u32>>,
    /// Index into `buckets` of the bucket being processed.
    current: usize,
    far: Vec<u32>,
    far_spare: Vec<u32>,
    pending: Vec<bool>,
    /// Emptied bucket buffers, kept to avoid allocating new ones.
    spare: Vec<Vec<u32>>,
}

const WINDOW: usize = 1 << 16;

impl BucketQueue {
    /// Empties the queue for a run over `nodes` nodes with buckets `width` wide (> 0),
    /// keeping every buffer it has grown.
    pub fn reset(&mut self, nodes: usize, width: f64) {
        self.inverse_width = 1.0 / width;
        self.base = 0;
        self.current = 0;
        self.recycle_window();
        self.far.clear();
        self.pending.clear();
        self.pending.resize(nodes, false);
    }

    /// Moves the window's bucket buffers to the spares (emptied) and the window to empty.
    fn recycle_window(&mut self) {
        for mut bucket in self.buckets.drain(..) {
            if bucket.capacity() > 0 {
                bucket.clear();
                self.spare.push(bucket);
            }
        }
    }

    #[inline(always)]
    fn bucket(&self, value: f64) -> usize {
        // Saturating float-to-int conversion: values beyond 2³² widths share the last
        // bucket (still exact, only slower). To `u32` because x86 converts to a signed
        // 64-bit integer in one instruction, and to an unsigned one only with a dozen.
        (value * self.inverse_width) as u32 as usize
    }

    /// Files `node` under absolute bucket `b`: in the window, or in `far`.
    #[inline(always)]
    fn file(&mut self, node: u32, b: usize) {
        // Costs are ≥ 0, so `b` is never below the bucket being processed; should it be,
        // the node is filed in the current bucket, where `pop` takes it as live.
        let slot = b.saturating_sub(self.base).max(self.current);
        if slot >= WINDOW {
            self.far.push(node);
            return;
        }
        if slot >= self.buckets.len() {
            self.buckets.resize_with(slot + 1, Vec::new);
        }
        let bucket = &mut self.buckets[slot];
        if bucket.capacity() == 0 {
            if let Some(spare) = self.spare.pop() {
                *bucket = spare;
            }
        }
        bucket.push(node);
    }

    /// Moves the window to the lowest far bucket and re-files the far entries; returns
    /// whether anything is left to process.
    fn refill(&mut self, distance: &[f64]) -> bool {
        let lowest = self
            .far
            .iter()
            .filter(|&&q| self.pending[q as usize])
            .map(|&q| self.bucket(distance[q as usize]))
            .min();
        let Some(lowest) = lowest else {
            self.far.clear();
            return false;
        };
        self.recycle_window();
        self.base = lowest;
        self.current = 0;
        // Swap with the spare list so that re-filing beyond the window reuses buffers.
        let mut far = std::mem::take(&mut self.far_spare);
        std::mem::swap(&mut far, &mut self.far);
        for &q in &far {
            if self.pending[q as usize] {
                let b = self.bucket(distance[q as usize]);
                self.file(q, b);
            }
        }
        far.clear();
        self.far_spare = far;
        true
    }
}

impl Queue for BucketQueue {
    #[inline(always)]
    fn push(&mut self, node: u32, value: f64, previous: f64) -> bool {
        // Buckets below the current one are filed as the current one.
        let now = self.base + self.current;
        let b = self.bucket(value).max(now);
        if self.pending[node as usize] && self.bucket(previous).max(now) == b {
            return false;
        }
        self.pending[node as usize] = true;
        self.file(node, b);
        true
    }

    #[inline]
    fn pop(&mut self, distance: &[f64]) -> Option<u32> {
        loop {
            while self.current < self.buckets.len() {
                let absolute = self.base + self.current;
                while let Some(q) = self.buckets[self.current].pop() {
                    // Live: queued, and filed where its distance belongs (or below).
                    let live =
                        self.pending[q as usize] && self.bucket(distance[q as usize]) <= absolute;
                    if live {
                        self.pending[q as usize] = false;
                        return Some(q);
                    }
                }
                let done = std::mem::take(&mut self.buckets[self.current]);
                if done.capacity() > 0 {
                    self.spare.push(done);
                }
                self.current += 1;
            }
            if !self.refill(distance) {
                return None;
            }
        }
    }

    fn is_final(&self, value: f64) -> bool {
        // Everything still queued lies in the current bucket or later, and improvements
        // never go below the bucket they come from.
        self.bucket(value) < self.base + self.current
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pops everything, returning the nodes in order.
    fn drain(queue: &mut BucketQueue, distance: &[f64]) -> Vec<u32> {
        std::iter::from_fn(|| queue.pop(distance)).collect()
    }

    #[test]
    fn buckets_pop_in_order_and_skip_stale_entries() {
        let mut queue = BucketQueue::default();
        queue.reset(4, 1.0);
        let mut distance = vec![f64::INFINITY; 4];
        for (node, value) in [(0, 2.5), (1, 0.5), (2, 1.5), (3, 7.0)] {
            distance[node as usize] = value;
            assert!(queue.push(node, value, f64::INFINITY));
        }
        // Node 3 improves to bucket 1: its old entry in bucket 7 is stale.
        assert!(queue.push(3, 1.2, 7.0));
        distance[3] = 1.2;
        // An improvement within the same bucket adds nothing.
        assert!(!queue.push(3, 1.1, 1.2));
        distance[3] = 1.1;
        let order = drain(&mut queue, &distance);
        assert_eq!(order.len(), 4);
        assert_eq!(order[0], 1);
        assert_eq!(order[3], 0);
        assert!(order[1..3].contains(&2) && order[1..3].contains(&3));
    }

    #[test]
    fn a_value_below_the_current_bucket_is_still_settled() {
        let mut queue = BucketQueue::default();
        queue.reset(3, 1.0);
        let mut distance = vec![f64::INFINITY; 3];
        distance[0] = 5.5;
        queue.push(0, 5.5, f64::INFINITY);
        assert_eq!(queue.pop(&distance), Some(0));
        // Processing bucket 5 now; node 1 gets a value of bucket 2, then improves
        // within it: it must come out once, not be taken for stale.
        distance[1] = 2.5;
        assert!(queue.push(1, 2.5, f64::INFINITY));
        distance[1] = 2.2;
        assert!(!queue.push(1, 2.2, 2.5));
        assert_eq!(drain(&mut queue, &distance), [1]);
    }

    #[test]
    fn far_values_wait_outside_the_window() {
        let mut queue = BucketQueue::default();
        queue.reset(2, 1.0);
        let distance = [3.0, 3.0 * WINDOW as f64];
        queue.push(1, distance[1], f64::INFINITY);
        queue.push(0, distance[0], f64::INFINITY);
        assert_eq!(drain(&mut queue, &distance), [0, 1]);
    }

    #[test]
    fn only_values_below_the_current_bucket_are_final() {
        let mut queue = BucketQueue::default();
        queue.reset(2, 1.0);
        let distance = [0.5, 2.5];
        queue.push(0, distance[0], f64::INFINITY);
        queue.push(1, distance[1], f64::INFINITY);
        assert_eq!(queue.pop(&distance), Some(0));
        assert!(
            !queue.is_final(0.5),
            "bucket 0 may still hold smaller values"
        );
        assert_eq!(queue.pop(&distance), Some(1));
        assert!(queue.is_final(0.5) && queue.is_final(1.99));
        assert!(!queue.is_final(2.0));

        let mut heap = HeapQueue::default();
        heap.reset();
        heap.push(0, 0.5, f64::INFINITY);
        heap.push(1, 2.5, f64::INFINITY);
        assert!(!heap.is_final(0.0));
        assert_eq!(heap.pop(&distance), Some(0));
        assert!(heap.is_final(0.5) && !heap.is_final(0.6));
    }
}
