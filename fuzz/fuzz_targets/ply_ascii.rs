//! PLY reader on ascii payloads: the input follows `ply\nformat ascii 1.0\n`, so the fuzzer spends its time on elements, properties and records.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut bytes = b"ply\nformat ascii 1.0\n".to_vec();
    bytes.extend_from_slice(data);
    let _ = geotracks::mesh::io::read_mesh_bytes("fuzz.ply", &bytes);
});
