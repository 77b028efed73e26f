//! STL reader on ascii files: the input follows `solid `.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut bytes = b"solid ".to_vec();
    bytes.extend_from_slice(data);
    let _ = geotracks::mesh::io::read_mesh_bytes("fuzz.stl", &bytes);
});
