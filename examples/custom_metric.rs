//! A user-defined metric in a few lines: climbing costs extra.
//!
//! ```text
//! cargo run --release --example custom_metric [MESH]
//! ```
//!
//! A segment costs its length plus `penalty × |Δz|`, the height it gains or loses
//! (world z, linear on each face). The engine asks the metric only for the cost of
//! straight segments inside one face; everything else is the same as for the
//! built-in metrics.

use geotracks::mesh::{io::read_mesh, Topology};
use geotracks::{distance_field, Euclidean, FacePoint, Metric, Options};

/// Length plus a penalty on height change.
struct Climb {
    /// Height (z) of each face's three corners, so a cost needs no vertex lookup.
    corner_heights: Vec<[f64; 3]>,
    penalty: f64,
}

impl Metric for Climb {
    fn cost(&self, face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
        let h = &self.corner_heights[face as usize];
        let z = |p: &FacePoint| h[0] * p.bary[0] + h[1] * p.bary[1] + h[2] * p.bary[2];
        a.distance(b) + self.penalty * (z(b) - z(a)).abs()
    }

    // |v| + c·|n·v| is a norm of v on each face, so track pruning stays exact.
    fn is_face_norm(&self) -> bool {
        true
    }

    fn name(&self) -> &str {
        "climb"
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/spot.obj").into());
    let mesh = read_mesh(&path)?;
    let climb = Climb {
        corner_heights: (0..mesh.face_count() as u32)
            .map(|f| mesh.face_vertices(f).map(|v| mesh.position(v).z))
            .collect(),
        penalty: 4.0,
    };
    let source = 0;
    let options = Options::DEFAULT;
    let flat = distance_field(&mesh, &Euclidean, &[source], &options)?;
    let steep = distance_field(&mesh, &climb, &[source], &options)?;
    let far = (0..mesh.vertex_count() as u32)
        .max_by(|&a, &b| flat.distance(a).total_cmp(&flat.distance(b)))
        .unwrap_or(source);
    println!("{path}: from vertex {source} to vertex {far}");
    println!("  euclidean distance  {:.4}", flat.distance(far));
    println!("  climb-penalised cost {:.4}", steep.distance(far));
    Ok(())
}
