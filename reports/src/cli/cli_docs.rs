//! `splinelab cli-docs` (hidden): the command line's reference, generated
//! from its own clap definition so it cannot drift from the program: one
//! man page per command and subcommand (clap_mangen, `splinelab.1`,
//! `splinelab-check.1`, `splinelab-check-prefilter.1`, ...) and one
//! Markdown page holding every command's `--help`, which the documentation
//! site includes (`scripts/docs.sh`).

use super::Cli;
use crate::error::CliError;
use crate::output::PendingFiles;
use clap::{Args, CommandFactory};
use std::path::{Path, PathBuf};

/// Arguments of `splinelab cli-docs`.
#[derive(Debug, Args)]
pub struct CliDocsArgs {
    /// Folder for the man pages (created if absent; pages of the same names
    /// are replaced).
    #[arg(long, value_name = "DIR")]
    pub man: PathBuf,
    /// The Markdown page of every command's `--help` (replaced whole).
    #[arg(long, value_name = "FILE")]
    pub markdown: PathBuf,
}

/// One visible command of the tree: its words (`["splinelab", "check",
/// "prefilter"]`) and its long help as `--help` prints it.
struct Page {
    words: Vec<String>,
    help: String,
    man: Vec<u8>,
}

/// Runs `splinelab cli-docs`: every page is written beside its target
/// first and moved into place only when all were written.
pub fn run(args: &CliDocsArgs) -> Result<(), CliError> {
    let pages = pages()?;
    std::fs::create_dir_all(&args.man).map_err(|source| CliError::Output {
        path: args.man.clone(),
        source,
    })?;
    let markdown = markdown(&pages);
    let names: Vec<PathBuf> = pages
        .iter()
        .map(|p| args.man.join(format!("{}.1", p.words.join("-"))))
        .collect();
    let mut files: Vec<(&Path, &[u8])> = names
        .iter()
        .zip(&pages)
        .map(|(name, p)| (name.as_path(), p.man.as_slice()))
        .collect();
    files.push((args.markdown.as_path(), markdown.as_bytes()));
    PendingFiles::write(&files)?.commit()?;
    crate::output::note(&format!(
        "cli-docs: {} man pages in {}, every --help in {}",
        pages.len(),
        args.man.display(),
        args.markdown.display()
    ));
    Ok(())
}

/// Every visible command, depth first, the root first.
fn pages() -> Result<Vec<Page>, CliError> {
    let mut root = Cli::command();
    // Sets each subcommand's full usage name (`splinelab check prefilter`).
    root.build();
    let mut out = Vec::new();
    collect(&mut root, vec!["splinelab".to_string()], &mut out)?;
    Ok(out)
}

fn collect(
    cmd: &mut clap::Command,
    words: Vec<String>,
    out: &mut Vec<Page>,
) -> Result<(), CliError> {
    let help = help_of(&words).unwrap_or_else(|| cmd.render_long_help().to_string());
    let mut man = Vec::new();
    // After `build`, a subcommand's display name is `splinelab-check-…` and
    // its usage name `splinelab check …`: the man page's NAME and SYNOPSIS.
    clap_mangen::Man::new(cmd.clone())
        .source(format!("splinelab {}", env!("CARGO_PKG_VERSION")))
        .manual("splinelab manual")
        .render(&mut man)
        .map_err(|source| CliError::Output {
            path: PathBuf::from(format!("{}.1", words.join("-"))),
            source,
        })?;
    out.push(Page {
        words: words.clone(),
        help,
        man,
    });
    for sub in cmd.get_subcommands_mut() {
        if sub.is_hide_set() || sub.get_name() == "help" {
            continue;
        }
        let mut next = words.clone();
        next.push(sub.get_name().to_string());
        collect(sub, next, out)?;
    }
    Ok(())
}

/// What `WORDS --help` prints: clap renders its long form only where some
/// option has a long help, so the page asks clap itself, as the program
/// does (`None` if clap did not answer with a help text).
fn help_of(words: &[String]) -> Option<String> {
    let mut args: Vec<&str> = words.iter().map(String::as_str).collect();
    args.push("--help");
    match Cli::command().try_get_matches_from(args) {
        Err(e) if e.kind() == clap::error::ErrorKind::DisplayHelp => Some(e.render().to_string()),
        _ => None,
    }
}

/// The reference page: one section per command, its `--help` verbatim.
fn markdown(pages: &[Page]) -> String {
    let version = Cli::command().get_version().unwrap_or_default().to_string();
    let mut text = format!(
        "# Command-line reference\n\n\
         Generated from the command line's own definition (clap) by the hidden \
         `splinelab cli-docs` command of splinelab {version}: every section is \
         exactly what `--help` prints. The same definition gives the man pages \
         (`man/splinelab.1` and one page per subcommand, e.g. \
         `man/splinelab-check-prefilter.1`).\n\n"
    );
    for page in pages {
        let command = page.words.join(" ");
        let depth = page.words.len().min(3);
        text.push_str(&format!(
            "{} `{command}`\n\n```text\n$ {command} --help\n{}\n```\n\n",
            "#".repeat(depth + 1),
            page.help.trim_end()
        ));
    }
    text
}
