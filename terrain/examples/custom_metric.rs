//! A user-written terrain cost in a few lines: walking costs more the steeper the
//! ground, with Tobler's hiking function, on an elevation grid or any mesh.
//!
//! ```text
//! cargo run --release --example custom_metric [DEM.asc|DEM.tif X0,Y0 X1,Y1]
//! ```
//!
//! Tobler's hiking speed is `6 · exp(-3.5 · |tan(slope) + 0.05|)` km/h, the slope taken
//! along the walk, signed: the fastest walk is a slight descent. A segment costs its 3D
//! length over that speed (hours per km × length). Going up and down differ, so the
//! metric says it is directed (`is_symmetric` is false) and the engine measures every
//! segment in the direction it is walked, from the start. The engine asks the metric
//! only for the cost of straight segments inside one face; everything else is the same
//! as for the built-in metrics. (`geotracks_terrain::DirectedModel::Tobler` is this cost
//! built in, over the map length and in seconds: `--cost tobler` on the command line.)
//!
//! Without arguments it builds a 300 m hill in memory and routes across it.

use geotracks::mesh::TriMesh;
use geotracks::{Euclidean, FacePoint, Metric, Options, Solver, Source};
use geotracks_terrain::{read_terrain, ElevationGrid, GridGeometry};

/// Walking time (hours, lengths in metres) by Tobler's hiking function.
struct Tobler {
    /// Per face: the world position of its three corners.
    corners: Vec<[[f64; 3]; 3]>,
}

impl Tobler {
    fn new(mesh: &TriMesh) -> Tobler {
        let corners = (0..mesh.face_count() as u32)
            .map(|f| mesh.face_vertices(f).map(|v| mesh.position(v).to_array()))
            .collect();
        Tobler { corners }
    }
}

impl Metric for Tobler {
    fn cost(&self, face: u32, a: &FacePoint, b: &FacePoint) -> f64 {
        let c = &self.corners[face as usize];
        let at = |p: &FacePoint, i: usize| (0..3).map(|k| c[k][i] * p.bary[k]).sum::<f64>();
        let (dx, dy, dz) = (
            at(b, 0) - at(a, 0),
            at(b, 1) - at(a, 1),
            at(b, 2) - at(a, 2),
        );
        let run = dx.hypot(dy);
        if run == 0.0 && dz == 0.0 {
            return 0.0;
        }
        // A vertical step (no run) is as steep as it gets: its tangent is infinite.
        let tan = if run > 0.0 {
            dz / run
        } else {
            f64::INFINITY.copysign(dz)
        };
        let speed_km_h = 6.0 * (-3.5 * (tan + 0.05).abs()).exp();
        (run * run + dz * dz).sqrt() / 1000.0 / speed_km_h
    }

    fn is_symmetric(&self) -> bool {
        false // uphill and downhill differ
    }

    /// Nobody walks faster than 6 km/h: a metre takes at least 1/6000 h. With this
    /// bound, a run that stops at a target is goal-directed (A*): it settles a corridor
    /// towards the target, not a disc around the start.
    fn min_cost_per_length(&self) -> f64 {
        1.0 / 6000.0
    }

    fn name(&self) -> &str {
        "tobler"
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (terrain, from, to) = match args.as_slice() {
        [dem, from, to] => (read_terrain(dem)?.1, xy(from)?, xy(to)?),
        _ => {
            // A 2 km square, 20 m cells, with a 300 m hill in the middle.
            let geometry = GridGeometry {
                ncols: 101,
                nrows: 101,
                lower_left: [0.0, 0.0],
                spacing: [20.0, 20.0],
            };
            let hill = ElevationGrid::from_fn(geometry, |x, y| {
                Some(300.0 * (-((x - 1000.0).powi(2) + (y - 1000.0).powi(2)) / 2.0e5).exp())
            })?;
            (hill.to_mesh()?, [100.0, 1000.0], [1900.0, 1000.0])
        }
    };
    let mesh = &terrain.mesh;
    let (from, to) = (
        terrain.locate(from[0], from[1])?,
        terrain.locate(to[0], to[1])?,
    );
    let tobler = Tobler::new(mesh);
    let options = Options::DEFAULT.with_k(3.0);
    let from = [Source::new(from)];
    let fastest = Solver::new(mesh, &tobler, &options)?
        .shortest_path(&from, to)?
        .0;
    let shortest = Solver::new(mesh, Euclidean, &options)?
        .shortest_path(&from, to)?
        .0;
    for (name, path) in [("shortest", &shortest), ("fastest", &fastest)] {
        println!(
            "{name} route: {:.0} m, {:.2} h on foot",
            path.metric_length(mesh, &Euclidean),
            path.metric_length(mesh, &tobler)
        );
    }
    // The way back costs another time: the walk is directed.
    let back = [Source::new(to)];
    let returning = Solver::new(mesh, &tobler, &options)?
        .shortest_path(&back, from[0].point)?
        .0;
    println!("fastest way back: {:.2} h", returning.length);
    Ok(())
}

fn xy(text: &str) -> Result<[f64; 2], Box<dyn std::error::Error>> {
    let v: Vec<f64> = text.split(',').map(str::parse).collect::<Result<_, _>>()?;
    match v[..] {
        [x, y] => Ok([x, y]),
        _ => Err(format!("'{text}' is not X,Y").into()),
    }
}
