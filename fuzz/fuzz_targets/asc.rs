//! ESRI ASCII grid reader, then meshing the grid: a result or an error, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(grid) = geotracks_terrain::read_asc_bytes("fuzz.asc", data) {
        // Small grids only: a big valid grid is no bug, just slow.
        if grid.values().len() <= 1 << 16 {
            let _ = grid.to_mesh();
        }
    }
});
