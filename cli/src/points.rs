//! Surface points on the command line (`V`, `e:E:t`, `f:F:b0,b1,b2`): the help text, and
//! checks against the mesh whose errors name the argument.

use crate::CliResult;
use geotracks::mesh::TriMesh;
use geotracks::{Error, PointError, Source, SurfacePoint};

/// The syntax of a surface point, shown after the options of the commands that take one.
pub const SP_HELP: &str = "\
Surface points (SP):
  V             vertex V (0-based id)
  e:E:t         edge E at parameter t in [0, 1], from its lower-id vertex
  f:F:b0,b1,b2  face F at barycentric coordinates b0,b1,b2 (in the face's vertex
                order; each >= 0, summing to 1)
Face and edge ids refer to the mesh as geotracks reads it: polygons fan-triangulated and
degenerate faces (zero area, repeated vertex) dropped, so face ids can differ from the
file's face numbering. Edges are numbered in the order of their (lower, higher)
vertex-id pairs.";

/// Checks a point given as `--{arg}` against `mesh`; the error names the argument.
pub fn check(mesh: &TriMesh, arg: &str, point: SurfacePoint) -> CliResult<SurfacePoint> {
    point
        .validated(mesh)
        .map_err(|e| format!("--{arg} {point}: {e}").into())
}

/// The `--source` points as sources starting from 0, each checked against `mesh`. A
/// vertex id out of range gives the error it always gave.
pub fn sources(mesh: &TriMesh, points: &[SurfacePoint]) -> CliResult<Vec<Source>> {
    points
        .iter()
        .map(|&point| match point.validated(mesh) {
            Ok(_) => Ok(Source::new(point)),
            Err(PointError::NoSuchVertex { vertex, count }) => Err(Error::SourceOutOfRange {
                vertex: vertex as u64,
                vertex_count: count,
            }
            .into()),
            Err(e) => Err(format!("--source {point}: {e}").into()),
        })
        .collect()
}
