//! `hibi`: renders hibi's three models to PNG and reproduces the papers' figures.
//!
//! It uses only `hibi_core`'s public API: the models compute into buffers this program
//! allocates, and this program turns their maps into pictures (normal maps and previews of
//! the crack models, PNG and animated PNG encoding, the gallery page).
// Doc comments here are `--help` text: units read "[px]", not links.
#![allow(rustdoc::broken_intra_doc_links)]

mod args;
mod gallery;
mod glass;
mod image;
mod mud;
mod output;
mod progress;
mod skin;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::error::ErrorKind;
use clap::{CommandFactory, Parser};

use args::{Animation, Cli, Command, GlassArgs, Layer, MudArgs, Output, SkinArgs};
use hibi_core::glass::GlassRender;
use hibi_core::mud::MudRender;
use image::Image;
use output::shown;
use progress::Progress;

/// Why a command failed.
#[derive(Debug)]
pub enum Failure {
    /// A bad option or value: clap prints it with the usage and exits with status 2.
    Usage(Box<clap::Error>),
    /// The run or writing its output failed: printed as `hibi: MESSAGE`, status 1.
    Runtime(String),
}

impl Failure {
    /// A usage error of subcommand `command` about `option`: `why` is what is wrong (a core
    /// message's `model: ` prefix is dropped).
    pub fn invalid(command: &str, option: &str, why: String) -> Failure {
        let mut cli = Cli::command();
        cli.build();
        let sub = cli.find_subcommand_mut(command).expect("a subcommand of hibi");
        let why = why.strip_prefix(&format!("{command}: ")).unwrap_or(&why);
        Failure::Usage(Box::new(sub.error(ErrorKind::ValueValidation, format!("invalid value for '{option}': {why}"))))
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Mud(a) => run_mud(&a),
        Command::Glass(a) => run_glass(&a),
        Command::Skin(a) => run_skin(&a),
        Command::Gallery(a) => gallery::run(&a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Usage(e)) => e.exit(),
        Err(Failure::Runtime(message)) => {
            eprintln!("hibi: {message}");
            ExitCode::FAILURE
        }
    }
}

/// Where a model writes: `--output`, or `MODEL.png`.
fn output_path(output: &Output, model: &str) -> PathBuf {
    output.output.clone().unwrap_or_else(|| PathBuf::from(format!("{model}.png")))
}

/// Refuses a time layer for an animation (its frames show the growth already).
fn check_animation(command: &str, output: &Output, animation: &Animation) -> Result<(), Failure> {
    if animation.frames.is_some() && output.layer == Layer::Time {
        let why = "the frames of an animation show the growth: choose mask, height, normal or shaded".to_string();
        return Err(Failure::invalid(command, "--layer", why));
    }
    Ok(())
}

/// Checks, before any work, that the output (or every frame of a sequence) can be written.
fn check_output(path: &Path, animation: Option<&Animation>) -> Result<(), Failure> {
    match animation {
        Some(Animation { frames: Some(n), sequence: true, .. }) => {
            output::sequence_paths(path, *n).iter().try_for_each(|p| output::check_writable(p))
        }
        _ => output::check_writable(path),
    }
}

/// Writes a crack model's picture or its growth (`pictures`: the still, or the frames); says
/// what was written.
fn write_cracks(pictures: &[Image], output: &Output, animation: &Animation, path: &Path) -> Result<String, Failure> {
    let (layer, size) = (output.layer.name(), format!("{}x{}", pictures[0].width, pictures[0].height));
    let Some(count) = animation.frames else {
        output::write_file(path, output::encode_png(&pictures[0]))?;
        return Ok(format!("{} ({size} {layer})", shown(path)));
    };
    if animation.sequence {
        let paths = output::sequence_paths(path, count);
        let files: Vec<_> = paths.iter().cloned().zip(pictures.iter().map(output::encode_png)).collect();
        output::write_all(&files)?;
        Ok(format!("{} ... {} ({count} frames, {size} {layer})", shown(&paths[0]), shown(&paths[paths.len() - 1])))
    } else {
        output::write_file(path, output::encode_apng(pictures, animation.frame_delay))?;
        Ok(format!("{} ({count}-frame animation, {size} {layer})", shown(path)))
    }
}

/// `hibi mud`.
fn run_mud(a: &MudArgs) -> Result<(), Failure> {
    let params = mud::params(a.preset.as_deref(), a.output.seed, &a.model);
    let render = MudRender { bump: a.output.bump, ..mud::view(&params, a.output.size, &a.model) };
    mud::check(&params, &render)?;
    check_animation("mud", &a.output, &a.animation)?;
    let path = output_path(&a.output, "mud");
    check_output(&path, Some(&a.animation))?;
    let progress = Progress::run("mud", a.output.quiet);
    if let Some(budget) = a.live {
        let threads = image::threads(a.output.threads);
        let live = mud::simulate_live(&params, &render, (a.output.layer, budget, threads), &progress);
        progress.finish();
        let (frames, run) = live?;
        let pictures = if frames.is_empty() { &run.pictures[0] } else { &frames };
        if frames.is_empty() {
            // Nothing broke: the one picture of the uncracked plate.
            output::write_file(&path, output::encode_png(&pictures[0]))?;
        } else {
            output::write_file(&path, output::encode_apng(pictures, a.animation.frame_delay))?;
        }
        if !a.output.quiet {
            let (layer, size) = (a.output.layer.name(), format!("{}x{}", render.width, render.height));
            let count = pictures.len();
            eprintln!("hibi: wrote {} ({count}-frame live animation, {size} {layer}): {}", shown(&path), run.summary());
        }
        return Ok(());
    }
    let wants = [(render, a.output.layer, a.animation.frames)];
    let run = mud::simulate(&params, &wants, image::threads(a.output.threads), &progress);
    progress.finish();
    let run = run?;
    let written = write_cracks(&run.pictures[0], &a.output, &a.animation, &path)?;
    if !a.output.quiet {
        eprintln!("hibi: wrote {written}: {}", run.summary());
    }
    Ok(())
}

/// `hibi glass`.
fn run_glass(a: &GlassArgs) -> Result<(), Failure> {
    let (params, impacts) = glass::params(a.preset.as_deref(), a.output.seed, &a.model);
    let render = GlassRender { bump: a.output.bump, ..glass::view(&params, a.output.size, &a.model) };
    glass::check(&params, &impacts, &render)?;
    check_animation("glass", &a.output, &a.animation)?;
    let path = output_path(&a.output, "glass");
    check_output(&path, Some(&a.animation))?;
    let progress = Progress::run("glass", a.output.quiet);
    let wants = [(a.output.layer, a.animation.frames)];
    let run = glass::simulate(&params, &impacts, &render, (&wants, image::threads(a.output.threads)), &progress);
    progress.finish();
    let run = run?;
    let written = write_cracks(&run.pictures[0], &a.output, &a.animation, &path)?;
    if !a.output.quiet {
        eprintln!("hibi: wrote {written}: {}", run.summary());
    }
    Ok(())
}

/// `hibi skin`.
fn run_skin(a: &SkinArgs) -> Result<(), Failure> {
    let (params, light) = skin::params(a.preset.as_deref(), a.output.seed, a.output.size, &a.model)?;
    skin::check(&params, &light, a.output.layer)?;
    let path = output_path(&a.output, "skin");
    check_output(&path, None)?;
    let run = skin::render(&params, &light, a.output.layer, image::threads(a.output.threads))?;
    output::write_file(&path, output::encode_png(&run.image))?;
    if !a.output.quiet {
        let size = format!("{}x{}", params.width, params.height);
        eprintln!("hibi: wrote {} ({size} {}): {}", shown(&path), a.output.layer.name(), run.summary());
    }
    Ok(())
}
