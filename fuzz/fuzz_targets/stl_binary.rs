//! STL reader on binary files: the input follows an 80-byte header of zeros, so it starts with the triangle count.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut bytes = vec![0u8; 80];
    bytes.extend_from_slice(data);
    let _ = geotracks::mesh::io::read_mesh_bytes("fuzz.stl", &bytes);
});
