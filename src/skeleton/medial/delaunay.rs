//! Delaunay tetrahedralization of a point set in space, with exact predicates.
//!
//! [`tetrahedralize`] returns the Delaunay tetrahedra of a set of points and their
//! adjacency. The medial axis of a closed surface is approximated from the
//! tetrahedralization of its vertices: the circumcentres of the tetrahedra are the
//! Voronoi vertices ([`circumcentre`]), and the ring of tetrahedra around a Delaunay
//! edge is the Voronoi facet dual to that edge.
//!
//! ## Algorithm
//! - Incremental Bowyer–Watson insertion (Bowyer 1981, Watson 1981): the tetrahedra
//!   whose circumsphere holds the new point (its cavity, searched breadth-first from the
//!   tetrahedron that contains it) are replaced by the point joined to the cavity's
//!   boundary facets.
//! - Order: BRIO (Amenta, Choi and Rote, "Incremental constructions con BRIO", 2003):
//!   a shuffle with a fixed seed, rounds of doubling size, each sorted along a Hilbert
//!   curve (Skilling, "Programming the Hilbert curve", 2004), every other one backwards.
//! - Location: a visibility walk from the last tetrahedron created (Devillers, Pion and
//!   Teillaud, "Walking in a triangulation", 2002), from a random facet at each step and
//!   never back through the facet it came by. It cannot cycle in a Delaunay (or regular)
//!   triangulation (Edelsbrunner, "An acyclicity theorem for cell complexes in d
//!   dimensions", 1990); should it all the same, it stops after as many steps as there
//!   are tetrahedra, with an error.
//! - Hull: a symbolic vertex at infinity joined to every hull facet, as in CGAL: a point
//!   is in conflict with the infinite tetrahedra whose hull facet it sees, so points
//!   outside the hull are inserted like the others and the result covers the whole hull
//!   (a super-tetrahedron's vertices would have to be "far enough" for each input).
//! - Predicates: exact and adaptive (Shewchuk, "Adaptive precision floating-point
//!   arithmetic and fast robust geometric predicates", 1997; crate `robust`), with a
//!   double-double stage before `robust`'s later stages for `insphere` ([`insphere`]).
//!   Coordinates beyond 2^±64 are first scaled by a power of two: exact, and no
//!   predicate's sign changes.
//! - Degeneracies: symbolic perturbation by index (Devillers and Teillaud,
//!   "Perturbations for Delaunay and weighted Delaunay 3D triangulations", 2011, as in
//!   CGAL): each point's height on the lifting paraboloid is raised by an infinitesimal,
//!   larger for a larger index, so a zero `insphere` is settled by `orient3d` of four of
//!   the points. The result is the Delaunay tetrahedralization of the perturbed points,
//!   which is one of the exact points': no flat tetrahedron (a regular triangulation has
//!   none), every distinct point a vertex (none is hidden by an infinitesimal weight),
//!   no point strictly inside a circumsphere (on one is allowed). Exact duplicates are
//!   merged beforehand ([`Delaunay::representative`]).
//!
//! ## Why it is written here
//! Measured before writing it: `delaunay` 0.8.x requires rustc 1.99 (this crate's MSRV
//! is 1.95); `delaunay` 0.7.8 (with `la-stack` held at 0.4.1 for our rustc) kept 2,830 of
//! the 2,930 points of a 3K-vertex surface mesh and took 181 s; `qhull` and `qhull-sys`
//! generate their bindings with bindgen, which needs libclang at build time (not on our
//! build machines, nor on a Python wheel builder's), and Qhull reports errors by
//! `longjmp`; `tritet` bundles TetGen, whose AGPL licence does not fit this crate's
//! MIT/Apache-2.0; `spade` and `delaunator` are 2D.

use robust::{Coord, Coord3D};
use std::ops::{Add, Mul, Sub};
use thiserror::Error;

/// Marks "no tetrahedron" (the outside of a hull facet) in [`Delaunay::neighbours`].
pub(crate) const OUTSIDE: u32 = u32::MAX;

/// The symbolic vertex at infinity, always in slot 3 of an infinite tetrahedron (the
/// insertion keeps it there: a new tetrahedron keeps the slots of the one it replaces).
const INFINITE: u32 = u32::MAX;

/// The vertices of a freed tetrahedron, until a later insertion reuses its slot.
const FREED: u32 = u32::MAX - 1;

/// Why a point set has no tetrahedralization.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub(crate) enum DelaunayError {
    /// Fewer than 4 distinct points (exact duplicates count once).
    #[error("{distinct} distinct points: a tetrahedralization needs at least 4")]
    TooFewPoints {
        /// How many distinct points there are.
        distinct: usize,
    },
    /// All the points lie in one plane (or on one line), so no tetrahedron has volume.
    #[error("all {distinct} distinct points lie in one plane")]
    Coplanar {
        /// How many distinct points there are.
        distinct: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("point {index} has a non-finite coordinate")]
    NonFinite {
        /// The index of the first such point.
        index: usize,
    },
    /// More points (or tetrahedra) than 32-bit indices can number.
    #[error("{count} points: more than 32-bit indices can number")]
    TooManyPoints {
        /// How many points were given.
        count: usize,
    },
    /// Inserting a point left the tetrahedra inconsistent. Not expected: the predicates
    /// are exact for coordinates in range, which scaling ensures; kept so that a
    /// failure of that reasoning is an error rather than a corrupt result or a panic.
    #[error("inserting point {point} left an inconsistent tetrahedralization")]
    Inconsistent {
        /// The index of the point being inserted.
        point: u32,
    },
}

/// The Delaunay tetrahedralization of a point set: finite tetrahedra and their adjacency.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Delaunay {
    /// Finite tetrahedra, as indices into the input points, positively oriented in
    /// Shewchuk's convention: `robust::orient3d(p[t[0]], p[t[1]], p[t[2]], p[t[3]]) > 0`,
    /// i.e. `t[3]` lies below the plane through the others seen counterclockwise from
    /// above (`[(0,0,0), (0,1,0), (1,0,0), (0,0,1)]` is positive), and the volume is
    /// that value over 6. A tetrahedron's vertices are never duplicates
    /// ([`Delaunay::representative`]).
    pub tets: Vec<[u32; 4]>,
    /// `neighbours[t][i]`: the tetrahedron across the facet opposite `tets[t][i]`, or
    /// [`OUTSIDE`] when that facet is on the convex hull.
    pub neighbours: Vec<[u32; 4]>,
    /// For each input point, the point it was merged with when it duplicates an earlier
    /// one exactly (the smallest index among its equals; itself otherwise).
    pub representative: Vec<u32>,
}

/// The Delaunay tetrahedralization of `points` (see the module notes for how it is made
/// and what it guarantees on degenerate input).
pub(crate) fn tetrahedralize(points: &[[f64; 3]]) -> Result<Delaunay, DelaunayError> {
    if points.len() >= FREED as usize {
        return Err(DelaunayError::TooManyPoints {
            count: points.len(),
        });
    }
    if let Some(index) = points.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
        return Err(DelaunayError::NonFinite { index });
    }
    // The smallest index of a point equal to each (`-0.0` equals `0.0`).
    let representative = crate::mesh::io::first_copies(points);
    let distinct: Vec<u32> = (0..points.len() as u32)
        .filter(|&i| representative[i as usize] == i)
        .collect();
    let count = distinct.len();
    if count < 4 {
        return Err(DelaunayError::TooFewPoints { distinct: count });
    }
    let pts = in_predicate_range(points);
    let order = insertion_order(&pts, distinct);
    let first = initial_simplex(&pts, &order).ok_or(DelaunayError::Coplanar { distinct: count })?;
    let mut builder = Builder::new(pts, first);
    for &p in &order {
        if !first.contains(&p) {
            builder.insert(p)?;
        }
    }
    Ok(builder.finish(representative))
}

/// The circumcentre of the tetrahedron `a b c d`, relative to `a` (rounding then depends
/// on its size, not its distance from the origin): with `b' = b − a`, `c' = c − a`,
/// `d' = d − a`, `a + (|b'|² c'×d' + |c'|² d'×b' + |d'|² b'×c') / (2 b'·(c'×d'))`, in
/// double-double arithmetic from the exact differences. A sliver's centre (four points
/// nearly on one circle, as on any regular grid of a surface) lies far along the
/// circle's axis, where a rounding of the numerator or of the volume in floats moves it
/// by as much as it is far; in double-double both keep about 100 bits through the
/// cancellation (on the tests' sliver the centre is within 1e-15, where the float
/// numerator is 5e-10 off). A flat one gives non-finite coordinates.
pub(crate) fn circumcentre(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> [f64; 3] {
    let diff = |p: [f64; 3]| [0, 1, 2].map(|k| two_sum(p[k], -a[k]));
    let cross = |u: [Dd; 3], v: [Dd; 3]| {
        [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ]
    };
    let dot = |u: [Dd; 3], v: [Dd; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    let [b3, c3, d3] = [b, c, d].map(diff);
    let (cd, db, bc) = (cross(c3, d3), cross(d3, b3), cross(b3, c3));
    let (lb, lc, ld) = (dot(b3, b3), dot(c3, c3), dot(d3, d3));
    let volume6 = dot(b3, cd);
    let denominator = 2.0 * (volume6.0 + volume6.1);
    [0, 1, 2].map(|k| {
        let n = lb * cd[k] + lc * db[k] + ld * bc[k];
        a[k] + (n.0 + n.1) / denominator
    })
}

/// A point as the predicates take it.
fn coord([x, y, z]: [f64; 3]) -> Coord3D<f64> {
    Coord3D { x, y, z }
}

/// `orient3d` of four of the points, by index.
fn orient(pts: &[[f64; 3]], v: [u32; 4]) -> f64 {
    let [a, b, c, d] = v.map(|i| coord(pts[i as usize]));
    robust::orient3d(a, b, c, d)
}

/// The points, scaled by a power of two when their largest coordinate is beyond 2^±64:
/// exact (short of subnormal results), sign-preserving for every predicate, and it keeps
/// `insphere`'s degree-5 products within the floating-point range.
fn in_predicate_range(points: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let largest = points.iter().flatten().fold(0.0f64, |m, c| m.max(c.abs()));
    // Clamped for all-zero points (which never come here: they are one point).
    let exponent = (largest.log2().floor() as i32).clamp(-1100, 1100);
    if exponent.abs() <= 64 {
        return points.to_vec();
    }
    // Two factors, each a normal number even for exponents near ±1074.
    let (f1, f2) = (2f64.powi(-exponent / 2), 2f64.powi(exponent / 2 - exponent));
    points.iter().map(|p| p.map(|c| c * f1 * f2)).collect()
}

/// The insertion order of the distinct points: BRIO rounds, each along a Hilbert curve.
fn insertion_order(pts: &[[f64; 3]], distinct: Vec<u32>) -> Vec<u32> {
    let bound = |f: fn(f64, f64) -> f64, k| distinct.iter().map(|&i| pts[i as usize][k]).reduce(f);
    let low = [0, 1, 2].map(|k| bound(f64::min, k).unwrap_or(0.0));
    let high = [0, 1, 2].map(|k| bound(f64::max, k).unwrap_or(0.0));
    let extent = (0..3).map(|k| high[k] - low[k]).fold(0.0, f64::max);
    // One cubic grid of 2^21 cells a side, so that the curve's locality is isotropic.
    let cells = f64::from((1u32 << HILBERT_BITS) - 1);
    let scale = if extent > 0.0 { cells / extent } else { 0.0 };
    let mut keyed: Vec<(u64, u32)> = distinct
        .into_iter()
        .map(|i| {
            let p = pts[i as usize];
            // `as` saturates, so rounding past either end stays on the grid.
            let cell = [0, 1, 2].map(|k| ((p[k] - low[k]) * scale) as u32);
            (hilbert_key(cell), i)
        })
        .collect();
    let mut state = 0x853c_49e6_748f_ea9b_u64;
    for i in (1..keyed.len()).rev() {
        let j = (splitmix64(&mut state) % (i as u64 + 1)) as usize;
        keyed.swap(i, j);
    }
    let (mut end, mut backwards) = (keyed.len(), false);
    while end > 0 {
        let start = if end <= 64 { 0 } else { end / 2 };
        let slice = &mut keyed[start..end];
        slice.sort_unstable();
        // Every other round backwards, so that each ends where the next starts.
        if backwards {
            slice.reverse();
        }
        (backwards, end) = (!backwards, start);
    }
    keyed.into_iter().map(|(_, i)| i).collect()
}

/// Bits per axis of the Hilbert curve's grid (3 × 21 = 63 bits of key).
const HILBERT_BITS: u32 = 21;

/// The position of a grid cell along the 3D Hilbert curve (Skilling's transpose
/// algorithm: the cell's coordinates are turned into the curve's transposed index, whose
/// bits interleave into the key).
fn hilbert_key(mut x: [u32; 3]) -> u64 {
    let top = 1u32 << (HILBERT_BITS - 1);
    let mut q = top;
    while q > 1 {
        let p = q - 1;
        for i in 0..3 {
            if x[i] & q != 0 {
                x[0] ^= p;
            } else {
                let t = (x[0] ^ x[i]) & p;
                x[0] ^= t;
                x[i] ^= t;
            }
        }
        q >>= 1;
    }
    x[1] ^= x[0];
    x[2] ^= x[1];
    let mut t = 0;
    q = top;
    while q > 1 {
        if x[2] & q != 0 {
            t ^= q - 1;
        }
        q >>= 1;
    }
    let mut key = 0u64;
    for bit in (0..HILBERT_BITS).rev() {
        for axis in x {
            key = (key << 1) | u64::from(((axis ^ t) >> bit) & 1);
        }
    }
    key
}

/// SplitMix64 (Steele, Lea and Flood, 2014): the shuffle's deterministic generator.
fn splitmix64(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Four points that span space, the first ones in `order` that do, or `None` when all
/// the points are coplanar. Three points are collinear when all three coordinate
/// projections of their triangle are (the projections are its normal's components).
fn initial_simplex(pts: &[[f64; 3]], order: &[u32]) -> Option<[u32; 4]> {
    let p = |i: u32| pts[i as usize];
    let (a, b) = (order[0], order[1]);
    let c = *order
        .iter()
        .find(|&&c| (0..3).any(|axis| projected_orientation(axis, [p(a), p(b), p(c)]) != 0))?;
    let d = *order.iter().find(|&&d| orient(pts, [a, b, c, d]) != 0.0)?;
    Some([a, b, c, d])
}

/// The sign of the 2D orientation of a triangle projected along `axis` (0: onto the yz
/// plane, 1: xz, 2: xy).
fn projected_orientation(axis: usize, t: [[f64; 3]; 3]) -> i32 {
    let (u, v) = [(1, 2), (0, 2), (0, 1)][axis];
    let c = |p: [f64; 3]| Coord { x: p[u], y: p[v] };
    sign(robust::orient2d(c(t[0]), c(t[1]), c(t[2])))
}

/// The orientation of three coplanar points within their plane: a sign that is
/// consistent for all triples of one plane (CGAL's `coplanar_orientation`): the first
/// nonzero projected orientation, onto xy, then yz, then xz. A plane's projection onto
/// xy is one-to-one unless the plane is vertical, in which case every triple of it
/// projects to 0 there, and likewise for the next projections.
fn coplanar_orientation(t: [[f64; 3]; 3]) -> i32 {
    [2, 0, 1]
        .into_iter()
        .map(|axis| projected_orientation(axis, t))
        .find(|&s| s != 0)
        .unwrap_or(0)
}

/// Whether `p` is inside the perturbed circumsphere (or circle) of the simplex `v` when
/// the unperturbed predicate is 0. Each point's lifted height is raised by an
/// infinitesimal, the larger the index the larger, and the perturbed determinant's terms
/// are taken from the most raised point down: raising `p` puts it outside; raising a
/// vertex gives the sign of `side` of `v` with that vertex replaced by `p` (`p` on the
/// vertex's side of the opposite facet: inside), unless that is 0. For distinct points
/// the first two terms always decide in 3D, the first three in the plane.
fn perturbed_side<const N: usize>(v: [u32; N], p: u32, side: impl Fn([u32; N]) -> i32) -> bool {
    let mut slots: [usize; N] = std::array::from_fn(|k| k);
    slots.sort_unstable_by_key(|&k| std::cmp::Reverse(v[k]));
    for k in slots.into_iter().take_while(|&k| v[k] > p) {
        let mut q = v;
        q[k] = p;
        let s = side(q);
        if s != 0 {
            return s > 0;
        }
    }
    false
}

/// The sign of a predicate's value.
fn sign(x: f64) -> i32 {
    i32::from(x > 0.0) - i32::from(x < 0.0)
}

/// The facet opposite slot `i` of a positively oriented tetrahedron `v`, ordered so that
/// `orient3d(facet, q) > 0` exactly when `q` is on the far side from `v[i]`: the facet
/// as the neighbour across it sees it.
fn outward_facet(v: [u32; 4], i: usize) -> [u32; 3] {
    match i {
        0 => [v[1], v[2], v[3]],
        1 => [v[2], v[0], v[3]],
        2 => [v[0], v[1], v[3]],
        _ => [v[1], v[0], v[2]],
    }
}

/// A small hash table matching the new tetrahedra's facets through the new point: each
/// is named by its other two vertices (an edge of the cavity's boundary) and is met
/// exactly twice. Stamped slots make starting afresh for each insertion free.
#[derive(Default)]
struct FacetTable {
    /// Per slot: the insertion that wrote it (other values: empty), the edge's key (its
    /// smaller vertex in the high half), and the tetrahedron and facet that put it there
    /// (the tetrahedron is `OUTSIDE` once met).
    slots: Vec<(u32, u64, u32, u8)>,
    /// The current insertion's stamp.
    stamp: u32,
    /// Keys put but not yet met: 0 at the end of a consistent insertion.
    open: usize,
}

impl FacetTable {
    /// Starts an insertion with room for `count` keys (the table stays at most half full).
    fn begin(&mut self, count: usize) {
        let size = (2 * count).next_power_of_two().max(64);
        if size > self.slots.len() || self.stamp == u32::MAX {
            self.slots = vec![(0, 0, 0, 0); size];
            self.stamp = 0;
        }
        self.stamp += 1;
        self.open = 0;
    }

    /// Puts facet `facet` of tetrahedron `tet`, named by the edge `a b`; returns the
    /// tetrahedron and facet that put the same edge before, if one did and is unmet.
    fn meet(&mut self, a: u32, b: u32, tet: u32, facet: u8) -> Option<(u32, u8)> {
        let key = (u64::from(a.min(b)) << 32) | u64::from(a.max(b));
        let (mask, bits) = (self.slots.len() - 1, self.slots.len().trailing_zeros());
        let mut h = (key.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> (64 - bits)) as usize;
        loop {
            let slot = &mut self.slots[h];
            if slot.0 != self.stamp {
                *slot = (self.stamp, key, tet, facet);
                self.open += 1;
                return None;
            }
            if slot.1 == key && slot.2 != OUTSIDE {
                self.open -= 1;
                let met = (slot.2, slot.3);
                slot.2 = OUTSIDE;
                return Some(met);
            }
            h = (h + 1) & mask;
        }
    }
}

/// A new tetrahedron waiting for its slot: its vertices, the slot of the new point, and
/// the tetrahedron outside the cavity across from it with the slot that points back.
type NewTet = ([u32; 4], usize, u32, usize);

/// The tetrahedralization under construction, with the infinite tetrahedra, and the
/// scratch space every insertion reuses.
#[derive(Default)]
struct Builder {
    /// The points (scaled into the predicates' range).
    pts: Vec<[f64; 3]>,
    /// Tetrahedra, finite and infinite (`INFINITE` in slot 3), and freed ones (`FREED`).
    tets: Vec<[u32; 4]>,
    /// Neighbours of each tetrahedron across the facet opposite each slot.
    nbrs: Vec<[u32; 4]>,
    /// Per tetrahedron: `stamp` if in the current cavity, `stamp + 1` if tested and not.
    mark: Vec<u32>,
    /// The current insertion's cavity stamp (even).
    stamp: u32,
    /// Freed tetrahedron slots.
    free: Vec<u32>,
    /// The current cavity's tetrahedra.
    cavity: Vec<u32>,
    /// The current cavity's boundary facets: cavity tetrahedron, slot, tetrahedron across.
    boundary: Vec<(u32, usize, u32)>,
    /// The new tetrahedra of the current insertion.
    created: Vec<NewTet>,
    /// Matches the new tetrahedra's facets to each other.
    facets: FacetTable,
    /// Where the next walk starts.
    last: u32,
    /// The walk's xorshift state.
    rng: u32,
}

impl Builder {
    /// The tetrahedron `first` and the four infinite tetrahedra on its facets.
    fn new(pts: Vec<[f64; 3]>, first: [u32; 4]) -> Self {
        let [a, b, c, d] = first;
        let t0 = if orient(&pts, first) > 0.0 {
            first
        } else {
            [b, a, c, d]
        };
        let mut tets = vec![t0];
        let mut nbrs = vec![[1, 2, 3, 4]];
        for i in 0..4 {
            let [x, y, z] = outward_facet(t0, i);
            tets.push([x, y, z, INFINITE]);
            nbrs.push([OUTSIDE, OUTSIDE, OUTSIDE, 0]);
        }
        // Infinite tetrahedra i and j share the facet opposite t0[j] in i.
        for i in 0..4 {
            for j in (0..4).filter(|&j| j != i) {
                if let Some(k) = tets[1 + i].iter().position(|&x| x == t0[j]) {
                    nbrs[1 + i][k] = 1 + j as u32;
                }
            }
        }
        Self {
            pts,
            mark: vec![0; tets.len()],
            tets,
            nbrs,
            rng: 0x2545_f491,
            ..Self::default()
        }
    }

    /// `orient3d` of four points by index.
    fn orient(&self, v: [u32; 4]) -> f64 {
        orient(&self.pts, v)
    }

    /// Inserts point `p`: locate, find the cavity, fill it.
    fn insert(&mut self, p: u32) -> Result<(), DelaunayError> {
        let inconsistent = DelaunayError::Inconsistent { point: p };
        let start = self.locate(p).ok_or(inconsistent)?;
        self.find_cavity(start, p);
        self.fill_cavity(p)
    }

    /// A tetrahedron in conflict with `p`: a finite one that contains it (in its closure),
    /// or an infinite one whose hull facet `p` is strictly beyond.
    fn locate(&mut self, p: u32) -> Option<u32> {
        let mut t = self.last;
        if self.tets[t as usize][3] == INFINITE {
            t = self.nbrs[t as usize][3];
        }
        let mut came_from = OUTSIDE;
        // Each step enters a tetrahedron not entered before, unless the walk cycles.
        for _ in 0..=self.tets.len() {
            self.rng ^= self.rng << 13;
            self.rng ^= self.rng >> 17;
            self.rng ^= self.rng << 5;
            let v = self.tets[t as usize];
            let next = (0..4).map(|k| (self.rng as usize + k) & 3).find(|&i| {
                let n = self.nbrs[t as usize][i];
                let mut q = v;
                q[i] = p;
                n != came_from && self.orient(q) < 0.0
            });
            let Some(i) = next else { return Some(t) };
            came_from = t;
            t = self.nbrs[t as usize][i];
            if self.tets[t as usize][3] == INFINITE {
                return Some(t);
            }
        }
        // A cycle: the predicates were fooled (not expected, see `Inconsistent`).
        None
    }

    /// Collects the cavity of `p` (the tetrahedra in conflict with it, connected to
    /// `start`) and its boundary facets, testing each tetrahedron once.
    fn find_cavity(&mut self, start: u32, p: u32) {
        self.stamp = self.stamp.wrapping_add(2);
        if self.stamp == 0 {
            // Wrapped after 2^31 insertions: old marks could pass for new ones.
            self.mark.fill(0);
            self.stamp = 2;
        }
        let (inside, outside) = (self.stamp, self.stamp + 1);
        self.cavity.clear();
        self.boundary.clear();
        self.mark[start as usize] = inside;
        self.cavity.push(start);
        let mut head = 0;
        while let Some(&t) = self.cavity.get(head) {
            head += 1;
            for i in 0..4 {
                let n = self.nbrs[t as usize][i];
                let m = self.mark[n as usize];
                if m == inside {
                    continue;
                }
                if m != outside {
                    if self.in_conflict(n, p) {
                        self.mark[n as usize] = inside;
                        self.cavity.push(n);
                        continue;
                    }
                    self.mark[n as usize] = outside;
                }
                self.boundary.push((t, i, n));
            }
        }
    }

    /// Whether `p` is in tetrahedron `t`'s perturbed circumsphere (for an infinite one:
    /// beyond its hull facet, or in that facet's plane and perturbed circumcircle).
    fn in_conflict(&self, t: u32, p: u32) -> bool {
        let v = self.tets[t as usize];
        if v[3] != INFINITE {
            let [a, b, c, d] = v.map(|i| self.pts[i as usize]);
            let s = insphere(a, b, c, d, self.pts[p as usize]);
            // Cospherical: raising a vertex puts `p` inside when `p` is on that vertex's
            // side of the opposite facet (CGAL's `side_of_oriented_sphere`, perturbed).
            return if s == 0.0 {
                perturbed_side(v, p, |q| sign(self.orient(q)))
            } else {
                s > 0.0
            };
        }
        let o = self.orient([v[0], v[1], v[2], p]);
        if o != 0.0 {
            return o > 0.0;
        }
        // In the hull facet's plane: inside its circumcircle exactly when inside any
        // sphere through it, such as the finite neighbour's, (b a c q) positively oriented.
        let inner = self.nbrs[t as usize][3];
        let w = self.tets[inner as usize];
        let Some(q) = w.into_iter().find(|x| !v.contains(x)) else {
            return false;
        };
        let [a, b, c] = [v[0], v[1], v[2]].map(|i| self.pts[i as usize]);
        let s = insphere(b, a, c, self.pts[q as usize], self.pts[p as usize]);
        if s == 0.0 {
            // Cocircular: the same within the plane, by orientations in it (CGAL's
            // `coplanar_side_of_bounded_circle`, perturbed).
            let f = [v[0], v[1], v[2]];
            let at = |t: [u32; 3]| t.map(|i| self.pts[i as usize]);
            let local = coplanar_orientation(at(f));
            perturbed_side(f, p, |q| coplanar_orientation(at(q)) * local)
        } else {
            s > 0.0
        }
    }

    /// Replaces the cavity by `p` joined to its boundary facets, and links the new
    /// tetrahedra to each other (through the facet table) and to the outside.
    fn fill_cavity(&mut self, p: u32) -> Result<(), DelaunayError> {
        let inconsistent = DelaunayError::Inconsistent { point: p };
        let too_many = DelaunayError::TooManyPoints {
            count: self.pts.len(),
        };
        self.created.clear();
        for &(t, i, n) in &self.boundary {
            let mut v = self.tets[t as usize];
            v[i] = p;
            let back = self.nbrs[n as usize].iter().position(|&x| x == t);
            self.created
                .push((v, i, n, back.ok_or(inconsistent.clone())?));
        }
        for &t in &self.cavity {
            self.tets[t as usize] = [FREED; 4];
            self.free.push(t);
        }
        self.facets.begin(3 * self.created.len());
        for k in 0..self.created.len() {
            let (v, i, n, back) = self.created[k];
            let t = match self.free.pop() {
                Some(t) => t,
                None if self.tets.len() < FREED as usize => {
                    self.tets.push([FREED; 4]);
                    self.nbrs.push([OUTSIDE; 4]);
                    self.mark.push(0);
                    (self.tets.len() - 1) as u32
                }
                None => return Err(too_many),
            };
            self.tets[t as usize] = v;
            self.nbrs[t as usize][i] = n;
            self.nbrs[n as usize][back] = t;
            for j in (0..4).filter(|&j| j != i) {
                // The facet opposite v[j] holds p and the two vertices other than v[i], v[j].
                let mut others = (0..4).filter(|&x| x != i && x != j).map(|x| v[x]);
                let (a, b) = (others.next().unwrap_or(p), others.next().unwrap_or(p));
                if let Some((u, slot)) = self.facets.meet(a, b, t, j as u8) {
                    self.nbrs[t as usize][j] = u;
                    self.nbrs[u as usize][slot as usize] = t;
                }
            }
            self.last = t;
        }
        if self.facets.open == 0 {
            Ok(())
        } else {
            Err(inconsistent)
        }
    }

    /// The finite tetrahedra, renumbered, with infinite neighbours as [`OUTSIDE`].
    fn finish(self, representative: Vec<u32>) -> Delaunay {
        let mut id = vec![OUTSIDE; self.tets.len()];
        let mut tets = Vec::new();
        for (t, v) in self.tets.iter().enumerate() {
            if v[0] != FREED && v[3] != INFINITE {
                id[t] = tets.len() as u32;
                tets.push(*v);
            }
        }
        let neighbours = (0..self.tets.len())
            .filter(|&t| id[t] != OUTSIDE)
            .map(|t| self.nbrs[t].map(|n| id[n as usize]))
            .collect();
        Delaunay {
            tets,
            neighbours,
            representative,
        }
    }
}

/// Shewchuk's `insphere` (positive when `e` is inside the sphere through the positively
/// oriented `a b c d`), with one more stage between his first and his exact ones: the
/// determinant in double-double arithmetic from the exact coordinate differences. Points
/// nearly on one sphere (a sampled sphere, or any round part of a surface) fail the first
/// stage every time, and the double-double stage settles them at a tenth of the cost of
/// the later stages of `robust`, which it falls back to when it cannot.
fn insphere(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3], e: [f64; 3]) -> f64 {
    const EPS: f64 = f64::EPSILON / 2.0;
    let sub = |p: [f64; 3]| [p[0] - e[0], p[1] - e[1], p[2] - e[2]];
    let diff = [sub(a), sub(b), sub(c), sub(d)];
    let det = lifted_det(diff, |x, y| x - y);
    let permanent = lifted_det(diff.map(|p| p.map(f64::abs)), |x, y| x + y);
    // Shewchuk's first-stage bound, for this very evaluation (robust's ISPERRBOUND_A).
    if det.abs() > (16.0 + 224.0 * EPS) * EPS * permanent {
        return det;
    }
    if permanent > f64::MIN_POSITIVE * 2f64.powi(300) {
        if let Some(det) = insphere_double_double([a, b, c, d], e, permanent) {
            return det;
        }
    }
    robust::insphere(coord(a), coord(b), coord(c), coord(d), coord(e))
}

/// The insphere determinant in double-double arithmetic from the exact differences, if
/// that settles its sign. Each operation errs by at most 7u² relatively (Joldes, Muller
/// and Popescu, "Tight and rigorous error bounds for basic building blocks of
/// double-word arithmetic", 2017) over a depth of 8 operations: within 56u² < 2^-100 of
/// the permanent (`u` = 2^-53); 2^-96 leaves room for the permanent's own rounding. Only
/// called far above underflow, where the operations' bounds hold.
fn insphere_double_double(pts: [[f64; 3]; 4], e: [f64; 3], permanent: f64) -> Option<f64> {
    let sub = |p: [f64; 3]| [0, 1, 2].map(|k| two_sum(p[k], -e[k]));
    let det = lifted_det(
        [sub(pts[0]), sub(pts[1]), sub(pts[2]), sub(pts[3])],
        Dd::sub,
    )
    .0;
    (det.abs() > 2f64.powi(-96) * permanent).then_some(det)
}

/// Shewchuk's insphere determinant of the differences `p − e`, in his order of
/// operations, with `minus` for subtraction: a sum on magnitudes gives the permanent
/// that bounds the rounding errors.
fn lifted_det<T, M>(d: [[T; 3]; 4], minus: M) -> T
where
    T: Copy + Add<Output = T> + Mul<Output = T>,
    M: Fn(T, T) -> T,
{
    let m = |i: usize, j: usize| minus(d[i][0] * d[j][1], d[j][0] * d[i][1]);
    let (ab, bc, cd, da, ac, bd) = (m(0, 1), m(1, 2), m(2, 3), m(3, 0), m(0, 2), m(1, 3));
    let z = |i: usize| d[i][2];
    let abc = minus(z(0) * bc, z(1) * ac) + z(2) * ab;
    let bcd = minus(z(1) * cd, z(2) * bd) + z(3) * bc;
    let cda = z(2) * da + z(3) * ac + z(0) * cd;
    let dab = z(3) * ab + z(0) * bd + z(1) * da;
    let lift = |i: usize| d[i][0] * d[i][0] + d[i][1] * d[i][1] + d[i][2] * d[i][2];
    minus(lift(3) * abc, lift(2) * dab) + minus(lift(1) * cda, lift(0) * bcd)
}

/// A double-double number: the unevaluated sum of a double and a far smaller one.
#[derive(Clone, Copy)]
struct Dd(f64, f64);

/// `a + b` exactly, as a double-double (Knuth's TwoSum).
fn two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    let bb = s - a;
    Dd(s, (a - (s - bb)) + (b - bb))
}

/// `a + b` exactly when `|a| ≥ |b|` (Dekker's Fast2Sum).
fn fast_two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    Dd(s, b - (s - a))
}

/// `a b` exactly, as a double-double, by Dekker's splitting (no fused multiply-add on the
/// default target; exact for magnitudes below 2^996, far above the scaled points').
fn two_prod(a: f64, b: f64) -> Dd {
    let split = |x: f64| {
        let c = 134_217_729.0 * x;
        let hi = c - (c - x);
        (hi, x - hi)
    };
    let p = a * b;
    let ((ah, al), (bh, bl)) = (split(a), split(b));
    Dd(p, al * bl - (((p - ah * bh) - al * bh) - ah * bl))
}

impl Add for Dd {
    type Output = Self;
    /// AccurateDWPlusDW (Joldes, Muller and Popescu 2017, relative error ≤ 3u²).
    fn add(self, o: Self) -> Self {
        let (s, t) = (two_sum(self.0, o.0), two_sum(self.1, o.1));
        let v = fast_two_sum(s.0, s.1 + t.0);
        fast_two_sum(v.0, v.1 + t.1)
    }
}

impl Sub for Dd {
    type Output = Self;
    /// The sum with the negation (exact), so as accurate as the sum.
    fn sub(self, o: Self) -> Self {
        self + Dd(-o.0, -o.1)
    }
}

impl Mul for Dd {
    type Output = Self;
    /// DWTimesDW1 (Joldes, Muller and Popescu 2017, relative error ≤ 7u²).
    fn mul(self, o: Self) -> Self {
        let c = two_prod(self.0, o.0);
        fast_two_sum(c.0, c.1 + (self.0 * o.1 + self.1 * o.0))
    }
}

#[cfg(test)]
#[path = "delaunay_tests.rs"]
mod tests;
