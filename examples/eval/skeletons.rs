//! Skeletons of the shared medial axes (`--skeletons`): topology at every pruning level
//! against the axis's Betti numbers, and, where `skeleton/<name>.mcf.obj` holds a
//! mean-curvature-flow skeleton of the same shape, the distances between the two curves
//! (the guide's Skeletons page table).

use geotracks::mesh::io::read_medial_axis;
use geotracks::mesh::io::{read_mesh, MedialAxis};
use geotracks::skeleton::medial::{medial_axis, solid_cycles, MedialAxisOptions};
use geotracks::skeleton::{
    medial_axis_skeleton_with_cycles, turning_per_length, Burn, Placement, Pruning, Skeleton,
};
use geotracks::{Method, Options};
use glam::DVec3;
use std::path::Path;
use std::time::Instant;

/// Pruning levels, in % of the axis's bounding-box diagonal.
const LEVELS: [f64; 8] = [0.0, 0.5, 1.0, 2.0, 3.0, 5.0, 10.0, f64::INFINITY];

/// Where the axes come from: the shared `.ma` files, or the shared meshes that have a
/// mean-curvature-flow reference (`meshes/<name>.obj`), through their medial axis at
/// this angle.
#[derive(Clone, Copy)]
pub enum Axes {
    Files,
    FromMeshes(MedialAxisOptions),
}

/// The axis of `name` and the most cycles its skeleton may have.
fn load(data: &Path, name: &str, axes: Axes) -> Result<(MedialAxis, usize), String> {
    match axes {
        Axes::Files => {
            let path = data.join("ma").join(format!("{name}.ma"));
            Ok((
                read_medial_axis(&path).map_err(|e| e.to_string())?,
                usize::MAX,
            ))
        }
        Axes::FromMeshes(options) => {
            let path = data.join("meshes").join(format!("{name}.obj"));
            let mesh = read_mesh(&path).map_err(|e| e.to_string())?;
            let axis = medial_axis(&mesh, &options).map_err(|e| format!("{name}: {e}"))?;
            Ok((axis, solid_cycles(&mesh)))
        }
    }
}

/// The pruning thresholds as the command line takes them.
pub struct Thresholds {
    /// Erosion thickness, in % of the diagonal.
    pub prune_percent: f64,
    pub tubular: f64,
    pub protrusion: f64,
    pub trim_tips: bool,
}

pub fn skeletons(
    data: &Path,
    thresholds: Thresholds,
    k: f64,
    burn: Burn,
    axes: Axes,
    placement: Placement,
) -> Result<(), String> {
    let Thresholds {
        prune_percent,
        tubular,
        protrusion,
        trim_tips,
    } = thresholds;
    let (dir, extension, suffix) = match axes {
        Axes::Files => (data.join("ma"), "ma", ".ma"),
        Axes::FromMeshes(_) => (data.join("skeleton"), "obj", ".mcf.obj"),
    };
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .filter_map(|entry| {
            let path = entry.ok()?.path();
            (path.extension()? == extension).then_some(())?;
            let name = path
                .file_name()?
                .to_str()?
                .strip_suffix(suffix)?
                .to_string();
            let mesh = data.join("meshes").join(format!("{name}.obj"));
            (matches!(axes, Axes::Files) || mesh.exists()).then_some(name)
        })
        .collect();
    names.sort();
    let options = Options::DEFAULT.with_k(k).with_method(Method::Tracks);
    println!("Topology: independent cycles of the skeleton (E − V + C) / components / tips at each --prune level (% of the diagonal), against the axis's b1 / b0 over GF(2).\n");
    let mut header = String::from("| axis | faces | b0 | b1 |");
    let mut rule = String::from("|---|---:|---:|---:|");
    for level in LEVELS {
        header += &format!(
            " {} |",
            if level.is_finite() {
                format!("{level} %")
            } else {
                "∞".into()
            }
        );
        rule += "---:|";
    }
    println!("{header} end to end |\n{rule}---:|");
    let mut failures = Vec::new();
    let mut comparisons = Vec::new();
    let mut breakdowns = Vec::new();
    for name in &names {
        let start = Instant::now();
        let (axis, max_cycles) = load(data, name, axes)?;
        let diagonal = axis.diagonal();
        let (at_default, _) = medial_axis_skeleton_with_cycles(
            &axis,
            burn,
            &options,
            Pruning {
                erosion_thickness: prune_percent / 100.0 * diagonal,
                tubularity: tubular,
                protrusion,
                trim_tips,
            },
            max_cycles,
            placement,
        )
        .map_err(|e| e.to_string())?;
        let seconds = start.elapsed().as_secs_f64();
        let betti = axis.betti_numbers();
        let (full, _) =
            Skeleton::of_medial_axis(&axis, burn, &options).map_err(|e| e.to_string())?;
        let faces = axis.surface.as_ref().map_or(0, |m| m.face_count());
        let mut row = format!("| {name} | {faces} | {} | {} |", betti.b0, betti.b1);
        for level in LEVELS {
            let pruned = full.pruned(level / 100.0 * diagonal);
            let (cycles, components) = (pruned.cycle_count(), pruned.component_count());
            row += &format!(" {cycles} / {components} / {} |", pruned.tip_count());
            if cycles != betti.b1 + full.added_cycles || components != betti.b0 {
                failures.push(format!(
                    "{name} at {level} %: {cycles} cycles, {components} components"
                ));
            }
        }
        println!("{row} {seconds:.3} s |");
        let reference = data.join("skeleton").join(format!("{name}.mcf.obj"));
        if reference.exists() {
            // How far the reference itself lies from the axis, mean and max: no skeleton
            // on the axis can come closer to it than that.
            let reference = read_polylines(&reference)?;
            let to_axis = |points: &[DVec3]| -> Option<(f64, f64)> {
                let mesh = axis.surface.as_ref()?;
                let gaps: Vec<f64> = points
                    .iter()
                    .map(|&p| {
                        geotracks::SurfacePoint::nearest(mesh, p.to_array())
                            .map_or(f64::INFINITY, |q| q.position(mesh).distance(p))
                    })
                    .collect();
                let mean = gaps.iter().sum::<f64>() / gaps.len().max(1) as f64;
                Some((mean, gaps.iter().copied().fold(0.0, f64::max)))
            };
            let floor = to_axis(&sample(&reference.segments, 0.002 * diagonal));
            // Per branch of the reference: its share of the samples, its mean distance
            // to ours, and its own floor.
            let ours_segments = segments_of(&at_default.polyline_positions());
            let mut branches: Vec<Branch> = reference
                .branches
                .iter()
                .map(|line| {
                    let points = sample(&segments_of(std::slice::from_ref(line)), 0.002 * diagonal);
                    Branch {
                        ends: [line[0], line[line.len() - 1]],
                        kind: "",
                        samples: points.len(),
                        to_other: spread(&points, &ours_segments).0,
                        floor: to_axis(&points).map(|(mean, _)| mean),
                    }
                })
                .collect();
            let degree = at_default.degrees();
            let mut ours_branches: Vec<Branch> = at_default
                .polylines()
                .iter()
                .filter(|ids| ids.len() > 1)
                .map(|ids| {
                    let line: Vec<[f64; 3]> = ids
                        .iter()
                        .map(|&i| at_default.points[i as usize].position)
                        .collect();
                    let points =
                        sample(&segments_of(std::slice::from_ref(&line)), 0.002 * diagonal);
                    // Points on the loops that carry the axis's cycles never burn.
                    let on_loop = ids
                        .iter()
                        .all(|&i| at_default.points[i as usize].significance.is_infinite());
                    let kind = if on_loop {
                        "loop"
                    } else if ids.iter().any(|&i| degree[i as usize] == 1) {
                        "to a tip"
                    } else {
                        "inner"
                    };
                    Branch {
                        ends: [line[0], line[line.len() - 1]],
                        kind,
                        samples: points.len(),
                        to_other: spread(&points, &reference.segments).0,
                        floor: None,
                    }
                })
                .collect();
            let excess = |b: &Branch| b.samples as f64 * (b.to_other - b.floor.unwrap_or(0.0));
            branches.sort_by(|a, b| excess(b).total_cmp(&excess(a)));
            ours_branches.sort_by(|a, b| excess(b).total_cmp(&excess(a)));
            breakdowns.push((name.clone(), diagonal, branches, ours_branches));
            comparisons.push((name.clone(), at_default, reference, diagonal, floor));
        }
    }
    println!("\nAgainst CGAL's mean-curvature-flow skeleton of the shape, at --prune {prune_percent} %, --tubular {tubular} and --protrusion {protrusion}{}, points {}: both sampled every 0.2 % of the diagonal; distances in % of the diagonal.\n", if trim_tips { "" } else { ", tips not trimmed (--keep-tips)" }, match placement { Placement::OnAxis => "on the axis", Placement::Centred => "centred" });
    println!("| axis | reference → ours mean / max | ours → reference mean / max | tips ours / reference | junctions ours / reference | length ours / reference | turning per length ours / reference | reference → axis mean / max |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|");
    let mut targets = Vec::new();
    for (name, ours, reference, diagonal, floor) in comparisons {
        let ours_segments = segments_of(&ours.polyline_positions());
        let step = 0.002 * diagonal;
        let (to_ours_mean, to_ours_max) =
            spread(&sample(&reference.segments, step), &ours_segments);
        let (to_ref_mean, to_ref_max) = spread(&sample(&ours_segments, step), &reference.segments);
        let pct = |x: f64| 100.0 * x / diagonal;
        let junctions = junction_count(&ours);
        println!(
            "| {name} | {:.2} % / {:.2} % | {:.2} % / {:.2} % | {} / {} | {} / {} | {:.1} / {:.1} | {:.2} / {:.2} | {} |",
            pct(to_ours_mean),
            pct(to_ours_max),
            pct(to_ref_mean),
            pct(to_ref_max),
            ours.tip_count(),
            reference.tips,
            junctions,
            reference.junctions,
            ours.length(),
            reference.segments.iter().map(|(a, b)| a.distance(*b)).sum::<f64>(),
            turning_per_length(&ours.polyline_positions()) * diagonal,
            turning_per_length(&reference.branches) * diagonal,
            floor.map_or("–".into(), |(mean, max)| format!(
                "{:.2} % / {:.2} %",
                pct(mean),
                pct(max)
            ))
        );
        let reference_length: f64 = reference.segments.iter().map(|(a, b)| a.distance(*b)).sum();
        targets.push(Targets {
            name,
            excess: floor.map(|(mean, _)| pct(to_ours_mean - mean)),
            max: pct(to_ours_max),
            to_reference: pct(to_ref_mean),
            tips: ours.tip_count() as f64 / reference.tips.max(1) as f64,
            length: ours.length() / reference_length,
        });
    }
    print_targets(&targets);
    println!("\nWhere the distances come from: the branches (polylines between tips and junctions) that add most to each mean, with their share of it (branch samples × distance / all samples, in % of the diagonal; reference → ours less the branch's own distance to the axis, which no skeleton on the axis can remove).\n");
    println!("| axis | direction | branch (ends) | samples | mean distance | to the axis | share of the mean |");
    println!("|---|---|---|---:|---:|---:|---:|");
    for (name, diagonal, reference, ours) in &breakdowns {
        let pct = |x: f64| 100.0 * x / diagonal;
        for (direction, branches) in [("reference → ours", reference), ("ours → reference", ours)]
        {
            let total: usize = branches.iter().map(|b| b.samples).sum();
            for b in branches.iter().take(BREAKDOWN_ROWS) {
                let share =
                    b.samples as f64 * (b.to_other - b.floor.unwrap_or(0.0)) / total.max(1) as f64;
                let at = |p: [f64; 3]| format!("({:.2}, {:.2}, {:.2})", p[0], p[1], p[2]);
                println!(
                    "| {name} | {direction} | {} – {}{} | {} | {:.2} % | {} | {:.2} % |",
                    at(b.ends[0]),
                    at(b.ends[1]),
                    if b.kind.is_empty() {
                        String::new()
                    } else {
                        format!(", {}", b.kind)
                    },
                    b.samples,
                    pct(b.to_other),
                    b.floor.map_or("–".into(), |f| format!("{:.2} %", pct(f))),
                    pct(share)
                );
            }
        }
    }
    if !failures.is_empty() {
        return Err(format!(
            "skeleton topology differs from the axis's: {}",
            failures.join("; ")
        ));
    }
    Ok(())
}

/// Rows of the breakdown per axis and direction.
const BREAKDOWN_ROWS: usize = 5;

/// One skeleton's measures against the targets for skeletons as good as MCF's.
struct Targets {
    name: String,
    /// Reference → ours mean less the reference's own mean distance to the axis (what
    /// no skeleton on the axis can remove), in % of the diagonal; unknown without axis.
    excess: Option<f64>,
    /// Reference → ours max, in % of the diagonal.
    max: f64,
    /// Ours → reference mean, in % of the diagonal.
    to_reference: f64,
    /// Tips, ours over the reference's.
    tips: f64,
    /// Length, ours over the reference's.
    length: f64,
}

/// The targets' table: reference → ours mean less the floor ≤ 0.5 %, its max ≤ 4 %,
/// ours → reference mean ≤ 2 %, tips and length within 2× and 1.25× of the
/// reference's (either way).
fn print_targets(targets: &[Targets]) {
    let mark = |ok: bool| if ok { "✓" } else { "✗" };
    let within = |ratio: f64, factor: f64| ratio <= factor && ratio >= 1.0 / factor;
    println!("\nAgainst the targets (reference → ours mean less the floor ≤ 0.5 %, its max ≤ 4 %; ours → reference mean ≤ 2 %; tips within 2× and length within 1.25× of the reference's):\n");
    println!("| axis | mean − floor | max | ours → reference | tips | length |");
    println!("|---|---:|---:|---:|---:|---:|");
    for t in targets {
        println!(
            "| {} | {} | {:.2} % {} | {:.2} % {} | {:.2}× {} | {:.2}× {} |",
            t.name,
            t.excess
                .map_or("–".into(), |e| format!("{e:.2} % {}", mark(e <= 0.5))),
            t.max,
            mark(t.max <= 4.0),
            t.to_reference,
            mark(t.to_reference <= 2.0),
            t.tips,
            mark(within(t.tips, 2.0)),
            t.length,
            mark(within(t.length, 1.25)),
        );
    }
}

/// One branch of a skeleton, measured against the other skeleton.
struct Branch {
    ends: [[f64; 3]; 2],
    /// For ours: on a loop, ending at a tip, or between junctions.
    kind: &'static str,
    samples: usize,
    /// Mean distance of its samples to the other skeleton.
    to_other: f64,
    /// Mean distance of its samples to the axis (reference branches only).
    floor: Option<f64>,
}

/// Points with three or more edges.
fn junction_count(skeleton: &Skeleton) -> usize {
    skeleton.degrees().iter().filter(|&&d| d > 2).count()
}

struct Polylines {
    segments: Vec<(DVec3, DVec3)>,
    /// The branches: polylines between tips and junctions.
    branches: Vec<Vec<[f64; 3]>>,
    tips: usize,
    junctions: usize,
}

/// OBJ `v` and `l` lines.
fn read_polylines(path: &Path) -> Result<Polylines, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut vertices = Vec::new();
    let mut edges = Vec::new();
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let c: Vec<f64> = words.take(3).filter_map(|w| w.parse().ok()).collect();
                vertices.push(DVec3::new(c[0], c[1], c[2]));
            }
            Some("l") => {
                let ids: Vec<usize> = words
                    .filter_map(|w| w.parse::<usize>().ok())
                    .map(|i| i - 1)
                    .collect();
                edges.extend(ids.windows(2).map(|w| (w[0].min(w[1]), w[0].max(w[1]))));
            }
            _ => {}
        }
    }
    edges.sort_unstable();
    edges.dedup();
    // The graph unpruned is itself: its polylines are the branches.
    let positions: Vec<[f64; 3]> = vertices.iter().map(|v| v.to_array()).collect();
    let pairs: Vec<[u32; 2]> = edges.iter().map(|&(a, b)| [a as u32, b as u32]).collect();
    let graph = Skeleton::from_curves(&positions, &pairs, None);
    Ok(Polylines {
        branches: graph.polyline_positions(),
        segments: edges
            .iter()
            .map(|&(a, b)| (vertices[a], vertices[b]))
            .collect(),
        tips: graph.tip_count(),
        junctions: junction_count(&graph),
    })
}

fn segments_of(lines: &[Vec<[f64; 3]>]) -> Vec<(DVec3, DVec3)> {
    lines
        .iter()
        .flat_map(|line| {
            line.windows(2)
                .map(|w| (DVec3::from(w[0]), DVec3::from(w[1])))
        })
        .collect()
}

/// Points every `step` along the segments (both ends of each included).
fn sample(segments: &[(DVec3, DVec3)], step: f64) -> Vec<DVec3> {
    let mut points = Vec::new();
    for &(a, b) in segments {
        let n = (a.distance(b) / step).ceil().max(1.0) as usize;
        points.extend((0..=n).map(|i| a.lerp(b, i as f64 / n as f64)));
    }
    points
}

/// Mean and max distance from the points to the segments.
fn spread(points: &[DVec3], segments: &[(DVec3, DVec3)]) -> (f64, f64) {
    let distances: Vec<f64> = points
        .iter()
        .map(|&p| {
            segments
                .iter()
                .map(|&(a, b)| {
                    let ab = b - a;
                    let t = if ab.length_squared() > 0.0 {
                        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    p.distance(a + t * ab)
                })
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    let mean = distances.iter().sum::<f64>() / distances.len().max(1) as f64;
    (mean, distances.iter().copied().fold(0.0, f64::max))
}
