//! PLY reader on binary payloads: the first byte picks the byte order, the rest follows `ply\nformat binary_…_endian 1.0\n`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&order, rest)) = data.split_first() else {
        return;
    };
    let format: &[u8] = if order & 1 == 0 {
        b"ply\nformat binary_little_endian 1.0\n"
    } else {
        b"ply\nformat binary_big_endian 1.0\n"
    };
    let mut bytes = format.to_vec();
    bytes.extend_from_slice(rest);
    let _ = geotracks::mesh::io::read_mesh_bytes("fuzz.ply", &bytes);
});
