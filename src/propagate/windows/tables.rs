//! What the exact engine works out once per solver: the faces' flattened frames, the
//! edges' lengths (checking that faces glue) and the vertices where paths bend.

use crate::flat::{flat_frame, EdgeGlue, P};
use crate::mesh::{vertex_is_manifold, FaceFrame, Topology};
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
                    // A pinch: two fans meeting at the vertex alone.
                    || !vertex_is_manifold(mesh, v)
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
