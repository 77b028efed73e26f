//! Thinning a complex of sheets and curves to a graph without changing its topology,
//! in the order a fire burns it, and how long each piece of curve survives.
//!
//! The complex is a mesh's faces, their edges and vertices, and its line elements. Two
//! elementary *collapses* remove simplices without changing the homotopy type:
//! - a face with a *free* edge (an edge of that face only) goes, with that edge;
//! - a vertex with one edge and no face (a tip) goes, with its edge.
//!
//! This is the *extended grassfire* of erosion thickness (Liu, Chambers, Letscher and
//! Ju 2011 in 2D; Yan, Sykes, Chambers, Letscher and Ju, ACM TOG 2016, on medial axes
//! of 3D shapes). Each vertex has a *reach* time, when the fire may first take it: on a
//! medial axis, its medial radius (when eroding the shape from its surface reaches the
//! ball's centre); on another surface, its grassfire distance from the boundary. A piece
//! burns once it is reached and is free: a face when it has a free edge, at the reach
//! of its last vertex or, if it became free later, when the fire has crossed it from
//! that edge; a tip, as the fire runs along its edge at the metric's speed. What stands
//! where the fronts meet are curves: edges that lost their last face.
//!
//! A vertex's *significance* (its erosion thickness) is how long it stood after it was
//! reached: the time it became a tip, minus its reach. A spur born at a saw tooth of a
//! sheet's border burns as soon as it forms; a leg's curve burns from the foot inwards
//! and its significance grows with the distance from the foot (less the radius); on a
//! graph of curves alone with reach 0 it is the classical length of the branch burnt so
//! far. It is taken as the largest of the vertex's own and its burnt children's, so it
//! never decreases from a tip inwards, and keeping the vertices above a threshold keeps
//! an upper set of the burning forest: branches shrink from their tips and the kept
//! graph retracts onto what never burns.
//!
//! What never burns (significance `inf`) is what no collapse removes: the loops that
//! carry the complex's cycles, and one vertex per component that collapses entirely.
//! If the collapse gets stuck with faces left (a closed sheet has no free edge; a few
//! contractible complexes, like Bing's house, have none either), one face is removed
//! without a free edge: a face on a 2-cycle if there is one (this removes that closed
//! surface and leaves b₁ unchanged), else the face reached last (which adds one cycle;
//! counted in [`Thinning::opened`]); the fire restarts there.

use crate::mesh::{Csr, CycleSheets, TriMesh, NONE};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// The result of thinning a complex.
pub(crate) struct Thinning {
    /// Per vertex: its branch's significance (see the module's notes); `inf` for
    /// vertices never removed; NaN for vertices that no face or line element uses.
    pub significance: Vec<f64>,
    /// Per vertex: where its branch ends, the vertex of a more significant branch (or
    /// of what never burns) that it burnt into; `NONE` for vertices never removed.
    pub ends: Vec<u32>,
    /// Every edge that was a curve at some time (a line element, or an edge that lost its
    /// last face), as a vertex pair.
    pub curves: Vec<[u32; 2]>,
    /// Faces removed without a free edge (the collapse was stuck).
    pub punctured: usize,
    /// Of those, faces on no 2-cycle: each added one independent cycle.
    pub opened: usize,
}

/// A complex of faces, edges and vertices: a mesh's faces (if any) and extra edges.
struct Complex<'m> {
    mesh: Option<&'m TriMesh>,
    vertex_count: usize,
    /// The mesh's edges (ids `0..`) then the extra edges.
    edge_vertices: Vec<[u32; 2]>,
    vertex_edges: Csr,
}

impl<'m> Complex<'m> {
    fn new(mesh: Option<&'m TriMesh>, vertex_count: usize, extra: &[[u32; 2]]) -> Self {
        let mut edge_vertices: Vec<[u32; 2]> = match mesh {
            Some(mesh) => (0..mesh.edge_count() as u32)
                .map(|e| mesh.edge_vertices(e))
                .collect(),
            None => Vec::new(),
        };
        edge_vertices.extend_from_slice(extra);
        let vertex_edges = Csr::from_pairs(
            vertex_count,
            edge_vertices
                .iter()
                .enumerate()
                .flat_map(|(e, ev)| ev.iter().map(move |&v| (v, e as u32))),
        );
        Complex {
            mesh,
            vertex_count,
            edge_vertices,
            vertex_edges,
        }
    }

    fn face_count(&self) -> usize {
        self.mesh.map_or(0, |m| m.face_count())
    }

    fn edge_faces(&self, e: u32) -> &[u32] {
        match self.mesh {
            Some(mesh) if (e as usize) < mesh.edge_count() => mesh.edge_faces(e),
            _ => &[],
        }
    }
}

/// One step of the burn: a face to collapse, or a tip to burn along its edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Event {
    Face(u32),
    Tip(u32),
}

/// The collapse's state: what is left of the complex, and the queue of moves.
struct Collapse<'c, 'm, L, C> {
    complex: &'c Complex<'m>,
    /// Per vertex, its reach (see the module's notes); in a part that had to be
    /// punctured, the puncture's time plus the distance from it.
    reach: Vec<f64>,
    cross: C,
    length: L,
    face_alive: Vec<bool>,
    faces_left: usize,
    edge_alive: Vec<bool>,
    vertex_alive: Vec<bool>,
    /// Per edge, its faces left.
    edge_faces: Vec<u32>,
    /// Per vertex, its faces and edges left.
    vertex_faces: Vec<u32>,
    vertex_edges: Vec<u32>,
    curve: Vec<bool>,
    tip_queued: Vec<bool>,
    /// Per vertex, the largest significance of the tips that burnt into it.
    children: Vec<f64>,
    /// Per burnt vertex, the vertex its tip burnt into.
    parent: Vec<u32>,
    /// The vertices in the order they burnt.
    burnt: Vec<u32>,
    /// Per vertex, when it stood on curves only: when it lost its last face, or its
    /// reach if it never had one.
    birth: Vec<f64>,
    significance: Vec<f64>,
    queue: BinaryHeap<Reverse<(Ordered, Event)>>,
    now: f64,
    punctured: usize,
    opened: usize,
}

/// Thins the faces of `mesh` (if any) with the `extra` edges (line elements that are no
/// face edge, `[lower, higher]`): `reach` per vertex (`inf` where no fire comes, as on
/// a closed sheet), tips moving along an edge in `length(edge)` (edges numbered as the
/// mesh's, then the extra ones), the fire crossing face `f` from its edge `e` to the
/// opposite corner in `cross(f, e)`.
pub(crate) fn thin(
    mesh: Option<&TriMesh>,
    vertex_count: usize,
    extra: &[[u32; 2]],
    reach: &[f64],
    length: impl Fn(u32) -> f64,
    cross: impl Fn(u32, u32) -> f64,
) -> Thinning {
    let complex = Complex::new(mesh, vertex_count, extra);
    let mut burn = Collapse::new(&complex, reach.to_vec(), length, cross);
    loop {
        burn.run();
        if burn.faces_left == 0 {
            break;
        }
        burn.puncture();
    }
    burn.finish()
}

impl<'c, 'm, L: Fn(u32) -> f64, C: Fn(u32, u32) -> f64> Collapse<'c, 'm, L, C> {
    fn new(complex: &'c Complex<'m>, reach: Vec<f64>, length: L, cross: C) -> Self {
        let (nv, ne, nf) = (
            complex.vertex_count,
            complex.edge_vertices.len(),
            complex.face_count(),
        );
        let edge_faces: Vec<u32> = (0..ne as u32)
            .map(|e| complex.edge_faces(e).len() as u32)
            .collect();
        let mut vertex_faces = vec![0u32; nv];
        if let Some(mesh) = complex.mesh {
            for t in mesh.triangles() {
                for &v in t {
                    vertex_faces[v as usize] += 1;
                }
            }
        }
        let vertex_edges: Vec<u32> = (0..nv as u32)
            .map(|v| complex.vertex_edges.row(v).len() as u32)
            .collect();
        let used: Vec<bool> = (0..nv)
            .map(|v| vertex_faces[v] > 0 || vertex_edges[v] > 0)
            .collect();
        let mut burn = Collapse {
            complex,
            reach,
            cross,
            length,
            face_alive: vec![true; nf],
            faces_left: nf,
            edge_alive: vec![true; ne],
            significance: used
                .iter()
                .map(|&u| if u { f64::INFINITY } else { f64::NAN })
                .collect(),
            vertex_alive: used,
            curve: edge_faces.iter().map(|&n| n == 0).collect(),
            edge_faces,
            vertex_faces,
            vertex_edges,
            tip_queued: vec![false; nv],
            children: vec![0.0; nv],
            parent: vec![NONE; nv],
            burnt: Vec::new(),
            birth: vec![f64::NAN; nv],
            queue: BinaryHeap::new(),
            now: f64::NEG_INFINITY,
            punctured: 0,
            opened: 0,
        };
        for e in 0..ne as u32 {
            if burn.edge_faces[e as usize] == 1 {
                let f = burn.alive_face_of(e);
                burn.push_face(f, f64::NEG_INFINITY);
            }
        }
        // Line elements burn from their free ends at time 0.
        for v in 0..nv as u32 {
            burn.check_tip(v, 0.0);
        }
        burn
    }

    /// When face `f` is reached: at the reach of its last vertex.
    fn face_time(&self, f: u32) -> f64 {
        let mesh = self.complex.mesh.expect("faces come from a mesh");
        mesh.face_vertices(f)
            .iter()
            .map(|&v| self.reach[v as usize])
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Queues face `f`, which the fire may enter at `not_before`.
    fn push_face(&mut self, f: u32, not_before: f64) {
        let time = self.face_time(f).max(not_before);
        self.queue.push(Reverse((Ordered(time), Event::Face(f))));
    }

    fn alive_face_of(&self, e: u32) -> u32 {
        *self
            .complex
            .edge_faces(e)
            .iter()
            .find(|&&f| self.face_alive[f as usize])
            .expect("an edge with a face left")
    }

    fn alive_edge_of(&self, v: u32) -> u32 {
        *self
            .complex
            .vertex_edges
            .row(v)
            .iter()
            .find(|&&e| self.edge_alive[e as usize])
            .expect("a vertex with an edge left")
    }

    /// If `v` has become a tip (one edge, no face), it burns along its edge from `now`.
    fn check_tip(&mut self, v: u32, now: f64) {
        let i = v as usize;
        if !self.vertex_alive[i]
            || self.tip_queued[i]
            || self.vertex_faces[i] != 0
            || self.vertex_edges[i] != 1
        {
            return;
        }
        self.tip_queued[i] = true;
        let birth = match self.birth[i] {
            b if b.is_nan() && self.reach[i].is_finite() => self.reach[i],
            b if b.is_nan() => now,
            b => b,
        };
        let reached = now.max(birth);
        self.significance[i] = (reached - birth).max(self.children[i]);
        let e = self.alive_edge_of(v);
        let arrival = reached + (self.length)(e);
        self.queue.push(Reverse((Ordered(arrival), Event::Tip(v))));
    }

    /// Collapses in time order until nothing is free.
    fn run(&mut self) {
        while let Some(Reverse((Ordered(time), event))) = self.queue.pop() {
            self.now = self.now.max(time);
            match event {
                Event::Face(f) => self.collapse_face(f, time),
                Event::Tip(v) => self.burn_tip(v, time),
            }
        }
    }

    fn collapse_face(&mut self, f: u32, time: f64) {
        if !self.face_alive[f as usize] {
            return;
        }
        let mesh = self.complex.mesh.expect("faces come from a mesh");
        // The free edge the fire came through: the one reached first on average. (Not
        // the later of its ends: where a ridge runs along an edge, that edge ties with
        // the side the fire came from, and taking it would leave no curve on the ridge.)
        let edge_time = |e: u32| {
            let [a, b] = mesh.edge_vertices(e);
            self.reach[a as usize] + self.reach[b as usize]
        };
        let free = mesh
            .face_edges(f)
            .into_iter()
            .filter(|&e| self.edge_faces[e as usize] == 1)
            .min_by(|&a, &b| edge_time(a).total_cmp(&edge_time(b)).then(a.cmp(&b)));
        let Some(free) = free else {
            // Not free yet; it is queued again when one of its edges becomes free.
            return;
        };
        self.remove_edge(free);
        self.remove_face(f, time);
        for v in mesh.face_vertices(f) {
            self.check_tip(v, time);
        }
    }

    /// Removes face `f` (not its edges); edges left with one face free that face, edges
    /// left with none become curves (unless already removed with it).
    fn remove_face(&mut self, f: u32, time: f64) {
        let mesh = self.complex.mesh.expect("faces come from a mesh");
        self.face_alive[f as usize] = false;
        self.faces_left -= 1;
        for v in mesh.face_vertices(f) {
            self.vertex_faces[v as usize] -= 1;
            if self.vertex_faces[v as usize] == 0 {
                self.birth[v as usize] = time.max(self.reach[v as usize]);
            }
        }
        for e in mesh.face_edges(f) {
            let left = &mut self.edge_faces[e as usize];
            *left -= 1;
            match *left {
                0 if self.edge_alive[e as usize] => self.curve[e as usize] = true,
                1 => {
                    let g = self.alive_face_of(e);
                    let crossed = time + (self.cross)(g, e);
                    self.push_face(g, crossed);
                }
                _ => {}
            }
        }
    }

    fn remove_edge(&mut self, e: u32) {
        self.edge_alive[e as usize] = false;
        for v in self.complex.edge_vertices[e as usize] {
            self.vertex_edges[v as usize] -= 1;
        }
    }

    fn burn_tip(&mut self, v: u32, time: f64) {
        let i = v as usize;
        // Both ends of a lone edge may be tips; the first to burn takes the edge.
        if !self.vertex_alive[i] || self.vertex_edges[i] != 1 {
            return;
        }
        let e = self.alive_edge_of(v);
        let [a, b] = self.complex.edge_vertices[e as usize];
        let other = if a == v { b } else { a };
        self.vertex_alive[i] = false;
        self.remove_edge(e);
        let o = other as usize;
        self.children[o] = self.children[o].max(self.significance[i]);
        self.parent[i] = other;
        self.burnt.push(v);
        self.check_tip(other, time);
    }

    /// Removes one face without a free edge: a face on a 2-cycle if any (the last to
    /// burn among them), else the last face to burn.
    fn puncture(&mut self) {
        let mesh = self.complex.mesh.expect("faces come from a mesh");
        let sheets = CycleSheets::new(mesh, |f| self.face_alive[f as usize]);
        let last = |on_cycle: bool| {
            (0..mesh.face_count() as u32)
                .filter(|&f| self.face_alive[f as usize])
                .filter(|&f| !on_cycle || sheets.closes_cycle[sheets.sheet_of[f as usize] as usize])
                .max_by(|&a, &b| {
                    self.face_time(a)
                        .total_cmp(&self.face_time(b))
                        .then(b.cmp(&a))
                })
        };
        let (face, on_cycle) = match last(true) {
            Some(f) => (f, true),
            None => (last(false).expect("a face is left"), false),
        };
        // A part no fire reached (a closed sheet on its own) starts burning now.
        let time = match self.face_time(face) {
            t if t.is_finite() => t.max(self.now),
            _ => self.now.max(0.0),
        };
        self.rekindle(face, time);
        self.remove_face(face, time);
        for v in mesh.face_vertices(face) {
            self.check_tip(v, time);
        }
        self.punctured += 1;
        if !on_cycle {
            self.opened += 1;
        }
    }

    /// The fire restarts at punctured face `face` at `time`: the vertices of the faces
    /// left burn at `time` plus their distance from it along the edges of those faces.
    fn rekindle(&mut self, face: u32, time: f64) {
        let mesh = self.complex.mesh.expect("faces come from a mesh");
        let mut reached = vec![f64::INFINITY; self.complex.vertex_count];
        let mut heap = BinaryHeap::new();
        for v in mesh.face_vertices(face) {
            reached[v as usize] = time;
            heap.push(Reverse((Ordered(time), v)));
        }
        while let Some(Reverse((Ordered(t), v))) = heap.pop() {
            if t > reached[v as usize] {
                continue;
            }
            self.reach[v as usize] = t;
            for &e in self.complex.vertex_edges.row(v) {
                if self.edge_faces[e as usize] == 0 {
                    continue;
                }
                let [a, b] = self.complex.edge_vertices[e as usize];
                let u = if a == v { b } else { a };
                let next = t + (self.length)(e);
                if next < reached[u as usize] {
                    reached[u as usize] = next;
                    heap.push(Reverse((Ordered(next), u)));
                }
            }
        }
    }

    /// Gives each burnt vertex its branch's significance. Where branches burnt into one
    /// vertex, the most significant one carries on through it and the others end there
    /// (the elder rule of persistence), so a branch is the chain from a tip to where it
    /// ended, and its significance is the largest along it: the one at its end.
    fn finish(mut self) -> Thinning {
        for (v, alive) in self.vertex_alive.iter().enumerate() {
            if *alive {
                self.significance[v] = f64::INFINITY;
            }
        }
        let own = self.significance.clone();
        let mut ends = vec![NONE; own.len()];
        let mut elder = vec![NONE; own.len()];
        for &v in &self.burnt {
            let p = self.parent[v as usize] as usize;
            let e = elder[p];
            if e == NONE || own[v as usize] > own[e as usize] {
                elder[p] = v;
            }
        }
        for &v in self.burnt.iter().rev() {
            let p = self.parent[v as usize] as usize;
            // What never burnt ends every branch that burnt into it.
            if elder[p] == v && !self.vertex_alive[p] {
                self.significance[v as usize] = self.significance[p];
                ends[v as usize] = ends[p];
            } else {
                ends[v as usize] = p as u32;
            }
        }
        let curves = self
            .curve
            .iter()
            .enumerate()
            .filter(|(_, &c)| c)
            .map(|(e, _)| self.complex.edge_vertices[e])
            .collect();
        Thinning {
            significance: self.significance,
            ends,
            curves,
            punctured: self.punctured,
            opened: self.opened,
        }
    }
}

/// An f64 with a total order, for sorting and heaps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Ordered(pub(super) f64);

impl Eq for Ordered {}

impl PartialOrd for Ordered {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Ordered {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}
