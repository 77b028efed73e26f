//! The inner Voronoi diagram of the samples: Voronoi vertices (the Delaunay
//! tetrahedra's circumcentres) that lie inside the solid, Voronoi edges between them
//! (one per Delaunay triangle) and Voronoi facets (one per Delaunay edge, through the
//! circumcentres of the tetrahedra around it) made only of them; then the facets that
//! are spikes toward the surface are collapsed away.

use super::delaunay::{circumcentre, Delaunay, OUTSIDE};
use super::facets;
use super::surface::Samples;
use super::winding::WindingNumbers;
use glam::DVec3;
use rayon::prelude::*;
use std::collections::HashMap;

/// The medial axis kept of the inner Voronoi diagram.
pub(super) struct InnerAxis {
    /// Voronoi vertices used by a kept facet or curve.
    pub positions: Vec<[f64; 3]>,
    /// Their medial ball radius (the circumradius).
    pub radii: Vec<f64>,
    /// The kept facets, fan-triangulated.
    pub triangles: Vec<[u32; 3]>,
    /// Voronoi edges kept outside every kept facet (they join parts of the axis).
    pub curves: Vec<[u32; 2]>,
    /// How many Voronoi vertices lay inside.
    pub inner_vertices: usize,
}

/// What makes a Voronoi facet a spike toward the surface, made by the sampling rather
/// than by the shape (see [`inner_axis`]).
#[derive(Clone, Copy, Debug)]
pub(super) struct SpikeFilter {
    /// The smallest angle (radians) under which one of a facet's vertices must see its
    /// Delaunay edge `p q`; the deepest vertex must see it under half that.
    pub min_angle: f64,
    /// The shortest edge `p q` between samples on one side of the surface.
    pub min_span: f64,
    /// The thinnest part whose two sides' samples (facing each other: their normals
    /// turned by more than 180° less `min_angle`) keep the facet between them, however
    /// close they are: its thickness between them, along their normals.
    pub min_across: f64,
}

/// The longest a ring of tetrahedra around one edge can be before the walk is taken for
/// a broken triangulation (a ring has a handful; thousands only on a sphere's centre).
const MAX_RING: usize = 1 << 16;

/// A Voronoi facet: its vertices (tetrahedra) in order around it, as a range of
/// [`Complex::corners`], and whether it is a spike toward the surface (see
/// [`inner_axis`]).
struct Facet {
    corners: std::ops::Range<usize>,
    spike: bool,
}

/// The inner Voronoi diagram as a 2-complex: facets, and every Voronoi edge between two
/// inner vertices (with the facets it bounds).
struct Complex {
    facets: Vec<Facet>,
    corners: Vec<u32>,
    /// Voronoi edges (between two inner tetrahedra that share a facet), lower first.
    edges: Vec<[u32; 2]>,
    /// The edge across each facet slot of each tetrahedron (its index in `edges`, kept
    /// at the lower of the two tetrahedra; `u32::MAX` elsewhere): a Voronoi edge is a
    /// Delaunay triangle, so the slot numbers it without a hash.
    slot_edges: Vec<u32>,
    /// Per corner of a facet, the edge from it to the next corner.
    corner_edges: Vec<u32>,
}

impl Complex {
    /// The edge between tetrahedra `a` and `b`, neighbours in `dt`.
    fn edge_between(&self, dt: &Delaunay, a: u32, b: u32) -> u32 {
        let (lo, hi) = (a.min(b), a.max(b));
        let k = dt.neighbours[lo as usize]
            .iter()
            .position(|&n| n == hi)
            .expect("consecutive tetrahedra of a ring are neighbours");
        self.slot_edges[lo as usize * 4 + k]
    }

    /// The edges of facet `f`, around it, as indices into `edges`.
    fn facet_edges(&self, f: usize) -> impl Iterator<Item = usize> + '_ {
        self.corner_edges[self.facets[f].corners.clone()]
            .iter()
            .map(|&e| e as usize)
    }

    /// Numbers the edges of every facet, once all are known ([`Complex::corner_edges`]).
    fn number_facet_edges(&mut self, dt: &Delaunay) {
        let mut corner_edges = Vec::with_capacity(self.corners.len());
        for facet in &self.facets {
            let ring = &self.corners[facet.corners.clone()];
            for i in 0..ring.len() {
                corner_edges.push(self.edge_between(dt, ring[i], ring[(i + 1) % ring.len()]));
            }
        }
        self.corner_edges = corner_edges;
    }
}

/// Which Voronoi vertices lie inside the solid, with their position: the
/// circumcentres where the surface's winding number is more than ½ (see
/// [`WindingNumbers`]). The test is the solid's own, not the samples': it holds where
/// the faces meet at sharp creases (whose vertex normals say little of the side a ball
/// lies on) and where they run through each other.
fn inner_centres(samples: &Samples, dt: &Delaunay, solid: &WindingNumbers) -> Vec<Option<DVec3>> {
    dt.tets
        .par_iter()
        .map(|tet| {
            let [a, b, c, d] = tet.map(|v| samples.points[v as usize]);
            let centre = DVec3::from_array(circumcentre(a, b, c, d));
            (centre.is_finite() && solid.contains(centre)).then_some(centre)
        })
        .collect()
}

/// The inner Voronoi diagram's facets and edges; a facet is a spike when no vertex of
/// it sees its Delaunay edge under `min_angle`, when its deepest vertex sees it under
/// less than half that, or when the edge is shorter than `min_span` (for samples that
/// face each other, on two sides of a thin part: when the part is thinner than
/// `min_across` between them). Near the surface,
/// where the balls are small, any two samples a few spacings apart are seen wide: a
/// spike between them passes the first test there, but where it reaches the axis, at
/// its deepest vertex, it sees them narrow. Sampled finer than a mesh's faces, the
/// creases between them make such spikes everywhere.
fn inner_complex(
    samples: &Samples,
    dt: &Delaunay,
    centres: &[Option<DVec3>],
    filter: SpikeFilter,
) -> Complex {
    let point = |v: u32| DVec3::from_array(samples.points[v as usize]);
    let mut complex = Complex {
        facets: Vec::new(),
        corners: Vec::new(),
        edges: Vec::new(),
        slot_edges: vec![u32::MAX; dt.tets.len() * 4],
        corner_edges: Vec::new(),
    };
    let mut ring = Vec::new();
    for t in 0..dt.tets.len() as u32 {
        if centres[t as usize].is_none() {
            continue;
        }
        for (k, &n) in dt.neighbours[t as usize].iter().enumerate() {
            if n != OUTSIDE && n > t && centres[n as usize].is_some() {
                complex.slot_edges[t as usize * 4 + k] = complex.edges.len() as u32;
                complex.edges.push([t, n]);
            }
        }
        for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
            // Each facet once: from the lowest tetrahedron of its ring, all inside.
            let skip = |r: u32| r < t || centres[r as usize].is_none();
            if !ring_around(dt, t, i, j, &mut ring, skip) {
                continue;
            }
            let tet = dt.tets[t as usize];
            let (p, q) = (point(tet[i]), point(tet[j]));
            let seen_from = |c: DVec3| (p - c).angle_between(q - c);
            let centre = |r: &u32| centres[*r as usize].expect("inner");
            let widest = ring
                .iter()
                .map(|r| seen_from(centre(r)))
                .fold(0.0, f64::max);
            // The deepest vertex (the largest ball) is where a spike meets the axis.
            let deepest = ring
                .iter()
                .map(centre)
                .max_by(|a, b| a.distance(p).total_cmp(&b.distance(p)))
                .map_or(0.0, seen_from);
            // Two samples a spacing or so apart are neighbours on the surface, and
            // the facet between them is the sampling's; unless they face each other:
            // then they are the two sides of a part about that thin (a horn, a tail),
            // and the facet is its axis.
            let (np, nq) = (
                samples.normals[tet[i] as usize],
                samples.normals[tet[j] as usize],
            );
            let spike_by_span = if np.angle_between(nq) > std::f64::consts::PI - filter.min_angle {
                // How thick the part is between them: along their normals, not
                // aslant (two samples of a plate's two sides a spacing apart).
                (q - p).dot(np - nq).abs() / 2.0 < filter.min_across
            } else {
                p.distance(q) < filter.min_span
            };
            let start = complex.corners.len();
            complex.corners.extend_from_slice(&ring);
            complex.facets.push(Facet {
                corners: start..complex.corners.len(),
                spike: widest < filter.min_angle
                    || deepest < filter.min_angle / 2.0
                    || spike_by_span,
            });
        }
    }
    complex.number_facet_edges(dt);
    complex
}

/// The medial axis of the inner Voronoi diagram of the samples (inside: by `solid`): its
/// facets whose Delaunay edge `p q` is seen from one of their vertices `c` under at
/// least `filter.min_angle` (radians, `∠ p c q`), from their deepest vertex under at
/// least half that, and is at least `filter.min_span` long (when `p` and `q` face
/// each other across a thin part: the part is at least `filter.min_across` thick
/// there), with the others collapsed away where they can be.
///
/// On a surface sampled densely enough, the inner Voronoi diagram has the solid's
/// topology (its facets, edges and vertices inside; those of the surface's own
/// Delaunay edges reach the outer poles and are left out). Where the ball touches the
/// surface at two far-apart points, as a medial ball does, the angle is large; facets
/// between neighbouring samples are spikes toward the surface. A spike is only removed
/// through a free edge (an elementary collapse, which changes no topology), so the
/// filter opens no hole and splits no part; edges left joining parts are kept as
/// curves, dangling ones collapsed too.
pub(super) fn inner_axis(
    samples: &Samples,
    dt: &Delaunay,
    solid: &WindingNumbers,
    filter: SpikeFilter,
) -> InnerAxis {
    let centres = inner_centres(samples, dt, solid);
    let complex = inner_complex(samples, dt, &centres, filter);
    let (alive, uses, gone) = collapse_spikes(&complex);
    let mut out = InnerAxis {
        positions: Vec::new(),
        radii: Vec::new(),
        triangles: Vec::new(),
        curves: Vec::new(),
        inner_vertices: centres.iter().flatten().count(),
    };
    let [lo, hi] = crate::mesh::bounding_box(samples.points.iter().copied());
    let extent = DVec3::from_array(lo).distance(DVec3::from_array(hi));
    let rep = merged_centres(&complex, &centres, 1e-9 * extent);
    let mut vertex_of = vec![u32::MAX; dt.tets.len()];
    let mut vertex = |r: u32, out: &mut InnerAxis| {
        let r = rep[r as usize] as usize;
        if vertex_of[r] == u32::MAX {
            let c = centres[r].expect("inner");
            out.positions.push(c.to_array());
            out.radii
                .push(c.distance(DVec3::from_array(samples.points[dt.tets[r][0] as usize])));
            vertex_of[r] = out.positions.len() as u32 - 1;
        }
        vertex_of[r]
    };
    let mut ring = Vec::new();
    let mut rings: Vec<Vec<u32>> = Vec::new();
    for (f, facet) in complex.facets.iter().enumerate() {
        if !alive[f] {
            continue;
        }
        ring.clear();
        for &r in &complex.corners[facet.corners.clone()] {
            if ring.last() != Some(&rep[r as usize]) {
                ring.push(rep[r as usize]);
            }
        }
        while ring.len() > 1 && ring.first() == ring.last() {
            ring.pop();
        }
        if ring.len() == 2 {
            // Shrunk to a segment by the merges: a curve.
            let (a, b) = (vertex(ring[0], &mut out), vertex(ring[1], &mut out));
            out.curves.push([a, b]);
        }
        if ring.len() >= 3 {
            rings.push(ring.iter().map(|&r| vertex(r, &mut out)).collect());
        }
    }
    facets::split_at_vertices_along_sides(&mut rings, &out.positions);
    for ring in &rings {
        facets::triangulate(ring, &out.positions, &mut out.triangles, &mut out.curves);
    }
    for [a, b] in joining_curves(&complex, &uses, &gone) {
        if rep[a as usize] != rep[b as usize] {
            let (a, b) = (vertex(a, &mut out), vertex(b, &mut out));
            out.curves.push([a, b]);
        }
    }
    out
}

/// For each tetrahedron, the one whose circumcentre stands for it: circumcentres closer
/// than rounding can tell apart (`tolerance`, `1e-9` of the samples' extent) along a
/// Voronoi edge are one. Five or more samples on one sphere (the corners of a mesh's planar quads, and
/// their neighbours) give several tetrahedra with the same circumcentre, computed a
/// rounding apart; kept apart, their facets would be flat slivers. Contracting the
/// edges between them changes no topology.
fn merged_centres(complex: &Complex, centres: &[Option<DVec3>], tolerance: f64) -> Vec<u32> {
    let mut sets = crate::mesh::DisjointSets::new(centres.len());
    for &[a, b] in &complex.edges {
        let (Some(ca), Some(cb)) = (centres[a as usize], centres[b as usize]) else {
            continue;
        };
        if ca.distance(cb) <= tolerance {
            sets.join(a, b);
        }
    }
    (0..centres.len() as u32).map(|t| sets.find(t)).collect()
}

/// Collapses the spikes through their free edges, until none is left with one;
/// returns which facets are left, how many of them use each edge, and which edges went
/// with a facet.
fn collapse_spikes(complex: &Complex) -> (Vec<bool>, Vec<u32>, Vec<bool>) {
    let mut uses = vec![0u32; complex.edges.len()];
    let mut facets_of: Vec<Vec<u32>> = vec![Vec::new(); complex.edges.len()];
    for f in 0..complex.facets.len() {
        for id in complex.facet_edges(f) {
            uses[id] += 1;
            facets_of[id].push(f as u32);
        }
    }
    let mut alive = vec![true; complex.facets.len()];
    let mut gone = vec![false; complex.edges.len()];
    let spike = |f: usize| complex.facets[f].spike;
    let mut queue: Vec<u32> = (0..complex.facets.len() as u32)
        .filter(|&f| spike(f as usize))
        .collect();
    while let Some(f) = queue.pop() {
        let f = f as usize;
        // An edge that went with a facet is used by none: no test for it needed.
        let free = complex.facet_edges(f).find(|&e| uses[e] == 1);
        let (true, Some(free)) = (alive[f], free) else {
            continue;
        };
        // The facet goes with its free edge: both leave the complex.
        alive[f] = false;
        gone[free] = true;
        for id in complex.facet_edges(f) {
            uses[id] -= 1;
            if uses[id] == 1 {
                queue.extend(
                    facets_of[id]
                        .iter()
                        .filter(|&&g| alive[g as usize] && spike(g as usize)),
                );
            }
        }
    }
    (alive, uses, gone)
}

/// The Voronoi edges in no facet left that join parts of the axis: dangling ones (an
/// end in nothing else) are collapsed, one after the other.
fn joining_curves(complex: &Complex, uses: &[u32], gone: &[bool]) -> Vec<[u32; 2]> {
    let mut degree: HashMap<u32, u32> = HashMap::new();
    // A vertex of a kept facet is never a free end.
    for (e, &[a, b]) in complex.edges.iter().enumerate() {
        if gone[e] {
            continue;
        }
        let weight = if uses[e] > 0 { 2 } else { 1 };
        *degree.entry(a).or_default() += weight;
        *degree.entry(b).or_default() += weight;
    }
    let mut kept: Vec<bool> = (0..uses.len()).map(|e| uses[e] == 0 && !gone[e]).collect();
    let mut at: HashMap<u32, Vec<u32>> = HashMap::new();
    for (e, &[a, b]) in complex.edges.iter().enumerate() {
        if kept[e] {
            at.entry(a).or_default().push(e as u32);
            at.entry(b).or_default().push(e as u32);
        }
    }
    let mut ends: Vec<u32> = degree
        .iter()
        .filter(|(_, &d)| d == 1)
        .map(|(&v, _)| v)
        .collect();
    while let Some(v) = ends.pop() {
        let Some(&e) = at[&v].iter().find(|&&e| kept[e as usize]) else {
            continue;
        };
        kept[e as usize] = false;
        for w in complex.edges[e as usize] {
            let d = degree.get_mut(&w).expect("an end of an edge");
            *d -= 1;
            if *d == 1 {
                ends.push(w);
            }
        }
    }
    (0..complex.edges.len())
        .filter(|&e| kept[e])
        .map(|e| complex.edges[e])
        .collect()
}

/// The tetrahedra around the edge between local vertices `i` and `j` of tetrahedron
/// `t`, in order, starting with `t`; `false` for an edge on the convex hull (its ring is
/// not closed, so it has no bounded Voronoi facet), or as soon as a tetrahedron of the
/// ring is one to `skip` (the walk around each edge is then done once, not once per
/// tetrahedron of its ring).
fn ring_around(
    dt: &Delaunay,
    t: u32,
    i: usize,
    j: usize,
    ring: &mut Vec<u32>,
    skip: impl Fn(u32) -> bool,
) -> bool {
    ring.clear();
    let tet = dt.tets[t as usize];
    let (a, b) = (tet[i], tet[j]);
    let k = (0..4).find(|&k| k != i && k != j).expect("four corners");
    let l = 6 - i - j - k;
    // Leave `t` across the facet opposite one of its two other vertices, `kept` being the
    // other; in each next tetrahedron, leave across the facet opposite the vertex kept
    // from the one before, and keep its new vertex.
    let (mut current, mut kept, mut leave) = (t, tet[l], tet[k]);
    loop {
        ring.push(current);
        let cur = dt.tets[current as usize];
        let k = cur
            .iter()
            .position(|&v| v == leave)
            .expect("vertex of the tetrahedron");
        let next = dt.neighbours[current as usize][k];
        if next == t {
            return true;
        }
        if next == OUTSIDE || ring.len() > MAX_RING || skip(next) {
            return false;
        }
        let fresh = *dt.tets[next as usize]
            .iter()
            .find(|&&v| v != a && v != b && v != kept)
            .expect("a tetrahedron has four vertices");
        leave = kept;
        kept = fresh;
        current = next;
    }
}
