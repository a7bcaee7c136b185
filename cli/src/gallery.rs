//! `hibi gallery DIR`: every preset that reproduces a paper figure, as a picture, and an
//! index page showing them with their parameters and the command that renders each.

use std::fmt::Write as _;
use std::fs;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use hibi_core::glass::GlassParams;
use hibi_core::mud::{MudParams, MudRender};
use hibi_core::skin::ShadeParams;

use crate::args::{GalleryArgs, GlassOptions, Layer, MudOptions};
use crate::image::Image;
use crate::output::{self, shown};
use crate::progress::Progress;
use crate::{Failure, glass, mud, skin};

/// What each mud preset reproduces.
const MUD: [(&str, &str); 10] = [
    (
        "fig6a",
        "Hexagonal elements, the paper's material (E = 1.0e6, G = 2.0e5, κ̄ = 1.02, σ = 0.001): \
         isotropic cracks enclosing closed polygonal cells.",
    ),
    (
        "fig6b",
        "Square elements, the same material: without in-plane shear the cracks run along the axes and \
         stay short and fine (run on to 3 % shrink).",
    ),
    ("fig6c", "A larger stiffness ratio, E/G = 10 (G = 1.0e5): the pattern coarsens."),
    ("fig6d", "E/G = 20 (G = 5.0e4): coarser still."),
    (
        "fig7a",
        "Anisotropic material: springs across x keep half their break margin κ − 1, so the cracks run \
         along x (stopped at fig6a's crack density).",
    ),
    ("fig7b", "The same along 60° (y runs down the picture), with the stiffness weakened across it too."),
    ("fig9a", "Mesh scale: one 64 cm plate, the same physical parameters, W = 2 cm (32 columns)."),
    ("fig9b", "The same plate at W = 1 cm (64 columns)."),
    ("fig9c", "The same plate at W = 0.5 cm (128 columns)."),
    ("fig10", "The growth process: fig6a's run drawn at six times from its first break to its last."),
];

/// What each glass preset reproduces.
const GLASS: [(&str, &str); 12] = [
    ("fig14a", "V1_ave = 30, V2_ave = 5, V3_ave = 10 (normal Rand); the caption's M = 113, R = 6."),
    ("fig14b", "V1_ave = 40; M = 104, R = 5. The faster the large cracks, the straighter they run."),
    ("fig14c", "V1_ave = 50; M = 113, R = 6 (fig14a's plate, faster large cracks)."),
    ("fig14d", "V1_ave = 60; M = 95, R = 5: nearly straight large cracks."),
    ("fig15a", "Normal Rand(x), V1_ave = 40, V2_ave = 10, V3_ave = 10; M = 114, R = 6."),
    ("fig15b", "Normal Rand(x); M = 98, R = 5."),
    ("fig15c", "Normal Rand(x); M = 105, R = 5."),
    ("fig15d", "Normal Rand(x); M = 92, R = 5."),
    ("fig16a", "Uniform Rand(x), the same speeds; M = 104, R = 5."),
    ("fig16b", "Uniform Rand(x); M = 89, R = 4."),
    ("fig16c", "Uniform Rand(x); M = 108, R = 5."),
    ("fig16d", "Uniform Rand(x); M = 96, R = 5."),
];

/// What each skin preset reproduces (Table 1).
const SKIN: [(&str, &str); 23] = [
    ("fig13a", "Slope with a kink: two segments (0,3)(2,3)(4,3)(8,3) + (8,3)(9,1.5)(9.75,1)(10,0)."),
    ("fig13b", "Steep but smooth: (0,3)(2,3)(4,3)(7,3) + (7,3)(8,3)(9,2.5)(10,0)."),
    ("fig13c", "Gentle: one segment (0,3)(5,3)(8,2.5)(10,0)."),
    ("fig14a", "Roundness 0.0 (no jitter): polygonal height contours."),
    ("fig14b", "Roundness 0.4."),
    ("fig14c", "Roundness 1.0: round contours."),
    ("fig15a", "Jitter 0.0: a regular triangular lattice of centre points."),
    ("fig15b", "Jitter 0.4."),
    ("fig15c", "Jitter 1.0."),
    ("fig16a", "Perturbation ratio 0.0: straight cell edges."),
    ("fig16b", "Perturbation ratio 0.1: wiggling edges."),
    ("fig17a", "Stretch (1, 1)."),
    ("fig17b", "Stretch (1, 3): cells drawn out vertically."),
    ("fig17c", "Stretch (3, 1): cells drawn out horizontally."),
    ("fig18a", "One hierarchy level."),
    ("fig18b", "Two levels: small ridges inside big ones."),
    ("fig18c", "Three levels."),
    ("fig19a", "Skin: three levels, perturbation 0.1."),
    ("fig19b", "Skin stretched (1, 3)."),
    ("fig19c", "Skin stretched (3, 1)."),
    ("fig19d", "Wrist: stretch Sx = 20 on level 1 only."),
    ("fig19e", "Wrist: Sx = 15 on level 1."),
    ("fig19f", "Wrist: Sx = 5 on level 1 (the paper's Fig. 20 maps it round a wrist)."),
];

/// Still frames of the growth figure (mud Fig. 10).
const GROWTH_STILLS: u32 = 6;

/// One picture on the page.
struct Card {
    /// Figure label, e.g. "Fig. 6 a".
    title: String,
    /// What it reproduces.
    caption: String,
    /// The picture's file name.
    file: String,
    /// Further pictures (frames) shown under it.
    extra: Vec<String>,
    /// What the run measured.
    summary: String,
    /// The command that renders it.
    command: String,
    /// Every parameter: option, value, and whether it differs from the model's default.
    parameters: Vec<(String, String, bool)>,
}

/// "fig6a" → "Fig. 6 a".
fn figure(preset: &str) -> String {
    let number = preset.trim_start_matches("fig");
    let split = number.find(|c: char| c.is_ascii_alphabetic()).unwrap_or(number.len());
    let (n, letter) = number.split_at(split);
    if letter.is_empty() { format!("Fig. {n}") } else { format!("Fig. {n} {letter}") }
}

/// A value as a shell word.
fn quoted(v: &str) -> String {
    if v.chars().all(|c| c.is_ascii_alphanumeric() || ",.=-_+x".contains(c)) { v.into() } else { format!("'{v}'") }
}

/// The command for `model --preset preset` with the options that differ from the preset's
/// own, and the parameter table (marking what differs from the model's defaults).
fn describe(
    model: &str,
    preset: &str,
    options: &[(&'static str, String)],
    of_preset: &[(&'static str, String)],
    defaults: &[(&'static str, String)],
    extra: &str,
) -> (String, Vec<(String, String, bool)>) {
    let mut command = format!("hibi {model} --preset {preset}");
    for (option, value) in options {
        if *option == "--size" || !of_preset.iter().any(|(o, v)| o == option && v == value) {
            write!(command, " {option} {}", quoted(value)).expect("writing to a string");
        }
    }
    command.push_str(extra);
    let table = options
        .iter()
        .map(|(o, v)| (o.to_string(), v.clone(), !defaults.iter().any(|(d, dv)| d == o && dv == v)))
        .collect();
    (command, table)
}

/// What every figure is rendered with.
#[derive(Clone, Copy)]
struct Settings {
    /// Width of every picture.
    size: u32,
    /// Frames of the growth animations.
    frames: u32,
    /// Threads that render figures.
    threads: usize,
}

/// One figure, rendered: its files (name, PNG bytes) and its card. fig6a and fig6b also
/// give their picture to the square-vs-hex comparison, fig9b the card of the tiled texture.
struct Piece {
    model: &'static str,
    files: Vec<(String, Vec<u8>)>,
    card: Card,
    comparison: Option<Image>,
    extra_card: Option<Card>,
}

/// The mud view for a preset: `width` pixels wide at the domain's aspect, drawn as the
/// command line draws by default.
fn mud_view(params: &MudParams, width: u32) -> MudRender {
    let fit = MudRender::fit(params.extent(), width);
    mud::view(params, Some([fit.width, fit.height]), &MudOptions::default())
}

/// A mud figure. fig10 is the growth: six stills and the animation.
fn mud_piece(s: Settings, preset: &'static str, caption: &str) -> Piece {
    let params = hibi_core::mud::preset(preset).expect("a listed preset");
    let view = mud_view(&params, s.size);
    // fig9b, a 64 cm periodic plate, is also drawn at half size to be laid 2×2.
    let mut wants = vec![(view, Layer::Shaded, None)];
    if preset == "fig9b" {
        wants.push((mud_view(&params, s.size / 2), Layer::Shaded, None));
    }
    if preset == "fig10" {
        wants.push((view, Layer::Shaded, Some(GROWTH_STILLS)));
        wants.push((view, Layer::Shaded, Some(s.frames)));
    }
    let run = match mud::simulate(&params, &wants, 1, &Progress::hidden()) {
        Ok(run) => run,
        Err(_) => unreachable!("the paper's mud presets run (the gallery test renders every one)"),
    };
    let still = &run.pictures[0][0];
    let file = format!("mud-{preset}.png");
    let mut files = Vec::new();
    let mut extra = Vec::new();
    let mut extra_command = String::new();
    if preset == "fig10" {
        for (k, frame) in run.pictures[1].iter().enumerate() {
            let name = format!("mud-{preset}-{}.png", k + 1);
            files.push((name.clone(), output::encode_png(frame)));
            extra.push(name);
        }
        files.push((file.clone(), output::encode_apng(&run.pictures[2], 80)));
        extra_command = format!(" --frames {}", s.frames);
    } else {
        files.push((file.clone(), output::encode_png(still)));
    }
    let comparison = matches!(preset, "fig6a" | "fig6b").then(|| still.clone());
    let extra_card = (preset == "fig9b").then(|| {
        let half = &run.pictures[1][0];
        files.push(("mud-tile-2x2.png".into(), output::encode_png(&half.tiled(2, 2))));
        Card {
            title: "A tileable texture".into(),
            caption: format!(
                "fig9b, a 64 cm plate on a periodic lattice, rendered at {}x{} and laid 2×2: the copies meet \
                 without seams.",
                half.width, half.height
            ),
            file: "mud-tile-2x2.png".into(),
            extra: Vec::new(),
            summary: run.summary(),
            command: format!("hibi mud --preset fig9b --size {}x{}", half.width, half.height),
            parameters: Vec::new(),
        }
    });
    let options = mud::options(&params, &view);
    let defaults = mud::options(&MudParams::default(), &mud_view(&MudParams::default(), s.size));
    let (command, parameters) = describe("mud", preset, &options, &options, &defaults, &extra_command);
    let card = Card {
        title: figure(preset),
        caption: caption.into(),
        file,
        extra,
        summary: run.summary(),
        command,
        parameters,
    };
    Piece { model: "mud", files, card, comparison, extra_card }
}

/// A glass figure; fig15a also grows as an animation.
fn glass_piece(s: Settings, preset: &'static str, caption: &str) -> Result<Piece, Failure> {
    let none = GlassOptions::default();
    let (params, impacts) = glass::params(Some(preset), None, &none);
    let view = glass::view(&params, Some([s.size, s.size]), &none);
    let mut wants = vec![(Layer::Shaded, None)];
    if preset == "fig15a" {
        wants.push((Layer::Shaded, Some(s.frames)));
    }
    let run = glass::simulate(&params, &impacts, &view, (&wants, 1), &Progress::hidden())?;
    let file = format!("glass-{preset}.png");
    let mut files = vec![(file.clone(), output::encode_png(&run.pictures[0][0]))];
    let mut extra = Vec::new();
    if preset == "fig15a" {
        let name = format!("glass-{preset}-growth.png");
        files.push((name.clone(), output::encode_apng(&run.pictures[1], 80)));
        extra.push(name);
    }
    let default_params = GlassParams::default();
    let default_view = glass::view(&default_params, Some([s.size, s.size]), &none);
    let defaults = glass::options(&default_params, &[default_params.impact], &default_view);
    let options = glass::options(&params, &impacts, &view);
    let (command, parameters) = describe("glass", preset, &options, &options, &defaults, "");
    let card = Card {
        title: figure(preset),
        caption: caption.into(),
        file,
        extra,
        summary: run.summary(),
        command,
        parameters,
    };
    Ok(Piece { model: "glass", files, card, comparison: None, extra_card: None })
}

/// A skin figure (Table 1), its spacings scaled to the gallery's size.
fn skin_piece(s: Settings, preset: &'static str, caption: &str) -> Result<Piece, Failure> {
    let light = ShadeParams::default();
    let params = skin::scaled_preset(preset, s.size);
    let run = skin::render(&params, &light, Layer::Shaded, 1)?;
    let file = format!("skin-{preset}.png");
    let files = vec![(file.clone(), output::encode_png(&run.image))];
    let defaults = skin::options(&hibi_core::skin::SkinParams::default(), &light);
    let options = skin::options(&params, &light);
    let of_preset = skin::options(&hibi_core::skin::preset(preset).expect("a listed preset"), &light);
    let (command, parameters) = describe("skin", preset, &options, &of_preset, &defaults, "");
    let card = Card {
        title: figure(preset),
        caption: caption.into(),
        file,
        extra: Vec::new(),
        summary: run.summary(),
        command,
        parameters,
    };
    Ok(Piece { model: "skin", files, card, comparison: None, extra_card: None })
}

/// Renders every figure, on `s.threads` threads (each figure on one), in figure order.
fn render_all(s: Settings, progress: &Progress) -> Result<Vec<Piece>, Failure> {
    let jobs: Vec<(&'static str, &'static str, &'static str)> = MUD
        .iter()
        .map(|&(p, c)| ("mud", p, c))
        .chain(GLASS.iter().map(|&(p, c)| ("glass", p, c)))
        .chain(SKIN.iter().map(|&(p, c)| ("skin", p, c)))
        .collect();
    let next = AtomicUsize::new(0);
    let workers = s.threads.min(jobs.len());
    let mut pieces: Vec<Option<Result<Piece, Failure>>> = (0..jobs.len()).map(|_| None).collect();
    std::thread::scope(|scope| {
        let handles: Vec<_> = (0..workers)
            .map(|_| {
                scope.spawn(|| {
                    let mut done = Vec::new();
                    while let Some(&(model, preset, caption)) = jobs.get(next.fetch_add(1, Ordering::Relaxed)) {
                        progress.start(&format!("{model} {preset}"));
                        let piece = match model {
                            "mud" => Ok(mud_piece(s, preset, caption)),
                            "glass" => glass_piece(s, preset, caption),
                            _ => skin_piece(s, preset, caption),
                        };
                        progress.done();
                        done.push(((model, preset), piece));
                    }
                    done
                })
            })
            .collect();
        for handle in handles {
            for (job, piece) in handle.join().expect("a gallery worker panicked") {
                let at = jobs.iter().position(|&(m, p, _)| (m, p) == job).expect("a listed job");
                pieces[at] = Some(piece);
            }
        }
    });
    pieces.into_iter().map(|p| p.expect("every job ran")).collect()
}

/// The gallery's pages: the figures' cards by model, and the extra pictures.
struct Gallery {
    size: u32,
    frames: u32,
    cards: Vec<(&'static str, Card)>,
    extras: Vec<Card>,
}

/// `hibi gallery DIR`.
pub fn run(a: &GalleryArgs) -> Result<(), Failure> {
    let start = Instant::now();
    if a.dir.exists() && !a.dir.is_dir() {
        return Err(Failure::Runtime(format!(
            "cannot write the gallery into {}: it is not a directory",
            shown(&a.dir)
        )));
    }
    fs::create_dir_all(&a.dir)
        .map_err(|e| Failure::Runtime(format!("cannot create the directory {}: {e}", shown(&a.dir))))?;
    output::check_writable(&a.dir.join("index.html"))?;
    let settings = Settings { size: a.size, frames: a.frames, threads: crate::image::threads(a.threads) };
    let progress = Progress::items((MUD.len() + GLASS.len() + SKIN.len()) as u64, a.quiet);
    let pieces = render_all(settings, &progress);
    progress.finish();
    let mut gallery = Gallery { size: a.size, frames: a.frames, cards: Vec::new(), extras: Vec::new() };
    let mut files = 0;
    let mut comparison = Vec::new();
    for piece in pieces? {
        for (name, bytes) in piece.files {
            output::write_file(&a.dir.join(name), bytes)?;
            files += 1;
        }
        comparison.extend(piece.comparison);
        gallery.extras.extend(piece.extra_card);
        gallery.cards.push((piece.model, piece.card));
    }
    // fig6a came first: show fig6b (square) on the left.
    comparison.reverse();
    let name = "mud-square-vs-hex.png";
    output::write_file(&a.dir.join(name), output::encode_png(&Image::row(&comparison, 8, [255, 255, 255])))?;
    gallery.extras.insert(
        0,
        Card {
            title: "Square vs hexagonal elements".into(),
            caption: "fig6b (left, square: axis-aligned, short cracks) and fig6a (right, hexagonal: isotropic \
                      closed cells), the same material."
                .into(),
            file: name.into(),
            extra: Vec::new(),
            summary: String::new(),
            command: "hibi mud --preset fig6b; hibi mud --preset fig6a".into(),
            parameters: Vec::new(),
        },
    );
    output::write_file(&a.dir.join("index.html"), index(&gallery, a).into_bytes())?;
    files += 2;
    if !a.quiet {
        eprintln!(
            "hibi: wrote {files} files to {} in {:.1} s; open {}",
            shown(&a.dir),
            start.elapsed().as_secs_f64(),
            shown(&a.dir.join("index.html"))
        );
    }
    Ok(())
}

/// Text for HTML.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// A command as HTML for a `<pre>` that does not wrap by itself: a line may break before
/// each option after the first (so `hibi MODEL --preset NAME` stays on one line, and an
/// option stays with its value) and after a `;`, never inside `--an-option`.
fn command_html(command: &str) -> String {
    let one = |command: &str| {
        let mut options = 0;
        let words: Vec<String> = command
            .split(' ')
            .map(|word| {
                let shown = escape(word);
                if word.starts_with("--") {
                    options += 1;
                    if options > 1 {
                        return format!("<wbr>{shown}");
                    }
                }
                shown
            })
            .collect();
        words.join(" ")
    };
    command.split("; ").map(one).collect::<Vec<_>>().join("; <wbr>")
}

/// One card as HTML.
fn card_html(card: &Card, width: u32) -> String {
    let mut h = String::new();
    let file = escape(&card.file);
    writeln!(h, "<figure>").unwrap();
    writeln!(h, "<a href=\"{file}\"><img src=\"{file}\" alt=\"{}\" width=\"{width}\"></a>", escape(&card.title))
        .unwrap();
    if !card.extra.is_empty() {
        writeln!(h, "<div class=\"frames\">").unwrap();
        for e in &card.extra {
            let e = escape(e);
            writeln!(h, "<a href=\"{e}\"><img src=\"{e}\" alt=\"{e}\"></a>").unwrap();
        }
        writeln!(h, "</div>").unwrap();
    }
    writeln!(h, "<figcaption><b>{}</b> {}", escape(&card.title), escape(&card.caption)).unwrap();
    if !card.summary.is_empty() {
        writeln!(h, "<br><span class=\"summary\">{}</span>", escape(&card.summary)).unwrap();
    }
    writeln!(h, "<pre class=\"command\"><code>{}</code></pre>", command_html(&card.command)).unwrap();
    if !card.parameters.is_empty() {
        writeln!(h, "<details><summary>parameters</summary><table>").unwrap();
        for (option, value, changed) in &card.parameters {
            let class = if *changed { " class=\"changed\"" } else { "" };
            writeln!(h, "<tr{class}><td>{}</td><td>{}</td></tr>", escape(option), escape(value)).unwrap();
        }
        writeln!(h, "</table></details>").unwrap();
    }
    writeln!(h, "</figcaption></figure>").unwrap();
    h
}

/// The index page.
fn index(g: &Gallery, a: &GalleryArgs) -> String {
    let sections = [
        (
            "mud",
            "Model A: drying mud",
            "Hirota, Hoshino, Kaneko, “Generation of Crack Patterns Based on a Physical Model”. A surface \
             layer of springs on a deep layer shrinks and cracks; the paper prints no parameters for its \
             figures beyond its defaults, so each preset shows what its figure shows (see \
             <code>core/src/mud/presets.rs</code>). Quasi-static solver, periodic lattices.",
        ),
        (
            "glass",
            "Model B: a glass plate hit by a ball",
            "Agui, Moriyama, Nagao, Nakajima, “Representation of cracks in plate glass by CG”. A 640 × 640 \
             plate hit at its centre; each preset's seed draws its caption's M (and so R).",
        ),
        (
            "skin",
            "Model C: skin",
            "Ishii, Yasuda, Yokoi, Toriwaki, “Human skin rendering based on the surface microstructures”, \
             Table 1. Spacings are scaled so that each picture shows the field of the paper's 400 × 400 image.",
        ),
    ];
    let mut h = String::new();
    h.push_str(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>hibi gallery</title>\n<style>\n\
         body{font:15px/1.45 system-ui,sans-serif;margin:2em auto;max-width:1400px;padding:0 1em;color:#222}\n\
         h1{margin-bottom:.2em} h2{margin-top:2em;border-bottom:1px solid #ccc}\n\
         .grid{display:grid;grid-template-columns:repeat(auto-fill,minmax(300px,1fr));gap:1.5em}\n\
         figure{margin:0} figure img{max-width:100%;height:auto;display:block;image-rendering:auto}\n\
         .frames{display:grid;grid-template-columns:repeat(6,1fr);gap:2px;margin-top:2px}\n\
         figcaption{font-size:13px;margin-top:.4em}\n\
         code{font:.9em ui-monospace,SFMono-Regular,Menlo,Consolas,monospace;background:#f4f4f4;\
         padding:.05em .3em;border-radius:3px}\n\
         pre.command{font-size:12px;background:#f4f4f4;padding:.3em .5em;margin:.4em 0;\
         white-space:pre;overflow-x:auto}\n\
         pre.command code{font-size:inherit;padding:0;background:none}\n\
         .summary{color:#555} table{font-size:12px;border-collapse:collapse} td{padding:0 .6em 0 0}\n\
         tr.changed td{font-weight:bold} .wide figure img{max-width:100%}\n\
         </style></head><body>\n<h1>hibi gallery</h1>\n",
    );
    writeln!(
        h,
        "<p>Every preset that reproduces a paper figure, rendered by <code>hibi gallery {} --size {} --frames {}</code>. \
         Each picture's command renders it alone; bold parameters differ from the model's defaults.</p>",
        escape(&a.dir.display().to_string()),
        g.size,
        g.frames
    )
    .unwrap();
    for (model, title, intro) in sections {
        writeln!(h, "<h2 id=\"{model}\">{title}</h2>\n<p>{intro}</p>\n<div class=\"grid\">").unwrap();
        for (_, card) in g.cards.iter().filter(|(m, _)| *m == model) {
            h.push_str(&card_html(card, g.size));
        }
        h.push_str("</div>\n");
        if model == "mud" {
            h.push_str("<h3>Square vs hexagonal, and seamless tiling</h3>\n<div class=\"grid wide\">\n");
            for card in &g.extras {
                h.push_str(&card_html(card, g.size));
            }
            h.push_str("</div>\n");
        }
    }
    h.push_str("</body></html>\n");
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_has_a_caption_in_order() {
        fn names(table: &[(&'static str, &str)]) -> Vec<&'static str> {
            table.iter().map(|(n, _)| *n).collect()
        }
        assert_eq!(names(&MUD), hibi_core::mud::PRESETS);
        assert_eq!(names(&GLASS), hibi_core::glass::PRESETS);
        assert_eq!(names(&SKIN), hibi_core::skin::PRESETS);
    }

    #[test]
    fn figure_labels_and_shell_words() {
        assert_eq!(figure("fig6a"), "Fig. 6 a");
        assert_eq!(figure("fig10"), "Fig. 10");
        assert_eq!(quoted("0,3 5,3"), "'0,3 5,3'");
        assert_eq!(quoted("2=13.5"), "2=13.5");
        assert_eq!(escape("<a & \"b\">"), "&lt;a &amp; &quot;b&quot;&gt;");
        assert_eq!(
            command_html("hibi skin --preset fig13a --size 160x160 --light -0.5,0.6,0.62"),
            "hibi skin --preset fig13a <wbr>--size 160x160 <wbr>--light -0.5,0.6,0.62"
        );
        assert_eq!(
            command_html("hibi mud --preset fig6b; hibi mud --preset fig6a"),
            "hibi mud --preset fig6b; <wbr>hibi mud --preset fig6a"
        );
    }
}
