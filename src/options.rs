//! How a run goes: which engine ([`Method`]) on which Steiner points ([`Options`], fixed
//! when a [`Solver`](crate::Solver) is built), and when a run may stop early ([`Stop`],
//! given per run).
//!
//! Plain data, apart from the engine: the field records the [`Method`] that made it, and
//! the command line parses these by name.

use crate::steiner::SteinerScheme;
use crate::surface::{Source, SurfacePoint};
use std::borrow::Cow;
use std::fmt;
use std::str::FromStr;

/// Which propagation runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// Steiner nodes that carry their wavefront (a virtual source and a window): exact
    /// on planar and developable meshes, far more accurate than the Steiner graph
    /// elsewhere. Needs a face-flat metric ([`Metric::face_gram`]); with any other
    /// metric the tracks engine runs instead (and the stats say so).
    ///
    /// [`Metric::face_gram`]: geotracks_metrics::Metric::face_gram
    Wave,
    /// Track-pruned Steiner-point propagation (the geodesic tracks method).
    Tracks,
    /// The complete Steiner graph per face (naive; the oracle).
    Graph,
    /// Dijkstra on mesh edges (no Steiner points).
    Dijkstra,
    /// Exact geodesics: windows of straight lines carried face to face, as many per
    /// edge as the geodesics need (no Steiner points). Exact to rounding for a metric
    /// that is a constant norm on each face and whose faces glue (every edge has one
    /// length in all its faces: `Euclidean`, a constant `Tensor`); any other metric
    /// is refused with [`Error::NotExact`](crate::Error::NotExact), never run
    /// approximately in its place.
    Exact,
}

impl Method {
    /// The name used on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Method::Wave => "wave",
            Method::Tracks => "tracks",
            Method::Graph => "graph",
            Method::Dijkstra => "dijkstra",
            Method::Exact => "exact",
        }
    }

    /// The mean number of Steiner points per edge this engine runs with when none is
    /// asked for ([`Options::steiner`] `None`): 2 for the wavefront engine, 5 for the
    /// Steiner-graph engines (`Tracks`, `Graph`), which need more points for the same
    /// accuracy; Dijkstra and the exact engine use none (2 is given). The solver asks the engine that
    /// actually runs: the tracks engine's 5 for a metric that is not flat on each face,
    /// where the wavefront engine gives way to it.
    ///
    /// ```
    /// use geotracks::{mesh::TriMesh, Density, Method, Options, Solver};
    /// assert_eq!(Method::Wave.default_k(), 2.0);
    /// assert_eq!(Method::Tracks.default_k(), 5.0);
    /// let mesh = TriMesh::new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2]],
    /// )?;
    /// // A density is not flat on each face: the tracks engine runs, at its own k.
    /// let density = Density::constant(&mesh, 2.0)?;
    /// let solver = Solver::new(mesh, density, &Options::DEFAULT)?;
    /// assert_eq!((solver.method(), solver.k()), (Method::Tracks, 5.0));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn default_k(self) -> f64 {
        match self {
            Method::Tracks | Method::Graph => 5.0,
            Method::Wave | Method::Dijkstra | Method::Exact => 2.0,
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Method {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "wave" => Ok(Method::Wave),
            "tracks" => Ok(Method::Tracks),
            "graph" => Ok(Method::Graph),
            "dijkstra" => Ok(Method::Dijkstra),
            "exact" => Ok(Method::Exact),
            other => Err(format!(
                "unknown method '{other}' (expected wave, tracks, graph, dijkstra or exact)"
            )),
        }
    }
}

/// How to propagate: where Steiner points go and which engine runs.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Options {
    /// Steiner points per edge. Default `None`: the engine that runs picks its own
    /// ([`Method::default_k`]): k = 2 for the wavefront engine (mean error
    /// 0.003–0.07 % on the shared real meshes; the guide's accuracy page), k = 5 for the
    /// Steiner-graph engines, which need more for the same accuracy (0.3–0.6 %), and
    /// run for a metric that is not flat on each face (`Density`, most custom metrics).
    pub steiner: Option<SteinerScheme>,
    /// The engine. Default: [`Method::Wave`] (which runs [`Method::Tracks`] for a
    /// metric that is not face-flat).
    pub method: Method,
    /// Bytes a solver and one run may take (mesh excluded), checked before anything is
    /// allocated: a k that would need more is refused with [`Error::KTooLarge`] and the
    /// largest k that fits. `None` (the default) uses the memory the system reports as
    /// available (Linux), or checks nothing where it reports none. A path searched
    /// from both ends ([`Stop::both_ends`]) needs a second run's buffers: it runs
    /// one-ended where they would not fit beside the first (under the limit, or in
    /// what the system reports available at the query).
    ///
    /// [`Error::KTooLarge`]: crate::Error::KTooLarge
    pub memory_limit: Option<u64>,
    /// The edge length the interval scheme's `k` is relative to: edges are cut every
    /// `mean_edge_length / k` (in the lengths the points are spaced by: 3D lengths, or
    /// the metric's for the wavefront engine). `None` (the default): the mean over the
    /// mesh's edges. Give the whole mesh's mean to run on a part of it (a window cut
    /// out of a larger surface) with the points the whole would have.
    pub mean_edge_length: Option<f64>,
    /// The most distance tests one full run may be estimated to make, checked before
    /// anything is allocated: a k that would need more is refused with
    /// [`Error::KTooLarge`] (naming the estimate and the limit) and the largest k that
    /// fits. The estimate grows with the square of the nodes on each face (the
    /// guide's Distances page has the figures). Default:
    /// [`DEFAULT_WORK_LIMIT`](Options::DEFAULT_WORK_LIMIT) (a few minutes of one
    /// core); `None`: no limit.
    ///
    /// [`Error::KTooLarge`]: crate::Error::KTooLarge
    pub work_limit: Option<u64>,
}

impl Options {
    /// The default [`work_limit`](Options::work_limit): 4·10⁹ estimated distance tests,
    /// a few minutes of one core (a test takes 50–100 ns). Every shared benchmark mesh
    /// fits at k = 20 with every engine (the largest, 1.1M faces, is estimated at
    /// 2.7·10⁹ with the complete graph, 1.1·10⁹ with the wavefront engine); a flat
    /// 18-face grid fits up to k ≈ 9,700 with the wavefront engine.
    pub const DEFAULT_WORK_LIMIT: u64 = 4_000_000_000;

    /// The defaults: the wavefront engine, with the Steiner points of the engine that
    /// runs ([`Method::default_k`]).
    pub const DEFAULT: Options = Options {
        steiner: None,
        method: Method::Wave,
        memory_limit: None,
        mean_edge_length: None,
        work_limit: Some(Options::DEFAULT_WORK_LIMIT),
    };

    /// Interval scheme with a mean of `k` points per edge.
    pub const fn with_k(mut self, k: f64) -> Self {
        self.steiner = Some(SteinerScheme::Interval { k });
        self
    }

    /// Exactly `count` points on every edge.
    pub const fn with_fixed_count(mut self, count: u32) -> Self {
        self.steiner = Some(SteinerScheme::Fixed { count });
        self
    }

    /// The Steiner scheme `scheme` (see [`Options::steiner`]).
    pub const fn with_scheme(mut self, scheme: SteinerScheme) -> Self {
        self.steiner = Some(scheme);
        self
    }

    /// The scheme a run with `method` uses: the one asked for, else the engine's own
    /// ([`Method::default_k`]).
    pub fn steiner_for(&self, method: Method) -> SteinerScheme {
        self.steiner.unwrap_or(SteinerScheme::Interval {
            k: method.default_k(),
        })
    }

    /// The memory budget in bytes (see [`Options::memory_limit`]).
    pub const fn with_memory_limit(mut self, bytes: u64) -> Self {
        self.memory_limit = Some(bytes);
        self
    }

    /// The work budget in estimated distance tests per run, `None` for none (see
    /// [`Options::work_limit`]).
    pub const fn with_work_limit(mut self, tests: Option<u64>) -> Self {
        self.work_limit = tests;
        self
    }

    /// The edge length `k` is relative to (see [`Options::mean_edge_length`]).
    pub const fn with_mean_edge_length(mut self, length: f64) -> Self {
        self.mean_edge_length = Some(length);
        self
    }

    /// The engine to run.
    pub const fn with_method(mut self, method: Method) -> Self {
        self.method = method;
        self
    }
}

/// When a run may stop before the whole mesh is reached.
///
/// Both conditions leave every node they do not settle unreached (`inf`): a finite value
/// after an early stop is always the value a full run gives, at a node and at any other
/// surface point ([`Field::distance_at`](crate::Field::distance_at)). A point beyond the
/// maximum is unreached, and so is one that a node the stop left unreached might have
/// given a smaller value. For the Steiner-graph engines (tracks, graph, Dijkstra) that
/// never happens within the maximum (a node gives a point its value plus a cost ≥ 0);
/// for the wavefront engine, whose waves give less than their nodes' values nearer
/// their sources, it can: a point within about an edge of the maximum, or of where a
/// stop at the targets left off, may be unreached.
///
/// ```
/// use geotracks::{Stop, SurfacePoint};
/// let stop = Stop::NONE
///     .with_max_distance(2.5)
///     .with_targets(vec![SurfacePoint::Vertex(7), "e:3:0.5".parse()?]);
/// assert_eq!(stop.targets.len(), 2);
/// # Ok::<(), geotracks::PointError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Stop {
    /// Nodes farther than this stay unreached (`inf`); the propagation ends when nothing
    /// closer is left. A goal-directed run (see [`goal_directed`](Self::goal_directed))
    /// also leaves unreached the nodes through which no target lies within it (their
    /// value plus the estimate exceeds it): targets farther than it are unreached, and
    /// finding that out costs the corridor, not the disc. Default: `inf`.
    pub max_distance: f64,
    /// Stop as soon as the value at each of these points is final (the distance at a
    /// point inside a face, or on an edge, depends on the nodes around it, so those are
    /// waited for). Default: none, run to the end.
    pub targets: Vec<SurfacePoint>,
    /// With targets, settle nodes in the order of their value plus a bound on what is
    /// left to the targets (A*): the metric's
    /// [`min_cost_per_length`](geotracks_metrics::Metric::min_cost_per_length) times
    /// the straight-line distance to the box around them. The targets' values are the
    /// same; what is settled before they are final shrinks from a disc to a corridor
    /// between sources and targets, the more so the closer the bound is to what paths
    /// cost. Nodes off the corridor stay unreached. Default: `true`; it has no effect
    /// without targets, for a metric that gives no bound, for targets spread over more
    /// than half the mesh (their box's diagonal against the mesh's: the estimate would
    /// be zero nearly everywhere, and computing it cost time for nothing; the guide's
    /// Paths page has the figures), and for the
    /// wavefront engine ([`Method::Wave`]), whose values depend on the order waves
    /// arrive in: settled out of value order, a node can replace the wave through
    /// which it gave others their values, and their paths can no longer be traced back
    /// exactly.
    pub goal_directed: bool,
    /// For a path between two points ([`Solver::shortest_path`] from one source):
    /// search from both ends at once, on two threads, and stop where the two searches
    /// meet. Each side settles about half of what a one-ended goal-directed run would,
    /// and the path is the same (the Steiner graph's cheapest; the sides work in lock
    /// step, so the result does not depend on how the threads ran). Under a directed
    /// metric the backward side runs the reversed metric ([`crate::Reversed`]) on a
    /// solver built for the query (its setup is the price). Default: `true`; it takes
    /// effect for the Steiner-graph engines (not [`Method::Wave`], which is not
    /// goal-directed), [`goal_directed`](Self::goal_directed) runs, when rayon's pool
    /// has two threads or more, and when a second run's buffers fit the memory budget
    /// ([`Options::memory_limit`]). Fields ([`Solver::field`]) come from their
    /// sources alone whatever this says. The backward side runs on a thread of its
    /// own: paths already run in parallel (one per core) are better one-ended.
    ///
    /// [`Solver::shortest_path`]: crate::Solver::shortest_path
    /// [`Solver::field`]: crate::Solver::field
    pub both_ends: bool,
}

impl Stop {
    /// No early stop.
    pub const NONE: Stop = Stop {
        max_distance: f64::INFINITY,
        targets: Vec::new(),
        goal_directed: true,
        both_ends: true,
    };

    /// Checks the stop's numbers for sources that start at 0 (the command line and the
    /// Python package call this same check): `max_distance` must be ≥ 0 and not NaN
    /// (`inf`: no limit). A negative one would leave every node unreached, the sources
    /// included. Runs check it against their sources' start values
    /// ([`Stop::check_from`]).
    ///
    /// ```
    /// use geotracks::Stop;
    /// assert!(Stop::NONE.with_max_distance(0.0).check().is_ok());
    /// let err = Stop::NONE.with_max_distance(-1.0).check().unwrap_err();
    /// assert_eq!(
    ///     err.to_string(),
    ///     "the maximum distance is -1; it must be a number >= 0, or >= the least start \
    ///      value of the sources (inf: no limit)"
    /// );
    /// assert!(Stop::NONE.with_max_distance(f64::NAN).check().is_err());
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidValue`](crate::Error::InvalidValue) naming
    /// [`ValueRole::MaxDistance`](crate::ValueRole::MaxDistance).
    pub fn check(&self) -> Result<(), crate::Error> {
        self.check_from(0.0)
    }

    /// As [`Stop::check`] for sources whose least start value is `lowest_start`
    /// ([`Source::with_start`](crate::Source::with_start)): `max_distance` must not be
    /// NaN nor below `lowest_start`, where it would leave every node unreached. Every
    /// run makes this check before it starts, with its sources' least start.
    ///
    /// ```
    /// use geotracks::Stop;
    /// // A source that starts at -2 is reached within a maximum of -1.
    /// assert!(Stop::NONE.with_max_distance(-1.0).check_from(-2.0).is_ok());
    /// assert!(Stop::NONE.with_max_distance(-3.0).check_from(-2.0).is_err());
    /// ```
    ///
    /// # Errors
    /// As [`Stop::check`].
    pub fn check_from(&self, lowest_start: f64) -> Result<(), crate::Error> {
        if self.max_distance.is_nan() || self.max_distance < lowest_start {
            return Err(crate::Error::InvalidValue {
                which: crate::ValueRole::MaxDistance,
                value: self.max_distance,
            });
        }
        Ok(())
    }

    /// Stop at distance `max_distance`.
    pub fn with_max_distance(self, max_distance: f64) -> Stop {
        Stop {
            max_distance,
            ..self
        }
    }

    /// Stop once `targets` are final.
    pub fn with_targets(self, targets: Vec<SurfacePoint>) -> Stop {
        Stop { targets, ..self }
    }

    /// For a path between two points, searched from both ends or not (see
    /// [`Stop::both_ends`]).
    pub fn with_both_ends(self, both_ends: bool) -> Stop {
        Stop { both_ends, ..self }
    }

    /// With targets, goal-directed or not (see [`Stop::goal_directed`]).
    pub fn with_goal_directed(self, goal_directed: bool) -> Stop {
        Stop {
            goal_directed,
            ..self
        }
    }
}

impl Default for Stop {
    fn default() -> Self {
        Stop::NONE
    }
}

impl Default for Options {
    fn default() -> Self {
        Options::DEFAULT
    }
}

/// Where a run starts, and when it may stop: what [`Solver::field`](crate::Solver::field),
/// [`Solver::run`](crate::Solver::run) and
/// [`Solver::shortest_path`](crate::Solver::shortest_path) take.
///
/// Anything that names sources converts into it: a vertex id (`u32`), a
/// [`SurfacePoint`], a [`Source`] (a point with a start value), or a slice, array or
/// `Vec` of any of them (borrowed ones are not copied: a run in a warm
/// [`Workspace`](crate::Workspace) allocates nothing). [`Sources::until`] adds a
/// [`Stop`]; without one the run goes to the end.
///
/// ```
/// use geotracks::{Source, Sources, Stop, SurfacePoint};
/// let one = Sources::from(7);
/// let several = Sources::from(&[0, 4, 9]);
/// let points = Sources::from(vec![Source::new(SurfacePoint::Edge { edge: 2, t: 0.5 })]);
/// let near = Sources::from(7).until(Stop::NONE.with_max_distance(1.5));
/// assert_eq!((one.len(), several.len(), points.len()), (1, 3, 1));
/// assert_eq!(near.stop().max_distance, 1.5);
/// ```
#[derive(Clone, Debug)]
pub struct Sources<'a> {
    list: SourceList<'a>,
    stop: Cow<'a, Stop>,
}

/// The sources themselves, borrowed where they can be.
#[derive(Clone, Debug)]
enum SourceList<'a> {
    One(Source),
    Vertices(Cow<'a, [u32]>),
    Points(Cow<'a, [Source]>),
}

impl<'a> Sources<'a> {
    /// These sources, stopping as `stop` says (a [`Stop`] or a `&Stop`).
    pub fn until(self, stop: impl Into<Cow<'a, Stop>>) -> Self {
        Sources {
            stop: stop.into(),
            ..self
        }
    }

    /// When the run may stop ([`Stop::NONE`] unless [`Sources::until`] said).
    pub fn stop(&self) -> &Stop {
        &self.stop
    }

    /// How many sources.
    pub fn len(&self) -> usize {
        match &self.list {
            SourceList::One(_) => 1,
            SourceList::Vertices(v) => v.len(),
            SourceList::Points(p) => p.len(),
        }
    }

    /// Whether there are none (a run refuses that: [`Error::NoSource`](crate::Error::NoSource)).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Appends the sources to `out` (which allocates only if it must grow).
    pub(crate) fn append_to(&self, out: &mut Vec<Source>) {
        match &self.list {
            SourceList::One(source) => out.push(*source),
            SourceList::Vertices(v) => out.extend(v.iter().map(|&v| Source::new(v))),
            SourceList::Points(p) => out.extend_from_slice(p),
        }
    }

    /// The sources, as a list.
    pub fn to_vec(&self) -> Vec<Source> {
        let mut out = Vec::with_capacity(self.len());
        self.append_to(&mut out);
        out
    }

    fn new(list: SourceList<'a>) -> Self {
        Sources {
            list,
            stop: Cow::Owned(Stop::NONE),
        }
    }
}

impl From<u32> for Sources<'_> {
    fn from(vertex: u32) -> Self {
        Sources::new(SourceList::One(Source::new(vertex)))
    }
}

impl From<SurfacePoint> for Sources<'_> {
    fn from(point: SurfacePoint) -> Self {
        Sources::new(SourceList::One(Source::new(point)))
    }
}

impl From<Source> for Sources<'_> {
    fn from(source: Source) -> Self {
        Sources::new(SourceList::One(source))
    }
}

impl<'a> From<&'a [u32]> for Sources<'a> {
    fn from(vertices: &'a [u32]) -> Self {
        Sources::new(SourceList::Vertices(Cow::Borrowed(vertices)))
    }
}

impl<'a, const N: usize> From<&'a [u32; N]> for Sources<'a> {
    fn from(vertices: &'a [u32; N]) -> Self {
        Sources::new(SourceList::Vertices(Cow::Borrowed(vertices)))
    }
}

impl<'a> From<&'a Vec<u32>> for Sources<'a> {
    fn from(vertices: &'a Vec<u32>) -> Self {
        Sources::new(SourceList::Vertices(Cow::Borrowed(vertices)))
    }
}

impl From<Vec<u32>> for Sources<'_> {
    fn from(vertices: Vec<u32>) -> Self {
        Sources::new(SourceList::Vertices(Cow::Owned(vertices)))
    }
}

impl<'a> From<&'a [Source]> for Sources<'a> {
    fn from(sources: &'a [Source]) -> Self {
        Sources::new(SourceList::Points(Cow::Borrowed(sources)))
    }
}

impl<'a, const N: usize> From<&'a [Source; N]> for Sources<'a> {
    fn from(sources: &'a [Source; N]) -> Self {
        Sources::new(SourceList::Points(Cow::Borrowed(sources)))
    }
}

impl<'a> From<&'a Vec<Source>> for Sources<'a> {
    fn from(sources: &'a Vec<Source>) -> Self {
        Sources::new(SourceList::Points(Cow::Borrowed(sources)))
    }
}

impl From<Vec<Source>> for Sources<'_> {
    fn from(sources: Vec<Source>) -> Self {
        Sources::new(SourceList::Points(Cow::Owned(sources)))
    }
}

impl From<&[SurfacePoint]> for Sources<'_> {
    fn from(points: &[SurfacePoint]) -> Self {
        Sources::from(points.iter().map(|&p| Source::new(p)).collect::<Vec<_>>())
    }
}

impl From<Vec<SurfacePoint>> for Sources<'_> {
    fn from(points: Vec<SurfacePoint>) -> Self {
        Sources::from(&points[..])
    }
}

impl<'a> From<&'a Stop> for Cow<'a, Stop> {
    fn from(stop: &'a Stop) -> Self {
        Cow::Borrowed(stop)
    }
}

impl From<Stop> for Cow<'_, Stop> {
    fn from(stop: Stop) -> Self {
        Cow::Owned(stop)
    }
}
