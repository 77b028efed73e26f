//! Medial axes of closed surfaces, from the Voronoi diagram of points sampled on them.
//!
//! The medial axis of a solid is the set of centres of its maximal inscribed balls. For
//! points sampled densely on the solid's boundary, the Voronoi vertices inside the solid
//! (the *inner poles* among them) lie near the medial axis, and the Voronoi facets
//! between far-apart samples approximate its sheets (Amenta, Choi & Kolluri, "The power
//! crust", 2001; Dey & Zhao, "Approximating the medial axis from the Voronoi diagram
//! with a convergence guarantee", 2004). So:
//!
//! 1. the surface is checked closed (every edge between two faces) and its faces turned
//!    outward;
//! 2. its vertices are sampled, with points added where its faces are larger than the
//!    sampling [`MedialAxisOptions::spacing`] (the poles need samples denser than the
//!    shape's features);
//! 3. their 3D Delaunay tetrahedralization gives the Voronoi vertices (circumcentres,
//!    in double-double arithmetic), each kept when it lies inside: where the surface's
//!    winding number is more than ½ (the samples on faces that lie inside the solid,
//!    where parts of the surface run through each other, are left out first);
//! 4. the Voronoi facets (one per Delaunay edge `p q`) whose vertices are all inside
//!    make the inner Voronoi diagram, which has the solid's topology on a dense enough
//!    sampling; a facet is a spike toward the surface, made by the sampling, when no
//!    vertex `c` of it sees `p q` under [`MedialAxisOptions::min_angle_degrees`], when
//!    its deepest vertex (the largest ball, where a spike meets the axis) sees it
//!    under less than half that, or when `p` and `q` are less than
//!    [`MedialAxisOptions::min_span`] spacings apart (a medial ball touches the surface
//!    at two far-apart points; for two samples facing each other across a thin part,
//!    when the part is thinner than [`MedialAxisOptions::MIN_ACROSS`] spacings).
//!    Spikes are removed only through a free edge, one after
//!    the other (elementary collapses), so the filter opens no hole and splits
//!    nothing: the axis keeps the topology of the inner Voronoi diagram, which is the
//!    solid's where the sampling is dense for the shape (where a part is only a few
//!    samples across, small cycles remain);
//! 5. circumcentres closer than rounding can tell apart (five samples or more on one
//!    sphere: a grid on a flat face, the corners of a mesh's planar quads) are one
//!    vertex, and the facets around it are split at the vertices along their sides and
//!    cut into triangles that are never flat, so that they fit without holes.
//!
//! The result is a [`MedialAxis`] with the circumradius as each vertex's medial radius,
//! ready for
//! [`medial_axis_skeleton_with_cycles`](crate::skeleton::medial_axis_skeleton_with_cycles)
//! (with the solid's [`solid_cycles`], which cuts the few cycles a coarse sampling
//! leaves).
//!
//! The inside test is the solid's own (the winding number, summed with a
//! bounding-volume hierarchy), not the samples' normals: it holds at sharp creases,
//! and a surface whose parts run through each other gets the axis of their union.
//!
//! ```
//! use geotracks::skeleton::medial::{medial_axis, MedialAxisOptions};
//! use geotracks::mesh::TriMesh;
//! // A box 4 × 1 × 1: its medial axis is a sheet along its length, with wedges at the
//! // ends.
//! let (x, y, z) = (4.0, 1.0, 1.0);
//! let positions = vec![
//!     [0.0, 0.0, 0.0], [x, 0.0, 0.0], [x, y, 0.0], [0.0, y, 0.0],
//!     [0.0, 0.0, z], [x, 0.0, z], [x, y, z], [0.0, y, z],
//! ];
//! let triangles = vec![
//!     [0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
//!     [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7],
//! ];
//! let mesh = TriMesh::new(positions, triangles)?;
//! let options = MedialAxisOptions::default().with_spacing(Some(0.1));
//! let axis = medial_axis(&mesh, &options)?;
//! // Every medial ball lies in the box and is about half its thickness wide at most (a
//! // ball empty of samples 0.1 apart can bulge out between them a little).
//! assert!(axis.radii.iter().all(|&r| r <= 0.5 + 0.01));
//! assert!(axis.positions.iter().all(|p| p[0] > 0.0 && p[0] < x && p[2] > 0.0 && p[2] < z));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod delaunay;
mod facets;
mod surface;
mod voronoi;
mod winding;

use crate::mesh::io::MedialAxis;
use crate::mesh::{MeshError, TriMesh};
use crate::Error;
use thiserror::Error as ThisError;

/// How [`medial_axis`] samples the surface and which Voronoi facets it keeps.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct MedialAxisOptions {
    /// The largest distance between neighbouring samples along a face's sides and
    /// across it; `None`: the mesh's mean edge length (only faces larger than usual get
    /// points added). Smaller gives a finer, more accurate axis for more time.
    pub spacing: Option<f64>,
    /// The smallest angle (degrees, in (0, 180)) under which a kept Voronoi facet's
    /// Delaunay edge is seen from one of its vertices; from its deepest vertex (the
    /// largest ball), it must be seen under at least half that. Larger drops more of
    /// the spikes toward the surface and, past a point, parts of the axis where the
    /// shape narrows quickly.
    pub min_angle_degrees: f64,
    /// The shortest distance (in units of the spacing) between the two samples a kept
    /// Voronoi facet separates. A medial ball touches the surface at points far apart;
    /// facets between samples a spacing or so apart are the sampling's, and go (where
    /// they can go without changing the axis's topology). Larger cleans more and eats
    /// the axis back more where the shape thins out (tips of limbs). Two samples that
    /// face each other (their normals turned by more than 180° less the angle) are the
    /// two sides of a thin part, not neighbours: their facet stays if the part is at
    /// least [`MedialAxisOptions::MIN_ACROSS`] spacings thick between them (or this,
    /// if smaller), and a horn or a tail about a spacing thick keeps its axis.
    pub min_span: f64,
    /// The most samples the surface may get: a `spacing` that needs more is refused
    /// before any work.
    pub max_samples: u64,
}

impl MedialAxisOptions {
    /// The default smallest angle, in degrees.
    pub const DEFAULT_MIN_ANGLE_DEGREES: f64 = 60.0;

    /// The default shortest span, in units of the spacing.
    pub const DEFAULT_MIN_SPAN: f64 = 1.5;

    /// The thinnest part, in units of the spacing, whose two sides' samples (facing
    /// each other) keep the facet between them: its thickness between them, measured
    /// along their normals (see [`MedialAxisOptions::min_span`]). A thinner part is not
    /// resolved by the sampling: its few facets are a crude sketch of its axis, and
    /// going, they leave the part without one (or the whole axis empty, an error that
    /// names the spacing to lower). On the shared cow's mesh, sampled at its mean edge
    /// length, the horns are 0.7 to 1.2 spacings across. Measured, not derived: at ½,
    /// an L-shaped plate 0.5 thick sampled every 1.7 kept an axis along one arm only;
    /// at 1, the cow's horns lost theirs.
    pub const MIN_ACROSS: f64 = 0.75;

    /// Sets [`MedialAxisOptions::min_span`].
    #[must_use]
    pub fn with_min_span(mut self, span: f64) -> Self {
        self.min_span = span;
        self
    }

    /// Sets [`MedialAxisOptions::spacing`].
    #[must_use]
    pub fn with_spacing(mut self, spacing: Option<f64>) -> Self {
        self.spacing = spacing;
        self
    }

    /// Sets [`MedialAxisOptions::min_angle_degrees`].
    #[must_use]
    pub fn with_min_angle_degrees(mut self, degrees: f64) -> Self {
        self.min_angle_degrees = degrees;
        self
    }

    /// Checks the options that are given (a spacing of `None` is the mesh's to choose).
    ///
    /// # Errors
    /// [`MedialAxisError::InvalidOption`] for an angle outside (0, 180), a span that is
    /// negative or not finite, or a spacing that is not positive and finite.
    pub fn validate(&self) -> Result<(), MedialAxisError> {
        let invalid = |option, value, expected| {
            Err(MedialAxisError::InvalidOption {
                option,
                value,
                expected,
            })
        };
        let angle = self.min_angle_degrees;
        if !(angle > 0.0 && angle < 180.0) {
            return invalid(
                "min_angle_degrees",
                angle,
                "an angle in degrees between 0 and 180",
            );
        }
        if !(self.min_span >= 0.0 && self.min_span.is_finite()) {
            return invalid(
                "min_span",
                self.min_span,
                "a finite number >= 0 (in units of the spacing)",
            );
        }
        match self.spacing {
            Some(s) if !(s > 0.0 && s.is_finite()) => {
                invalid("spacing", s, "a positive, finite length")
            }
            _ => Ok(()),
        }
    }

    /// Sets [`MedialAxisOptions::max_samples`].
    #[must_use]
    pub fn with_max_samples(mut self, max: u64) -> Self {
        self.max_samples = max;
        self
    }
}

impl Default for MedialAxisOptions {
    fn default() -> Self {
        Self {
            spacing: None,
            min_angle_degrees: Self::DEFAULT_MIN_ANGLE_DEGREES,
            min_span: Self::DEFAULT_MIN_SPAN,
            max_samples: 5_000_000,
        }
    }
}

/// Why a medial axis could not be computed from a surface.
#[derive(Debug, ThisError)]
#[non_exhaustive]
pub enum MedialAxisError {
    /// The surface has a border: it bounds no solid.
    #[error(
        "the surface is not closed: edge ({}, {}) has one face; a medial axis needs the \
         closed boundary of a solid (fill the holes, or weld vertices that seams split)",
        edge[0], edge[1]
    )]
    OpenSurface {
        /// The edge's vertices.
        edge: [u32; 2],
    },
    /// An edge has more than two faces: the surface is no solid's boundary.
    #[error("edge ({}, {}) has {faces} faces; a medial axis needs a surface where every edge joins two", edge[0], edge[1])]
    NonManifoldSurface {
        /// The edge's vertices.
        edge: [u32; 2],
        /// How many faces it has.
        faces: usize,
    },
    /// No winding of the faces agrees across every edge (a Klein bottle): the surface
    /// has no inside.
    #[error("the surface cannot be oriented (face {face} disagrees with itself around a loop): it has no inside")]
    NonOrientableSurface {
        /// A face where the disagreement was found.
        face: u32,
    },
    /// An option is out of range.
    #[error("medial axis option {option} is {value}; it must be {expected}")]
    InvalidOption {
        /// The option's name.
        option: &'static str,
        /// The value given.
        value: f64,
        /// What it must be.
        expected: &'static str,
    },
    /// The sampling would take more points than allowed.
    #[error(
        "sampling the surface every {spacing} would take {samples} points, more than the \
         {max} allowed: use a larger spacing"
    )]
    TooManySamples {
        /// The spacing asked for (or the default).
        spacing: f64,
        /// How many points it would take.
        samples: u64,
        /// The limit.
        max: u64,
    },
    /// The spacing is finer than the mesh's coordinates can place points: far from the
    /// origin, rounding moves a sample by more than the small steps the method takes
    /// against the spacing (a thousandth of it, to tell the surface's two sides apart),
    /// and the axis would be noise.
    #[error(
        "samples every {spacing} are finer than coordinates as large as {magnitude} can \
         place: use a spacing of at least {least}, or move the mesh near the origin"
    )]
    SpacingBelowResolution {
        /// The spacing asked for (or the default).
        spacing: f64,
        /// The largest coordinate's magnitude.
        magnitude: f64,
        /// The finest spacing those coordinates allow.
        least: f64,
    },
    /// The samples span no volume (a flat surface), or fewer than four are distinct.
    #[error("the surface encloses no volume: {0}")]
    Flat(String),
    /// No Voronoi facet inside the surface passed the angle test.
    #[error(
        "no part of the medial axis was kept ({inner} Voronoi vertices inside): samples \
         every {spacing} are too coarse for the shape (use a smaller spacing, a few \
         samples across its thinnest part), or the angle {min_angle_degrees}° is too large"
    )]
    Empty {
        /// How many Voronoi vertices lay inside.
        inner: usize,
        /// The spacing of the samples (the one given, or the mesh's mean edge length).
        spacing: f64,
        /// The angle used.
        min_angle_degrees: f64,
    },
}

/// The medial axis of the solid that the closed surface `mesh` bounds: its sheets with
/// the medial ball radius at each vertex (see the [module](self) for the method).
///
/// Wires (line elements) of the mesh are ignored, as are vertices no face uses.
///
/// # Errors
/// [`Error::MedialAxis`] with [`MedialAxisError::OpenSurface`],
/// [`MedialAxisError::NonManifoldSurface`] or
/// [`MedialAxisError::NonOrientableSurface`] for a surface that bounds no solid,
/// [`MedialAxisError::InvalidOption`] for a spacing that is not positive and finite or
/// an angle outside (0, 180), [`MedialAxisError::TooManySamples`] for a spacing too
/// fine, [`MedialAxisError::SpacingBelowResolution`] for one finer than the
/// coordinates' rounding allows, [`MedialAxisError::Flat`] for a surface with no volume and
/// [`MedialAxisError::Empty`] when nothing inside passes the angle test.
pub fn medial_axis(mesh: &TriMesh, options: &MedialAxisOptions) -> Result<MedialAxis, Error> {
    options.validate()?;
    let angle = options.min_angle_degrees;
    // The mean edge length of a mesh, which has a face of non-zero area: positive.
    let spacing = options.spacing.unwrap_or_else(|| mesh.mean_edge_length());
    // Samples step a thousandth of the spacing outward (below) to tell which faces lie
    // inside the solid: that step must stay a thousand times the coordinates' rounding.
    let magnitude = mesh
        .positions()
        .iter()
        .flat_map(|p| p.to_array())
        .fold(0.0, |m: f64, x| m.max(x.abs()));
    let least = 1e6 * f64::EPSILON * magnitude;
    if spacing < least {
        return Err(MedialAxisError::SpacingBelowResolution {
            spacing,
            magnitude,
            least,
        }
        .into());
    }
    let count = surface::sample_count(mesh, spacing);
    if count > options.max_samples {
        return Err(MedialAxisError::TooManySamples {
            spacing,
            samples: count,
            max: options.max_samples,
        }
        .into());
    }
    let triangles = surface::outward_triangles(mesh)?;
    let solid = winding::WindingNumbers::new(triangles.iter().map(|t| t.map(|v| mesh.position(v))));
    // A step small against the sampling, far above rounding.
    let samples =
        surface::samples(mesh, &triangles, spacing).on_the_boundary(&solid, 1e-3 * spacing);
    let dt = delaunay::tetrahedralize(&samples.points)
        .map_err(|e| MedialAxisError::Flat(e.to_string()))?;
    let filter = voronoi::SpikeFilter {
        min_angle: angle.to_radians(),
        min_span: options.min_span * spacing,
        // A part thinner than this has no two samples across it that the sampling
        // can tell from neighbours: sampled too coarsely for the shape (the error
        // below says so when nothing is kept).
        min_across: (options.min_span * spacing).min(MedialAxisOptions::MIN_ACROSS * spacing),
    };
    let inner = voronoi::inner_axis(&samples, &dt, &solid, filter);
    // Nothing kept: no usable face nor curve for the axis.
    let empty = MedialAxisError::Empty {
        inner: inner.inner_vertices,
        spacing,
        min_angle_degrees: angle,
    };
    MedialAxis::from_parts(inner.positions, inner.radii, inner.triangles, inner.curves).map_err(
        |e| match e {
            MeshError::NoUsableFace { .. } => empty.into(),
            e => e.into(),
        },
    )
}

/// How many independent cycles the solid that the closed surface `mesh` bounds has
/// (its handles: half the surface's first Betti number), which is what its medial
/// axis and curve skeleton have; the axis [`medial_axis`] computes has more (small holes
/// where its sheets are thin), which
/// [`medial_axis_skeleton_with_cycles`](crate::skeleton::medial_axis_skeleton_with_cycles)
/// cuts.
pub fn solid_cycles(mesh: &TriMesh) -> usize {
    mesh.betti_numbers().b1 / 2
}

/// The medial axis a file gives, and how many cycles its skeleton should have when
/// that is known: a `.ma` file (by its extension, any case) is read as it is
/// ([`read_medial_axis`](crate::mesh::io::read_medial_axis); no limit), any other mesh
/// file is read (welding vertices at identical positions if `weld`) and its
/// [`medial_axis`] computed with `options` (the limit: [`solid_cycles`]).
///
/// # Errors
/// The reader's ([`Error::Mesh`]) or [`medial_axis`]'s.
pub fn medial_axis_of_file(
    path: impl AsRef<std::path::Path>,
    weld: bool,
    options: &MedialAxisOptions,
) -> Result<(MedialAxis, Option<usize>), Error> {
    let path = path.as_ref();
    if crate::mesh::io::is_medial_axis_path(path) {
        return Ok((crate::mesh::io::read_medial_axis(path)?, None));
    }
    let read = crate::mesh::io::ReadOptions::DEFAULT.with_weld(weld);
    let mesh = crate::mesh::io::read_mesh_with(path, &read)?;
    Ok((medial_axis(&mesh, options)?, Some(solid_cycles(&mesh))))
}
