//! OFF reader: any bytes give a mesh or an error, never a panic or an abort.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = geotracks::mesh::io::read_mesh_bytes("fuzz.off", data);
});
