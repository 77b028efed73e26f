//! The closed surface a medial axis is computed from: its checks, its faces turned
//! outward, and the points sampled on it with their outward normals.

use super::winding::WindingNumbers;
use super::MedialAxisError;
use crate::mesh::TriMesh;
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// Points on the surface with the outward unit normal there.
pub(super) struct Samples {
    /// The mesh's vertices that faces use, then the added points.
    pub points: Vec<[f64; 3]>,
    /// Outward unit normal per point.
    pub normals: Vec<DVec3>,
}

impl Samples {
    /// The samples on the boundary of the solid: those a step of `offset` outward
    /// (along their normal) leaves. A surface whose parts run through each other (two
    /// shells that overlap, a limb pushed into the body) has faces inside the solid;
    /// their samples would make the Voronoi diagram wall the solid off along them, so
    /// they are left out and the axis is the one of the solid, the parts' union.
    pub(super) fn on_the_boundary(self, solid: &WindingNumbers, offset: f64) -> Self {
        // A sample without a normal (a vertex whose faces are all degenerate) cannot be
        // judged: it stays.
        let keep: Vec<bool> = self
            .points
            .par_iter()
            .zip(&self.normals)
            .map(|(p, &n)| n == DVec3::ZERO || !solid.contains(DVec3::from_array(*p) + offset * n))
            .collect();
        let (points, normals) = self
            .points
            .into_iter()
            .zip(self.normals)
            .zip(keep)
            .filter_map(|(sample, keep)| keep.then_some(sample))
            .unzip();
        Self { points, normals }
    }
}

/// The mesh's triangles with every face turned so that its normal (by the right-hand
/// rule) points out of the solid the surface bounds.
///
/// Faces are turned to agree with their neighbours across every edge (a file whose
/// winding is inconsistent is mended); each connected part keeps the winding most of its
/// faces had, and when the whole then encloses a negative volume every face is turned.
/// So a hollow solid whose inner shell is wound inward, as it should be, stays right.
///
/// # Errors
/// [`MedialAxisError::OpenSurface`] for an edge with one face,
/// [`MedialAxisError::NonManifoldSurface`] for one with more than two,
/// [`MedialAxisError::NonOrientableSurface`] when no winding agrees across every edge.
pub(super) fn outward_triangles(mesh: &TriMesh) -> Result<Vec<[u32; 3]>, MedialAxisError> {
    for e in 0..mesh.edge_count() as u32 {
        let faces = mesh.edge_faces(e).len();
        let edge = mesh.edge_vertices(e);
        match faces {
            1 => return Err(MedialAxisError::OpenSurface { edge }),
            2 => {}
            _ => return Err(MedialAxisError::NonManifoldSurface { edge, faces }),
        }
    }
    let mut turned = consistent_winding(mesh)?;
    let oriented = |f: usize, turned: &[bool]| {
        let [a, b, c] = mesh.triangles()[f];
        if turned[f] {
            [a, c, b]
        } else {
            [a, b, c]
        }
    };
    let volume: f64 = (0..mesh.face_count())
        .map(|f| {
            let [a, b, c] = oriented(f, &turned).map(|v| mesh.position(v));
            a.dot(b.cross(c))
        })
        .sum();
    if volume < 0.0 {
        turned.iter_mut().for_each(|t| *t = !*t);
    }
    Ok((0..mesh.face_count())
        .map(|f| oriented(f, &turned))
        .collect())
}

/// Which faces to turn so that neighbours cross each shared edge in opposite
/// directions, each connected part keeping its majority's winding.
fn consistent_winding(mesh: &TriMesh) -> Result<Vec<bool>, MedialAxisError> {
    let n = mesh.face_count();
    let mut turned = vec![false; n];
    let mut seen = vec![false; n];
    let mut stack = Vec::new();
    let mut part = Vec::new();
    for start in 0..n {
        if seen[start] {
            continue;
        }
        seen[start] = true;
        stack.push(start as u32);
        part.clear();
        while let Some(f) = stack.pop() {
            part.push(f);
            let [a, b, c] = mesh.triangles()[f as usize];
            let oriented = if turned[f as usize] {
                [a, c, b]
            } else {
                [a, b, c]
            };
            for &e in &mesh.face_edges(f) {
                let [u, v] = mesh.edge_vertices(e);
                let forward = runs(oriented, u, v);
                for &g in mesh.edge_faces(e) {
                    if g == f {
                        continue;
                    }
                    // `g` must run the other way along `e`: its file winding does
                    // unless it runs the way `f` does.
                    let turn_g = runs(mesh.triangles()[g as usize], u, v) == forward;
                    if !seen[g as usize] {
                        seen[g as usize] = true;
                        turned[g as usize] = turn_g;
                        stack.push(g);
                    } else if turned[g as usize] != turn_g {
                        return Err(MedialAxisError::NonOrientableSurface { face: g });
                    }
                }
            }
        }
        if 2 * part.iter().filter(|&&f| turned[f as usize]).count() > part.len() {
            for &f in &part {
                turned[f as usize] = !turned[f as usize];
            }
        }
    }
    Ok(turned)
}

/// Whether the triangle runs from `u` to `v` along one of its sides.
fn runs([a, b, c]: [u32; 3], u: u32, v: u32) -> bool {
    (a, b) == (u, v) || (b, c) == (u, v) || (c, a) == (u, v)
}

/// The vertices with their angle-weighted outward normals, and, where a face's side is
/// longer than `spacing`, points added along its sides and across it (a regular
/// barycentric grid; on a large face, its plane's lattice, [`lattice_points`]) so that
/// no sample is farther than about `spacing` from the next:
/// poles need samples denser than the shape's features, and a mesh's large flat faces
/// (a machined part's) have them only at their corners.
pub(super) fn samples(mesh: &TriMesh, triangles: &[[u32; 3]], spacing: f64) -> Samples {
    let p = |v: u32| mesh.position(v);
    let face_normal = |t: [u32; 3]| unit_normal(t.map(p));
    let mut normals = vec![DVec3::ZERO; mesh.vertex_count()];
    for &t in triangles {
        let n = face_normal(t);
        for i in 0..3 {
            let (v, a, b) = (t[i], t[(i + 1) % 3], t[(i + 2) % 3]);
            let angle = (p(a) - p(v)).angle_between(p(b) - p(v));
            if angle.is_finite() {
                normals[v as usize] += angle * n;
            }
        }
    }
    // A vertex no face uses is no point of the surface: it is left out.
    let mut samples = Samples {
        points: Vec::new(),
        normals: Vec::new(),
    };
    for (v, n) in normals.iter().enumerate() {
        if !mesh.vertex_faces(v as u32).is_empty() {
            samples.points.push(mesh.positions()[v].to_array());
            samples.normals.push(n.normalize_or_zero());
        }
    }
    for e in 0..mesh.edge_count() as u32 {
        let [a, b] = mesh.edge_vertices(e);
        let pieces = edge_pieces(mesh, e, spacing);
        let n = mesh
            .edge_faces(e)
            .iter()
            .map(|&f| face_normal(triangles[f as usize]))
            .sum::<DVec3>()
            .normalize_or_zero();
        for i in 1..pieces {
            let s = f64::from(i) / f64::from(pieces);
            samples.points.push(p(a).lerp(p(b), s).to_array());
            samples.normals.push(n);
        }
    }
    for (f, &t) in triangles.iter().enumerate() {
        let pieces = face_pieces(mesh, f as u32, spacing);
        let n = face_normal(t);
        if on_lattice(pieces, n) {
            lattice_points(t.map(p), n, spacing, |point, i_lo, i_hi| {
                for k in 0..=(i_hi - i_lo) as u64 {
                    samples.points.push(point(i_lo + k as f64).to_array());
                    samples.normals.push(n);
                }
            });
            continue;
        }
        for i in 1..pieces {
            for j in 1..pieces - i {
                let (bi, bj) = (f64::from(i), f64::from(j));
                let bk = f64::from(pieces) - bi - bj;
                let q = (bi * p(t[0]) + bj * p(t[1]) + bk * p(t[2])) / f64::from(pieces);
                samples.points.push(q.to_array());
                samples.normals.push(n);
            }
        }
    }
    samples
}

/// The fewest pieces along its longest side for a face to get the points of its plane's
/// lattice ([`lattice_points`]) rather than a barycentric grid: 6, a face at least five
/// spacings across, where grids of faces side by side or across a plate can be offset
/// over long runs. The smaller faces of a mesh of a smooth shape keep their grids (the
/// shared cow's and Spot's faces are cut into 5 pieces at most at their default
/// spacing, so their axes are unchanged).
const LATTICE_PIECES: u32 = 6;

/// The unit normal of the triangle `corners` (by their order), or zero if it is
/// degenerate.
fn unit_normal([a, b, c]: [DVec3; 3]) -> DVec3 {
    (b - a).cross(c - a).normalize_or_zero()
}

/// Whether a face cut into `pieces` along its longest side, with unit normal `normal`,
/// is sampled on its plane's lattice ([`lattice_points`]) rather than a barycentric
/// grid: [`samples`] and [`sample_count`] decide alike.
fn on_lattice(pieces: u32, normal: DVec3) -> bool {
    pieces >= LATTICE_PIECES && normal != DVec3::ZERO
}

/// The points of a square lattice of step `spacing` in the plane of the triangle
/// `corners` (unit normal `normal`) that lie inside it at least half a step from its
/// sides (which have points of their own), row by row: `row(point, i_lo, i_hi)` for
/// each row that has some, whose points are `point(i)` for `i` from `i_lo` to `i_hi`
/// (whole numbers, finite), so that they can be counted without being made.
///
/// The lattice is the plane's own: its axes and origin depend on the plane alone (its
/// normal up to sign, and its offset), so the faces of one flat patch share it, and so
/// do two parallel faces across a plate, whose points then stand in pairs straight
/// across it. Why: each face's barycentric grid runs along its own sides, so the two
/// triangles of one rectangle, or the two sides of a plate, get grids offset from each
/// other, and the Voronoi sheet between offset grids comes in strips a hair wide, which
/// the skeleton's thinning leaves as a comb of branches across a plate (the guide's
/// Plates section). Within half a step of a face's sides, where the sides' own points
/// are, the pairs do not hold.
fn lattice_points(
    corners: [DVec3; 3],
    normal: DVec3,
    spacing: f64,
    mut row: impl FnMut(&dyn Fn(f64) -> DVec3, f64, f64),
) {
    if normal == DVec3::ZERO || spacing.is_nan() || spacing <= 0.0 {
        return;
    }
    // The normal up to its sign: its largest component made positive.
    let m = if normal[normal.abs().max_position()] < 0.0 {
        -normal
    } else {
        normal
    };
    // The plane's axes: across the world axis least along the normal.
    let least = [DVec3::X, DVec3::Y, DVec3::Z][m.abs().min_position()];
    let u = least.cross(m).normalize();
    let w = m.cross(u);
    let offset = m.dot(corners[0]);
    let flat = corners.map(|c| DVec2::new(u.dot(c), w.dot(c)));
    let orientation = (flat[1] - flat[0]).perp_dot(flat[2] - flat[0]).signum();
    let margin = 0.5 * spacing;
    let (lo, hi) = (
        flat[0].min(flat[1]).min(flat[2]),
        flat[0].max(flat[1]).max(flat[2]),
    );
    // Row by row: on row y, each side bounds x on one side (a point is inside when it
    // is at least `margin` inside every side), so only the lattice points found are
    // visited, however thin the triangle.
    let (j0, j1) = ((lo.y / spacing).ceil(), (hi.y / spacing).floor());
    if !(j0.is_finite() && j1.is_finite()) || j1 < j0 {
        return;
    }
    // Counted in whole steps: far from the origin, adding 1 to a row's number may not
    // change it (the rows are as many as the face is spacings tall).
    for r in 0..=(j1 - j0) as u64 {
        let y = (j0 + r as f64) * spacing;
        let (mut x_lo, mut x_hi) = (lo.x, hi.x);
        for s in 0..3 {
            let (a, b) = (flat[s], flat[(s + 1) % 3]);
            let side = b - a;
            let length = side.length();
            if length == 0.0 {
                continue;
            }
            // Inside by `margin`: orientation × cross(side, x − a) / length ≥ margin,
            // linear in x: coef × x + rest ≥ margin.
            let coef = -orientation * side.y / length;
            let rest = orientation * (side.x * (y - a.y) + side.y * a.x) / length;
            let bound = (margin - rest) / coef;
            if coef > 0.0 {
                x_lo = x_lo.max(bound);
            } else if coef < 0.0 {
                x_hi = x_hi.min(bound);
            } else if rest < margin {
                x_hi = f64::NEG_INFINITY;
            }
        }
        let (i_lo, i_hi) = ((x_lo / spacing).ceil(), (x_hi / spacing).floor());
        if i_lo <= i_hi && i_lo.is_finite() && i_hi.is_finite() {
            row(&|i| i * spacing * u + y * w + offset * m, i_lo, i_hi);
        }
    }
}

/// How many samples [`samples`] makes for `spacing`, without making them.
pub(super) fn sample_count(mesh: &TriMesh, spacing: f64) -> u64 {
    let edges: u64 = (0..mesh.edge_count() as u32)
        .map(|e| u64::from(edge_pieces(mesh, e, spacing)) - 1)
        .sum();
    let faces: u64 = (0..mesh.face_count() as u32)
        .map(|f| {
            let pieces = face_pieces(mesh, f, spacing);
            let n = u64::from(pieces);
            let corners = mesh.face_vertices(f).map(|v| mesh.position(v));
            let normal = unit_normal(corners);
            if on_lattice(pieces, normal) {
                let mut count = 0.0;
                lattice_points(corners, normal, spacing, |_, lo, hi| {
                    count += hi - lo + 1.0;
                });
                count as u64
            } else {
                (n - 1) * n.saturating_sub(2) / 2
            }
        })
        .sum();
    mesh.vertex_count() as u64 + edges + faces
}

/// How many pieces edge `e` is cut into so that none is longer than `spacing` (at
/// least one; the count saturates for an edge beyond four billion spacings, which the
/// sample count then refuses).
fn edge_pieces(mesh: &TriMesh, e: u32, spacing: f64) -> u32 {
    (mesh.edge_length(e) / spacing).ceil().max(1.0) as u32
}

/// The pieces of face `f`'s longest side: its barycentric grid's size.
fn face_pieces(mesh: &TriMesh, f: u32, spacing: f64) -> u32 {
    mesh.face_edges(f)
        .iter()
        .map(|&e| edge_pieces(mesh, e, spacing))
        .max()
        .unwrap_or(1)
}
