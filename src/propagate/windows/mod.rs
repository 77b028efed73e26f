//! The exact engine: edges that hold as many *windows* as the geodesics need.
//!
//! # Idea
//! Under a metric that is a constant norm on each face (`Metric::face_gram`) and
//! whose faces glue isometrically (every edge has one length in all its faces), a
//! shortest path is a straight line in the unfolding of the faces it crosses, bending
//! only at vertices where the surface is not flat around them (saddles, boundary and
//! non-manifold vertices) or along wires (Mitchell, Mount and Papadimitriou 1987). A
//! *window* stands for a bundle of such lines: a virtual source `S` (the start of the
//! straight piece, unfolded behind an edge), `σ` (the path length up to `S`), and the
//! part `[b0, b1]` of the edge the lines cross. Carried across a face, a window's
//! lines reach one or both of the face's other edges: its *children*, with the same
//! `S` and `σ`, seen from the new edges. A vertex where paths may bend, once its
//! value is final, starts windows of its own on the far edge of every face around
//! it; so does every source.
//!
//! # Order and pruning
//! Each edge keeps its windows not carried yet in a list of their own, side by side
//! in memory. Edges are taken from a radix heap (`radix`; vertices' events in the
//! same heap) in the order of the least value among their waiting windows, and all
//! of an edge's windows are carried together ([`ExactRun::carry`] says why that stays
//! exact): a vertex's value is final when the heap's least key reaches it, since no
//! window yet to come is shorter than the one that made it. This is the batching of
//! VTP (Qin et al. 2016), which carries an edge's list of windows at once, in the
//! order of a heap of edges where VTP orders vertices; on a million faces it is
//! several times faster than a heap of windows, which hops through memory from one
//! window to the next.
//!
//! What keeps the count of windows small is the *vertex check* of Xin and Wang
//! (2009) and Qin et al. (2016), made exact: along its edge, a window's value less the
//! way from an end of the edge only falls away from that end, so the part of a window
//! longer than the path through an end (the end's value plus the way along the edge)
//! is cut off in closed form ([`Lines::trim`]). Every window is trimmed when made and
//! again when carried (values only fall meanwhile), and the windows carried together
//! are first compared with each other ([`trim_pair`]). Trimming only removes lines that
//! another path matches or beats, so what is left still holds a shortest path to
//! every point: the engine is exact up to rounding (`TOLERANCE`).
//!
//! # Topology
//! A window entering an edge from one face continues into every other face around it
//! (non-manifold edges), ends at the boundary, and vertices on the boundary, on
//! non-manifold edges or where two fans of faces pinch start windows as saddles do.
//! Wires carry values between their vertices, which then start windows. Each window
//! remembers the window it came from, so a geodesic is traced back along straight
//! lines, with no search: a window is never cut once carried, so its children's lines
//! all cross it.
//!
//! # Cost
//! A window waiting on its edge is 56 bytes in its edge's list; a field keeps every
//! window carried (56 bytes each: a path or a query at a point reads them), 14 to 58
//! per edge on the shared meshes, several gigabytes on a mesh of a million faces. A run
//! that wants values at vertices only (`keeps_windows` off) forgets each once carried
//! and holds only the wavefront's, as VTP does (the Performance page measures both
//! beside it). The run refuses to grow past the memory limit ([`Error::ExactTooLarge`])
//! instead of exhausting the machine: window counts
//! grow faster than the faces (about as `n √n` on the shared bunnies: 14.6, 29.4 and
//! 57.9 per edge at 69 K, 278 K and 1.1 M faces; `O(n²)` at worst, as for MMP).

mod geometry;
mod radix;
mod tables;

pub(crate) use geometry::Lines;
use geometry::{norm, project, trim_pair, Across, Child};
use radix::RadixHeap;
pub(in crate::propagate) use tables::ExactTables;

use crate::field::{Origin, Window, WindowField};
use crate::flat::P;
use crate::mesh::{Csr, Topology, NONE};
use crate::surface::{Source, SurfacePoint};
use crate::Error;
use std::cmp::Ordering;

/// How much longer than another path a window may be and keep its lines, relative to
/// the values compared: a few units in the last place, so that rounding does not cut
/// the lines of two equal windows (the same lines reached twice), and no wider: a
/// wider tie keeps slivers of lines along every ray that grazes a vertex (on a ray
/// from the source through a boundary vertex, the vertex's own windows tie the
/// source's), and slivers carried on from vertex to vertex grow quadratically in
/// number on long strips.
const TOLERANCE: f64 = 1e-13;

/// Lines narrower than this, seen from their source (the window's width over its
/// distance from the source, in radians), are dropped: the rays of such a window are
/// rounding apart, and a point they alone would reach is reached by the lines on
/// either side bending at a window's end, longer by about `D · angle² / 8`: 1e-20 of
/// the distance `D`.
const NARROWEST: f64 = 1e-10;

/// Two windows are the same wave when their sources and `σ` agree to this, relative
/// to the edge: rounding through different chains of faces stays far below it, and
/// joining two that differ by it changes values by as little. (A hundred times tighter
/// than the wavefront engine's `flat::SAME_SOURCE`: an exact engine's budget is 1e-9
/// of the distance in all, not per join.)
const SAME_WAVE: f64 = 1e-11;

/// Whether `a` and `b` are lines of one wave (see [`SAME_WAVE`]) on an edge `len` long.
fn same_wave(a: &Lines, b: &Lines, len: f64) -> bool {
    let slack = SAME_WAVE * (len + a.sigma.abs());
    (a.sx - b.sx).abs() <= slack
        && (a.sy - b.sy).abs() <= slack
        && (a.sigma - b.sigma).abs() <= slack
}

/// A vertex event in the heap: the vertex's id with this bit set.
const VERTEX_EVENT: u32 = 1 << 31;

/// The per-run buffers of the exact engine, kept in a workspace.
#[derive(Default)]
pub(crate) struct ExactBuffers {
    pub heap: RadixHeap,
    /// Per vertex, whether it started its windows.
    pub started: Vec<bool>,
    /// Per edge, its windows not carried yet, compared with each other when they are.
    /// Side by side in memory, so that the comparison reads them in one sweep (they
    /// are many on a large mesh, and a walk from window to window through the run's
    /// arena misses the cache at every step). A window enters the field, and gets
    /// its id, when it is carried.
    pub pending: Vec<Vec<Pending>>,
    /// Emptied lists kept for the next edges to start one (at most [`SPARE_LISTS`],
    /// each with room for at most [`SPARE_ROOM`] windows): freeing an edge's list when
    /// carried and allocating, and growing, a fresh one for every batch took 6 % more
    /// of the run's instructions (callgrind on bunny: 2.18 G against 2.06 G).
    pub spare: Vec<Vec<Pending>>,
    /// Per edge, the least key its pending windows are queued at (`inf`: none).
    pub queued: Vec<f64>,
    /// How many windows wait in all the lists.
    pub waiting: usize,
}

/// How many emptied lists [`ExactBuffers::spare`] keeps: the lists begun between two
/// carried ones are few, so a short stack serves almost every start.
const SPARE_LISTS: usize = 1024;
/// The largest list kept spare (in windows): a long one's room would sit idle.
const SPARE_ROOM: usize = 64;

/// A window waiting on its edge to be carried (see [`ExactBuffers::pending`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Pending {
    lines: Lines,
    /// The face its lines came through.
    from: u32,
    /// As [`Window::parent`] and [`Window::source`].
    parent: u32,
    source: u32,
}

/// A face that windows of one of its edges cross, in that edge's frame.
struct Crossing {
    face: u32,
    across: Across,
    /// The face's third corner.
    apex_vertex: u32,
    /// The edges of the two sides (from the first end to the apex, then from the apex
    /// to the second end).
    sides: [u32; 2],
}

/// How a run may end early, and what it may spend.
pub(in crate::propagate) struct Bounds<'a> {
    pub max_distance: f64,
    /// Vertices whose values must be final (`point_targets`: plus the engine's reach,
    /// for points inside their faces) before the run may stop.
    pub targets: &'a [u32],
    pub point_targets: bool,
    /// The most windows the run may hold at once (its memory).
    pub max_windows: usize,
    /// The most windows the run may make (its work).
    pub max_made: u64,
}

/// What a run did.
#[derive(Clone, Copy, Debug, Default)]
pub(in crate::propagate) struct Counts {
    /// Windows made.
    pub created: u64,
    /// Windows carried across faces.
    pub carried: u64,
    /// Face crossings.
    pub crossings: u64,
    pub stopped_early: bool,
    /// The heap's key when the run stopped at its targets (`inf` otherwise).
    pub level: f64,
}

/// One run of the exact engine over borrowed state.
pub(in crate::propagate) struct ExactRun<'a, T> {
    pub mesh: &'a T,
    pub tables: &'a ExactTables,
    pub wires: &'a Csr<(u32, f64)>,
    pub distance: &'a mut [f64],
    pub field: &'a mut WindowField,
    pub buffers: &'a mut ExactBuffers,
    pub touched: &'a mut Vec<u32>,
    /// Whether to record first-reached vertices in `touched`.
    pub records: bool,
    /// Whether the field keeps the windows (for queries at points and paths); else
    /// each is forgotten once carried, and the run holds only the wavefront's.
    pub keeps_windows: bool,
    pub bounds: Bounds<'a>,
    pub counts: Counts,
}

impl<T: Topology> ExactRun<'_, T> {
    /// Starts windows from `sources` (validated) and carries them until the heap runs
    /// out or the bounds stop the run.
    ///
    /// # Errors
    /// [`Error::ExactTooLarge`] when the windows would outgrow `bounds`.
    pub fn run(&mut self, sources: &[Source]) -> Result<Counts, Error> {
        let ran = self.carry_all(sources);
        // A run that stops early or at a limit leaves windows waiting: every edge
        // that holds some is in the heap (queued at their least value).
        while let Some((_, id)) = self.buffers.heap.pop() {
            if id & VERTEX_EVENT == 0 {
                self.buffers.pending[id as usize] = Vec::new();
                self.buffers.queued[id as usize] = f64::INFINITY;
            }
        }
        self.buffers.waiting = 0;
        ran
    }

    /// [`ExactRun::run`]'s work.
    fn carry_all(&mut self, sources: &[Source]) -> Result<Counts, Error> {
        self.buffers.heap.clear();
        if self.buffers.pending.len() != self.mesh.edge_count() {
            self.buffers.pending.clear();
            self.buffers
                .pending
                .resize(self.mesh.edge_count(), Vec::new());
            self.buffers.queued.clear();
            self.buffers
                .queued
                .resize(self.mesh.edge_count(), f64::INFINITY);
        }
        self.counts = Counts {
            level: f64::INFINITY,
            ..Counts::default()
        };
        for (index, source) in sources.iter().enumerate() {
            self.seed(index as u32, source)?;
        }
        // The key from which the targets' values are final: it only falls (values
        // do), and is looked at again once the heap reaches it, or, while a target is
        // unreached (`inf`), once every as many pops as there are targets (so that
        // looking costs O(1) a pop).
        let mut threshold = f64::NEG_INFINITY;
        let mut pops_to_look = 0usize;
        while let Some((key, id)) = self.buffers.heap.pop() {
            if key > self.bounds.max_distance {
                break;
            }
            pops_to_look = pops_to_look.saturating_sub(1);
            let targets = self.bounds.targets.len();
            if targets > 0 && (key >= threshold || pops_to_look == 0) {
                threshold = self.targets_final_at();
                pops_to_look = targets;
                if key >= threshold {
                    self.counts.stopped_early = true;
                    self.counts.level = key;
                    break;
                }
            }
            if id & VERTEX_EVENT != 0 {
                let v = id & !VERTEX_EVENT;
                // The first event of a vertex is its final value's: a later value
                // is a lower key, taken first. (Its key may sit a rounding above the
                // value: the queue keeps nothing below what it took last.)
                if !self.buffers.started[v as usize] {
                    self.buffers.started[v as usize] = true;
                    self.start_at_vertex(v)?;
                }
            } else {
                self.carry(id, key)?;
            }
        }
        self.finish();
        Ok(self.counts)
    }

    /// The heap key from which every target's value is final: the most of their
    /// vertices' values (plus the reach, for points inside faces).
    fn targets_final_at(&self) -> f64 {
        let most = self
            .bounds
            .targets
            .iter()
            .map(|&v| self.distance[v as usize])
            .fold(f64::NEG_INFINITY, f64::max);
        if self.bounds.point_targets {
            most + self.tables.reach
        } else {
            most
        }
    }

    /// Source `index`'s first windows and values.
    fn seed(&mut self, index: u32, source: &Source) -> Result<(), Error> {
        let mesh = self.mesh;
        let sigma = source.start;
        match source.point {
            SurfacePoint::Vertex(v) => self.offer(v, sigma, Origin::Start(index), index),
            SurfacePoint::Edge { edge, t } => {
                let [lo, hi] = mesh.edge_vertices(edge);
                for &f in mesh.edge_faces(edge).iter() {
                    let s = mesh.edge_slot(f, edge).expect("an edge of its face");
                    let c = self.tables.frames[f as usize]
                        .corners()
                        .map(|[x, y]| P(x, y));
                    let (a, b) = if mesh.slot_is_reversed(f, s) {
                        (c[(s + 1) % 3], c[s])
                    } else {
                        (c[s], c[(s + 1) % 3])
                    };
                    let ab = b.sub(a);
                    let (at, len) = (a.add(ab.scale(t)), norm(ab.0, ab.1));
                    // Along the edge: a segment of this face.
                    let face = f;
                    let origin = Origin::Source { index, face };
                    self.offer(lo, sigma + t * len, origin, index);
                    self.offer(hi, sigma + (1.0 - t) * len, origin, index);
                    for other in [(s + 1) % 3, (s + 2) % 3] {
                        self.start_on(f, other, at, sigma, index)?;
                    }
                }
            }
            SurfacePoint::Face { face, bary } => {
                let at = self.tables.frames[face as usize].point(bary).uv;
                for slot in 0..3 {
                    self.start_on(face, slot, P(at[0], at[1]), sigma, index)?;
                }
            }
        }
        Ok(())
    }

    /// Vertex `v`'s windows (its value final): one on the far edge of every face
    /// around it, and its wires' values.
    fn start_at_vertex(&mut self, v: u32) -> Result<(), Error> {
        let mesh = self.mesh;
        let sigma = self.distance[v as usize];
        for &f in mesh.vertex_faces(v).iter() {
            let corner = mesh.corner_of(f, v).expect("a corner of its face");
            let c = self.tables.frames[f as usize].corners();
            let at = P(c[corner][0], c[corner][1]);
            let label = self.field.label[v as usize];
            self.start_on(f, (corner + 1) % 3, at, sigma, label | Window::AT_VERTEX)?;
        }
        let wires = self.wires;
        for &(u, cost) in wires.row(v) {
            let label = self.field.label[v as usize];
            self.offer(u, sigma + cost, Origin::Wire { from: v }, label);
        }
        Ok(())
    }

    /// A window with its source at `at` (a point of face `f`'s plane, `σ = sigma`)
    /// over the whole edge in slot `slot` of `f`, into the faces beyond it.
    /// `source` as [`Window::source`] (the vertex, with `AT_VERTEX`, is `f`'s corner
    /// opposite the edge).
    fn start_on(
        &mut self,
        f: u32,
        slot: usize,
        at: P,
        sigma: f64,
        source: u32,
    ) -> Result<(), Error> {
        let mesh = self.mesh;
        let frame = &self.tables.frames[f as usize];
        let edge = crate::flat::EdgeFrame::new(frame, slot, mesh.slot_is_reversed(f, slot));
        let (sx, y) = edge.edge_coords(at);
        if y.partial_cmp(&0.0) != Some(Ordering::Greater) {
            // A source on the edge's own line: its lines only graze the edge.
            return Ok(());
        }
        let child = Child {
            lines: Lines {
                sx,
                sy: y,
                sigma,
                b0: 0.0,
                b1: edge.len,
            },
            len: edge.len,
        };
        let origin = if source & Window::AT_VERTEX != 0 {
            Origin::Vertex {
                from: mesh.face_vertices(f)[(slot + 2) % 3],
                face: f,
            }
        } else {
            Origin::Source {
                index: source,
                face: f,
            }
        };
        let e = mesh.face_edges(f)[slot];
        self.make(child, e, f, (NONE, source), origin)
    }

    /// Takes `edge`'s windows from the heap (at `key`, the least value of one of
    /// them) and carries them all, each trimmed first against its ends' values, into
    /// every face around the edge but the one it came from.
    ///
    /// All at once, not each at its own least value: the windows of one edge then
    /// cross its faces together (their frames and values read once, each window's
    /// lines side by side), and the queue holds an entry per edge, not per window.
    /// What this gives up is pruning: a window carried before its own least value
    /// was due is trimmed against its ends' values as they are then, not as they will
    /// be, and may make children a later value would have cut. Counted on bunny,
    /// against a heap of windows: 0.1 % more windows carried (2.3 % more made, most
    /// cut when their list is compared). Values stay exact: a
    /// vertex starts its windows when the queue's least key reaches its value, and
    /// every window made later comes from one carried at a key at least as large (a
    /// child is never shorter than its parent), so none can lower a value already
    /// final.
    fn carry(&mut self, edge: u32, key: f64) -> Result<(), Error> {
        if self.buffers.queued[edge as usize] > key {
            // An entry left from before a shorter window came (or nothing waits).
            return Ok(());
        }
        self.buffers.queued[edge as usize] = f64::INFINITY;
        let mesh = self.mesh;
        let [lo, hi] = mesh.edge_vertices(edge);
        let len = self.tables.lengths[edge as usize];
        let tolerance = TOLERANCE * key.abs().max(len);
        let mut list = std::mem::take(&mut self.buffers.pending[edge as usize]);
        self.buffers.waiting -= list.len();
        let (d_lo, d_hi) = (self.distance[lo as usize], self.distance[hi as usize]);
        list.retain_mut(|waiting| waiting.lines.trim(len, d_lo, d_hi, tolerance));
        if list.len() > 1 {
            compare_on_edge(&mut list, len, tolerance);
        }
        self.counts.carried += list.len() as u64;
        // The field's windows are those carried: their ids follow on from `first`.
        let first = self.field.windows.len() as u32;
        if self.keeps_windows {
            self.field.windows.extend(list.iter().map(|w| Window {
                lines: w.lines,
                edge,
                from: w.from,
                parent: w.parent,
                source: w.source,
            }));
        }
        for &f in mesh.edge_faces(edge).iter() {
            if list.iter().all(|w| w.from == f) {
                // Every window came through this face (the common case on one side
                // of a manifold edge): nothing to work out for it.
                continue;
            }
            let crossing = self.crossing(edge, f);
            for (i, waiting) in list.iter().enumerate() {
                if waiting.from != f {
                    let id = if self.keeps_windows {
                        first + i as u32
                    } else {
                        NONE
                    };
                    let label = waiting.source & !Window::AT_VERTEX;
                    self.cross(id, &waiting.lines, &crossing, label)?;
                }
            }
        }
        // Children land on the faces' other edges, never on this one. The list's
        // memory goes to the spare lists, not back to its edge: kept per edge, every
        // list would stay as long as it ever was, twice the memory on the bunnies.
        debug_assert!(self.buffers.pending[edge as usize].is_empty());
        if self.buffers.spare.len() < SPARE_LISTS && list.capacity() <= SPARE_ROOM {
            list.clear();
            self.buffers.spare.push(list);
        }
        Ok(())
    }

    /// Queues `edge` at `key` unless it is queued at a lesser key already.
    fn queue_edge(&mut self, edge: u32, key: f64) {
        let queued = &mut self.buffers.queued[edge as usize];
        if key < *queued {
            *queued = key;
            self.buffers.heap.push(key, edge);
        }
    }

    /// What carrying windows of `edge` across face `f` needs of the face, worked out
    /// once for all of them.
    fn crossing(&self, edge: u32, f: u32) -> Crossing {
        let mesh = self.mesh;
        let s = mesh.edge_slot(f, edge).expect("an edge of its face");
        let c = self.tables.frames[f as usize]
            .corners()
            .map(|[x, y]| P(x, y));
        let (ia, ib) = if mesh.slot_is_reversed(f, s) {
            ((s + 1) % 3, s)
        } else {
            (s, (s + 1) % 3)
        };
        let ic = (s + 2) % 3;
        let ab = c[ib].sub(c[ia]);
        let len = norm(ab.0, ab.1);
        let u = ab.scale(1.0 / len);
        let n = P(-u.1, u.0);
        let to_c = c[ic].sub(c[ia]);
        let mut apex = P(to_c.dot(u), to_c.dot(n));
        if apex.1 < 0.0 {
            apex.1 = -apex.1;
        }
        let vertices = mesh.face_vertices(f);
        let edges = mesh.face_edges(f);
        // The slot of the edge between corners i and j.
        let slot_of = |i: usize, j: usize| if (i + 1) % 3 == j { i } else { j };
        let corners = [(ia, ic), (ic, ib)];
        Crossing {
            face: f,
            across: Across::new(len, apex, corners.map(|(i, j)| vertices[i] < vertices[j])),
            apex_vertex: vertices[ic],
            sides: corners.map(|(i, j)| edges[slot_of(i, j)]),
        }
    }

    /// Carries window `id` (its lines `lines`) across a face (`crossing`): the value
    /// of the face's third corner where the lines reach it, and the children on the
    /// face's two other edges.
    fn cross(
        &mut self,
        id: u32,
        lines: &Lines,
        crossing: &Crossing,
        label: u32,
    ) -> Result<(), Error> {
        self.counts.crossings += 1;
        let (children, sees_apex) = project(lines, &crossing.across);
        let origin = Origin::Window {
            id,
            face: crossing.face,
        };
        if sees_apex {
            let apex = crossing.across.apex;
            let value = lines.sigma + norm(apex.0 - lines.sx, apex.1 + lines.sy);
            self.offer(crossing.apex_vertex, value, origin, label);
        }
        for (child, edge) in children.into_iter().zip(crossing.sides) {
            if let Some(child) = child {
                self.make(child, edge, crossing.face, (id, label), origin)?;
            }
        }
        Ok(())
    }

    /// A new window on `edge` (seen from face `from`, whose plane the child's frame
    /// is in): its ends' values offered (with `origin`), then trimmed and left to
    /// wait on its edge unless nothing is left or no face lies beyond.
    fn make(
        &mut self,
        child: Child,
        edge: u32,
        from: u32,
        (parent, source): (u32, u32),
        origin: Origin,
    ) -> Result<(), Error> {
        let mesh = self.mesh;
        let [lo, hi] = mesh.edge_vertices(edge);
        let Child { mut lines, len } = child;
        let covers = 1e-9 * len;
        let label = source & !Window::AT_VERTEX;
        if lines.b0 <= covers {
            self.offer(lo, lines.value_at(0.0), origin, label);
        }
        if lines.b1 >= len - covers {
            self.offer(hi, lines.value_at(len), origin, label);
        }
        if mesh.edge_faces(edge).iter().all(|&g| g == from) {
            return Ok(());
        }
        let (d_lo, d_hi) = (self.distance[lo as usize], self.distance[hi as usize]);
        let scale = lines.sigma.abs().max(len);
        if !lines.trim(len, d_lo, d_hi, TOLERANCE * scale) {
            return Ok(());
        }
        let key = lines.least();
        if lines.b1 - lines.b0 < NARROWEST * (key - lines.sigma) {
            return Ok(());
        }
        if key > self.bounds.max_distance {
            return Ok(());
        }
        // What the run holds: the windows waiting, and those the field keeps.
        let held = self.buffers.waiting + self.field.windows.len();
        let made = self.counts.created;
        if held >= self.bounds.max_windows || made >= self.bounds.max_made {
            let windows = if held >= self.bounds.max_windows {
                held as u64
            } else {
                made
            };
            return Err(Error::ExactTooLarge {
                windows,
                bytes: windows.saturating_mul(BYTES_PER_WINDOW as u64),
            });
        }
        self.counts.created += 1;
        self.buffers.waiting += 1;
        let list = &mut self.buffers.pending[edge as usize];
        if list.capacity() == 0 {
            match self.buffers.spare.pop() {
                Some(spare) => *list = spare,
                // Room for about as many as an edge holds on the shared meshes (14 to
                // 58 windows): one allocation where growing from nothing takes three.
                None => list.reserve_exact(16),
            }
        }
        list.push(Pending {
            lines,
            from,
            parent,
            source,
        });
        self.queue_edge(edge, key);
        Ok(())
    }

    /// Offers vertex `v` the value `value`, reached by `origin`; a vertex where paths
    /// bend (or reached otherwise than along a window's lines) is queued to start its
    /// own windows once final.
    #[inline]
    fn offer(&mut self, v: u32, value: f64, origin: Origin, label: u32) {
        let d = &mut self.distance[v as usize];
        if value.partial_cmp(d) != Some(Ordering::Less) {
            return;
        }
        if *d == f64::INFINITY && self.records {
            self.touched.push(v);
        }
        *d = value;
        self.field.origin[v as usize] = origin;
        self.field.label[v as usize] = label;
        let starts = self.tables.bends[v as usize]
            || matches!(origin, Origin::Start(_) | Origin::Wire { .. });
        if starts && value <= self.bounds.max_distance {
            self.buffers.heap.push(value, v | VERTEX_EVENT);
        }
    }

    /// After the run: values beyond the maximum distance forgotten, the kept windows
    /// indexed by edge.
    fn finish(&mut self) {
        let max = self.bounds.max_distance;
        if max < f64::INFINITY {
            let (distance, origin, label) = (
                &mut *self.distance,
                &mut self.field.origin,
                &mut self.field.label,
            );
            let vertices = distance.len();
            let mut forget = |v: usize| {
                if distance[v] > max {
                    distance[v] = f64::INFINITY;
                    origin[v] = Origin::None;
                    label[v] = NONE;
                }
            };
            if self.records {
                self.touched.iter().for_each(|&v| forget(v as usize));
            } else {
                (0..vertices).for_each(forget);
            }
        }
        self.field.index(self.mesh.edge_count());
    }
}

/// Compares the windows waiting on an edge `len` long, before they are carried: in
/// the order of their first end, each with those after it that overlap it, cutting
/// each back where the other is shorter ([`trim_pair`]); those left empty or too
/// narrow ([`NARROWEST`]) are forgotten.
///
/// Lines of the same wave (the same source and `σ`, from the same face) that reach
/// the edge through two faces, split by a flat vertex, are joined first, into one
/// window. On planar and developable meshes this keeps one window per edge and
/// source, where every vertex the wave passes would otherwise split it for good (a
/// strip's windows grow quadratically).
///
/// Once, on the whole list, rather than each new window against those waiting when
/// it is made: the same pairs meet (only those waiting together can), the ones apart
/// on the edge are never looked at, and a window's arrival costs nothing.
fn compare_on_edge(list: &mut Vec<Pending>, len: f64, tolerance: f64) {
    list.sort_unstable_by(|a, b| a.lines.b0.total_cmp(&b.lines.b0));
    let touch = SAME_WAVE * len;
    let n = list.len();
    for i in 0..n {
        for j in i + 1..n {
            let (head, tail) = list.split_at_mut(j);
            let (a, b) = (&mut head[i], &mut tail[0]);
            if a.lines.b0 > a.lines.b1 || b.lines.b0 > a.lines.b1 + touch {
                break;
            }
            if b.lines.b0 <= b.lines.b1 && a.from == b.from && same_wave(&a.lines, &b.lines, len) {
                a.lines.b1 = a.lines.b1.max(b.lines.b1);
                b.lines.b0 = f64::INFINITY;
                b.lines.b1 = f64::NEG_INFINITY;
            }
        }
    }
    for i in 0..n {
        for j in i + 1..n {
            let (head, tail) = list.split_at_mut(j);
            let (a, b) = (&mut head[i].lines, &mut tail[0].lines);
            if a.b0 > a.b1 || b.b0 >= a.b1 {
                break;
            }
            if b.b0 <= b.b1 {
                trim_pair(a, b, tolerance);
            }
        }
    }
    list.retain(|w| {
        let lines = &w.lines;
        lines.b0 <= lines.b1 && lines.b1 - lines.b0 >= NARROWEST * (lines.least() - lines.sigma)
    });
}

/// What one window a run holds costs, at most: its place in its edge's list and its
/// copy in the field (both, as while its list is carried), a queue entry and its
/// place in the field's edge index.
pub(in crate::propagate) const BYTES_PER_WINDOW: usize =
    std::mem::size_of::<Pending>() + std::mem::size_of::<Window>() + 16 + 4;
