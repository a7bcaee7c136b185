//! Helpers shared by the cross-crate tests in `tests/`.

use std::path::{Path, PathBuf};

/// A readable difference between two texts: every differing line, numbered, as
/// `-expected` / `+actual`, with a count of the lines that differ.
pub fn line_diff(expected: &str, actual: &str) -> String {
    let (old, new): (Vec<&str>, Vec<&str>) = (expected.lines().collect(), actual.lines().collect());
    let mut out = String::new();
    let mut differing = 0;
    for i in 0..old.len().max(new.len()) {
        let (a, b) = (old.get(i), new.get(i));
        if a != b {
            differing += 1;
            if differing <= 40 {
                if let Some(a) = a {
                    out += &format!("{:>5} -{a}\n", i + 1);
                }
                if let Some(b) = b {
                    out += &format!("{:>5} +{b}\n", i + 1);
                }
            }
        }
    }
    format!("{differing} line(s) differ (- checked in, + generated):\n{out}")
}

/// The workspace root.
pub fn workspace_root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The directory cargo builds this profile into (`target/debug` or `target/release`), found
/// from the running test binary (`target/<profile>/deps/<test>`).
pub fn profile_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test binary path");
    exe.parent().and_then(Path::parent).expect("target/<profile>/deps").to_path_buf()
}

/// FNV-1a, 64-bit: the hash of golden snapshots (one definition, in the scenes crate).
pub use hibi_scenes::fnv1a64;

/// Owned memory for a glass plate, sized by [`hibi_core::glass::GlassParams::memory`].
pub struct GlassVecs {
    cracks: Vec<hibi_core::glass::Crack>,
    vertices: Vec<hibi_core::glass::Vertex>,
    edges: Vec<hibi_core::glass::Edge>,
    words: Vec<u32>,
}

impl GlassVecs {
    /// Memory of the sizes `m` asks for.
    pub fn new(m: &hibi_core::glass::GlassMemory) -> Self {
        GlassVecs {
            cracks: vec![Default::default(); m.cracks],
            vertices: vec![Default::default(); m.vertices],
            edges: vec![Default::default(); m.edges],
            words: vec![0; m.words],
        }
    }

    /// The buffers for [`hibi_core::glass::Glass::new`].
    pub fn buffers(&mut self) -> hibi_core::glass::GlassBuffers<'_> {
        hibi_core::glass::GlassBuffers {
            cracks: &mut self.cracks,
            vertices: &mut self.vertices,
            edges: &mut self.edges,
            words: &mut self.words,
        }
    }
}

/// Owned memory for a skin, sized by [`hibi_core::skin::SkinParams::memory`].
pub struct SkinVecs {
    cells: Vec<hibi_core::skin::SkinCell>,
    vertices: Vec<[i64; 2]>,
    sites: Vec<hibi_core::skin::Site>,
    clip: Vec<hibi_core::skin::ClipVertex>,
    words: Vec<u32>,
}

impl SkinVecs {
    /// Memory of the sizes `m` asks for.
    pub fn new(m: &hibi_core::skin::SkinMemory) -> Self {
        SkinVecs {
            cells: vec![Default::default(); m.cells],
            vertices: vec![[0; 2]; m.vertices],
            sites: vec![Default::default(); m.sites],
            clip: vec![Default::default(); m.clip],
            words: vec![0; m.words],
        }
    }

    /// The buffers for [`hibi_core::skin::Skin::new`].
    pub fn buffers(&mut self) -> hibi_core::skin::SkinBuffers<'_> {
        hibi_core::skin::SkinBuffers {
            cells: &mut self.cells,
            vertices: &mut self.vertices,
            sites: &mut self.sites,
            clip: &mut self.clip,
            words: &mut self.words,
        }
    }
}
