//! [`Query`]: the questions to a distance field that need its mesh and metric.

use super::face_field::FaceField;
use super::ValueSource;
use crate::field::FieldView;
use crate::mesh::Topology;
use crate::mesh::NONE;
use crate::surface::SurfacePoint;
use crate::{Error, PointRole};
use geotracks_metrics::Metric;
use std::fmt;

/// A finished run's state together with the mesh and metric it was computed with,
/// borrowed: what the queries of a [`Field`](crate::Field) (and the joins of a route
/// searched from both ends) run on. Cheap to make and copy.
pub(crate) struct Query<'a, M, T> {
    pub(super) mesh: &'a T,
    pub(super) metric: &'a M,
    pub(super) field: FieldView<'a>,
    /// How far two copies of one wave's source may lie apart and be one, as the engine
    /// allowed (`Setup::wave_turn`).
    pub(super) turn: f64,
}

impl<M, T> Clone for Query<'_, M, T> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<M, T> Copy for Query<'_, M, T> {}

impl<M, T> fmt::Debug for Query<'_, M, T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Query")
            .field("vertices", &self.field.layout.vertex_count())
            .field("nodes", &self.field.distance.len())
            .field("sources", &self.field.sources.len())
            .finish_non_exhaustive()
    }
}

/// The candidates of the last few faces queried (see [`Field::origin_cached`](crate::Field::origin_cached)).
#[derive(Default)]
pub(super) struct FaceFields {
    fields: Vec<FaceField>,
    /// Faces' own candidates, which their neighbours' fields unfold.
    own: Vec<FaceField>,
}

impl FaceFields {
    /// A worker's recent faces and their neighbours (measured on bunny_loop1: 16 or
    /// 96 are slower).
    const CAPACITY: usize = 48;

    /// Face `f`'s candidates, built if not cached (dropping the oldest when full).
    pub(super) fn get<M: Metric, T: Topology>(
        &mut self,
        query: &Query<'_, M, T>,
        f: u32,
    ) -> &FaceField {
        match self.fields.iter().position(|c| c.face == f) {
            Some(i) => &self.fields[i],
            None => {
                if self.fields.len() == Self::CAPACITY {
                    self.fields.remove(0);
                }
                let field = query.face_field_using(f, &mut self.own);
                self.fields.push(field);
                self.fields.last().expect("just pushed")
            }
        }
    }
}

/// Where the value at a surface point comes from: a node of one of its faces, or a
/// source that shares a face with it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Origin {
    /// The point is this node.
    Node(u32),
    /// A straight segment in `face` from this node.
    NodeInFace(u32, u32),
    /// A straight segment in `face` from this source.
    SourceInFace(u32, u32),
    /// A straight line in `face` from this node's wave (wavefront engine).
    WaveInFace(u32, u32),
    /// A straight line in `face` from this window's source (exact engine).
    WindowInFace(u32, u32),
    /// A straight line in `face` to the point `t` of `edge`, and on from there as
    /// `source` gives it in face `then` across the edge.
    Across {
        edge: u32,
        t: f64,
        face: u32,
        source: ValueSource,
        then: u32,
    },
}

impl Origin {
    /// Where a face's own candidate `source` gives the value in face `f`.
    pub(super) fn from_source(source: ValueSource, f: u32) -> Origin {
        match source {
            ValueSource::Node(n) => Origin::NodeInFace(n, f),
            ValueSource::Source(s) => Origin::SourceInFace(s, f),
            ValueSource::Wave(q) | ValueSource::WaveBend(q) => Origin::WaveInFace(q, f),
            ValueSource::Window(id) => Origin::WindowInFace(id, f),
        }
    }
}

impl<'a, M: Metric, T: Topology> Query<'a, M, T> {
    /// A query on `field`, which was computed on `mesh` under `metric` (the solver
    /// checks that) by an engine that took copies of one source `turn` apart
    /// (relative) for one.
    pub(crate) fn new(mesh: &'a T, metric: &'a M, field: FieldView<'a>, turn: f64) -> Self {
        Query {
            mesh,
            metric,
            field,
            turn,
        }
    }

    /// The mesh the field was computed on.
    pub fn mesh(&self) -> &'a T {
        self.mesh
    }

    /// The largest finite distance over the nodes (vertices and Steiner points): the
    /// top of the field's range, to spread isoline levels over
    /// ([`spread_levels`](crate::trace::spread_levels)); 0 when nothing is reached.
    pub fn max_reached_distance(&self) -> f64 {
        self.field
            .distance
            .iter()
            .copied()
            .filter(|d| d.is_finite())
            .fold(0.0, f64::max)
    }

    /// The distance at any surface point, as the engine defines it: at a vertex, its
    /// value; elsewhere, the least over the *candidates* of the faces holding the point
    /// ([`ValueSource`](crate::trace::ValueSource)): each node on a face's boundary,
    /// its value plus the metric's cost of the straight segment to the point; each
    /// source sharing the face, its start plus its segment; for a field of the
    /// wavefront engine also each node's wave that crosses into the face, `σ` plus the
    /// straight line from its source where it passes the node's window (or bends at the
    /// window's end), and the candidates of the faces across the face's edges, unfolded
    /// onto it, whose lines cross the shared edge (so that the field is continuous
    /// across edges but where a neighbour's neighbour gives less, by the engine's
    /// error). Each candidate is a real path's length. Not an interpolation of vertex
    /// values. `inf` when no source reaches the point, or when its value would exceed
    /// the run's [`Stop::max_distance`](crate::Stop::max_distance).
    ///
    /// # Complexity
    /// O(k) metric evaluations per face around the point (for the wavefront engine,
    /// and its neighbours).
    ///
    /// # Errors
    /// [`Error::InvalidPoint`] if `point` is not a point of the mesh.
    pub fn distance_at(&self, point: SurfacePoint) -> Result<f64, Error> {
        Ok(self.origin(point)?.0)
    }

    /// The value at `point` and where it comes from (`None` when unreached).
    pub(super) fn origin(&self, point: SurfacePoint) -> Result<(f64, Option<Origin>), Error> {
        self.origin_cached(point, &mut FaceFields::default())
    }

    /// As [`Field::origin`](crate::Field::origin), reading the faces' candidates from `cache` (and adding
    /// those it lacks): for many queries in a few faces, each face's are built once.
    pub(super) fn origin_cached(
        &self,
        point: SurfacePoint,
        cache: &mut FaceFields,
    ) -> Result<(f64, Option<Origin>), Error> {
        let (mesh, metric, field) = (self.mesh, self.metric, &self.field);
        let point = point.validated(mesh).map_err(|error| Error::InvalidPoint {
            which: PointRole::Query,
            error,
        })?;
        // A vertex is its own node: its value is the run's (a neighbour's line may pass
        // it a little shorter; the field is continuous elsewhere).
        if let SurfacePoint::Vertex(v) = point {
            let d = field.distance[v as usize];
            return Ok((d, d.is_finite().then_some(Origin::Node(v))));
        }
        let mut best = (f64::INFINITY, None);
        // The least value a node the stop left unreached could give the point (through
        // its wave, which may reach the point with less than the node's value).
        let mut unsettled = f64::INFINITY;
        for &f in point.faces(mesh).iter() {
            let x = point.in_face(mesh, f).expect("the point lies on its faces");
            let face = cache.get(self, f);
            if field.horizon.is_bounded() {
                let horizon = field.horizon.in_face(mesh, f);
                unsettled = unsettled.min(face.unsettled(metric, horizon, &x));
            }
            if let Some((d, c)) = face.best(metric, &x, |_| false) {
                if d < best.0 {
                    let candidate = &face.candidates[c];
                    let origin = match candidate.across {
                        None => Origin::from_source(candidate.source, f),
                        Some((edge, g)) => Origin::Across {
                            edge,
                            t: face.crossing(candidate, &x).expect("an unfolded candidate"),
                            face: f,
                            source: candidate.source,
                            then: g,
                        },
                    };
                    best = (d, Some(origin));
                }
            }
        }
        // A point beyond the stop's maximum is unreached, as a node there is: the
        // nodes around it may lie within the maximum while the point does not. So is a
        // point that a node the stop left unreached might give less: a finite value
        // after an early stop is always the value a full run gives.
        if best.0 > field.horizon.max_distance || best.0 > unsettled {
            best = (f64::INFINITY, None);
        }
        Ok(best)
    }

    /// The index of the nearest source of every vertex (the geodesic Voronoi diagram of
    /// the sources, start values included), [`NONE`] where unreached.
    ///
    /// # Complexity
    /// O(nodes): parents are followed to the source that started each chain, and every
    /// node is labelled once.
    pub fn vertex_labels(&self) -> Vec<u32> {
        let vertices = self.field.layout.vertex_count();
        let mut label = self.labels(vertices);
        label.truncate(vertices as usize);
        label
    }

    /// As [`Field::vertex_labels`](crate::Field::vertex_labels), for every node (vertices, then Steiner points in
    /// [`SteinerLayout`] order).
    pub fn node_labels(&self) -> Vec<u32> {
        self.labels(self.field.distance.len() as u32)
    }

    /// Labels of nodes `0..count` (and of the nodes their chains pass through).
    fn labels(&self, count: u32) -> Vec<u32> {
        if self.has_windows() {
            // (Vertices only: the exact engine has no Steiner points.)
            return self.window_labels();
        }
        let field = &self.field;
        let n = field.distance.len();
        let mut label = vec![NONE; n];
        let mut known = vec![false; n];
        let mut chain = Vec::new();
        for start in 0..count {
            let mut node = start;
            // Walk up to a labelled node or a root; parents have lower values, so the
            // walk ends (a step cap guards against a metric with zero costs).
            let found = loop {
                if known[node as usize] {
                    break label[node as usize];
                }
                if field.distance[node as usize].is_infinite() {
                    break NONE;
                }
                chain.push(node);
                let p = field.parent[node as usize];
                if p == NONE {
                    break field.root_source(node).unwrap_or(NONE);
                }
                if chain.len() > n {
                    break NONE;
                }
                node = p;
            };
            for &c in &chain {
                label[c as usize] = found;
                known[c as usize] = true;
            }
            chain.clear();
        }
        label
    }
}
