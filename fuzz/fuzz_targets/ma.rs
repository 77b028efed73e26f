//! Medial-axis (.ma) reader, with and without a surface: a result or an error, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = geotracks::mesh::io::read_medial_axis_bytes("fuzz.ma", data);
    let _ = geotracks::mesh::io::read_mesh_bytes("fuzz.ma", data);
});
