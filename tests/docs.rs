//! The README and the guide (`docs/`, an mdBook): what they show a user is checked here.
//!
//! - The parameter tables in `docs/src/generated/` are made from `include/hibi.h` (the doc
//!   comments cbindgen copies from `ffi/`, and the defaults the C library returns);
//!   `HIBI_BLESS=1 cargo test --test docs` rewrites them, and the test fails while a table is
//!   stale.
//! - No page narrates history: no issue numbers, commit hashes, paths of one machine or
//!   accounts of sessions and attempts (`CHANGELOG.md` holds the history).
//! - The book builds with `mdbook` without a warning, and every link in it and in the README
//!   reaches a page and an anchor that exist.
//! - Every code block is compiled or run: ```` ```rust ```` blocks are doctests (the pages are
//!   included in `tests/support/lib.rs`), ```` ```c ```` and ```` ```cpp ```` blocks are
//!   complete programs built at `-Werror` against `libhibi.a` and run, ```` ```sh ```` blocks
//!   run under `bash -euo pipefail` in an empty directory with the `hibi` tool on `PATH`. A
//!   block that cannot run says why on the line above it: `<!-- not run: REASON -->`.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use hibi_tests::{NATIVE_STATIC_LIBS, c_library_dir, line_diff, tool, workspace_root};

/// The README and every page of the guide, as (path relative to the root, text).
fn pages() -> Vec<(String, String)> {
    let mut files = vec![PathBuf::from("README.md")];
    let mut dirs = vec![workspace_root().join("docs/src")];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).expect("read docs/src") {
            let path = entry.expect("entry").path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "md") {
                files.push(path.strip_prefix(workspace_root()).expect("under the root").to_path_buf());
            }
        }
    }
    files.sort();
    files
        .into_iter()
        .map(|f| {
            let text = std::fs::read_to_string(workspace_root().join(&f))
                .unwrap_or_else(|e| panic!("read {}: {e}", f.display()));
            (f.to_string_lossy().into_owned(), text)
        })
        .collect()
}

/// A fenced code block of a page.
struct Block {
    file: String,
    /// The line of its opening fence, from 1.
    line: usize,
    info: String,
    code: String,
    /// The reason given by `<!-- not run: REASON -->` on the line above the fence.
    not_run: Option<String>,
}

impl Block {
    fn language(&self) -> &str {
        self.info.split([',', ' ']).next().unwrap_or("")
    }
    fn at(&self) -> String {
        format!("{}:{}", self.file, self.line)
    }
}

fn blocks(file: &str, text: &str) -> Vec<Block> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        let trimmed = lines[i].trim_start();
        if let Some(rest) = trimmed.strip_prefix("```") {
            let fence_len = 3 + rest.chars().take_while(|&c| c == '`').count();
            let info = rest.trim_start_matches('`').trim().to_string();
            let not_run = lines[..i]
                .iter()
                .rev()
                .find(|l| !l.trim().is_empty())
                .and_then(|l| l.trim().strip_prefix("<!-- not run:"))
                .and_then(|l| l.strip_suffix("-->"))
                .map(|reason| reason.trim().to_string());
            let start = i;
            let mut code = String::new();
            i += 1;
            while i < lines.len() {
                let t = lines[i].trim_start();
                if t.starts_with(&"`".repeat(fence_len)) && t.trim_matches('`').trim().is_empty() {
                    break;
                }
                code += lines[i];
                code.push('\n');
                i += 1;
            }
            out.push(Block { file: file.to_string(), line: start + 1, info, code, not_run });
        }
        i += 1;
    }
    out
}

/// The page's text outside its code blocks.
fn prose(text: &str) -> String {
    let mut out = String::new();
    let mut fence: Option<usize> = None;
    for line in text.lines() {
        let t = line.trim_start();
        let ticks = t.chars().take_while(|&c| c == '`').count();
        match fence {
            None if ticks >= 3 => fence = Some(ticks),
            Some(n) if ticks >= n && t.trim_matches('`').trim().is_empty() => fence = None,
            None => {
                out += line;
                out.push('\n');
            }
            Some(_) => {}
        }
    }
    out
}

// ---------------------------------------------------------------------------------------
// Generated parameter tables.

/// A field of a C struct in `hibi.h`, with its doc comment joined into one line.
struct Field {
    ty: String,
    name: String,
    /// The array length, for `float impact[2]` or `struct hibi_skin_level level[4]`.
    len: Option<String>,
    doc: String,
}

fn header() -> String {
    std::fs::read_to_string(workspace_root().join("include/hibi.h")).expect("read include/hibi.h")
}

fn struct_fields(header: &str, name: &str) -> Vec<Field> {
    let open = format!("typedef struct {name} {{");
    let start = header.find(&open).unwrap_or_else(|| panic!("include/hibi.h declares no {name}")) + open.len();
    let end = start + header[start..].find(&format!("}} {name};")).expect("end of struct");
    let mut fields = Vec::new();
    let mut doc = String::new();
    for line in header[start..end].lines() {
        let t = line.trim();
        if t.starts_with("/**") || t == "*/" {
            continue;
        }
        if let Some(text) = t.strip_prefix('*') {
            if !doc.is_empty() && !text.trim().is_empty() {
                doc.push(' ');
            }
            doc += text.trim();
            continue;
        }
        if let Some(decl) = t.strip_suffix(';') {
            let (ty, declarator) = decl.rsplit_once(' ').expect("a field");
            let (name, len) = match declarator.split_once('[') {
                Some((n, l)) => (n.to_string(), Some(l.trim_end_matches(']').to_string())),
                None => (declarator.to_string(), None),
            };
            fields.push(Field { ty: ty.to_string(), name, len, doc: std::mem::take(&mut doc) });
        }
    }
    fields
}

/// `#define HIBI_X 3` constants of the header.
fn defines(header: &str) -> BTreeMap<String, String> {
    header
        .lines()
        .filter_map(|l| l.strip_prefix("#define "))
        .filter_map(|l| l.split_once(' '))
        .map(|(k, v)| (k.to_string(), v.trim().to_string()))
        .collect()
}

/// Builds a C program against `libhibi.a` in this test's profile and returns its path.
fn build_c(name: &str, source: &str, cpp: bool) -> Result<PathBuf, String> {
    let dir =
        workspace_root().join("target/docs-programs").join(if cfg!(debug_assertions) { "debug" } else { "release" });
    std::fs::create_dir_all(&dir).expect("create target/docs-programs");
    let src = dir.join(format!("{name}.{}", if cpp { "cpp" } else { "c" }));
    std::fs::write(&src, source).expect("write the program");
    let exe = dir.join(name);
    let (compiler, standard) = if cpp {
        (std::env::var("CXX").unwrap_or_else(|_| "c++".into()), "-std=c++17")
    } else {
        (std::env::var("CC").unwrap_or_else(|_| "cc".into()), "-std=c99")
    };
    let output = tool(&compiler)
        .args([standard, "-Wall", "-Wextra", "-Wpedantic", "-Werror", "-O1", "-o"])
        .arg(&exe)
        .arg("-I")
        .arg(workspace_root().join("include"))
        .arg(&src)
        .arg(c_library_dir().join("libhibi.a"))
        .args(NATIVE_STATIC_LIBS)
        .output()
        .expect("run the compiler");
    if output.status.success() {
        Ok(exe)
    } else {
        Err(format!("{compiler} failed:\n{}", String::from_utf8_lossy(&output.stderr)))
    }
}

/// The models whose parameter structs the guide tabulates: (model, C struct, default function).
const MODELS: [(&str, &str); 3] =
    [("mud", "hibi_mud_params"), ("glass", "hibi_glass_params"), ("skin", "hibi_skin_params")];

/// The defaults the C library returns, as `model.field` (or `model.level[i].field`) -> text.
fn c_defaults(header: &str) -> BTreeMap<String, String> {
    let mut program =
        String::from("#include <inttypes.h>\n#include <stdio.h>\n#include \"hibi.h\"\nint main(void) {\n");
    for (model, ty) in MODELS {
        writeln!(program, "    {ty} {model} = {ty}_default();").unwrap();
        for f in struct_fields(header, ty) {
            let mut print = |expr: &str, key: &str, ty: &str| {
                let line = if ty == "float" {
                    format!("    printf(\"{key}\\t%.9g\\n\", (double){expr});\n")
                } else {
                    format!("    printf(\"{key}\\t%\" PRIu64 \"\\n\", (uint64_t){expr});\n")
                };
                program += &line;
            };
            match (&f.len, f.ty.strip_prefix("struct ")) {
                (Some(len), Some(inner)) => {
                    let n: usize = defines(header)[len].parse().expect("a count");
                    for i in 0..n {
                        for g in struct_fields(header, inner) {
                            let key = format!("{model}.{}[{i}].{}", f.name, g.name);
                            match (&g.len, g.ty.starts_with("struct ")) {
                                // A nested record (a level's profile) is described, not listed.
                                (_, true) => {}
                                (Some(len), false) => {
                                    for j in 0..len.parse::<usize>().expect("a length") {
                                        print(&format!("{key}[{j}]"), &format!("{key}[{j}]"), &g.ty);
                                    }
                                }
                                (None, false) => print(&key, &key, &g.ty),
                            }
                        }
                    }
                }
                (Some(len), None) => {
                    for i in 0..len.parse::<usize>().expect("a length") {
                        print(&format!("{model}.{}[{i}]", f.name), &format!("{model}.{}[{i}]", f.name), &f.ty);
                    }
                }
                (None, _) => print(&format!("{model}.{}", f.name), &format!("{model}.{}", f.name), &f.ty),
            }
        }
    }
    program += "    return 0;\n}\n";
    let exe = build_c("param_defaults", &program, false).unwrap_or_else(|e| panic!("{e}"));
    let output = std::process::Command::new(&exe).output().expect("run param_defaults");
    assert!(output.status.success(), "param_defaults failed");
    String::from_utf8(output.stdout)
        .expect("utf-8")
        .lines()
        .map(|l| {
            let (k, v) = l.split_once('\t').expect("key and value");
            (k.to_string(), v.to_string())
        })
        .collect()
}

/// A default as a user would write it: a float in its shortest exact form, an enumeration
/// as the constant the field's doc names with that value.
fn show_default(field: &Field, value: &str, defines: &BTreeMap<String, String>) -> String {
    if field.ty == "float" {
        let v: f32 = value.parse().expect("a float");
        return if v == f32::MAX { "FLT_MAX".into() } else { format!("{v}") };
    }
    let named: Vec<&str> = field
        .doc
        .split('`')
        .skip(1)
        .step_by(2)
        .filter(|w| w.starts_with("HIBI_") && defines.get(*w).is_some_and(|d| d == value))
        .collect();
    match named.first() {
        Some(name) => format!("`{name}`"),
        None => value.to_string(),
    }
}

/// The paper's symbol a field's doc starts with ("H, surface layer thickness ..."), if any.
fn symbol(doc: &str) -> (String, String) {
    if let Some((head, rest)) = doc.split_once(", ")
        && !head.is_empty()
        && head.chars().count() <= 8
        && !head.contains(' ')
        && !head.starts_with('`')
    {
        let mut rest = rest.to_string();
        if let Some(first) = rest.get(..1) {
            rest = first.to_uppercase() + &rest[1..];
        }
        return (head.to_string(), rest);
    }
    (String::new(), doc.to_string())
}

fn table(rows: &[Vec<String>], head: &[&str]) -> String {
    let mut out = format!("| {} |\n|{}\n", head.join(" | "), "---|".repeat(head.len()));
    for row in rows {
        let cells: Vec<String> = row.iter().map(|c| c.replace('|', "\\|")).collect();
        out += &format!("| {} |\n", cells.join(" | "));
    }
    out
}

fn generated_tables() -> BTreeMap<String, String> {
    let header = header();
    let defines = defines(&header);
    let defaults = c_defaults(&header);
    let mut pages = BTreeMap::new();
    for (model, ty) in MODELS {
        let mut page = format!(
            "<!-- Generated from include/hibi.h by tests/docs.rs: `HIBI_BLESS=1 cargo test --test docs` rewrites it. -->\n\n\
             The fields of `{ty}` (C) and of the Rust parameters, which have the same names. \
             Defaults are what `{ty}_default()` returns; the papers' values unless the text says otherwise.\n\n"
        );
        let mut rows = Vec::new();
        let mut nested = None;
        for f in struct_fields(&header, ty) {
            if f.name == "cookie" {
                continue;
            }
            let (sym, doc) = symbol(&f.doc);
            let default = match (&f.len, f.ty.strip_prefix("struct ")) {
                (Some(len), Some(inner)) => {
                    nested = Some((f.name.clone(), inner.to_string(), len.clone()));
                    "see below".to_string()
                }
                (Some(len), None) => (0..len.parse::<usize>().expect("length"))
                    .map(|i| show_default(&f, &defaults[&format!("{model}.{}[{i}]", f.name)], &defines))
                    .collect::<Vec<_>>()
                    .join(", "),
                (None, _) => show_default(&f, &defaults[&format!("{model}.{}", f.name)], &defines),
            };
            rows.push(vec![format!("`{}`", f.name), sym, default, doc]);
        }
        page += &table(&rows, &["field", "symbol", "default", "meaning"]);
        if let Some((name, inner, len)) = nested {
            let n: usize = defines[&len].parse().expect("a count");
            writeln!(page, "\nEach of the `{name}[{len}]` records (`{inner}`), defaults of levels 0 to {}:\n", n - 1)
                .unwrap();
            let mut rows = Vec::new();
            for g in struct_fields(&header, &inner) {
                let (sym, doc) = symbol(&g.doc);
                let values: Vec<String> = (0..n)
                    .map(|i| {
                        let key = format!("{model}.{name}[{i}].{}", g.name);
                        match (&g.len, g.ty.strip_prefix("struct ")) {
                            (_, Some(inner)) => format!("`{inner}`"),
                            (Some(len), None) => (0..len.parse::<usize>().expect("a length"))
                                .map(|j| show_default(&g, &defaults[&format!("{key}[{j}]")], &defines))
                                .collect::<Vec<_>>()
                                .join(", "),
                            (None, None) => show_default(&g, &defaults[&key], &defines),
                        }
                    })
                    .collect();
                rows.push(vec![format!("`{}`", g.name), sym, values.join(" / "), doc]);
            }
            page += &table(&rows, &["field", "symbol", "defaults", "meaning"]);
        }
        pages.insert(format!("docs/src/generated/{model}-params.md"), page);
    }
    pages
}

#[test]
fn parameter_tables_are_generated_from_the_header() {
    let bless = std::env::var_os("HIBI_BLESS").is_some();
    let mut stale = Vec::new();
    for (path, page) in generated_tables() {
        let file = workspace_root().join(&path);
        let old = std::fs::read_to_string(&file).unwrap_or_default();
        if old != page {
            if bless {
                std::fs::write(&file, &page).expect("write a generated page");
            } else {
                stale.push(format!("{path}: {}", line_diff(&old, &page)));
            }
        }
    }
    assert!(
        stale.is_empty(),
        "stale generated pages; run `HIBI_BLESS=1 cargo test --test docs` and commit:\n{}",
        stale.join("\n")
    );
}

// ---------------------------------------------------------------------------------------
// No history.

/// What a page must not say, with a reason: a narrative of the work belongs in CHANGELOG.md.
fn history(text: &str) -> Vec<String> {
    let lower = text.to_lowercase();
    let mut found = Vec::new();
    for path in ["/work/", "/tmp/", "/home/", "/root/", "/users/", "c:\\"] {
        if lower.contains(path) {
            found.push(format!("a path of one machine ({path})"));
        }
    }
    for phrase in [
        "session",
        "we tried",
        "tried at",
        "previously",
        "until commit",
        "at commit",
        "before the change",
        "since the change",
        "used to be",
        "this machine",
        "earlier code",
        "left out, all",
        "changed no code",
    ] {
        if lower.contains(phrase) {
            found.push(format!("a narrative (\"{phrase}\")"));
        }
    }
    let words: Vec<&str> =
        lower.split(|c: char| !(c.is_ascii_alphanumeric() || c == '#')).filter(|w| !w.is_empty()).collect();
    for pair in words.windows(2) {
        if matches!(pair[0], "issue" | "issues" | "item" | "deliverable" | "defect")
            && pair[1].trim_start_matches('#').chars().next().is_some_and(|c| c.is_ascii_digit())
        {
            found.push(format!("an issue reference (\"{} {}\")", pair[0], pair[1]));
        }
        if pair[0] == "was" && pair[1].chars().next().is_some_and(|c| c.is_ascii_digit()) {
            found.push(format!("a former figure (\"was {}\")", pair[1]));
        }
    }
    for word in lower.split(|c: char| !c.is_ascii_alphanumeric()) {
        let hex = (7..=40).contains(&word.len()) && word.chars().all(|c| c.is_ascii_hexdigit());
        if hex && word.chars().any(|c| c.is_ascii_digit()) && word.chars().any(|c| c.is_ascii_alphabetic()) {
            found.push(format!("a commit hash ({word})"));
        }
    }
    found
}

#[test]
fn pages_hold_no_history() {
    let mut bad = Vec::new();
    for (file, text) in pages() {
        for (n, line) in text.lines().enumerate() {
            // Golden hashes are written 0x...; hex there is data, not a commit.
            let line = line.replace("0x", " ");
            for what in history(&line) {
                bad.push(format!("{file}:{}: {what}", n + 1));
            }
        }
    }
    assert!(bad.is_empty(), "history belongs in CHANGELOG.md:\n{}", bad.join("\n"));
}

#[test]
fn the_history_check_finds_what_it_looks_for() {
    assert!(!history("as issue 23 asks").is_empty());
    assert!(!history("measured at 16551b9").is_empty());
    assert!(!history("in /work/main/target").is_empty());
    assert!(!history("A second session took").is_empty());
    assert!(!history("(was 63.8 deg)").is_empty());
    assert!(history("the hash 0 and a seed of 7; the crack meets the edge").is_empty());
}

#[test]
fn the_readme_is_a_front_page() {
    let readme = std::fs::read_to_string(workspace_root().join("README.md")).expect("read README.md");
    let lines = readme.lines().count();
    assert!(lines <= 250, "README.md has {lines} lines; the guide (docs/) holds the rest (at most 250)");
    assert!(readme.contains("./test"), "README.md shows the test command");
    // The quick starts: one Rust, one C and one C++ example, each at most 15 lines as shown
    // (a Rust block's hidden `# ` lines are not shown).
    for language in ["rust", "c", "cpp"] {
        let examples: Vec<Block> = blocks("README.md", &readme)
            .into_iter()
            .filter(|b| b.language() == language && b.not_run.is_none())
            .collect();
        assert_eq!(examples.len(), 1, "README.md has one {language} quick start");
        let shown =
            examples[0].code.lines().filter(|l| !(language == "rust" && (l.starts_with("# ") || *l == "#"))).count();
        assert!(shown <= 15, "README.md's {language} quick start shows {shown} lines (at most 15)");
    }
}

#[test]
fn every_page_is_in_the_summary() {
    let summary = std::fs::read_to_string(workspace_root().join("docs/src/SUMMARY.md")).expect("read SUMMARY.md");
    let listed: BTreeSet<String> =
        summary.split("](").skip(1).filter_map(|s| s.split(')').next()).map(|s| format!("docs/src/{s}")).collect();
    let missing: Vec<String> = pages()
        .into_iter()
        .map(|(f, _)| f)
        .filter(|f| f.starts_with("docs/src/") && !f.starts_with("docs/src/generated/") && f != "docs/src/SUMMARY.md")
        .filter(|f| !listed.contains(f))
        .collect();
    assert!(missing.is_empty(), "pages no reader can reach (add them to docs/src/SUMMARY.md): {missing:?}");
}

// ---------------------------------------------------------------------------------------
// The book builds, and every link resolves.

/// Builds the book once per profile with `mdbook` into target/, returning its directory.
fn book() -> &'static Path {
    static BOOK: OnceLock<PathBuf> = OnceLock::new();
    BOOK.get_or_init(|| {
        let out =
            workspace_root().join("target/docs-book").join(if cfg!(debug_assertions) { "debug" } else { "release" });
        let _ = std::fs::remove_dir_all(&out);
        let output = tool("mdbook")
            .arg("build")
            .arg(workspace_root().join("docs"))
            .arg("-d")
            .arg(&out)
            .output()
            .expect("run mdbook");
        let log = String::from_utf8_lossy(&output.stderr).into_owned() + &String::from_utf8_lossy(&output.stdout);
        assert!(output.status.success(), "mdbook build docs failed:\n{log}");
        let warnings: Vec<&str> = log.lines().filter(|l| l.contains("WARN") || l.contains("ERROR")).collect();
        assert!(warnings.is_empty(), "mdbook build docs warned:\n{}", warnings.join("\n"));
        out
    })
}

/// Every `id="..."` of an HTML page.
fn ids(html: &str) -> BTreeSet<String> {
    html.split(" id=\"").skip(1).filter_map(|s| s.split('"').next()).map(str::to_string).collect()
}

fn html_pages(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut dirs = vec![dir.to_path_buf()];
    while let Some(d) = dirs.pop() {
        for entry in std::fs::read_dir(&d).expect("read the book") {
            let path = entry.expect("entry").path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "html") {
                out.push(path);
            }
        }
    }
    out
}

/// Checks a link `target` (a path relative to `base`, maybe with `#anchor`): the file exists,
/// and for an HTML page the anchor is one of its ids.
fn check_link(base: &Path, target: &str, id_of: &dyn Fn(&Path) -> Option<BTreeSet<String>>) -> Result<(), String> {
    let (file, anchor) = match target.split_once('#') {
        Some((f, a)) => (f, Some(a)),
        None => (target, None),
    };
    let path = if file.is_empty() { base.to_path_buf() } else { base.parent().expect("a directory").join(file) };
    if !path.exists() {
        return Err(format!("{target}: no such file"));
    }
    if let Some(anchor) = anchor.filter(|a| !a.is_empty()) {
        match id_of(&path) {
            Some(ids) if ids.contains(anchor) => {}
            Some(_) => return Err(format!("{target}: no anchor #{anchor}")),
            None => {}
        }
    }
    Ok(())
}

fn external(target: &str) -> bool {
    target.contains("://") || target.starts_with("mailto:")
}

#[test]
fn the_book_builds_without_warnings_and_its_links_resolve() {
    let book = book();
    let mut broken = Vec::new();
    for page in html_pages(book) {
        let rel = page.strip_prefix(book).expect("in the book").display().to_string();
        // mdBook's own pages (print view, 404) repeat the others' links.
        if rel == "print.html" || rel == "404.html" || rel == "toc.html" {
            continue;
        }
        let html = std::fs::read_to_string(&page).expect("read a page");
        for attr in [" href=\"", " src=\""] {
            for target in html.split(attr).skip(1).filter_map(|s| s.split('"').next()) {
                if external(target) || target.starts_with("javascript:") || target.starts_with("data:") {
                    continue;
                }
                let id_of = |p: &Path| {
                    (p.extension().is_some_and(|e| e == "html"))
                        .then(|| ids(&std::fs::read_to_string(p).unwrap_or_default()))
                };
                if let Err(e) = check_link(&page, target, &id_of) {
                    broken.push(format!("{rel}: {e}"));
                }
            }
        }
    }
    broken.sort();
    broken.dedup();
    assert!(broken.is_empty(), "broken links in the book:\n{}", broken.join("\n"));
}

/// The markdown links `[text](target)` and images of a page's prose.
fn markdown_links(text: &str) -> Vec<String> {
    let prose = prose(text);
    let mut out = Vec::new();
    for piece in prose.split("](").skip(1) {
        if let Some(end) = piece.find(')') {
            let target = piece[..end].split_whitespace().next().unwrap_or("").trim_matches(['<', '>']);
            out.push(target.to_string());
        }
    }
    out
}

#[test]
fn the_readmes_links_resolve() {
    let readme = workspace_root().join("README.md");
    let text = std::fs::read_to_string(&readme).expect("read README.md");
    let book = book();
    let mut broken = Vec::new();
    for target in markdown_links(&text) {
        if external(&target) {
            continue;
        }
        // An anchor into a guide page is checked against the built page's ids.
        let id_of = |p: &Path| {
            let rel = p.strip_prefix(workspace_root().join("docs/src")).ok()?;
            let html = book.join(rel.with_extension("html"));
            Some(ids(&std::fs::read_to_string(html).unwrap_or_default()))
        };
        if let Err(e) = check_link(&readme, &target, &id_of) {
            broken.push(e);
        }
    }
    assert!(broken.is_empty(), "broken links in README.md:\n{}", broken.join("\n"));
}

// ---------------------------------------------------------------------------------------
// Every code block is compiled or run.

fn all_blocks() -> Vec<Block> {
    pages().iter().filter(|(f, _)| !f.starts_with("docs/src/generated/")).flat_map(|(f, t)| blocks(f, t)).collect()
}

#[test]
fn every_code_block_says_what_it_is() {
    let mut bad = Vec::new();
    for b in all_blocks() {
        if b.info.is_empty() {
            bad.push(format!("{}: a fence without a language (```text for output)", b.at()));
        }
        if b.not_run.as_deref() == Some("") {
            bad.push(format!("{}: `not run` without a reason", b.at()));
        }
        if b.language() == "rust" && b.info.contains("ignore") && b.not_run.is_none() {
            bad.push(format!("{}: an ignored Rust block without `<!-- not run: REASON -->`", b.at()));
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
fn rust_blocks_are_doctests() {
    let lib =
        std::fs::read_to_string(workspace_root().join("tests/support/lib.rs")).expect("read tests/support/lib.rs");
    let included: BTreeSet<String> =
        lib.split("include_str!(\"../../").skip(1).filter_map(|s| s.split('"').next()).map(str::to_string).collect();
    let with_rust: BTreeSet<String> =
        all_blocks().into_iter().filter(|b| b.language() == "rust" && b.not_run.is_none()).map(|b| b.file).collect();
    let missing: Vec<&String> = with_rust.difference(&included).collect();
    assert!(
        missing.is_empty(),
        "pages with Rust blocks that no doctest includes (add them to tests/support/lib.rs): {missing:?}"
    );
}

#[test]
fn c_and_cpp_blocks_build_and_run() {
    let mut failures = Vec::new();
    let mut ran = 0;
    for (n, b) in all_blocks().into_iter().enumerate() {
        let cpp = match b.language() {
            "c" => false,
            "cpp" | "c++" => true,
            _ => continue,
        };
        if b.not_run.is_some() {
            continue;
        }
        let name = format!("block{n}_{}", b.file.replace(['/', '.'], "_"));
        match build_c(&name, &b.code, cpp) {
            Err(e) => failures.push(format!("{}: {e}", b.at())),
            Ok(exe) => {
                let dir = scratch_dir(&name);
                let output = std::process::Command::new(&exe).current_dir(&dir).output().expect("run a block");
                ran += 1;
                if !output.status.success() {
                    failures.push(exited(&b, &output));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    assert!(ran >= 2, "the README's C and C++ quick starts run ({ran} programs)");
}

/// What a block that failed when run printed.
fn exited(b: &Block, output: &std::process::Output) -> String {
    let (stdout, stderr) = (String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr));
    format!("{}: exited with {}:\n{stdout}{stderr}", b.at(), output.status)
}

/// An empty directory for one block to run in.
fn scratch_dir(name: &str) -> PathBuf {
    let dir = workspace_root()
        .join("target/docs-programs")
        .join(if cfg!(debug_assertions) { "debug" } else { "release" })
        .join(format!("{name}.run"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create a scratch directory");
    dir
}

#[test]
fn sh_blocks_run() {
    let mut failures = Vec::new();
    let path = format!("{}:{}", hibi_tests::cli_dir().display(), std::env::var("PATH").unwrap_or_default());
    for (n, b) in all_blocks().into_iter().enumerate() {
        if !matches!(b.language(), "sh" | "bash") || b.not_run.is_some() {
            continue;
        }
        let dir = scratch_dir(&format!("sh{n}"));
        let output = std::process::Command::new("bash")
            .args(["-euo", "pipefail", "-c", &b.code])
            .current_dir(&dir)
            .env("PATH", &path)
            .env("HIBI_ROOT", workspace_root())
            .output()
            .expect("run bash");
        if !output.status.success() {
            failures.push(exited(&b, &output));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}
