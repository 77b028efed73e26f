//! Single-band GeoTIFF elevation grids (the `tiff` crate decodes; this reads the
//! georeference).
//!
//! Georeference: `ModelPixelScaleTag` (33550) and `ModelTiepointTag` (33922), or a
//! `ModelTransformationTag` (34264) without rotation. The raster type
//! (`GTRasterTypeGeoKey`, 1025, in the `GeoKeyDirectoryTag`) says what a raster
//! position means: `PixelIsArea` (the default) puts raster position (0, 0) at the
//! corner of the first pixel, so sample centres sit half a pixel in; `PixelIsPoint`
//! puts it at the first sample's centre. NODATA comes from `GDAL_NODATA` (42113); NaN
//! samples are missing too.
//!
//! Refused, with a message saying what to do: several bands, colour images, a rotated
//! or sheared transformation, no georeference at all (positions would be in pixels
//! and slopes meaningless), and geographic coordinates (x and y in degrees while
//! elevations are in metres; reproject first, e.g. `gdalwarp -t_srs EPSG:32632`).

use super::grid::{ElevationGrid, GridGeometry};
use super::TerrainError;
use std::io::{BufReader, Read, Seek};
use std::path::Path;
use tiff::decoder::{Decoder, DecodingResult, Limits};
use tiff::tags::Tag;
use tiff::ColorType;

/// The most any codec the reader accepts expands its data: deflate reaches 1032:1, LZW
/// (12-bit codes of at most 4096 bytes) less than 3641:1.
const MAX_RATIO: u64 = 4096;

/// `GTModelTypeGeoKey`: 2 is a geographic (latitude/longitude) coordinate system.
const MODEL_TYPE_KEY: u16 = 1024;
const MODEL_TYPE_GEOGRAPHIC: u16 = 2;
/// `GTRasterTypeGeoKey`: 1 is PixelIsArea, 2 PixelIsPoint.
const RASTER_TYPE_KEY: u16 = 1025;
const PIXEL_IS_POINT: u16 = 2;
/// `ProjectedCSTypeGeoKey`: the projected CRS's EPSG code.
const PROJECTED_CS_TYPE_KEY: u16 = 3072;

/// Reads a single-band GeoTIFF (8-, 16-, 32- or 64-bit integer or 32- or 64-bit float
/// samples; uncompressed, deflate or LZW; strips or tiles).
///
/// # Errors
/// [`TerrainError::Io`], [`TerrainError::Tiff`] for a file the decoder rejects,
/// [`TerrainError::Unsupported`] for what this reader refuses (see the module docs),
/// [`TerrainError::CellSize`], [`TerrainError::InvalidGrid`] for an infinite sample.
pub fn read_geotiff(path: impl AsRef<Path>) -> Result<ElevationGrid, TerrainError> {
    let path = path.as_ref();
    let io = |source| TerrainError::Io {
        path: path.to_path_buf(),
        source,
    };
    super::refuse_non_file(path)?;
    let file = std::fs::File::open(path).map_err(io)?;
    let file_len = file.metadata().map_err(io)?.len();
    read_geotiff_from(path, BufReader::new(file), file_len)
}

/// [`read_geotiff`] on a GeoTIFF held in memory; errors name `path`.
///
/// # Errors
/// As [`read_geotiff`].
pub fn read_geotiff_bytes(
    path: impl AsRef<Path>,
    bytes: &[u8],
) -> Result<ElevationGrid, TerrainError> {
    read_geotiff_from(
        path.as_ref(),
        std::io::Cursor::new(bytes),
        bytes.len() as u64,
    )
}

fn read_geotiff_from<R: Read + Seek>(
    path: &Path,
    mut file: R,
    file_len: u64,
) -> Result<ElevationGrid, TerrainError> {
    // The decoder sizes buffers from the header's claims (tag value counts, the image's
    // size) within its limits. Tag values cannot be larger than the file, so the first
    // directory is checked against the file's size before the decoder reads it, and
    // the limits are the file's size until the image itself is decoded.
    check_first_directory(path, &mut file, file_len)?;
    let (mut decoder, ncols, nrows) = open_image(path, file, file_len)?;
    let (pixel_is_point, epsg) = geo_keys(path, &mut decoder)?;
    let geometry = georeference(path, &mut decoder, ncols, nrows, pixel_is_point)?;
    let values = read_samples(path, &mut decoder, ncols, nrows)?;
    Ok(ElevationGrid::checked(geometry, values)?.with_epsg(epsg))
}

/// An error of the decoder's, naming what was being read (`context`).
fn tiff_error<'a>(
    path: &'a Path,
    context: &str,
) -> impl FnOnce(tiff::TiffError) -> TerrainError + 'a {
    let context = context.to_string();
    move |source| TerrainError::Tiff {
        path: path.to_path_buf(),
        context,
        source,
    }
}

/// An error of the decoder's while reading tag `tag`.
fn tag_error(path: &Path, tag: Tag) -> impl FnOnce(tiff::TiffError) -> TerrainError + '_ {
    tiff_error(path, &tag_name(tag))
}

/// What this reader refuses, in words.
fn unsupported(path: &Path, message: String) -> TerrainError {
    TerrainError::Unsupported {
        path: path.to_path_buf(),
        message,
    }
}

/// The decoder on the first image, with its size (columns, rows): one band, and no
/// more samples than the file can hold; its limits then let the image be decoded.
fn open_image<R: Read + Seek>(
    path: &Path,
    file: R,
    file_len: u64,
) -> Result<(Decoder<R>, u32, u32), TerrainError> {
    let file_limit = usize::try_from(file_len).unwrap_or(usize::MAX).max(1024);
    let mut limits = Limits::default();
    limits.decoding_buffer_size = file_limit;
    limits.ifd_value_size = file_limit;
    limits.intermediate_buffer_size = file_limit;
    let mut decoder = Decoder::new(file)
        .map_err(tiff_error(
            path,
            "reading the header and the first image directory",
        ))?
        .with_limits(limits.clone());
    let (ncols, nrows) = decoder.dimensions().map_err(tiff_error(
        path,
        "reading the image size (tags ImageWidth 256, ImageLength 257)",
    ))?;
    let colour = decoder.colortype().map_err(tiff_error(
        path,
        "reading the sample type (tags BitsPerSample 258, SampleFormat 339, \
         PhotometricInterpretation 262)",
    ))?;
    let bits = match colour {
        ColorType::Gray(bits) => bits,
        ColorType::Multiband { num_samples, .. } => {
            return Err(unsupported(path, format!(
                "the image has {num_samples} bands; an elevation grid has one (extract it, e.g. gdal_translate -b 1)"
            )))
        }
        other => {
            return Err(unsupported(
                path,
                format!(
                    "the image is {}, not a single band of elevations",
                    color_name(other)
                ),
            ))
        }
    };
    // Decoded samples cannot outnumber what the file holds, allowing for the best
    // compression any codec reaches (deflate at most 1032:1, LZW below 3641:1).
    let compressed = decoder
        .find_tag_unsigned::<u16>(Tag::Compression)
        .map_err(tag_error(path, Tag::Compression))?
        .is_some_and(|c| c != 1);
    let sample_bytes = u64::from(bits).div_ceil(8).max(1);
    let declared = u64::from(ncols) * u64::from(nrows);
    let at_most = file_len.saturating_mul(if compressed { MAX_RATIO } else { 1 }) / sample_bytes;
    if declared > at_most {
        return Err(TerrainError::ImplausibleSize {
            path: path.to_path_buf(),
            what: format!(
                "samples in the header (ImageWidth {ncols} × ImageLength {nrows}, {bits}-bit{})",
                if compressed { ", compressed" } else { "" }
            ),
            declared,
            bytes: file_len,
            at_most,
        });
    }
    limits.decoding_buffer_size = usize::try_from(declared * sample_bytes)
        .unwrap_or(usize::MAX)
        .max(file_limit);
    Ok((decoder.with_limits(limits), ncols, nrows))
}

/// From the GeoKey directory: whether samples are points (PixelIsPoint) rather than
/// areas, and the projected CRS's EPSG code; a grid in degrees is refused.
fn geo_keys<R: Read + Seek>(
    path: &Path,
    decoder: &mut Decoder<R>,
) -> Result<(bool, Option<u32>), TerrainError> {
    let geo_keys = decoder
        .find_tag(Tag::GeoKeyDirectoryTag)
        .map_err(tag_error(path, Tag::GeoKeyDirectoryTag))?
        .map(|v| v.into_u16_vec())
        .transpose()
        .map_err(tag_error(path, Tag::GeoKeyDirectoryTag))?
        .unwrap_or_default();
    let geo_key = |id: u16| -> Option<u16> {
        // Header of 4 shorts, then entries (key, location, count, value); location 0
        // means the value is inline.
        geo_keys
            .get(4..)?
            .chunks_exact(4)
            .find(|e| e[0] == id && e[1] == 0)
            .map(|e| e[3])
    };
    if geo_key(MODEL_TYPE_KEY) == Some(MODEL_TYPE_GEOGRAPHIC) {
        return Err(unsupported(
            path,
            "the grid is in geographic coordinates (degrees); distances and slopes need x, y in \
             the same unit as the elevations: reproject it first (e.g. gdalwarp -t_srs EPSG:<UTM zone>)"
                .into(),
        ));
    }
    let pixel_is_point = geo_key(RASTER_TYPE_KEY) == Some(PIXEL_IS_POINT);
    // An EPSG code, not 0 (undefined) or 32767 (user-defined: no code to name).
    let epsg = geo_key(PROJECTED_CS_TYPE_KEY)
        .filter(|&c| (1..32767).contains(&c))
        .map(u32::from);
    Ok((pixel_is_point, epsg))
}

/// Where the samples are: the georeference tags (pixel scale and tie point, or a
/// transformation without rotation) as the grid's geometry, north up.
fn georeference<R: Read + Seek>(
    path: &Path,
    decoder: &mut Decoder<R>,
    ncols: u32,
    nrows: u32,
    pixel_is_point: bool,
) -> Result<GridGeometry, TerrainError> {
    let f64_tag = |decoder: &mut Decoder<_>, tag| -> Result<Option<Vec<f64>>, TerrainError> {
        decoder
            .find_tag(tag)
            .map_err(tag_error(path, tag))?
            .map(|v| v.into_f64_vec())
            .transpose()
            .map_err(tag_error(path, tag))
    };
    let scale = f64_tag(decoder, Tag::ModelPixelScaleTag)?;
    let tie = f64_tag(decoder, Tag::ModelTiepointTag)?;
    let transform = f64_tag(decoder, Tag::ModelTransformationTag)?;
    // Raster position (i, j) maps to (x0 + i·sx, y0 − j·sy).
    let (x0, y0, sx, sy) = match (scale, tie, transform) {
        (Some(s), Some(t), _) if s.len() >= 2 && t.len() >= 6 => {
            (t[3] - t[0] * s[0], t[4] + t[1] * s[1], s[0], s[1])
        }
        (_, _, Some(m)) if m.len() >= 16 => {
            if m[1] != 0.0 || m[4] != 0.0 {
                return Err(unsupported(
                    path,
                    "the raster is rotated or sheared (ModelTransformationTag); warp it to a \
                     north-up grid first (gdalwarp)"
                        .into(),
                ));
            }
            (m[3], m[7], m[0], -m[5])
        }
        _ => {
            return Err(unsupported(
                path,
                "the TIFF has no georeference (ModelPixelScaleTag and ModelTiepointTag, or \
                 ModelTransformationTag): without it the sample spacing is unknown"
                    .into(),
            ))
        }
    };
    if sy < 0.0 && sx > 0.0 {
        return Err(unsupported(
            path,
            "the raster's rows run south to north (negative y scale); flip it to north-up first"
                .into(),
        ));
    }
    for value in [sx, sy] {
        if !(value.is_finite() && value > 0.0) {
            return Err(TerrainError::CellSize {
                path: Some(path.to_path_buf()),
                value,
            });
        }
    }
    // Raster position of the first sample's centre.
    let half = if pixel_is_point { 0.0 } else { 0.5 };
    let top_left = [x0 + half * sx, y0 - half * sy];
    let geometry = GridGeometry {
        ncols: ncols as usize,
        nrows: nrows as usize,
        lower_left: [top_left[0], top_left[1] - (nrows as f64 - 1.0) * sy],
        spacing: [sx, sy],
    };
    if !(geometry.lower_left[0].is_finite() && geometry.lower_left[1].is_finite()) {
        return Err(unsupported(path, "the georeference is not finite".into()));
    }
    Ok(geometry)
}

/// The NODATA value (tag GDAL_NODATA), then the image decoded: its samples as `f64`,
/// NODATA ones as NaN.
fn read_samples<R: Read + Seek>(
    path: &Path,
    decoder: &mut Decoder<R>,
    ncols: u32,
    nrows: u32,
) -> Result<Vec<f64>, TerrainError> {
    let nodata = decoder
        .find_tag(Tag::GdalNodata)
        .map_err(tag_error(path, Tag::GdalNodata))?
        .and_then(|v| v.into_string().ok())
        .and_then(|s| {
            s.trim_matches(|c: char| c == '\0' || c.is_whitespace())
                .parse::<f64>()
                .ok()
        });

    let samples = match decoder.read_image() {
        Ok(samples) => samples,
        Err(source) => {
            let context = failing_chunk(decoder)
                .unwrap_or_else(|| format!("decoding the image ({ncols} × {nrows} samples)"));
            return Err(TerrainError::Tiff {
                path: path.to_path_buf(),
                context,
                source,
            });
        }
    };
    let single = matches!(samples, DecodingResult::F32(_));
    let values: Vec<f64> = match samples {
        DecodingResult::U8(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::U16(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::U32(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::U64(v) => v.into_iter().map(|x| x as f64).collect(),
        DecodingResult::I8(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::I16(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::I32(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::I64(v) => v.into_iter().map(|x| x as f64).collect(),
        DecodingResult::F16(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::F32(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::F64(v) => v,
    };
    Ok(values
        .into_iter()
        .map(|z| match nodata {
            // GDAL writes the NODATA value as decimal text, which may not round-trip
            // to the f64 of an f32 sample: compare f32 samples at their own precision.
            Some(n) if z == n || (single && (z as f32) == (n as f32)) => f64::NAN,
            _ => z,
        })
        .collect())
}

/// A colour type in words, for messages.
fn color_name(color: ColorType) -> String {
    match color {
        ColorType::RGB(bits) => format!("an RGB image ({bits}-bit)"),
        ColorType::RGBA(bits) => format!("an RGBA image ({bits}-bit)"),
        ColorType::GrayA(bits) => format!("a grey image with alpha ({bits}-bit)"),
        ColorType::CMYK(bits) => format!("a CMYK image ({bits}-bit)"),
        ColorType::CMYKA(bits) => format!("a CMYK image with alpha ({bits}-bit)"),
        ColorType::YCbCr(bits) => format!("a YCbCr image ({bits}-bit)"),
        ColorType::Palette(bits) => format!("a palette image ({bits}-bit)"),
        _ => "a colour image".to_string(),
    }
}

/// A tag as messages name it: its name in the specification and its number.
fn tag_name(tag: Tag) -> String {
    format!("reading tag {tag:?} ({})", tag.to_u16())
}

/// After the image failed to decode, which strip or tile fails on its own, as "reading
/// strip 3 of 8 (at byte 1234, 567 bytes)"; `None` if none does (or the layout itself
/// cannot be read). Only run on the error path: it decodes chunks again one by one.
fn failing_chunk<R: Read + Seek>(decoder: &mut Decoder<R>) -> Option<String> {
    use tiff::decoder::ChunkType;
    let (kind, count, offsets, sizes) = match decoder.get_chunk_type() {
        ChunkType::Strip => (
            "strip",
            decoder.strip_count().ok()?,
            Tag::StripOffsets,
            Tag::StripByteCounts,
        ),
        ChunkType::Tile => (
            "tile",
            decoder.tile_count().ok()?,
            Tag::TileOffsets,
            Tag::TileByteCounts,
        ),
    };
    let offsets = decoder.get_tag_u64_vec(offsets).ok();
    let sizes = decoder.get_tag_u64_vec(sizes).ok();
    let at =
        |list: &Option<Vec<u64>>, i: u32| list.as_ref().and_then(|l| l.get(i as usize).copied());
    (0..count).find_map(|i| {
        decoder.read_chunk(i).err().map(|_| {
            let place = match (at(&offsets, i), at(&sizes, i)) {
                (Some(offset), Some(size)) => format!(" (at byte {offset}, {size} bytes)"),
                (Some(offset), None) => format!(" (at byte {offset})"),
                _ => String::new(),
            };
            format!("reading {kind} {i} of {count}{place}")
        })
    })
}

/// Checks the first image directory's entries against the file's size: a directory of
/// more entries than the file holds, or a tag whose values would take more bytes than
/// the file has, is refused before the decoder reads (and sizes buffers for) it.
fn check_first_directory<R: Read + Seek>(
    path: &Path,
    file: &mut R,
    file_len: u64,
) -> Result<(), TerrainError> {
    use std::io::SeekFrom;
    let io = |source| TerrainError::Io {
        path: path.to_path_buf(),
        source,
    };
    let lie = |what: String, declared: u64, at_most: u64| TerrainError::ImplausibleSize {
        path: path.to_path_buf(),
        what,
        declared,
        bytes: file_len,
        at_most,
    };
    let cut = |offset: u64| TerrainError::Parse {
        path: path.to_path_buf(),
        line: 0,
        message: format!(
            "the first image directory (at byte {offset}) is cut off: the file ends inside it"
        ),
    };
    let mut head = [0u8; 16];
    let n = file.read(&mut head).map_err(io)?;
    let big_endian = match &head[..2.min(n)] {
        b"II" => false,
        b"MM" => true,
        // Not a TIFF: the decoder says so in its own words.
        _ => return file.seek(SeekFrom::Start(0)).map(drop).map_err(io),
    };
    let order = ByteOrder { big_endian };
    let (u16_at, u32_at, u64_at) = (
        |b: &[u8]| order.u16(b),
        |b: &[u8]| order.u32(b),
        |b: &[u8]| order.u64(b),
    );
    let bigtiff = n >= 4 && u16_at(&head[2..4]) == 43;
    let offset = match (bigtiff, n) {
        (false, 8..) => u64::from(u32_at(&head[4..8])),
        (true, 16..) => u64_at(&head[8..16]),
        _ => return file.seek(SeekFrom::Start(0)).map(drop).map_err(io),
    };
    let (count_size, entry_size) = if bigtiff { (8, 20) } else { (2, 12) };
    if offset.saturating_add(count_size) <= file_len {
        file.seek(SeekFrom::Start(offset)).map_err(io)?;
        let mut count = [0u8; 8];
        file.read_exact(&mut count[..count_size as usize])
            .map_err(|_| cut(offset))?;
        let entries = if bigtiff {
            u64_at(&count)
        } else {
            u64::from(u16_at(&count))
        };
        let room = (file_len - offset - count_size) / entry_size;
        if entries > room {
            return Err(lie(
                format!("entries of the first image directory (at byte {offset})"),
                entries,
                room,
            ));
        }
        let mut entry = [0u8; 20];
        for _ in 0..entries {
            file.read_exact(&mut entry[..entry_size as usize])
                .map_err(|_| cut(offset))?;
            let tag = u16_at(&entry[0..2]);
            let value_size: u64 = match u16_at(&entry[2..4]) {
                1 | 2 | 6 | 7 => 1,
                3 | 8 => 2,
                4 | 9 | 11 | 13 => 4,
                5 | 10 | 12 | 16 | 17 | 18 => 8,
                _ => continue, // unknown types are the decoder's to judge
            };
            let values = if bigtiff {
                u64_at(&entry[4..12])
            } else {
                u64::from(u32_at(&entry[4..8]))
            };
            if values.saturating_mul(value_size) > file_len {
                return Err(lie(
                    format!("values of tag {tag} ({value_size} bytes each)"),
                    values,
                    file_len / value_size,
                ));
            }
        }
    }
    file.seek(SeekFrom::Start(0)).map(drop).map_err(io)
}

/// The byte order of a TIFF's numbers (`II`: little-endian, `MM`: big-endian), to read
/// its header and directory entries before the decoder does.
#[derive(Clone, Copy)]
struct ByteOrder {
    big_endian: bool,
}

impl ByteOrder {
    /// The `u16` in the first 2 bytes of `b`.
    fn u16(self, b: &[u8]) -> u16 {
        let a = [b[0], b[1]];
        if self.big_endian {
            u16::from_be_bytes(a)
        } else {
            u16::from_le_bytes(a)
        }
    }

    /// The `u32` in the first 4 bytes of `b`.
    fn u32(self, b: &[u8]) -> u32 {
        let a = [b[0], b[1], b[2], b[3]];
        if self.big_endian {
            u32::from_be_bytes(a)
        } else {
            u32::from_le_bytes(a)
        }
    }

    /// The `u64` in the first 8 bytes of `b`.
    fn u64(self, b: &[u8]) -> u64 {
        let a = [b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]];
        if self.big_endian {
            u64::from_be_bytes(a)
        } else {
            u64::from_le_bytes(a)
        }
    }
}
