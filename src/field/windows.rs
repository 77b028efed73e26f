//! What the exact engine leaves in a field: its windows, found by edge, and how each
//! vertex got its value. Queries read them to give the exact distance at any point
//! and to trace a geodesic back along the straight lines the windows stand for.

use crate::mesh::Csr;
use crate::propagate::windows::Lines;

/// One window the exact engine carried: straight lines from a virtual source across
/// part of an edge, into every face around the edge but the one they came through.
///
/// Coordinates are in the edge's frame seen from a face the window enters: `x` along
/// the edge from its lower vertex, the source at `(sx, −sy)`, behind the edge. 56
/// bytes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Window {
    pub lines: Lines,
    pub edge: u32,
    /// The face the lines came through ([`NONE`](crate::mesh::NONE): none, a source on the edge's line).
    pub from: u32,
    /// The window whose lines these continue, or [`NONE`](crate::mesh::NONE) for one a source or a
    /// vertex started (see [`Window::source`]).
    pub parent: u32,
    /// The run's source (an index into its sources) the lines descend from; with
    /// [`Window::AT_VERTEX`] set on a window without a parent, the lines start at the
    /// corner of `from` opposite the edge (a vertex where paths bend), not at the
    /// source itself.
    pub source: u32,
}

impl Window {
    /// Marks a window started at a vertex (see [`Window::source`]).
    pub const AT_VERTEX: u32 = 1 << 31;
}

/// How a vertex got its value in the exact engine: where its geodesic goes first.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub(crate) enum Origin {
    /// Not reached.
    #[default]
    None,
    /// A source is this vertex (the index into the run's sources).
    Start(u32),
    /// Straight to a source (an index) inside `face`, or along an edge of `face` (a
    /// source on the edge).
    Source { index: u32, face: u32 },
    /// Straight to the virtual source of window `id`, across `face` (a face the
    /// window enters; the vertex is one of its corners).
    Window { id: u32, face: u32 },
    /// Straight to vertex `from` (a vertex that started windows) along their shared
    /// edge, in `face`.
    Vertex { from: u32, face: u32 },
    /// Along a wire from vertex `from`.
    Wire { from: u32 },
}

/// The exact engine's part of a field.
#[derive(Clone, Debug, Default)]
pub(crate) struct WindowField {
    /// Every window the run carried across a face, as carried (ids are indices; a
    /// window is never cut once carried).
    pub windows: Vec<Window>,
    /// The windows' ids by edge (built when the run ends).
    pub by_edge: Csr<u32>,
    /// Per vertex, how it got its value.
    pub origin: Vec<Origin>,
    /// Per vertex, its nearest source (an index into the run's sources).
    pub label: Vec<u32>,
}

impl WindowField {
    /// The windows on edge `e` (none unless the exact engine ran).
    pub fn on_edge(&self, e: u32) -> &[u32] {
        if self.by_edge.is_empty() {
            return &[];
        }
        self.by_edge.row(e)
    }

    /// Indexes the windows by edge, once a run over `edges` edges ends.
    pub fn index(&mut self, edges: usize) {
        let ids = self.windows.iter().enumerate();
        self.by_edge = Csr::from_pairs(edges, ids.map(|(id, w)| (w.edge, id as u32)));
    }

    /// Forgets the windows of the last run (capacity is kept; the origins are
    /// reset with the values, by the workspace).
    pub fn clear(&mut self) {
        self.windows.clear();
        self.by_edge = Csr::default();
    }
}
