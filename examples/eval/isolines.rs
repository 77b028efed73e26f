//! `--isolines N`: how far isoline points lie from their level, ours against a linear
//! interpolation of the exact vertex distances.
//!
//! For each mesh with references and each reference's source: N levels spread over
//! `(0, max exact)`; ours are `Query::isolines` of the default engine (wave, k = 2); the
//! others are the crossings that a linear interpolation of the exact vertex values puts
//! on each edge. Neither set's points are vertices, so no exact value is known there: the
//! distance of a point is estimated independently, by the straightened path from it of a
//! separate run at k = 8 (the guide's Paths page: within 0.002 % of exact on average). Up to
//! `SAMPLES` points per set, spread evenly over its points, each scored
//! |estimate − level| / level.

use super::{load, read_reference, source_of, Args, MeshEntry};
use geotracks::trace::{spread_levels, IsolineOptions};
use geotracks::{Euclidean, Options, Solver, SurfacePoint};
use std::time::Instant;

/// Points scored per set, per reference.
const SAMPLES: usize = 400;

pub fn isolines(args: &Args, meshes: &[&MeshEntry], levels: usize) -> Result<(), String> {
    println!("| mesh | faces | levels | points scored | ours: mean / max off | exact vertex values, linear: mean / max off | ours: s to draw |");
    println!("|---|---:|---:|---:|---:|---:|---:|");
    let mut all = [(0usize, 0.0f64, 0.0f64); 2];
    for entry in meshes {
        let Some(mesh) = load(args, entry, true)? else {
            continue;
        };
        let k = args.ks[0];
        let ours = Solver::new(&mesh, Euclidean, &Options::DEFAULT.with_k(k))
            .map_err(|e| e.to_string())?;
        let judge = Solver::new(&mesh, Euclidean, &Options::DEFAULT.with_k(8.0))
            .map_err(|e| e.to_string())?;
        let mut rows = [(0usize, 0.0f64, 0.0f64); 2];
        let mut seconds = 0.0;
        for reference in &entry.references {
            let exact = read_reference(&args.data.join(reference))?;
            let source = source_of(reference)?;
            let max = exact
                .iter()
                .copied()
                .filter(|d| d.is_finite())
                .fold(0.0, f64::max);
            let levels = spread_levels(max, levels);
            let field = ours.field(&[source]).map_err(|e| e.to_string())?;
            let start = Instant::now();
            let lines = field
                .isolines(&levels, &IsolineOptions::DEFAULT)
                .map_err(|e| e.to_string())?;
            seconds += start.elapsed().as_secs_f64();
            let our_points: Vec<(SurfacePoint, f64)> = lines
                .iter()
                .flat_map(|l| l.points.iter().map(move |&p| (p, l.level)))
                .collect();
            let mut linear = Vec::new();
            for e in 0..mesh.edge_count() as u32 {
                let [a, b] = mesh.edge_vertices(e);
                let (da, db) = (exact[a as usize], exact[b as usize]);
                for &level in &levels {
                    if (da < level) != (db < level) && da.is_finite() && db.is_finite() {
                        let t = (level - da) / (db - da);
                        linear.push((SurfacePoint::Edge { edge: e, t }, level));
                    }
                }
            }
            let judge_field = judge.field(&[source]).map_err(|e| e.to_string())?;
            let estimate = Ok::<_, geotracks::Error>(&judge_field).map_err(|e| e.to_string())?;
            for (row, points) in rows.iter_mut().zip([&our_points, &linear]) {
                let stride = (points.len() / SAMPLES).max(1);
                for &(p, level) in points.iter().step_by(stride) {
                    let Ok(path) = estimate.path(p) else { continue };
                    let off = (path.length - level).abs() / level;
                    *row = (row.0 + 1, row.1 + off, row.2.max(off));
                }
            }
        }
        println!(
            "| {} | {} | {levels} | {} + {} | {} | {} | {:.2} |",
            entry.name,
            entry.faces,
            rows[0].0,
            rows[1].0,
            cell(rows[0]),
            cell(rows[1]),
            seconds / entry.references.len().max(1) as f64
        );
        for (total, row) in all.iter_mut().zip(rows) {
            *total = (total.0 + row.0, total.1 + row.1, total.2.max(row.2));
        }
    }
    println!(
        "| all | | | {} + {} | {} | {} | |",
        all[0].0,
        all[1].0,
        cell(all[0]),
        cell(all[1])
    );
    Ok(())
}

/// `mean % / max %` of a row's (count, sum, max).
fn cell(r: (usize, f64, f64)) -> String {
    format!(
        "{:.4} % / {:.3} %",
        100.0 * r.1 / r.0.max(1) as f64,
        100.0 * r.2
    )
}
