//! A path between two points searched from both ends at once, on two threads: what
//! the two searches share, and how they decide, in lock step, that they have met.
//!
//! Each side is an ordinary goal-directed run (the forward one from the path's start
//! under the metric, the backward one from its end under the metric reversed: the
//! same metric when it is symmetric), ordered by its value plus the average of the
//! two ends' estimates ([`Goal::between`]): a node's two keys add up to the cost of
//! the best path through it plus `offset`. Each side settles nodes in key order, so
//! every node whose key is below its side's *level* (the queue's lower bound on what
//! it still holds) has its final value, and has made its offers.
//!
//! # When the search is over
//! Let `μ` be the least `forward(v) + backward(v)` found so far (over the nodes one
//! side settled, with the other side's values then, each the cost of a path).
//! Once the two levels add up to at least `μ + offset`, no path is cheaper than `μ`.
//! Along a cheaper path `P`, every node's two keys add up to `cost(P) + offset`, less
//! than the two levels: so the forward side settled the path up to some node `u`,
//! and the backward side settled it from the next node `w` on, both with final
//! values. The forward side offered `w` its final value when it settled `u`, so after
//! the runs `forward(w) + backward(w) = cost(P)`: the least sum over *all* nodes once
//! both sides have stopped (not only over the settled ones) finds it. The values are
//! the Steiner graph's, as a one-ended run's.
//!
//! # Lock step
//! The sides run in rounds of the same work, settles plus pushes (or until a side
//! has nothing left to settle: its level is then `inf`). At a round's end both sides wait
//! for each other, each checks the nodes the other settled in the round (handed over
//! as a list, with their values) against its own values, they wait again, and take
//! the same decision from the same numbers. What each side does in a round depends
//! only on its own run, so the result does not depend on how the threads were
//! scheduled: the same query gives the same path, every time. Equal work per round
//! keeps either side from waiting long for the other; the side whose nodes cost less
//! to settle gets further, as a search from both ends should.
//!
//! Why pushes count: a side's time follows its pushes (queue insertions, each a
//! random write), not its settles or its metric evaluations. On the 1000 × 1000
//! terrain bench's `slope:4` corner route, rounds of equal settles gave the forward
//! side 22 % more pushes (3.86 M against 3.17 M) for the same settles and metric
//! evaluations (within 1 %), and the backward side waited 0.2–0.3 s of its 1.3–1.6 s
//! (scratch timers); both work times came to 0.34–0.35 µs per push.
//!
//! [`Goal::between`]: crate::field::Goal::between

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Mutex;

/// What the two sides of a search from both ends share.
pub(crate) struct Meeting {
    /// Per side, the nodes it settled in its last round, with their values: the other
    /// side adds its own values to them. (Lists, not a per-node array: a search costs
    /// what it settles, not the mesh.)
    settled: [Mutex<Vec<(u32, f64)>>; 2],
    /// Per round parity and side: the side's level at the round's end (parity, so that
    /// a side that starts its next round cannot overwrite what the other still reads).
    level: [[AtomicU64; 2]; 2],
    /// Per round parity and side: the least sum of the two values the side found.
    best: [[AtomicU64; 2]; 2],
    /// Arrivals at the rendezvous, both sides together.
    arrived: AtomicU64,
    /// Set by a side that will not come (see `Side`'s `Drop`): the other stops
    /// waiting for it.
    abandoned: AtomicBool,
    /// The sides' estimates add up to this.
    offset: f64,
    /// How much work (settles plus pushes) a side does in a round.
    round: u64,
}

impl Meeting {
    /// A meeting whose sides' estimates add up to `offset`, in rounds of `round`
    /// settles and pushes.
    pub fn new(offset: f64, round: u64) -> Meeting {
        let unset = f64::INFINITY.to_bits();
        let pair = || [AtomicU64::new(unset), AtomicU64::new(unset)];
        Meeting {
            settled: [Mutex::new(Vec::new()), Mutex::new(Vec::new())],
            level: [pair(), pair()],
            best: [pair(), pair()],
            arrived: AtomicU64::new(0),
            abandoned: AtomicBool::new(false),
            offset,
            round,
        }
    }

    /// Side `side` (0: forward, 1: backward) of the meeting.
    pub fn side(&self, side: usize) -> Side<'_> {
        Side {
            meeting: self,
            side,
            rounds: 0,
            round_began: 0,
            settled: Vec::new(),
            best: f64::INFINITY,
            over: false,
        }
    }

    /// Waits until both sides have arrived as often as this one; `false` if the other
    /// side will never come.
    fn rendezvous(&self) -> bool {
        let n = self.arrived.fetch_add(1, Ordering::AcqRel) + 1;
        let all = n.div_ceil(2) * 2;
        let mut spins = 0u32;
        while self.arrived.load(Ordering::Acquire) < all {
            if self.abandoned.load(Ordering::Relaxed) {
                return false;
            }
            // Rounds are short and both sides work at once: spin a little, then let
            // the other thread have the core.
            spins += 1;
            if spins < 1 << 10 {
                std::hint::spin_loop();
            } else {
                std::thread::yield_now();
            }
        }
        true
    }
}

/// One side's part in a [`Meeting`], held by its run.
pub(crate) struct Side<'a> {
    meeting: &'a Meeting,
    side: usize,
    rounds: usize,
    /// The side's pushes (in its run) when its round began.
    round_began: u64,
    /// The nodes it settled this round, with their values.
    settled: Vec<(u32, f64)>,
    /// The least sum of the two values it found so far.
    best: f64,
    /// The sides decided that the search is over.
    over: bool,
}

impl Side<'_> {
    /// Records that `node` settled with `value`.
    #[inline]
    pub fn settle(&mut self, node: u32, value: f64) {
        self.settled.push((node, value));
    }

    /// Whether the side is done with its round, having pushed nodes `pushes` times in
    /// its run so far.
    #[inline]
    pub fn round_over(&self, pushes: u64) -> bool {
        self.settled.len() as u64 + (pushes - self.round_began) >= self.meeting.round
    }

    /// Ends the side's round at `level` (`inf`: nothing left to settle), with its
    /// values `distance` and `pushes` so far, and returns whether the search is over
    /// (as the other side's call returns the same).
    pub fn end_round(&mut self, level: f64, distance: &[f64], pushes: u64) -> bool {
        if self.over {
            return true;
        }
        self.round_began = pushes;
        let m = self.meeting;
        let parity = self.rounds % 2;
        self.rounds += 1;
        m.level[parity][self.side].store(level.to_bits(), Ordering::Relaxed);
        {
            // The other side reads the list only between the next two rendezvous.
            let mut mine = lock(&m.settled[self.side]);
            std::mem::swap(&mut *mine, &mut self.settled);
        }
        self.settled.clear();
        if !m.rendezvous() {
            self.over = true;
            return true;
        }
        // Both sides wait: what the other settled this round, against this side's
        // values (final or not, each is the cost of a path).
        for &(node, value) in lock(&m.settled[1 - self.side]).iter() {
            self.best = self.best.min(value + distance[node as usize]);
        }
        m.best[parity][self.side].store(self.best.to_bits(), Ordering::Relaxed);
        if !m.rendezvous() {
            self.over = true;
            return true;
        }
        let read =
            |slot: &[AtomicU64; 2], i: usize| f64::from_bits(slot[i].load(Ordering::Relaxed));
        let levels = read(&m.level[parity], 0) + read(&m.level[parity], 1);
        let best = read(&m.best[parity], 0).min(read(&m.best[parity], 1));
        // (A side with nothing left ends it: `inf` is at least anything.)
        self.over = levels >= best + m.offset;
        self.over
    }

    /// Takes part in rounds, with nothing left to settle, until the search is over.
    pub fn finish(&mut self, distance: &[f64]) {
        while !self.end_round(f64::INFINITY, distance, self.round_began) {}
    }
}

/// The list behind `mutex`: a side that panicked holding it left nothing the other
/// could misread (it swaps whole lists).
fn lock<T>(mutex: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    mutex
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// A side dropped before the search was over (its run failed before it began, or
/// panicked) will never come to the rendezvous: the other side stops waiting for it.
impl Drop for Side<'_> {
    fn drop(&mut self) {
        if !self.over {
            self.meeting.abandoned.store(true, Ordering::Relaxed);
        }
    }
}
