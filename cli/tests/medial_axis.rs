//! `geotracks medial-axis`, and `geotracks skeleton` on a surface mesh: outputs that
//! read back, and surfaces that bound no solid refused with nothing written.

mod support;

use support::{assert_fails, geotracks_ok};

const SPOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/spot.obj");

#[test]
fn the_medial_axis_of_spot_reads_back_and_skeletonizes() {
    let dir = tempfile::tempdir().unwrap();
    let ma = dir.path().join("spot.ma");
    let png = dir.path().join("spot.png");
    let out = geotracks_ok(&[
        "medial-axis",
        SPOT,
        "-o",
        ma.to_str().unwrap(),
        "--png",
        png.to_str().unwrap(),
        "--size",
        "200x150",
    ]);
    let summary = String::from_utf8_lossy(&out.stderr);
    assert!(summary.contains("1 component(s)"), "{summary}");
    let axis = geotracks::mesh::io::read_medial_axis(&ma).unwrap();
    assert!(axis.surface.as_ref().unwrap().face_count() > 1000);
    assert!(axis.radii.iter().all(|&r| r > 0.0 && r < 1.0));
    assert!(std::fs::metadata(&png).unwrap().len() > 0);
    // The skeleton straight from the mesh: one tree (Spot has no handle).
    let json = dir.path().join("spot.json");
    let out = geotracks_ok(&["skeleton", SPOT, "-o", json.to_str().unwrap()]);
    let summary = String::from_utf8_lossy(&out.stderr);
    assert!(
        summary.contains("0 cycle(s) (the solid has b1 = 0)"),
        "{summary}"
    );
    let graph: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(graph["components"], 1);
    assert_eq!(graph["cycles"], 0);
    // Its points are centred by default, from the mesh and from the axis written as a
    // file alike.
    let read = |path: &std::path::Path| std::fs::read_to_string(path).unwrap();
    let placed = |input: &str, flag: Option<&str>, name: &str| {
        let path = dir.path().join(name);
        let mut args = vec!["skeleton", input, "-o", path.to_str().unwrap()];
        args.extend(flag);
        geotracks_ok(&args);
        read(&path)
    };
    let default = read(&json);
    assert_eq!(default, placed(SPOT, Some("--centred"), "centred.json"));
    assert_ne!(default, placed(SPOT, Some("--on-axis"), "on_axis.json"));
    let ma = ma.to_str().unwrap();
    assert_eq!(
        placed(ma, None, "axis.json"),
        placed(ma, Some("--centred"), "axis_centred.json")
    );
    assert_ne!(
        placed(ma, None, "axis.json"),
        placed(ma, Some("--on-axis"), "axis_on_axis.json")
    );
    let both = dir.path().join("both.json");
    assert_fails(
        &[
            "skeleton",
            SPOT,
            "--centred",
            "--on-axis",
            "-o",
            both.to_str().unwrap(),
        ],
        &both,
        "cannot be used with",
    );
}

#[test]
fn surfaces_that_bound_no_solid_fail_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let ma = dir.path().join("axis.ma");
    let m = ma.to_str().unwrap();
    let open = dir.path().join("open.obj");
    std::fs::write(
        &open,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\n",
    )
    .unwrap();
    let open = open.to_str().unwrap();
    assert_fails(&["medial-axis", open, "-o", m], &ma, "not closed");
    let obj = dir.path().join("skeleton.obj");
    assert_fails(
        &["skeleton", open, "-o", obj.to_str().unwrap()],
        &obj,
        "not closed",
    );
    assert_fails(
        &["medial-axis", SPOT, "--angle", "0", "-o", m],
        &ma,
        "--angle",
    );
    assert_fails(
        &["medial-axis", SPOT, "--spacing=-1", "-o", m],
        &ma,
        "--spacing",
    );
    assert_fails(
        &["medial-axis", SPOT, "--span", "nan", "-o", m],
        &ma,
        "--span",
    );
    let txt = dir.path().join("axis.txt");
    assert_fails(
        &["medial-axis", SPOT, "-o", txt.to_str().unwrap()],
        &txt,
        "unknown output format",
    );
    assert_fails(
        &["medial-axis", SPOT, "--spacing", "1e-5", "-o", m],
        &ma,
        "more than the",
    );
}
