//! What the exact engine works out once per solver: the faces' flattened frames, the
//! edges' lengths (checking that faces glue) and the vertices where paths bend.

use crate::flat::{flat_frame, EdgeGlue, P};
use crate::mesh::{FaceFrame, Topology};
use crate::Error;
use geotracks_metrics::Metric;

/// What the exact engine works out once per solver.
pub(in crate::propagate) struct ExactTables {
    /// Every face's frame in the metric's flattening.
    pub frames: Vec<FaceFrame>,
    /// Per vertex, whether shortest paths may bend there (so it starts windows when
    /// reached): a saddle (angles adding to more than 2π; lines through a flat
    /// vertex go on in the windows on either side of it), a vertex on
    /// the boundary or on a non-manifold edge, one with wires, one with no face.
    pub bends: Vec<bool>,
    /// The longest edge (flattened): no point of a face is farther from its corners.
    pub reach: f64,
    /// Per edge, its length (the longest its faces' planes give it; they glue, to
    /// 1e-9 of it or to rounding of their size: [`EdgeGlue::glues`]).
    pub lengths: Vec<f64>,
}

impl ExactTables {
    /// The flattened frames and the vertices where paths bend, checking that the
    /// metric flattens every face and that faces glue along every edge.
    ///
    /// # Errors
    /// [`Error::NotExact`] naming the first face the metric does not flatten, or the
    /// first edge whose faces give it different lengths.
    pub fn new<M: Metric, T: Topology>(mesh: &T, metric: &M) -> Result<ExactTables, Error> {
        let not_exact = |reason: String| Error::NotExact {
            metric: metric.name().to_string(),
            reason,
        };
        let mut frames = Vec::with_capacity(mesh.face_count());
        for f in 0..mesh.face_count() as u32 {
            let frame = flat_frame(metric, f, &mesh.frame(f)).ok_or_else(|| {
                not_exact(format!(
                    "it is not a constant norm on face {f} (it gives no flattening there)"
                ))
            })?;
            frames.push(frame);
        }
        let glue = EdgeGlue::of_edges(mesh, &frames);
        if let Some((e, g)) = glue.iter().enumerate().find(|(_, g)| !g.glues()) {
            return Err(not_exact(format!(
                "its faces do not glue: edge {e} is {:e} long in one face and {:e} in another",
                g.shortest, g.longest
            )));
        }
        let lengths: Vec<f64> = glue.iter().map(|g| g.longest).collect();
        let reach = lengths.iter().fold(0.0f64, |m, &l| m.max(l));
        let mut angles = vec![0.0f64; mesh.vertex_count()];
        for (f, frame) in frames.iter().enumerate() {
            let c = frame.corners().map(|[x, y]| P(x, y));
            let vertices = mesh.face_vertices(f as u32);
            for s in 0..3 {
                let d = c[(s + 1) % 3].sub(c[s]);
                // The angle at corner s, between its two edges.
                let (to_next, to_prev) = (d, c[(s + 2) % 3].sub(c[s]));
                let angle = to_next.cross(to_prev).abs().atan2(to_next.dot(to_prev));
                angles[vertices[s] as usize] += angle;
            }
        }
        let full_turn = 2.0 * std::f64::consts::PI;
        let bends = (0..mesh.vertex_count() as u32)
            .map(|v| {
                let faces = mesh.vertex_faces(v);
                faces.is_empty()
                    || !mesh.vertex_wires(v).is_empty()
                    || angles[v as usize] > full_turn * (1.0 + 1e-12)
                    || mesh
                        .vertex_edges(v)
                        .iter()
                        .any(|&e| mesh.edge_faces(e).len() != 2)
                    || fans_around(mesh, v) > 1
            })
            .collect();
        Ok(ExactTables {
            frames,
            bends,
            reach,
            lengths,
        })
    }
}

/// How many fans of faces meet at `v`: its faces, joined where two share an edge at
/// `v`. More than one (two cones touching at their apexes, or faces given twice, each
/// pair closed on itself) makes `v` a pinch that paths go through, bending, from one
/// fan to another, although every edge at it has two faces.
fn fans_around<T: Topology>(mesh: &T, v: u32) -> usize {
    let faces: Vec<u32> = mesh.vertex_faces(v).iter().copied().collect();
    let mut parent: Vec<usize> = (0..faces.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for &e in mesh.vertex_edges(v).iter() {
        let around: Vec<usize> = mesh
            .edge_faces(e)
            .iter()
            .filter_map(|f| faces.iter().position(|g| g == f))
            .collect();
        for pair in around.windows(2) {
            let (a, b) = (root(&mut parent, pair[0]), root(&mut parent, pair[1]));
            parent[a] = b;
        }
    }
    (0..faces.len())
        .filter(|&i| root(&mut parent, i) == i)
        .count()
}
