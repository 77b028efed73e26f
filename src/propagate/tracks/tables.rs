//! The tracks engine's read-only tables, built once per (mesh, layout) by a `Solver`:
//! one 64-byte record per face and one 16-byte record per edge, laid out so that
//! settling a node reads one edge record and, per face it enters, one face record.
//!
//! Records are stored in a spatial order, not in the mesh's: edges in the layout's
//! block order (a Morton curve), faces along a Morton curve through their centroids,
//! with each face's instances in the same order. A wavefront then touches memory that
//! is close together whatever order the input file had. Incidences name faces by their
//! record index; the record holds the mesh's face id for the metric and the results.

use crate::mesh::Topology;
use crate::mesh::{Csr, FaceFrame, NONE};
use crate::steiner::{SlotPoints, SteinerLayout};
use crate::Error;
use geotracks_metrics::FacePoint;
use rayon::prelude::*;

/// Everything the engine reads about one face.
///
/// Its boundary is a cycle of positions: corner 0, the points of slot 0 (the edge from
/// corner 0 to corner 1), corner 1, slot 1, corner 2, slot 2. The face's instances (see
/// the module docs) are stored at `base + position`.
#[derive(Clone, Copy, Debug)]
pub(in crate::propagate) struct FaceRecord {
    /// The face's local frame.
    pub frame: FaceFrame,
    /// Node id of the first point (from the edge's lower vertex) of each slot's edge.
    pub lo: [u32; 3],
    pub vertex: [u32; 3],
    /// Offset of the face's instances in the per-instance arrays.
    pub base: u32,
    /// The face's id in the mesh.
    pub face: u32,
    /// Points on each slot.
    pub count: [u16; 3],
    /// Bit `s`: slot `s` runs from its edge's higher vertex (points in reverse order).
    pub reversed: u8,
}

// The record is meant to fill one cache line.
const _: () = assert!(std::mem::size_of::<FaceRecord>() <= 64);

impl FaceRecord {
    /// Points on slot `s`.
    #[inline]
    pub fn count(&self, s: usize) -> u32 {
        self.count[s] as u32
    }

    /// Position of corner `c` on the boundary cycle.
    #[inline]
    pub fn corner(&self, c: usize) -> u32 {
        // A table rather than a match: which corner is asked for is data, and a
        // mispredicted branch costs more than the two additions.
        let after_0 = self.count(0) + 1;
        [0, after_0, after_0 + self.count(1) + 1][c]
    }

    /// Number of positions on the boundary cycle.
    #[inline]
    pub fn cycle_len(&self) -> u32 {
        self.count(0) + self.count(1) + self.count(2) + 3
    }

    #[inline]
    pub fn is_reversed(&self, s: usize) -> bool {
        self.reversed & (1 << s) != 0
    }

    /// Position of point `index` (numbered from the edge's lower vertex) of slot `s`.
    #[inline]
    pub fn slot_position(&self, s: usize, index: u32) -> u32 {
        self.corner(s) + 1 + self.slot(s).slot_index(index)
    }

    /// The point numbered `i` along the edge of slot `s`, counted from the edge's lower
    /// vertex: 0 and `count + 1` are the edge's vertices, the Steiner points between.
    #[inline]
    pub fn edge_point(&self, s: usize, i: u32) -> FacePoint {
        self.point_of(&self.slot(s), s, i)
    }

    /// Points `a` and `b` along the edge of slot `s`, numbered as in
    /// [`edge_point`](Self::edge_point): the slot's line and spacing found once for both
    /// (an edge step asks for two points in each face of its edge).
    #[inline]
    pub fn edge_points(&self, s: usize, a: u32, b: u32) -> (FacePoint, FacePoint) {
        let slot = self.slot(s);
        (self.point_of(&slot, s, a), self.point_of(&slot, s, b))
    }

    /// [`edge_point`](Self::edge_point) with the slot's points at hand.
    #[inline(always)]
    fn point_of(&self, slot: &SlotPoints, s: usize, i: u32) -> FacePoint {
        // Numbered from corner `s` instead: the ends are corners `s` and `s + 1`.
        let j = if self.is_reversed(s) {
            slot.count + 1 - i
        } else {
            i
        };
        if j == 0 {
            self.corner_point(s)
        } else if j == slot.count + 1 {
            self.corner_point((s + 1) % 3)
        } else {
            slot.at(j - 1).1
        }
    }

    /// The points of slot `s`, in slot order (from corner `s`).
    #[inline]
    pub fn slot(&self, s: usize) -> SlotPoints {
        SlotPoints::new(
            self.frame.edge_line(s),
            self.lo[s],
            self.count(s),
            self.is_reversed(s),
        )
    }

    /// Corner `c` as a face point.
    #[inline]
    pub fn corner_point(&self, c: usize) -> FacePoint {
        self.frame.corner(c)
    }
}

/// A face seen from one of its edges or corners: the face's record index and which slot
/// (or corner) of it the edge (or vertex) is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(in crate::propagate) struct Incidence(u32);

impl Incidence {
    const NONE: Incidence = Incidence(NONE);

    pub(in crate::propagate) fn new(record: u32, side: usize) -> Incidence {
        Incidence(record << 2 | side as u32)
    }

    #[inline]
    pub fn record(self) -> u32 {
        self.0 >> 2
    }

    /// The slot (for an edge) or corner (for a vertex).
    #[inline]
    pub fn side(self) -> usize {
        (self.0 & 3) as usize
    }
}

/// What the engine reads about one edge besides its nodes (which the layout's block
/// gives) and its vertices (which only its end points need, from the mesh).
#[derive(Clone, Copy, Debug)]
pub(in crate::propagate) struct EdgeRecord {
    /// Cost between consecutive nodes in the cheapest face, when the metric is a norm on
    /// each face (NaN otherwise: steps are then measured one by one).
    pub step: f64,
    /// The faces around it when there are at most two (`Incidence::NONE` fills the
    /// rest); otherwise `[NONE, i]`, and the faces are row `i` of `overflow`.
    faces: [Incidence; 2],
}

const _: () = assert!(std::mem::size_of::<EdgeRecord>() == 16);

/// The engine's tables for one mesh and Steiner layout, shared by all runs of a solver.
pub(in crate::propagate) struct TrackTables {
    /// Face records in spatial order.
    pub(in crate::propagate) faces: Vec<FaceRecord>,
    /// Edge records in the layout's block order.
    pub(in crate::propagate) edges: Vec<EdgeRecord>,
    /// Faces around edges with more than two (non-manifold edges), a row each.
    overflow: Csr<Incidence>,
    /// The record of each face (by mesh face id); the faces and edges around a vertex
    /// come from the mesh through it and the layout's blocks.
    record_of: Vec<u32>,
    pub(in crate::propagate) instances: usize,
    /// For the wavefront engine (see [`TrackTables::with_vertex_rows`]): per vertex,
    /// the blocks of its edges (`block << 1 | 1` where it is the edge's higher end) and
    /// its corners (record and corner), and per block the edge's two vertices. They
    /// save the chains of lookups (edge → block → nodes, face → record) that settling a
    /// vertex otherwise makes, each a likely cache miss on a large mesh.
    pub(in crate::propagate) spokes: Csr<u32>,
    pub(in crate::propagate) corners: Csr<Incidence>,
    pub(in crate::propagate) ends: Vec<[u32; 2]>,
}

impl TrackTables {
    /// Builds the tables; `steps` are the cached steps per edge (`None` when the metric
    /// is not a norm on each face); `flat_frames`, the faces' frames in the metric's
    /// flattening, replace the mesh's frames (the wavefront engine measures in them).
    ///
    /// # Errors
    /// [`Error::TooLarge`] when instances or faces exceed what the records can index, or
    /// an edge carries more than 65535 points.
    pub(in crate::propagate) fn new<T: Topology>(
        mesh: &T,
        layout: &SteinerLayout,
        steps: Option<&[f64]>,
        flat_frames: Option<&[FaceFrame]>,
    ) -> Result<TrackTables, Error> {
        if mesh.face_count() >= 1 << 30 {
            return Err(Error::TooLarge {
                what: "faces for the tracks engine",
                count: mesh.face_count() as u64,
            });
        }
        let face_order = crate::mesh::spatial_face_order(mesh);
        let mut record_of = vec![0u32; mesh.face_count()];
        for (r, &f) in face_order.iter().enumerate() {
            record_of[f as usize] = r as u32;
        }

        if let Some(c) = (0..mesh.edge_count() as u32)
            .map(|e| layout.count(e))
            .find(|&c| c > u16::MAX as u32)
        {
            return Err(Error::TooLarge {
                what: "Steiner points on one edge",
                count: c as u64,
            });
        }
        // Record `r` is face `face_order[r]`: made in record order, on all cores.
        let record = |f: u32| {
            let edges = mesh.face_edges(f);
            let mut reversed = 0u8;
            for s in 0..3 {
                if mesh.slot_is_reversed(f, s) {
                    reversed |= 1 << s;
                }
            }
            FaceRecord {
                frame: flat_frames.map_or(mesh.frame(f), |frames| frames[f as usize]),
                lo: edges.map(|e| layout.edge_nodes(e).start),
                vertex: mesh.face_vertices(f),
                base: 0,
                face: f,
                // (At most 65535: checked above.)
                count: edges.map(|e| layout.count(e) as u16),
                reversed,
            }
        };
        let mut faces: Vec<FaceRecord> = face_order.par_iter().map(|&f| record(f)).collect();
        let mut total: u64 = 0;
        for r in &mut faces {
            r.base = total as u32;
            total += r.cycle_len() as u64;
            if total >= u32::MAX as u64 {
                return Err(Error::TooLarge {
                    what: "face-node instances",
                    count: total,
                });
            }
        }

        let mut edges = vec![
            EdgeRecord {
                step: f64::NAN,
                faces: [Incidence::NONE; 2],
            };
            mesh.edge_count()
        ];
        let mut overflow = Vec::new();
        for e in 0..mesh.edge_count() as u32 {
            let step = steps.map_or(f64::NAN, |steps| steps[e as usize]);
            let around_ids = mesh.edge_faces(e);
            let around = around_ids.iter().map(|&f| {
                let slot = mesh.edge_slot(f, e).expect("edge of its face");
                Incidence::new(record_of[f as usize], slot)
            });
            let mut faces = [Incidence::NONE; 2];
            if mesh.edge_faces(e).len() <= 2 {
                for (slot, inc) in faces.iter_mut().zip(around) {
                    *slot = inc;
                }
            } else {
                let row = overflow.last().map_or(0, |&(row, _)| row + 1);
                overflow.extend(around.map(|inc| (row, inc)));
                faces[1] = Incidence(row);
            }
            edges[layout.block_of_edge(e) as usize] = EdgeRecord { step, faces };
        }

        let rows = overflow.last().map_or(0, |&(row, _)| row as usize + 1);
        Ok(TrackTables {
            faces,
            edges,
            overflow: Csr::from_pairs(rows, overflow.into_iter()),
            record_of,
            instances: total as usize,
            spokes: Csr::from_pairs(0, std::iter::empty()),
            corners: Csr::from_pairs(0, std::iter::empty()),
            ends: Vec::new(),
        })
    }

    /// Adds the per-vertex rows and per-block ends the wavefront engine reads.
    pub(in crate::propagate) fn with_vertex_rows<T: Topology>(
        mut self,
        mesh: &T,
        layout: &SteinerLayout,
    ) -> TrackTables {
        let vertices = mesh.vertex_count();
        let edge_pairs = (0..mesh.edge_count() as u32).flat_map(|e| {
            let b = layout.block_of_edge(e);
            let [lo, hi] = mesh.edge_vertices(e);
            [(lo, b << 1), (hi, b << 1 | 1)]
        });
        self.spokes = Csr::from_pairs(vertices, edge_pairs);
        let record_of = &self.record_of;
        let corner_pairs = (0..mesh.face_count() as u32).flat_map(move |f| {
            let r = record_of[f as usize];
            let t = mesh.face_vertices(f);
            (0..3).map(move |c| (t[c], Incidence::new(r, c)))
        });
        self.corners = Csr::from_pairs(vertices, corner_pairs);
        let mut ends = vec![[0u32; 2]; mesh.edge_count()];
        for e in 0..mesh.edge_count() as u32 {
            ends[layout.block_of_edge(e) as usize] = mesh.edge_vertices(e);
        }
        self.ends = ends;
        self
    }

    /// The instance of `node` in face `face`, whose closure must hold the node.
    pub(in crate::propagate) fn instance(&self, face: u32, node: u32) -> u32 {
        let r = &self.faces[self.record_of(face) as usize];
        let position = match (0..3).find(|&c| r.vertex[c] == node) {
            Some(c) => r.corner(c),
            None => {
                let s = (0..3)
                    .find(|&s| node.wrapping_sub(r.lo[s]) < r.count(s))
                    .expect("the node lies on the face");
                r.slot_position(s, node - r.lo[s])
            }
        };
        debug_assert_eq!(r.face, face);
        r.base + position
    }

    /// The faces around an edge.
    #[inline]
    pub(in crate::propagate) fn edge_faces<'t>(&'t self, edge: &'t EdgeRecord) -> &'t [Incidence] {
        if edge.faces[0] != Incidence::NONE {
            let n = if edge.faces[1] == Incidence::NONE {
                1
            } else {
                2
            };
            &edge.faces[..n]
        } else {
            self.overflow.row(edge.faces[1].0)
        }
    }

    /// The record of mesh face `f`.
    #[inline]
    pub(in crate::propagate) fn record_of(&self, f: u32) -> u32 {
        self.record_of[f as usize]
    }
}
