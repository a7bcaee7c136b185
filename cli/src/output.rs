//! PNG encoding (still and animated) and writing files so that nothing is ever half-written:
//! each file is written to a temporary file beside its target, flushed to disk and renamed
//! into place.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

use crate::Failure;
use crate::image::{Image, Pixels};

/// The PNG colour type and bit depth of a picture, and its bytes in PNG order.
fn png_format(image: &Image) -> (png::ColorType, png::BitDepth, Vec<u8>) {
    match &image.pixels {
        Pixels::Gray8(p) => (png::ColorType::Grayscale, png::BitDepth::Eight, p.clone()),
        Pixels::Gray16(p) => {
            (png::ColorType::Grayscale, png::BitDepth::Sixteen, p.iter().flat_map(|v| v.to_be_bytes()).collect())
        }
        Pixels::Rgb8(p) => (png::ColorType::Rgb, png::BitDepth::Eight, p.clone()),
    }
}

/// The encoder for pictures like `image`.
fn encoder<'w>(image: &Image, out: &'w mut Vec<u8>) -> png::Encoder<'w, &'w mut Vec<u8>> {
    let (colour, depth, _) = png_format(image);
    let mut e = png::Encoder::new(out, image.width, image.height);
    e.set_color(colour);
    e.set_depth(depth);
    e.set_compression(png::Compression::Balanced);
    if colour == png::ColorType::Rgb {
        e.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
    }
    e
}

/// A PNG file's bytes.
pub fn encode_png(image: &Image) -> Vec<u8> {
    let mut out = Vec::new();
    let (_, _, data) = png_format(image);
    let mut writer = encoder(image, &mut out).write_header().expect("writing to memory cannot fail");
    writer.write_image_data(&data).expect("the data matches the header");
    writer.finish().expect("writing to memory cannot fail");
    out
}

/// An animated PNG's bytes: `frames` (all of one size and format), each shown `delay_ms`,
/// looping forever. Viewers without APNG support show the first frame.
pub fn encode_apng(frames: &[Image], delay_ms: u16) -> Vec<u8> {
    let mut out = Vec::new();
    let first = &frames[0];
    let mut e = encoder(first, &mut out);
    e.set_animated(frames.len() as u32, 0).expect("at least one frame");
    e.set_frame_delay(delay_ms, 1000).expect("valid delay");
    let mut writer = e.write_header().expect("writing to memory cannot fail");
    for frame in frames {
        let (_, _, data) = png_format(frame);
        writer.write_image_data(&data).expect("every frame matches the header");
    }
    writer.finish().expect("writing to memory cannot fail");
    out
}

/// `path` quoted for messages.
pub fn shown(path: &Path) -> String {
    format!("'{}'", path.display())
}

/// The temporary file `path` is written through.
fn temporary(path: &Path) -> PathBuf {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

/// The directory `path` lives in.
fn parent(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Checks, before any work, that `path` can be written: it is not a directory and its
/// directory exists and takes new files (a temporary file is created and removed).
pub fn check_writable(path: &Path) -> Result<(), Failure> {
    let fail = |why: String| Failure::Runtime(format!("cannot write {}: {why}", shown(path)));
    if path.file_name().is_none() || path.is_dir() {
        return Err(fail("it is a directory".into()));
    }
    let dir = parent(path);
    if !dir.is_dir() {
        return Err(fail(format!("directory {} does not exist", shown(dir))));
    }
    let probe = temporary(path);
    fs::File::create(&probe).map_err(|e| fail(e.to_string()))?;
    let _ = fs::remove_file(&probe);
    Ok(())
}

/// Writes `files` (path, bytes) all or nothing: each goes to a temporary file first; only
/// when every one is on disk are they renamed into place. On failure every temporary file is
/// removed and no target is touched.
pub fn write_all(files: &[(PathBuf, Vec<u8>)]) -> Result<(), Failure> {
    let mut written: Vec<PathBuf> = Vec::new();
    let result = (|| {
        for (path, bytes) in files {
            let temp = temporary(path);
            written.push(temp.clone());
            let write = || -> std::io::Result<()> {
                let mut f = fs::File::create(&temp)?;
                f.write_all(bytes)?;
                f.sync_all()
            };
            write().map_err(|e| Failure::Runtime(format!("cannot write {}: {e}", shown(path))))?;
        }
        for (path, _) in files {
            fs::rename(temporary(path), path)
                .map_err(|e| Failure::Runtime(format!("cannot write {}: {e}", shown(path))))?;
        }
        Ok(())
    })();
    if result.is_err() {
        for temp in &written {
            let _ = fs::remove_file(temp);
        }
    }
    result
}

/// Writes one file atomically.
pub fn write_file(path: &Path, bytes: Vec<u8>) -> Result<(), Failure> {
    write_all(&[(path.to_path_buf(), bytes)])
}

/// The paths of a numbered sequence: `dir/name.png` gives `dir/name-001.png`, ... (three
/// digits, more if `count` needs them).
pub fn sequence_paths(path: &Path, count: u32) -> Vec<PathBuf> {
    let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let extension = path.extension().map(|e| e.to_string_lossy().into_owned()).unwrap_or_else(|| "png".into());
    let digits = count.to_string().len().max(3);
    (1..=count).map(|k| path.with_file_name(format!("{stem}-{k:0digits$}.{extension}"))).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pictures_round_trip_through_png() {
        let image = Image { width: 3, height: 2, pixels: Pixels::Gray16(vec![0, 1, 256, 65535, 7, 9]) };
        let bytes = encode_png(&image);
        let mut reader = png::Decoder::new(std::io::Cursor::new(bytes)).read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buf).unwrap();
        assert_eq!((info.width, info.height, info.bit_depth), (3, 2, png::BitDepth::Sixteen));
        assert_eq!(&buf[..4], &[0, 0, 0, 1]);
    }

    #[test]
    fn animations_hold_every_frame() {
        let frame = |v| Image { width: 2, height: 2, pixels: Pixels::Gray8(vec![v; 4]) };
        let bytes = encode_apng(&[frame(0), frame(100), frame(255)], 50);
        let reader = png::Decoder::new(std::io::Cursor::new(bytes)).read_info().unwrap();
        let control = reader.info().animation_control.unwrap();
        assert_eq!(control.num_frames, 3);
    }

    #[test]
    fn sequences_are_numbered_beside_the_target() {
        let paths = sequence_paths(Path::new("out/growth.png"), 12);
        assert_eq!(paths[0], Path::new("out/growth-001.png"));
        assert_eq!(paths[11], Path::new("out/growth-012.png"));
    }
}
