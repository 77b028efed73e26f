//! GeoTIFF reader, then meshing the grid: a result or an error, never a panic or an abort.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(grid) = geotracks_terrain::read_geotiff_bytes("fuzz.tif", data) {
        if grid.values().len() <= 1 << 16 {
            let _ = grid.to_mesh();
        }
    }
});
