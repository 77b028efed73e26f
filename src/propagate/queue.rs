//! The two priority queues: a binary heap (exact order, O(log n)) for the baselines, and
//! a bucket queue (O(1) near the wavefront, order only up to the bucket width) for the
//! tracks engine.

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
    fn pop(&mut self, key: impl Fn(u32) -> f64 + Copy) -> Option<u32> {
        while let Some(Entry(d, q)) = self.heap.pop() {
            if d <= key(q) {
                self.floor = d;
                return Some(q);
            }
        }
        None
    }

    fn is_final(&self, value: f64) -> bool {
        value <= self.floor
    }

    fn level(&self) -> f64 {
        self.floor
    }
}

/// Buckets `width` wide over a window of [`WINDOW`] buckets, a binary heap beyond it,
/// and an exact order inside a bucket whose nodes keep coming back.
///
/// Bucket `b` of the window holds nodes with distance in `[base + b·width, base +
/// (b+1)·width)`, unsorted. Popping takes any node of the lowest non-empty bucket, so a
/// node may be settled before its final value; it is then queued again when it improves,
/// and the result is still exact. Improvements never fall below the bucket being
/// processed (costs are ≥ 0), so buckets are visited in order, once.
///
/// # Why the work is bounded, whatever the costs
/// One width cannot suit a mesh whose edge costs span many orders of magnitude. Two
/// things keep a bad width from costing more than O(n log n):
/// - *Too narrow* (values many widths apart): entries beyond the window wait in a heap
///   keyed by value; when the window is used up it restarts at the heap's least value
///   and takes what falls inside. Empty buckets are skipped through a bitmap, so a
///   window costs O(WINDOW / 64) plus its entries, and each refill takes at least one
///   live entry: at worst the queue degrades to a heap.
/// - *Too wide* (many nodes that improve one another in one bucket): popped in no
///   order, such nodes can settle again and again, which is where exponential cascades
///   came from. Each bucket counts its live pops and its *returns* (pushes of a node
///   already popped in it); once returns exceed half the pops (plus a small slack), the
///   rest of the bucket is popped in exact order from a heap. Before the switch pops ≤
///   2 · (first pops) + slack; after it, every node pops at most once more (an exact
///   order with costs ≥ 0 settles each node at its final value). A node pops in one
///   bucket only (an improvement after its first pop lands in the bucket being
///   processed), so a run pops at most 3 n + slack · (buckets used) times.
///
/// A node has at most one live entry in the window: `pending` says it is queued where
/// its current distance belongs; an improvement within the same bucket adds nothing.
#[derive(Default)]
pub(super) struct BucketQueue {
    width: f64,
    inverse_width: f64,
    /// Value at the lower edge of the window's bucket 0.
    base: f64,
    buckets: Vec<Vec<u32>>,
    /// Bit `b` of word `b / 64`: bucket `b` of the window may hold entries.
    occupied: Vec<u64>,
    /// The bucket being processed (an index into the window).
    current: usize,
    /// Entries beyond the window (any value, stale ones included).
    far: BinaryHeap<Entry>,
    /// Nodes whose live entry is in `far`; the heap is rebuilt without its stale
    /// entries when they outnumber the live ones, so it never holds more than about
    /// twice the nodes, however often they improve.
    far_live: usize,
    /// The rest of the current bucket in exact order, once it switched.
    exact: BinaryHeap<Entry>,
    /// The current bucket once it switched to exact order, else `usize::MAX`.
    exact_slot: usize,
    /// Live pops and returns in the current bucket.
    pops: u32,
    returns: u32,
    pending: Vec<bool>,
    /// Emptied bucket buffers, kept to avoid allocating new ones (so the window holds
    /// about as much memory as it holds entries, not its widest buckets' sum).
    spare: Vec<Vec<u32>>,
}

/// Buckets in the window (256 words of occupancy bits). Entries beyond it pay a heap
/// push; 2¹⁴ widths hold nearly every push of a normal run (2¹² sent most of the
/// bunny's pushes to the heap: same instructions, 7 MB more peak memory).
const WINDOW: usize = 1 << 14;
/// Returns a bucket tolerates before it switches to exact order, besides half its pops.
const RETURN_SLACK: u32 = 32;

impl BucketQueue {
    /// Empties the queue for a run over `nodes` nodes with buckets `width` wide (> 0),
    /// keeping every buffer it has grown.
    pub fn reset(&mut self, nodes: usize, width: f64) {
        self.width = width;
        self.inverse_width = 1.0 / width;
        if self.buckets.len() != WINDOW {
            self.buckets.resize_with(WINDOW, Vec::new);
            self.occupied = vec![0; WINDOW / 64];
        }
        if self.pending.len() == nodes {
            // A pending node has an entry in the window, the far heap or the exact
            // heap: clearing those nodes clears `pending`, at the cost of what the last
            // run left queued rather than of the whole mesh.
            let pending = &mut self.pending;
            for (w, &word) in self.occupied.iter().enumerate() {
                let mut bits = word;
                while bits != 0 {
                    let b = w * 64 + bits.trailing_zeros() as usize;
                    for &q in &self.buckets[b] {
                        pending[q as usize] = false;
                    }
                    bits &= bits - 1;
                }
            }
            for &Entry(_, q) in self.far.iter().chain(self.exact.iter()) {
                pending[q as usize] = false;
            }
            debug_assert!(pending.iter().all(|&p| !p), "a pending node left no entry");
        } else {
            self.pending.clear();
            self.pending.resize(nodes, false);
        }
        self.clear_window();
        self.current = 0;
        self.far.clear();
        self.far_live = 0;
        self.exact.clear();
        self.exact_slot = usize::MAX;
        self.pops = 0;
        self.returns = 0;
        // No window until the first pop: everything waits in the heap.
        self.base = f64::NEG_INFINITY;
    }

    /// Empties every bucket of the window, keeping their buffers.
    fn clear_window(&mut self) {
        for (w, word) in self.occupied.iter_mut().enumerate() {
            let mut bits = *word;
            while bits != 0 {
                let b = w * 64 + bits.trailing_zeros() as usize;
                Self::recycle(&mut self.buckets[b], &mut self.spare);
                bits &= bits - 1;
            }
            *word = 0;
        }
    }

    /// Empties `bucket`, moving its buffer to the spares.
    fn recycle(bucket: &mut Vec<u32>, spare: &mut Vec<Vec<u32>>) {
        let mut done = std::mem::take(bucket);
        if done.capacity() > 0 {
            done.clear();
            spare.push(done);
        }
    }

    /// The window bucket of `value`: an index ≥ [`WINDOW`] beyond the window (and for
    /// every value before the window is placed, when `base` is −∞).
    #[inline(always)]
    fn slot(&self, value: f64) -> usize {
        // Saturating conversion: a value below the base gives 0 (filed as the current
        // bucket), one far beyond gives a huge index (the heap). To `u32` because x86
        // converts to a signed 64-bit integer in one instruction.
        ((value - self.base) * self.inverse_width) as u32 as usize
    }

    /// Files `node` in window bucket `b` (not below the current one).
    #[inline(always)]
    fn file(&mut self, node: u32, b: usize) {
        let bucket = &mut self.buckets[b];
        if bucket.capacity() == 0 {
            if let Some(spare) = self.spare.pop() {
                *bucket = spare;
            }
        }
        bucket.push(node);
        self.occupied[b / 64] |= 1 << (b % 64);
    }

    /// The first possibly occupied bucket at or after `from`, if any.
    #[inline]
    fn next_occupied(&self, from: usize) -> Option<usize> {
        let mut w = from / 64;
        if w >= self.occupied.len() {
            return None;
        }
        let mut bits = self.occupied[w] & (!0u64 << (from % 64));
        loop {
            if bits != 0 {
                return Some(w * 64 + bits.trailing_zeros() as usize);
            }
            w += 1;
            if w == self.occupied.len() {
                return None;
            }
            bits = self.occupied[w];
        }
    }

    /// Restarts the window at the least live value waiting in the heap and moves every
    /// live entry that falls inside it there; returns whether anything is left.
    fn refill(&mut self, key: impl Fn(u32) -> f64) -> bool {
        let live = |pending: &[bool], Entry(v, q): Entry| pending[q as usize] && key(q) == v;
        while let Some(&top) = self.far.peek() {
            if live(&self.pending, top) {
                break;
            }
            self.far.pop();
        }
        let Some(&Entry(lowest, _)) = self.far.peek() else {
            return false;
        };
        self.clear_window();
        self.base = lowest;
        self.current = 0;
        while let Some(&top) = self.far.peek() {
            let b = self.slot(top.0);
            if b >= WINDOW {
                break;
            }
            self.far.pop();
            if live(&self.pending, top) {
                self.far_live -= 1;
                self.file(top.1, b);
            }
        }
        true
    }

    /// Moves on from the current bucket (emptied).
    fn next_bucket(&mut self) {
        let b = self.current;
        Self::recycle(&mut self.buckets[b], &mut self.spare);
        self.occupied[b / 64] &= !(1 << (b % 64));
        self.current += 1;
        self.exact_slot = usize::MAX;
        self.pops = 0;
        self.returns = 0;
    }

    /// Switches the rest of the current bucket to exact order.
    #[cold]
    fn go_exact(&mut self, key: impl Fn(u32) -> f64) {
        let b = self.current;
        self.exact_slot = b;
        self.exact.clear();
        for &q in &self.buckets[b] {
            let d = key(q);
            if self.pending[q as usize] && self.slot(d) <= b {
                self.exact.push(Entry(d, q));
            }
        }
        self.buckets[b].clear();
    }
}

impl Queue for BucketQueue {
    #[inline(always)]
    fn push(&mut self, node: u32, value: f64, previous: f64) -> bool {
        if value == previous && self.pending[node as usize] {
            // Queued again at the value it waits with (a requeue): already there.
            return false;
        }
        let slot = self.slot(value);
        let was_far = self.pending[node as usize] && self.slot(previous) >= WINDOW;
        if slot >= WINDOW {
            self.far_live += !was_far as usize;
            self.pending[node as usize] = true;
            self.far.push(Entry(value, node));
            return true;
        }
        self.far_live -= was_far as usize;
        // Buckets below the current one are filed as the current one.
        let current = self.current;
        let b = slot.max(current);
        if self.pending[node as usize] {
            // Queued where `previous` belongs: nothing to add if that is `b` (but a
            // heap needs the new key).
            if self.slot(previous).max(current) == b && b != self.exact_slot {
                return false;
            }
        } else if b == current && self.slot(previous) <= current {
            // Popped in this bucket already, and back.
            self.returns += 1;
        }
        self.pending[node as usize] = true;
        if b == self.exact_slot {
            self.exact.push(Entry(value, node));
        } else {
            self.file(node, b);
        }
        true
    }

    #[inline]
    fn pop(&mut self, key: impl Fn(u32) -> f64 + Copy) -> Option<u32> {
        if self.far.len() > 2 * self.far_live + WINDOW {
            let pending = &self.pending;
            self.far
                .retain(|&Entry(v, q)| pending[q as usize] && key(q) == v);
        }
        loop {
            if self.exact_slot != usize::MAX {
                while let Some(Entry(d, q)) = self.exact.pop() {
                    if self.pending[q as usize] && key(q) == d {
                        self.pending[q as usize] = false;
                        return Some(q);
                    }
                }
                self.next_bucket();
            }
            if self.base != f64::NEG_INFINITY {
                while let Some(b) = self.next_occupied(self.current) {
                    if b != self.current {
                        self.current = b;
                        self.pops = 0;
                        self.returns = 0;
                    }
                    if 2 * self.returns > self.pops + RETURN_SLACK {
                        self.go_exact(key);
                        break;
                    }
                    let absolute = self.current;
                    while let Some(q) = self.buckets[absolute].pop() {
                        // Live: queued, and filed where its key belongs (or below).
                        let d = key(q);
                        let live = self.pending[q as usize] && self.slot(d) <= absolute;
                        if live {
                            self.pending[q as usize] = false;
                            self.pops += 1;
                            return Some(q);
                        }
                    }
                    self.next_bucket();
                }
                if self.exact_slot != usize::MAX {
                    continue;
                }
            }
            if !self.refill(key) {
                return None;
            }
        }
    }

    fn is_final(&self, value: f64) -> bool {
        // Everything still queued lies in the current bucket or later, and improvements
        // never go below the bucket they come from.
        value < self.level()
    }

    fn level(&self) -> f64 {
        self.base + self.current as f64 * self.width
    }
}
#[cfg(test)]
mod tests {
    use super::*;

    /// Pops everything, returning the nodes in order.
    fn drain(queue: &mut BucketQueue, distance: &[f64]) -> Vec<u32> {
        std::iter::from_fn(|| queue.pop(|q| distance[q as usize])).collect()
    }

    #[test]
    fn buckets_pop_in_order_and_skip_stale_entries() {
        let mut queue = BucketQueue::default();
        queue.reset(5, 1.0);
        let mut distance = vec![f64::INFINITY; 5];
        // The first pop places the window at the least value: bucket b is
        // [b, b + 1) from then on.
        distance[4] = 0.0;
        queue.push(4, 0.0, f64::INFINITY);
        assert_eq!(queue.pop(|q| distance[q as usize]), Some(4));
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
    fn values_spanning_hundreds_of_orders_of_magnitude_pop_in_order() {
        // Buckets 1e-9 wide for values up to 1e300: no bucket index saturates, and
        // values many windows apart come out in order through the heap.
        let values = [1e300, 3.0, 1e-12, 1e30, 2e30, 1e30 + 1e15, 0.0, 7e-10, 1e9];
        let mut queue = BucketQueue::default();
        queue.reset(values.len(), 1e-9);
        for (node, &v) in values.iter().enumerate() {
            queue.push(node as u32, v, f64::INFINITY);
        }
        let popped: Vec<f64> = drain(&mut queue, &values)
            .iter()
            .map(|&q| values[q as usize])
            .collect();
        let mut sorted = values.to_vec();
        sorted.sort_by(f64::total_cmp);
        // 0, 7e-10 and 1e-12 share the first bucket; the rest are buckets apart.
        assert_eq!(popped.len(), values.len());
        assert_eq!(popped[3..], sorted[3..]);
    }

    #[test]
    fn a_bucket_whose_nodes_keep_coming_back_switches_to_exact_order() {
        // One bucket as wide as every value: popped in no order, a chain where each
        // node improves the next would settle nodes again and again. After the switch
        // every node pops at most once more, in exact order.
        let n = 2000usize;
        let mut queue = BucketQueue::default();
        queue.reset(n, 1e9);
        let mut distance = vec![f64::INFINITY; n];
        let mut pops = 0;
        distance[0] = 0.0;
        queue.push(0, 0.0, f64::INFINITY);
        while let Some(q) = queue.pop(|q| distance[q as usize]) {
            pops += 1;
            // Node q offers the next 49 nodes a cost that grows faster than the jump,
            // so the best path steps one node at a time, and LIFO order pops far
            // nodes with values that their predecessors undercut later.
            for t in q as usize + 1..n.min(q as usize + 50) {
                let jump = (t - q as usize) as f64;
                let value = distance[q as usize] + jump * 1e-3 + jump * jump * 1e-6;
                if value < distance[t] {
                    let previous = distance[t];
                    distance[t] = value;
                    queue.push(t as u32, value, previous);
                }
            }
        }
        assert!(
            pops <= 3 * n + RETURN_SLACK as usize,
            "{pops} pops for {n} nodes"
        );
        for (t, &d) in distance.iter().enumerate() {
            assert!((d - t as f64 * 1.001e-3).abs() < 1e-9, "{t}: {d}");
        }
    }

    #[test]
    fn a_value_below_the_current_bucket_is_still_settled() {
        let mut queue = BucketQueue::default();
        queue.reset(3, 1.0);
        let mut distance = vec![f64::INFINITY; 3];
        distance[0] = 5.5;
        queue.push(0, 5.5, f64::INFINITY);
        assert_eq!(queue.pop(|q| distance[q as usize]), Some(0));
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
        assert_eq!(queue.pop(|q| distance[q as usize]), Some(0));
        assert!(
            !queue.is_final(0.5),
            "bucket 0 may still hold smaller values"
        );
        assert_eq!(queue.pop(|q| distance[q as usize]), Some(1));
        // The window starts at the least value (0.5), so bucket 2 is [2.5, 3.5).
        assert!(queue.is_final(0.5) && queue.is_final(2.49));
        assert!(!queue.is_final(2.5));

        let mut heap = HeapQueue::default();
        heap.reset();
        heap.push(0, 0.5, f64::INFINITY);
        heap.push(1, 2.5, f64::INFINITY);
        assert!(!heap.is_final(0.0));
        assert_eq!(heap.pop(|q| distance[q as usize]), Some(0));
        assert!(heap.is_final(0.5) && !heap.is_final(0.6));
    }
}
