//! Goal-directed stops (A*) against plain ones: 20 runs of the track-pruned engine from
//! 20 sources to one target, and to 10 scattered targets, each way.
//!
//! ```text
//! cargo run --release --example goal_bench -- MESH [K]
//! ```
//!
//! With one target, a goal-directed run settles a corridor instead of a disc. With
//! targets spread over the mesh the estimate is zero nearly everywhere: such runs are
//! plain (`Stop::goal_directed` says when), and the two rows should match.
//!
//! Then the same 20 paths to the one target, traced and straightened
//! (`Solver::shortest_path`), searched from both ends at once (two threads) and
//! from one end.

use geotracks::mesh::io::read_mesh;
use geotracks::Sources;
use geotracks::{Euclidean, Method, Options, Solver, Source, Stop, SurfacePoint};
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let path = args.next().ok_or("usage: goal_bench MESH [K]")?;
    let k: f64 = args.next().map_or(Ok(5.0), |s| s.parse())?;
    let mesh = read_mesh(&path)?;
    let options = Options::DEFAULT.with_method(Method::Tracks).with_k(k);
    let solver = Solver::new(&mesh, Euclidean, &options)?;
    let n = mesh.vertex_count() as u32;
    // Spread deterministically over the vertex ids.
    let sources: Vec<u32> = (0..20u32).map(|i| (i * 104_729) % n).collect();
    println!(
        "{path}: {n} vertices, tracks, k = {k}, {} runs per row",
        sources.len()
    );
    println!("| targets | goal-directed | seconds | settles |");
    println!("|---|---|---:|---:|");
    for count in [1u32, 10] {
        let targets: Vec<SurfacePoint> = (0..count)
            .map(|i| SurfacePoint::Vertex((i * 7919 + 11) % n))
            .collect();
        for goal_directed in [true, false] {
            let stop = Stop::NONE
                .with_targets(targets.clone())
                .with_goal_directed(goal_directed);
            let mut workspace = solver.workspace();
            let (start, mut settles) = (Instant::now(), 0);
            for &s in &sources {
                settles += solver
                    .run(
                        &mut workspace,
                        Sources::from(&[Source::new(s)]).until(&stop),
                    )?
                    .stats()
                    .settles;
            }
            let seconds = start.elapsed().as_secs_f64();
            println!("| {count} | {goal_directed} | {seconds:.3} | {settles} |");
        }
    }
    println!();
    println!("| paths to one target | both ends | seconds | settles | total cost |");
    println!("|---|---|---:|---:|---:|");
    let target = SurfacePoint::Vertex(11 % n);
    for both_ends in [true, false] {
        let stop = Stop::NONE.with_both_ends(both_ends);
        let (start, mut settles, mut cost) = (Instant::now(), 0, 0.0);
        for &s in &sources {
            let (path, stats) =
                solver.shortest_path(Sources::from(&[Source::new(s)]).until(&stop), target)?;
            settles += stats.settles;
            cost += path.length;
        }
        let seconds = start.elapsed().as_secs_f64();
        println!("| 20 | {both_ends} | {seconds:.3} | {settles} | {cost:.6} |");
    }
    Ok(())
}
